"""What the dynamics scenes ask for, computed from the core and nothing more (one function per request)."""
from __future__ import annotations

import time

import numpy as np

from ..mechanisms import MECHANISMS, GeometryError, Notice
from . import compiled
from . import flywheel as fw
from .flywheel_analysis import flywheel_cycle
from .friction_iteration import friction_iteration
from .machine import Machine
from .merzalov_sheet import merzalov_sheet
from .motion import startup, steady_cycle
from ..numerics import Numerics
from .. import errata
from .reduction import Inertias, reduced_inertia, textbook_inertia_approximation
from .resistance import CONVENTIONS, Load, mean_over_cycle, resisting_moment
from .resisting_forces import kink_bound

MEAN_POINTS = 8192      # intervals for the cycle means (kinks make the trapezoid rule second order: kink_bound)
DISPLAY_POINTS = 512    # curves are computed on thousands of nodes and sent on about this many
TIME_BUDGET_S = 5.0     # wall-clock bound of one motion request (each path stops there with its partial result)


def slider_viscous_shape(p: dict, phi: np.ndarray) -> dict:
    """Eremyants (3.33) and its approximation (3.34) for the central crank-slider, as M_T/(βω) in m² (any β, ω):
    exact u₃₁² = l₁²(sin φ − sin 2φ/(2√(λ² − sin²φ)))², for λ² ≫ 1 l₁² sin²φ(1 − cos φ/λ)² (λ = l₂/l₁); the
    largest difference relative to the exact curve's largest value."""
    l1, lam = p["l1"], p["l2"] / p["l1"]
    exact = (l1 * (np.sin(phi) - np.sin(2 * phi) / (2 * np.sqrt(lam**2 - np.sin(phi) ** 2)))) ** 2
    approximation = l1**2 * np.sin(phi) ** 2 * (1 - np.cos(phi) / lam) ** 2
    return {"exact": exact, "approximation": approximation,
            "largest_error": float(np.max(np.abs(approximation - exact)) / np.max(exact))}


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
        started = time.perf_counter()
        moment = resisting_moment(mechanism, p, load, phi, omega)
        notices += moment.notices
        fine = np.linspace(0.0, mech.cycle(p), MEAN_POINTS + 1)
        kinematics = mech.evaluate(p, fine, set())          # one evaluation for both conventions
        totals = {convention: resisting_moment(mechanism, p, Load(**{**load.__dict__, "convention": convention}),
                                               fine, omega, kinematics).total for convention in CONVENTIONS}
        means = {convention: mean_over_cycle(total) for convention, total in totals.items()}
        total = totals[load.convention]
        error = max(abs(means[load.convention] - mean_over_cycle(total[::2])), kink_bound(total))
        result["numerics"] = _mean_numerics(totals[load.convention], error, started)
        locked = moment.self_locking
        result["resisting"] = {
            "total": moment.total, "useful": moment.useful, "dry": moment.dry, "viscous": moment.viscous,
            "mean": means[load.convention], "means": means, "friction_angle": float(np.arctan(load.f)),
            "self_locking": None if locked is None else phi[locked]}
        if mechanism == "slider_crank" and p["e"] == 0:
            result["resisting"]["viscous_shape"] = slider_viscous_shape(p, phi)
    if "friction_iteration" in outputs:
        if mechanism not in ("sine", "slider_crank"):
            raise GeometryError("outputs", "the textbook iterates friction forces for the sine mechanism and the "
                                "crank-slider only", "no_iteration")
        log = friction_iteration(mechanism, p, iteration_phi, load.force, load.f)
        result["friction_iteration"] = {"phi": iteration_phi, "ratio": log.ratio, "converged": log.converged,
                                        "steps": log.steps, "limit": log.limit}
        where = {"phi": float(np.degrees(iteration_phi)), "ratio": log.ratio}
        if log.ratio >= 1:                      # the physics decides divergence: the series' ratio, not a step cap
            notices.append(Notice("iteration_diverges", f"Self-locking at φ = {where['phi']:.1f}°: the ratio of the "
                                  f"series is {log.ratio:.3g} ≥ 1, the approximations diverge.", where))
        elif not log.converged:
            notices.append(Notice("iteration_unfinished", f"At φ = {where['phi']:.1f}° the series converges (ratio "
                                  f"{log.ratio:.3g} < 1), but the steps shown stop before their tolerance; its limit "
                                  "is the value to use.", where))
    return result, notices


