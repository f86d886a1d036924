"""Taking the motor's characteristic into account by successive approximations (Lecture 10 §10.10).

Step 1 takes the driving moment constant (forces of position alone): it balances the cycle's resistance,
and the mean speed is the operating point of the characteristic (§10.9).  Step k + 1 reads the moment
M_д^(k+1)(φ) = M_д(ω^(k)(φ) + c) off the characteristic along the previous law of motion, c the shift of
the mean speed that makes the cycle's work zero (A_д^ц = A_с^ц, Lecture 10 (L1)), and solves the energy
equation again (L4):

    I(φ) ω^(k+1)(φ)²/2 = T₀ + ∫₀^φ (M_д^(k+1) − M_с) dφ,   T₀: mean of ω^(k+1) = mean of ω^(k) + c.

The steps stop when two laws differ by less than the tolerance.  Linearised about the mean speed
(M_д − M_с ≈ M̄ + k·Δω, k = dM_д/dω − dM_с/dω at the operating point; k₁* of (L30) for the
linearised characteristic and a load independent of speed), a step maps a speed error e(φ) to
(k/(Ī ω̄))·∫(e − ē)dφ (its mean removed), whose largest factor, on the first harmonic, is

    ρ = |k|/(Ī ω̄) = 1/(τ ω̄),   τ = Ī/|k| the drive's time constant (Lecture 10 §10.9),

so the steps converge when ρ < 1 (the drive's time constant longer than the time of one radian) and
diverge otherwise: a steep characteristic or a small flywheel.  ρ decides; the count of
steps is only a guard.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import brentq

from ..mechanisms import Notice
from ..numerics import Numerics
from .approximations_compiled import CONVERGED, NO_BALANCE, ROOT_FAILED, ROWS, STOPS, approximation_steps
from .machine import Machine, Tables
from .speed_moment import speed_parameters

STEPS_MAX = 200             # guard only: ρ < 1 decides convergence, the steps needed are log(tol)/log ρ
SHOWN_DIVERGING = 6         # steps shown of a diverging sequence


@dataclass
class Approximations:
    """The laws of motion ω^(k)(φ) and the driving moments M_д^(k)(φ) of each step, with the table."""

    phi: np.ndarray
    omega: list[np.ndarray] = field(default_factory=list)
    moment: list[np.ndarray] = field(default_factory=list)
    rows: list[dict] = field(default_factory=list)
    ratio: float = 0.0          # ρ predicted
    converged: bool = False
    notices: list[Notice] = field(default_factory=list)
    numerics: Numerics | None = None


def cumulative_trapezoid(values: np.ndarray, phi: np.ndarray) -> np.ndarray:
    """∫ from the first node to each node (nodes of cycle_tables: every kink on a node, a zero-width step at
    a kink adds nothing)."""
    return np.concatenate([[0.0], np.cumsum(0.5 * np.diff(phi) * (values[1:] + values[:-1]))])


def cycle_mean(values: np.ndarray, phi: np.ndarray) -> float:
    """(1/Φ)∫ values dφ over the cycle's nodes (trapezoidal rule)."""
    return float(cumulative_trapezoid(values, phi)[-1] / (phi[-1] - phi[0]))


def energy_law(tables: Tables, work: np.ndarray, mean: float) -> np.ndarray | None:
    """ω(φ) = √(2(T₀ + A)/I) (Lecture 10 (L4))
    with the cycle mean of ω equal to ``mean``; None where even the lowest level
    (the speed touching zero) has a larger mean: the machine stops within the cycle."""
    lowest = float(np.max(-work))

    def excess(T0):
        return cycle_mean(np.sqrt(np.maximum(2 * (T0 + work) / tables.J, 0.0)), tables.phi) - mean
    if excess(lowest) > 0:
        return None
    high = lowest + 0.5 * float(tables.J.max()) * (2 * mean) ** 2 + 1.0
    T0 = brentq(excess, lowest, high, xtol=1e-15 * high, rtol=1e-15)
    return np.sqrt(np.maximum(2 * (T0 + work) / tables.J, 0.0))


