"""The answer of the induction-motor study (Lecture 10 §10.9–§10.10): the reduced static characteristic with
its branches and the load line, the operating point and its stability, the successive approximations beside
the joint solution of the equation of motion with the characteristic (motion.steady_cycle)."""
from __future__ import annotations

import time

import numpy as np

from ..mechanisms import Notice
from ..numerics import Numerics
from . import motor_characteristic as mc
from .machine import Machine
from .motion import cycle_tables, steady_cycle
from .successive_approximations import cycle_mean, successive_approximations

GRID = 2048                 # steps per 2π of the successive approximations (trapezoid, error ~1e-8 here)
PLOTTED = 361               # points of each plotted law of motion
SHOWN_STEPS = (1, 2, 3)     # the steps drawn beside the last one
TIME_BUDGET_S = 3.0         # the joint solution's bound (as /motion's)


def mean_load(machine: Machine, tables) -> tuple[float, float]:
    """M_с0(ω) = M_с0 + β_red ω: the cycle mean of the resistance (useful, dry, viscous) and its slope."""
    return -cycle_mean(tables.net_phi, tables.phi), machine.load.beta * cycle_mean(tables.sliding, tables.phi)


def motor_study(machine: Machine, outputs: list[str], tol: float) -> tuple[dict, list[Notice]]:
    """Lecture 10 §10.9–§10.10 on the machine: the operating point M_д(ω*) = M_с(ω*), its stability
    dM_д/dω < dM_с/dω (Fig. 10.14), the successive approximations and the joint solution (module docstring)."""
    motor, i = machine.motor, machine.inertias.gear_ratio
    tables = cycle_tables(machine, machine.kinks(), GRID)
    load, load_slope = mean_load(machine, tables)
    points = mc.operating_points(motor, i, load, load_slope)
    result, notices = {}, []
    last = None
    working = next((p for p in points if p.branch == "stable"), None)
    if working is None:
        peak = mc.characteristic(motor, i)["maximum"]["moment"]
        notices.append(Notice("motor_stalls", f"The motor stalls: the mean load {load:.4g} N·m exceeds the largest "
                              f"torque of the characteristic M_d,max = {peak:.4g} N·m.", {"load": load, "peak": peak}))
    if "characteristic" in outputs:
        curve = mc.characteristic(motor, i, extra=[p.omega for p in points])
        omega = curve["omega"]
        curve["load"] = load + load_slope * omega
        curve["operating"] = np.where(np.isin(omega, [p.omega for p in points]), load + load_slope * omega, np.nan)
        if working is not None:
            line = mc.linearised(motor, i, working)
            curve["linearised"] = np.where(omega >= curve["maximum"]["omega"], line["b"] + line["k"] * omega, np.nan)
        result["characteristic"] = curve
    if "operating_point" in outputs:
        residual = max((abs(p.moment - load - load_slope * p.omega) for p in points), default=0.0)
        result["numerics"] = Numerics(
            method="operating points by Brent's method on M_d(ω) − M_c(ω) on each branch (bracketed at ω₁k)",
            code="operating_point_brent", rtol=1e-14, iterations=len(points),
            error_estimate=residual / max(abs(load), 1e-300)).as_dict()
        result["operating_point"] = [{"omega": p.omega, "moment": p.moment, "drive_slope": p.drive_slope,
                                      "load_slope": p.load_slope, "branch": p.branch, "stable": p.stable}
                                     for p in points]
        if working is not None:
            line = mc.linearised(motor, i, working)
            result["linearised"] = {key: line[key] for key in ("k", "b", "b_printed", "at_sync", "at_sync_printed")}
            result["figures"] = {"omega": working.omega, "moment": working.moment,
                                 "drive_slope": working.drive_slope, "load_slope": working.load_slope,
                                 "margin": working.load_slope - working.drive_slope,
                                 "time_constant": cycle_mean(tables.J, tables.phi)
                                 / abs(working.drive_slope - working.load_slope)}
        unstable = [p for p in points if not p.stable]
        notices += [Notice("operating_point_unstable", f"The crossing at ω = {p.omega:.4g} rad/s is on the unstable "
                           f"branch: dM_d/dω = {p.drive_slope:.4g} ≥ dM_c/dω = {p.load_slope:.4g}.",
                           {"omega": p.omega, "drive": p.drive_slope, "load": p.load_slope}) for p in unstable]
    if "approximations" in outputs and working is not None:
        steps = successive_approximations(machine, tables, working.omega, mc.critical_speed(motor, i), tol)
        notices += steps.notices
        plotted = np.linspace(0.0, machine.cycle(), PLOTTED)
        curves = {"phi": plotted}
        for name, laws in (("omega", steps.omega), ("moment", steps.moment)):
            for k in SHOWN_STEPS:
                if k <= len(laws):
                    curves[f"{name}_{k}"] = np.interp(plotted, tables.phi, laws[k - 1])
            if laws:
                curves[f"{name}_last"] = np.interp(plotted, tables.phi, laws[-1])
        last = steps.omega[-1] if steps.omega else None
        result["approximations"] = {"rows": steps.rows, "contraction": steps.ratio, "converged": steps.converged,
                                    "curves": curves, "numerics": steps.numerics.as_dict()}
    if "joint" in outputs and working is not None:
        motion = steady_cycle(machine, min(tol * 10, 1e-6), deadline=time.perf_counter() + TIME_BUDGET_S)
        notices += motion.notices
        result["joint"] = {"numerics": motion.numerics.as_dict()}
        if motion.steady is not None:
            s = motion.steady
            plotted = np.linspace(0.0, machine.cycle(), PLOTTED)
            result["joint"] |= {"phi": s.phi, "omega": s.omega, "omega_mean": s.omega_mean, "delta": s.delta,
                                "omega_max": float(s.omega.max()), "omega_min": float(s.omega.min()),
                                "omega_plotted": np.interp(plotted, s.phi, s.omega)}
            if last is not None:       # the last approximation against the joint solution, at its nodes
                result["joint"]["difference"] = float(np.max(np.abs(np.interp(s.phi, tables.phi, last) - s.omega))
                                                      / s.omega_mean)
    return result, notices