def motion(machine: Machine, outputs: list[str], omega0: float, rtol: float, omega_mean: float | None,
           balance: bool, max_cycles: int, preview: float | None = None) -> tuple[dict, list[Notice]]:
    """The steady cycle and/or the start-up transient, each with its numerics; ``preview``: a family member's
    accuracy, a fraction of each drawn curve's span (motion.steady_cycle; None: the exact answer)."""
    result, notices = {}, machine.linkage_notices()
    compiled.warm_up()                      # compiled before the clock starts (once per process)
    deadline = time.perf_counter() + TIME_BUDGET_S
    if "steady" in outputs:
        steady = steady_cycle(machine, rtol, omega_mean, balance, deadline, preview)
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


def _mean_numerics(total: np.ndarray, error: float, started: float) -> dict:
    """How M_c0 was computed; its error relative to the cycle mean of |M_c| (M_c0 itself may be zero)."""
    numerics = Numerics(
        method="closed forms at each angle; M_c0 by the trapezoid rule on a closed uniform grid, error estimated "
               "as the larger of the difference from the grid of half as many points and the rule's bound at the "
               "corners and jumps of M_c seen in its second differences, relative to the cycle mean of |M_c|",
        code="closed_forms", steps=MEAN_POINTS, runtime_ms=1e3 * (time.perf_counter() - started))
    if not np.isfinite(total).all():
        numerics.message = "no M_c0: the moment is not finite at every angle (self-locking or a singular position)"
        numerics.message_code = "no_mean_moment"
        return numerics.as_dict()
    scale = mean_over_cycle(np.abs(total))
    numerics.error_estimate = error / scale if scale > 0 else 0.0
    return numerics.as_dict()


