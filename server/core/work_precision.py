"""A small live work–precision study for the current machine (the scenes' in-app Numerics page, "Run the study").

Each entry is (method, tolerance, relative error, run time in ms) against a reference computed at a
tighter tolerance by a different route.  One deadline per study (BUDGET_S from its start), the reference
included: the reference may take REFERENCE_SHARE of it, the runs the rest; a run the deadline reaches is skipped,
and the study says in words that the time budget stopped it (study_notices: the API marks the answer partial).
bench/work_precision.py runs the full study offline.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp

from .dynamics.machine import Machine
from .dynamics.motion import steady_cycle
from .elastic.report import ElasticMachine, absolute_tolerances, build, no_load_speed
from .elastic.warm import ready
from .elastic.simulate import STIFF_RATIO, WorkBound, bounded, integrate, stiffness_ratio
from .mechanisms import Notice

BUDGET_S = 6.0
REFERENCE_SHARE = 0.5      # of the budget, at most, for the reference run(s)


def study_notices(study: dict) -> list[Notice]:
    """The study's words when its deadline stopped it: which runs it skipped."""
    if not study.get("out_of_time"):
        return []
    return [Notice("study_time_budget", f"The study stopped at its time budget of {BUDGET_S:g} s: "
                   f"{len(study['skipped'])} runs skipped.", {"budget": BUDGET_S, "skipped": len(study["skipped"])})]


@dataclass
class Periodic:
    """The general way to a steady cycle: ω at φ = 0 of the first cycle that repeats, that cycle's dense
    solution (t ↦ φ, ω), and the work it took."""

    omega0: float
    last_cycle: object
    nfev: int
    cycles: int


def cycles_until_periodic(machine: Machine, method: str, rtol: float, omega_start: float,
                          deadline: float = math.inf, max_cycles: int = 400) -> Periodic | None:
    """Integrate J ω̇ + ½J′ω² = M in time by solve_ivp(method), cycle after cycle, until ω(φ = kΦ) repeats
    to rtol; None when the deadline or max_cycles comes first, or the machine does not reach the next cycle."""
    def rhs(_, y):
        tables = machine.tables(np.array([y[0]]))
        moment = tables.net_phi[0] + machine.speed_moment(y[1], tables.sliding[0])[0]
        return [y[1], (moment - 0.5 * tables.dJ[0] * y[1] ** 2) / tables.J[0]]
    y, t, previous, nfev = np.array([0.0, omega_start]), 0.0, None, 0
    cycle = machine.cycle()
    for k in range(max_cycles):
        if time.perf_counter() > deadline:
            return None
        target = cycle * (k + 1)
        event = lambda _, s: s[0] - target
        event.terminal = True
        try:                                 # the deadline holds inside a cycle too (a stalling machine)
            solution = solve_ivp(bounded(rhs, math.inf, deadline), (t, t + 100.0), y, method=method, rtol=rtol,
                                 atol=rtol * 1e-3, events=event, dense_output=True)
        except WorkBound:
            return None
        if not solution.t_events[0].size:    # it came to rest or turned back before the next cycle
            return None
        nfev += solution.nfev
        t, y = float(solution.t_events[0][0]), solution.y_events[0][0]
        if previous is not None and abs(y[1] - previous) <= rtol * y[1]:
            return Periodic(float(y[1]), solution, nfev, k + 1)
        previous = y[1]
    return None


def _whole(motion) -> bool:
    """Whether a steady cycle was found in full, not stopped by the time budget (its numerics say so)."""
    return motion.steady is not None and "time budget" not in (motion.numerics.message or "")


