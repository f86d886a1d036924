"""The analysis problem of Merzalov's method (Lecture 10 §10.4, step 8): the group-I inertia given, the δ it
gives, beside the synthesis (the inertia a permissible [δ] needs), with the driving-moment diagram (Fig. 10.6)
and the transfer functions (Fig. 10.5) of the crank-slider.

    analysis (Merzalov, (L6) solved for δ):  δ = ΔT_Imax/(I_I ω_ср²),  ΔT_I = A − I_II ω_ср²/2   (L10)
    exact:  the periodic solution ω(φ)² = 2(T₀ + A)/(I_I + I_II) with (ω_max + ω_min)/2 = ω_ср,
            δ = (ω_max − ω_min)/ω_ср                                                        (L3), (L4)
    synthesis: I_I = ΔT_Imax/([δ] ω_ср²) (L6) and the exact inertia for [δ] (flywheel.exact)
    Fig. 10.5: u₂₁, V_qC = u₃₁, V_qS2 = √(V_qS2x² + V_qS2y²)  (L13)–(L14);  Fig. 10.6: M_д^пр = F_д V_qC cos(F, V) (L17)
"""
from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from ..mechanisms import MECHANISMS, Notice
from ..numerics import Numerics, cumulative_simpson, parabola_extremum
from . import flywheel as fw
from .machine import Machine, Tables
from .motion import node_tables, steps_per_cycle

STEPS = 2048                # Simpson steps per 2π (the flywheel study's grid)
DISPLAY_POINTS = 360


@dataclass
class SteadyCycle:
    """The flywheel study's cycle: the tables on the uniform nodes of ``steps`` Simpson steps per 2π, the work
    A(φ) of all the φ-moments and the driving work A_д(φ) (Simpson), group I's inertia J₁ + J_rotor i² and the
    cycle of group II (fw.Cycle) on the step nodes."""

    tables: Tables
    nodes: slice
    phi: np.ndarray
    work: np.ndarray
    driving: np.ndarray
    existing: float
    cycle: fw.Cycle

    @property
    def closes(self) -> bool:
        """A steady cycle exists: the work over a cycle is finite and zero (to 1e-9 of the driving work)."""
        return bool(np.isfinite(self.work).all()) and \
            abs(self.work[-1]) <= 1e-9 * max(abs(self.driving[-1]), 1e-300)


def flywheel_cycle(machine: Machine, steps: int, balance: bool) -> SteadyCycle:
    """The cycle of the machine on the flywheel study's grid (``SteadyCycle``): the analysis here, the flywheel
    report (report.flywheel) and both their error estimates start from it."""
    tables = node_tables(machine, steps_per_cycle(machine, steps), balance)
    nodes = slice(0, None, 2)
    h = float(tables.phi[2] - tables.phi[0])
    phi = tables.phi[nodes]
    work = cumulative_simpson(tables.net_phi, h)
    existing = machine.inertias.J1 + machine.inertias.J_rotor * machine.inertias.gear_ratio**2
    return SteadyCycle(tables, nodes, phi, work, cumulative_simpson(tables.drive_phi, h), existing,
                       fw.Cycle(phi, work, tables.J[nodes] - existing))


def merzalov_delta(cycle: fw.Cycle, inertia_i: float, omega_mean: float) -> float:
    """(L6) solved for δ: ΔT_Imax/(I_I ω_ср²), Merzalov's ΔT_I computed at ω_ср (L9)–(L10)."""
    group_one = cycle.work - 0.5 * cycle.inertia_ii * omega_mean**2
    swing = parabola_extremum(group_one, +1) - parabola_extremum(group_one, -1)
    return swing / (inertia_i * omega_mean**2)


def flywheel_analysis(machine: Machine, omega_mean: float, flywheel: float, delta: float, balance: bool,
                      outputs: list[str], steps: int = STEPS) -> tuple[dict, list[Notice]]:
    """Merzalov's analysis problem (Lecture 10 §10.4): δ = ΔT_Imax/(I_I ω_ср²), (L6) solved for δ, with
    ΔT_I = A − I_II ω_ср²/2 (L10); beside it the exact δ (L3) of the periodic solution, the synthesis for [δ]
    (L6) and the diagrams of Figs. 10.5, 10.6 (module docstring)."""
    started = time.perf_counter()
    steady = flywheel_cycle(machine, steps, balance)
    if not steady.closes:
        return {}, [Notice("no_steady_cycle_analysis", "No steady cycle: the work over a cycle is not zero, so "
                           "there is no δ to find (balance the cycle).", {})]
    tables, nodes, phi, work, driving = steady.tables, steady.nodes, steady.phi, steady.work, steady.driving
    existing, cycle = steady.existing, steady.cycle
    inertia_i = existing + flywheel
    shown = slice(0, None, max(1, (phi.size - 1) // DISPLAY_POINTS))
    result, notices = {"phi": phi[shown]}, []
    if "analysis" in outputs:
        omega = fw.periodic_speed(cycle, inertia_i, omega_mean)
        if not np.isfinite(omega).all():
            notices.append(Notice("stall_in_cycle", f"Stall at φ = {np.degrees(phi[int(np.argmin(work))]):.1f}°: "
                                  "the kinetic energy runs out within the cycle; there is no steady motion.",
                                  {"phi": float(np.degrees(phi[int(np.argmin(work))]))}))
        else:
            exact = fw.achieved_delta(cycle, inertia_i, omega_mean)
            approx = merzalov_delta(cycle, inertia_i, omega_mean)
            result["analysis"] = {"inertia_i": inertia_i, "existing": existing, "delta_exact": exact,
                                  "delta_merzalov": approx, "meets": bool(exact <= delta),
                                  "omega": omega[shown], "omega_max": float(omega.max()),
                                  "omega_min": float(omega.min())}
            result["analysis"]["numerics"] = Numerics(
                method="Simpson's rule for A(φ); the periodic energy solution's level T₀ by Brent's method",
                code="flywheel_simpson", steps=int(phi.size - 1), runtime_ms=1e3 * (time.perf_counter() - started),
                error_estimate=_error(machine, omega_mean, inertia_i, balance, steps, exact),
                energy_residual=abs(work[-1]) / max(abs(driving[-1]), 1e-300)).as_dict()
    if "synthesis" in outputs:
        merz = fw.merzalov(cycle, omega_mean, delta)
        exact_needed = fw.exact(cycle, omega_mean, delta, merz.inertia)
        result["synthesis"] = {"delta": delta, "merzalov": merz.inertia, "exact": exact_needed.inertia,
                               "flywheel_merzalov": max(merz.inertia - existing, 0.0),
                               "flywheel_exact": max(exact_needed.inertia - existing, 0.0)}
    if "driving_moment" in outputs:
        result["driving_moment"] = {"driving": tables.drive_phi[nodes][shown],
                                    "resisting": (tables.useful + tables.dry)[nodes][shown],
                                    "mean": tables.balancing_moment}
    if "transfer_functions" in outputs:
        values = MECHANISMS[machine.mechanism].evaluate(machine.params, phi[shown], set()).values
        result["transfer_functions"] = {"u21": values["u21"], "u31": values["u31"], "v_s2": values["chi21"]}
    return result, notices


def _error(machine: Machine, omega_mean: float, inertia_i: float, balance: bool, steps: int, delta: float) -> float:
    """|δ on half the grid / δ − 1|: the grid's error (Simpson on A, O(h⁴) on smooth pieces)."""
    coarse = flywheel_cycle(machine, steps // 2, balance).cycle
    return abs(fw.achieved_delta(coarse, inertia_i, omega_mean) / delta - 1)