def successive_approximations(machine: Machine, tables: Tables, omega_operating: float, knee: float,
                              tol: float = 1e-8, compiled: bool = True) -> Approximations:
    """The steps of (§10.10) on the nodes of ``tables``, from the operating point's speed; ``knee``: the speed
    where the characteristic's stable branch begins (motor_characteristic.critical_speed); ``compiled``: by the
    compiled loop (the same steps to rounding) where it knows the machine's moments, else in numpy."""
    sync = machine.motor.omega_sync / machine.inertias.gear_ratio
    started = time.perf_counter()
    phi = tables.phi
    result = Approximations(phi)
    sliding = cycle_mean(tables.sliding, phi)
    J_mean = cycle_mean(tables.J, phi)
    slope = float(machine.speed_moment(omega_operating, sliding)[1])
    result.ratio = abs(slope) / (J_mean * omega_operating)
    limit = STEPS_MAX if result.ratio < 1 else SHOWN_DIVERGING
    if not (compiled and compiled_steps(machine, tables, omega_operating, knee, sync, tol, limit, result)):
        plain_steps(machine, tables, omega_operating, knee, sync, tol, limit, result)
    if result.ratio >= 1:
        result.notices.append(Notice("motor_approximations_diverge", f"The successive approximations diverge: ρ = "
                                     f"|k|/(Ī ω̄) = {result.ratio:.3g} ≥ 1 (the drive's time constant is shorter "
                                     "than one radian's time). Add inertia or take the joint solution.",
                                     {"ratio": result.ratio}))
    steps = len(result.rows)
    result.numerics = Numerics(
        method="successive approximations of Lecture 10 §10.10: the characteristic read along the previous law "
               "of motion, the energy equation by the trapezoid rule on the cycle's nodes",
        code="successive_approximations", rtol=tol, steps=int(phi.size - 1), iterations=steps,
        converged=result.converged, runtime_ms=1e3 * (time.perf_counter() - started),
        error_estimate=(result.rows[-1]["change"] * result.ratio / (1 - result.ratio)
                        if result.converged else None))
    if result.notices:
        result.numerics.tell(result.notices[-1])
    return result


def plain_steps(machine: Machine, tables: Tables, omega_operating: float, knee: float, sync: float, tol: float,
                limit: int, result: Approximations) -> None:
    """The steps in numpy, each root by scipy's brentq: the reference of the compiled loop, and the path of a
    machine whose moments it does not know."""
    phi = tables.phi

    def moment_at(omega):
        return machine.speed_moment(omega, tables.sliding)[0]

    def balance(omega):
        return cycle_mean(tables.net_phi + moment_at(omega), phi)

    omega = np.full_like(phi, omega_operating)
    for step in range(1, limit + 1):
        level = cycle_mean(omega, phi)      # the shift keeps the mean speed on the stable branch, knee to ω₁с
        low, high = knee - level, sync - level
        if balance(omega + low) * balance(omega + high) > 0:
            result.notices.append(no_balance(step))
            break
        shift = brentq(lambda c: balance(omega + c), low, high, xtol=1e-14 * omega_operating, rtol=1e-15)
        driving = moment_at(omega + shift)
        work = cumulative_trapezoid(tables.net_phi + driving, phi)
        new = energy_law(tables, work, cycle_mean(omega, phi) + shift)
        if new is None:
            result.notices.append(stops(step))
            break
        change = float(np.max(np.abs(new - omega)) / np.mean(new))
        w_max, w_min = float(new.max()), float(new.min())
        result.omega.append(new)
        result.moment.append(driving)
        result.rows.append(step_row(step, w_max, w_min, cycle_mean(driving, phi), change))
        omega = new
        if change < tol and step > 1:
            result.converged = True
            break


def step_row(step: int, w_max: float, w_min: float, moment_mean: float, change: float) -> dict:
    """A row of the steps' table: the law's ω_max, ω_min, their mean and δ, the mean driving moment and the
    largest change from the previous law (relative)."""
    return {"step": step, "omega_mean": 0.5 * (w_max + w_min), "omega_max": w_max, "omega_min": w_min,
            "delta": (w_max - w_min) / (0.5 * (w_max + w_min)), "moment_mean": moment_mean, "change": change}


def compiled_steps(machine: Machine, tables: Tables, omega_operating: float, knee: float, sync: float, tol: float,
                   limit: int, result: Approximations) -> bool:
    """The steps by the compiled loop (approximations_compiled.py); False (nothing done) where it does not know
    the machine's moments or a root search failed there (the plain loop then says why)."""
    speed, kind, params = speed_parameters(machine)
    if not speed:
        return False
    n = tables.phi.size
    laws, moments, rows = np.empty((limit, n)), np.empty((limit, n)), np.empty((limit, ROWS))
    arrays = [np.ascontiguousarray(a, dtype=float) for a in (tables.phi, tables.J, tables.net_phi, tables.sliding)]
    done, ending, step = approximation_steps(*arrays, kind, params,
                                             float(omega_operating), float(knee), float(sync), float(tol), limit,
                                             laws, moments, rows)
    if ending == ROOT_FAILED:
        return False
    result.omega = list(laws[:done])
    result.moment = list(moments[:done])
    result.rows = [step_row(k + 1, *map(float, rows[k])) for k in range(done)]
    result.converged = ending == CONVERGED
    if ending == NO_BALANCE:
        result.notices.append(no_balance(step))
    elif ending == STOPS:
        result.notices.append(stops(step))
    return True


def no_balance(step: int) -> Notice:
    return Notice("motor_approximation_no_balance", f"Step {step}: no mean speed balances the cycle's work on the "
                  "characteristic: the motor cannot carry the load.", {"step": step})


def stops(step: int) -> Notice:
    return Notice("motor_approximation_stops", f"Step {step}: the kinetic energy runs out within the cycle: the "
                  "machine stops.", {"step": step})