def _flywheel_error(machine: Machine, omega_mean: float, delta: float, balance: bool, steps: int, inertia: float) -> float | None:
    """Relative change of the exact inertia when the grid is halved (Simpson: the error is ~1/16 of it)."""
    coarse = fw.exact(flywheel_cycle(machine, steps // 2, balance).cycle, omega_mean, delta, inertia).inertia
    if inertia == 0:                     # group II alone keeps δ: nothing relative to compare unless both agree
        return 0.0 if coarse == 0 else None
    return abs(coarse / inertia - 1)


def flywheel(machine: Machine, omega_mean: float, delta: float, balance: bool, width_ratio: float,
             density: float, steps: int = 2048, with_numerics: bool = True) -> tuple[dict, list[Notice]]:
    """Merzalov, Gutyar, Wittenbauer and the exact inertia for δ, with the sizing and the curves to draw;
    ``with_numerics``: also how it was computed, with the error estimate (the exact inertia again on half
    the grid), left out (no "numerics") for a caller that does not read it."""
    started = time.perf_counter()
    steady = flywheel_cycle(machine, steps, balance)
    tables, nodes, phi, work, driving = steady.tables, steady.nodes, steady.phi, steady.work, steady.driving
    if not np.isfinite(work).all():
        return {}, tables.notices
    driving_cycle = max(abs(driving[-1]), 1e-300)
    if not steady.closes:
        trend = "speeds up" if work[-1] > 0 else "slows down"
        return {}, [Notice(f"no_steady_cycle_{trend.split()[0]}", f"No steady cycle: the work over a cycle is "
                           f"{work[-1]:.4g} J, not zero, so the machine {trend} every cycle.", {"work": float(work[-1])})]
    group_i_existing, cycle = steady.existing, steady.cycle
    methods = [fw.merzalov(cycle, omega_mean, delta), fw.gutyar(cycle, omega_mean, delta)]
    witt, diagram = fw.wittenbauer(cycle, omega_mean, delta)
    methods += [witt, fw.exact(cycle, omega_mean, delta, methods[0].inertia)]
    rows = [{"method": m.name, "inertia": m.inertia, "additional": m.inertia - group_i_existing,
             "energy_swing": m.energy_swing, "delta_achieved": fw.achieved_delta(cycle, m.inertia, omega_mean)}
            for m in methods]
    notices = machine.linkage_notices()
    required = rows[-1]["inertia"]
    chosen = max(required, group_i_existing)
    if required <= group_i_existing:
        achieved = fw.achieved_delta(cycle, group_i_existing, omega_mean)
        notices.append(Notice("no_flywheel_needed", f"No flywheel needed: the crank and rotor alone (I = "
                              f"{group_i_existing:.4g} kg·m²) already give δ = {achieved:.4g} ≤ {delta:g}.",
                              {"inertia": group_i_existing, "achieved": achieved, "delta": delta}))
    flywheel_inertia = max(required - group_i_existing, 0.0)
    merz = rows[0]
    omega_before = fw.periodic_speed(cycle, group_i_existing, omega_mean)
    if not np.isfinite(omega_before).all():
        stall = float(np.degrees(phi[int(np.argmin(work))]))
        notices.append(Notice("stall_in_cycle", f"Without the flywheel the machine cannot run at ω_m = {omega_mean:g} "
                              f"rad/s: stall at φ = {stall:.1f}°, the kinetic energy runs out within the cycle.",
                              {"phi": stall}))
    omega_after = fw.periodic_speed(cycle, chosen, omega_mean)
    total = chosen + cycle.inertia_ii
    moment = tables.net_phi[nodes]
    epsilon = (moment - 0.5 * tables.dJ[nodes] * omega_after**2) / total
    group_one = work - 0.5 * cycle.inertia_ii * omega_mean**2
    delta_t_i = group_one - group_one[0]
    delta_residual = abs(rows[-1]["delta_achieved"] / delta - 1)
    shown = slice(0, None, max(1, (phi.size - 1) // DISPLAY_POINTS))   # computed finely, sent coarsely
    curves = {
        "work_driving": driving, "work_resisting": driving - work, "work_total": work,
        "kinetic_ii": 0.5 * cycle.inertia_ii * omega_mean**2, "delta_t_i": delta_t_i, "inertia_ii": cycle.inertia_ii,
        "delta_omega": (delta_t_i - 0.5 * (delta_t_i.max() + delta_t_i.min())) / (merz["inertia"] * omega_mean),
        "omega_before": omega_before, "omega_after": omega_after, "epsilon": epsilon}
    result = {
        "phi": phi[shown], "methods": rows, "group_i_existing": group_i_existing, "flywheel_inertia": flywheel_inertia,
        "merzalov_excess": merz["inertia"] / required - 1 if required > 0 else None,
        "curves": {name: values[shown] for name, values in curves.items()},
        "wittenbauer": diagram,
        "disk": fw.disk(flywheel_inertia, width_ratio, density).__dict__,
        "disk_as_printed": fw.disk_as_printed(flywheel_inertia).__dict__,
        "rim": fw.rim(flywheel_inertia, fw.disk(flywheel_inertia, width_ratio, density).diameter, density)
        if flywheel_inertia > 0 else None,
        "balancing_moment": tables.balancing_moment,
        "errata": [errata.gutyar_squares(work, cycle.inertia_ii, omega_mean, delta, rows[1]["inertia"]),
                   errata.wittenbauer_axes(omega_mean, delta),
                   errata.flywheel_part(required, machine.inertias.J1, group_i_existing - machine.inertias.J1),
                   *errata.lecture10_rig(group_i_existing, cycle.inertia_ii, float(driving[-1]), omega_mean)],
    }
    motor = machine.motor
    result["merzalov_sheet"] = merzalov_sheet(
        phi, np.gradient(driving, phi), driving, work, cycle.inertia_ii, omega_mean, delta, merz["inertia"],
        (motor.p_max, motor.piston_diameter) if motor.kind == "indicator" else None)
    if with_numerics:
        result["numerics"] = Numerics(
            method="Simpson's rule for A(φ) on a uniform grid; exact inertia by Brent's method on the periodic "
                   "energy solution", code="flywheel_simpson", steps=steps,
            runtime_ms=1e3 * (time.perf_counter() - started),
            error_estimate=_flywheel_error(machine, omega_mean, delta, balance, steps, rows[-1]["inertia"]),
            energy_residual=abs(work[-1]) / driving_cycle,
            message=f"the exact inertia gives δ to a relative {delta_residual:.1e}",
            message_code="flywheel_delta", message_context={"residual": f"{delta_residual:.1e}"}).as_dict()
    return result, notices
