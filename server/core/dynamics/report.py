"""What the dynamics scenes ask for, computed from the core and nothing more (one function per request)."""
from __future__ import annotations

import time

import numpy as np

from ..mechanisms import MECHANISMS, GeometryError, Notice
from .friction_iteration import friction_iteration
from .machine import Machine
from .motion import startup, steady_cycle
from .reduction import Inertias, reduced_inertia, textbook_inertia_approximation
from .resistance import CONVENTIONS, Load, mean_over_cycle, resisting_moment

TIME_BUDGET_S = 5.0     # wall-clock bound of one motion request (each path stops there with its partial result)


def reduction(mechanism: str, params: dict, inertias: Inertias, load: Load, n: int, omega: float,
              outputs: list[str], iteration_phi: float) -> tuple[dict, list[Notice]]:
    """J(φ), dJ/dφ, M_c(φ) over one cycle (closed grid of n points) and the friction iteration."""
    mech = MECHANISMS[mechanism]
    p = mech.check(params)
    phi = np.linspace(0.0, mech.cycle(p), n)
    result, notices = {"phi": phi}, []
    if "inertia" in outputs:
        inertia = reduced_inertia(mechanism, p, inertias, phi)
        mean = inertia.mean
        result["inertia"] = {"J": inertia.J, "dJ": inertia.dJ, "mean": mean, "variable": inertia.J - mean,
                             "parts": inertia.parts,
                             "approximation": textbook_inertia_approximation(mechanism, p, inertias, phi)}
    if "resisting" in outputs:
        moment = resisting_moment(mechanism, p, load, phi, omega)
        notices += moment.notices
        means = {}
        for convention in CONVENTIONS:
            other = moment if convention == load.convention else resisting_moment(
                mechanism, p, Load(**{**load.__dict__, "convention": convention}), phi, omega)
            means[convention] = mean_over_cycle(other.total)
        locked = moment.self_locking
        result["resisting"] = {
            "total": moment.total, "useful": moment.useful, "dry": moment.dry, "viscous": moment.viscous,
            "mean": means[load.convention], "means": means, "friction_angle": float(np.arctan(load.f)),
            "self_locking": None if locked is None else phi[locked]}
    if "friction_iteration" in outputs:
        if mechanism not in ("sine", "slider_crank"):
            raise GeometryError("outputs", "the textbook iterates friction forces for the sine mechanism and the "
                                "crank-slider only", "no_iteration")
        log = friction_iteration(mechanism, p, iteration_phi, load.force, load.f)
        result["friction_iteration"] = {"phi": iteration_phi, "ratio": log.ratio, "converged": log.converged,
                                        "steps": log.steps, "limit": log.limit}
        if not log.converged:
            notices.append(Notice("iteration_diverges", f"Self-locking at φ = {np.degrees(iteration_phi):.1f}°: the "
                                  f"ratio of the series is {log.ratio:.3g} ≥ 1, the approximations diverge.",
                                  {"phi": float(np.degrees(iteration_phi)), "ratio": log.ratio}))
    return result, notices


def motion(machine: Machine, outputs: list[str], omega0: float, rtol: float, omega_mean: float | None,
           balance: bool, max_cycles: int) -> tuple[dict, list[Notice]]:
    """The steady cycle and/or the start-up transient, each with its numerics."""
    result, notices = {}, []
    deadline = time.perf_counter() + TIME_BUDGET_S
    if "steady" in outputs:
        steady = steady_cycle(machine, rtol, omega_mean, balance, deadline)
        notices += steady.notices
        result["numerics"] = steady.numerics.as_dict()
        if steady.steady is not None:
            s = steady.steady
            result |= {"phi": s.phi, "omega": s.omega, "t": s.t, "epsilon": s.epsilon, "omega_mean": s.omega_mean,
                       "omega_time_mean": s.omega_time_mean, "delta": s.delta, "efficiency": s.efficiency,
                       "works": s.works}
    if "startup" in outputs:
        start = startup(machine, omega0, max(rtol, 1e-9), max_cycles, balance, deadline)
        notices += start.notices
        run = start.transient
        result["startup"] = {"numerics": start.numerics.as_dict()}
        if run is not None:
            keep = slice(None, None, max(1, run.phi.size // 4000))   # at most ~4000 points to draw
            result["startup"] |= {"phi": run.phi[keep], "omega": run.omega[keep], "t": run.t[keep]}
    return result, notices