def motion_study(machine: Machine, deadline: float | None = None) -> dict:
    """Ours at four tolerances and solve_ivp's cycles until periodic, all by one deadline (BUDGET_S from now
    when None); the reference, ours at 1e-11, by REFERENCE_SHARE of it."""
    started = time.perf_counter()
    deadline = started + BUDGET_S if deadline is None else deadline
    tight = steady_cycle(machine, 1e-11, deadline=started + REFERENCE_SHARE * (deadline - started))
    if not _whole(tight):
        return {"rows": [], "skipped": [], "reference": None, "out_of_time": tight.steady is not None}
    reference = tight.steady
    rows, skipped = [], []
    for rtol in (1e-3, 1e-5, 1e-7, 1e-9):
        start = time.perf_counter()
        motion = steady_cycle(machine, rtol, deadline=deadline)
        if not _whole(motion):
            skipped.append(f"ours {rtol:.0e}")
            continue
        rows.append({"method": "ours: Newton shooting", "rtol": rtol, "runtime_ms": 1e3 * (time.perf_counter() - start),
                     "error": abs(motion.steady.omega[0] / reference.omega[0] - 1)})
    for method in ("DOP853", "LSODA", "Radau"):
        for rtol in (1e-3, 1e-5):
            start = time.perf_counter()
            periodic = cycles_until_periodic(machine, method, rtol, 0.9 * reference.omega[0], deadline, 200)
            if periodic is None:
                skipped.append(f"{method} {rtol:.0e}")
                continue
            omega = periodic.omega0
            rows.append({"method": f"solve_ivp {method}, cycles until periodic", "rtol": rtol,
                         "runtime_ms": 1e3 * (time.perf_counter() - start), "error": abs(omega / reference.omega[0] - 1)})
    return {"rows": rows, "skipped": skipped, "reference": "ours at rtol 1e-11", "quantity": "ω(φ = 0) on the steady cycle",
            "reference_code": "ours_tight", "quantity_code": "cycle_speed",
            "out_of_time": bool(skipped) and time.perf_counter() > deadline}


def elastic_study(machine: ElasticMachine, t_end: float, deadline: float | None = None) -> dict:
    """Every method at loose tolerances first, then tighter ones, so each gets its cheap points in the budget;
    the server's own pick (by the measured stiffness) runs as the server runs it, compiled, and is labelled ours;
    the others are scipy's solve_ivp (the reference path); the reference is compiled DOP853 (Radau) at 1e-10,
    within REFERENCE_SHARE of the study's one deadline (BUDGET_S from the start when None)."""
    model, y0 = build(machine)
    samples = np.linspace(0.0, t_end, 201)
    ratio = stiffness_ratio(model, y0, max(2 * np.pi / t_end, machine.speed, no_load_speed(machine)))[0]
    picked = "Radau" if ratio > STIFF_RATIO else "DOP853"
    ready()                                            # compiled before the clock starts
    started = time.perf_counter()
    deadline = started + BUDGET_S if deadline is None else deadline
    reference_deadline = started + REFERENCE_SHARE * (deadline - started)
    reference = integrate(model, y0, t_end, 1e-10, "DOP853", samples, reference_deadline,
                          absolute_tolerances(machine, model, 1e-10))
    if not reference.complete:
        reference = integrate(model, y0, t_end, 1e-10, "Radau", samples, reference_deadline,
                              absolute_tolerances(machine, model, 1e-10))
    out_of_time = not reference.complete and time.perf_counter() > reference_deadline
    if not reference.complete:                         # no reference to measure errors against: every run skipped
        deadline = -math.inf
    twist = reference.y[2]
    scale = max(float(np.max(np.abs(twist), initial=0.0)), 1e-300)
    rows, skipped = [], []
    for rtol in (1e-3, 1e-5, 1e-7):
        for method in ("DOP853", "Radau", "LSODA", "RK45"):
            engine = "compiled" if method == picked else "scipy"
            label = f"ours: compiled {method}" if method == picked else method
            if time.perf_counter() > deadline:
                skipped.append(f"{label} {rtol:.0e}")
                continue
            start = time.perf_counter()
            run = integrate(model, y0, t_end, rtol, method, samples, deadline, absolute_tolerances(machine, model, rtol),
                            engine=engine)
            if not run.complete:
                skipped.append(f"{label} {rtol:.0e}")
                continue
            rows.append({"method": label, "rtol": rtol, "runtime_ms": 1e3 * (time.perf_counter() - start),
                         "error": float(np.max(np.abs(run.y[2] - twist))) / scale})
    return {"rows": rows, "skipped": skipped, "reference": "rtol 1e-10", "quantity": "the twist over the run",
            "reference_code": "tight", "quantity_code": "twist",
            "out_of_time": out_of_time or (bool(skipped) and time.perf_counter() > deadline > -math.inf)}
