"""Equation of motion of the machine: start-up transient and the steady periodic cycle.

Two paths, chosen by what the moments depend on (seed 000 §1.1):
- moments of φ alone: the energy integral (1.9)–(1.12), T = T₀ + ∫(M_д − M_c)dφ by Simpson's
  rule; ω = √(2T/J), t = ∫dφ/ω, ε = (M − ½J′ω²)/J.  A steady cycle exists only when the
  cycle work is zero, and then for any energy level: the caller gives the mean speed.
- moments that depend on ω (linear or induction motor, viscous friction): RK4 on
  dT/dφ = M(φ, ω) and the steady cycle found directly by Newton's method on the cycle map
  P(T₀) = T(φ₀ + Φ), P(T*) = T*, with P′ from the variational equation (shooting).
Accuracy: the step is halved until the Richardson estimate |ω_h − ω_h/2|/15 falls below
rtol·ω; that estimate is reported with the method, steps and run time.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import brentq

from ..mechanisms import Notice
from .integrator import RestBudget, Run, integrate
from .machine import Machine

STEPS_START = 32           # RK4 steps per 2π at the coarsest level
STEPS_MAX = 1 << 15        # per 2π: bounds the work of one request
NEWTON_MAX = 30
SUBSTEPS = 64              # sub-steps per step where extreme_speed integrates again around an extreme
MAX_CYCLES = 200


class NoMotion(Exception):
    """The machine has no motion of the kind asked for; ``notice`` says why in words."""

    def __init__(self, code: str, text: str, **context):
        super().__init__(text)
        self.notice = Notice(code, text, context)


@dataclass
class Numerics:
    """How the answer was computed, like scipy's OdeResult: method, tolerance, work, error."""

    method: str
    rtol: float
    code: str = ""                  # names the method for the interface's translations
    message_code: str = ""          # names a routine message (with message_context) for the same
    message_context: dict = field(default_factory=dict)
    steps: int = 0
    cycles: int = 0
    iterations: int = 0
    runtime_ms: float = 0.0
    error_estimate: float | None = 0.0
    energy_residual: float = 0.0
    message: str = ""

    def as_dict(self) -> dict:
        return dict(self.__dict__)


@dataclass
class Steady:
    """The steady periodic cycle: ω(φ), t(φ), ε(φ) and its figures of merit."""

    phi: np.ndarray
    omega: np.ndarray
    t: np.ndarray
    epsilon: np.ndarray
    omega_mean: float          # (ω_max + ω_min)/2, seed 004 (L3)
    omega_time_mean: float     # cycle angle / cycle time
    delta: float               # (ω_max − ω_min)/ω_mean
    efficiency: float          # |A_useful| / A_driving over the cycle, seed 002 (3.38)
    works: dict[str, float]


@dataclass
class Motion:
    steady: Steady | None = None
    transient: Run | None = None
    numerics: Numerics | None = None
    notices: list[Notice] = field(default_factory=list)


def blocked(tables) -> list[Notice]:
    """Why the machine cannot pass some angle: the notices of the tables, or the angles themselves."""
    if tables.notices:
        return list(tables.notices)
    where = np.degrees(tables.phi[~np.isfinite(tables.net_phi)])
    return [Notice("singular_position", f"The reduced moments are undefined at φ = {where[0]:.1f}° (a singular "
                   "position of the mechanism); the machine cannot pass it.", {"phi": float(where[0])})]


def node_tables(machine: Machine, steps: int, balance: bool = False):
    """φ-dependent tables on the step and half-step nodes of one cycle.

    balance: add the constant crank moment that makes the cycle work of the φ-dependent
    moments zero on these very nodes (the driven machine of a piston engine, M_c = A_д/Φ).
    """
    tables = machine.tables(np.linspace(0.0, machine.cycle(), 2 * steps + 1))
    if balance:   # Simpson on all nodes is the quadrature RK4 applies to moments of φ alone
        tables.balancing_moment = simpson(tables.net_phi, float(tables.phi[1] - tables.phi[0])) / machine.cycle()
        tables.useful = tables.useful + tables.balancing_moment
    return tables


def steps_per_cycle(machine: Machine, per_2pi: int) -> int:
    return int(per_2pi * round(machine.cycle() / (2 * np.pi)))


def mean_speed_balance(machine: Machine, tables) -> float | None:
    """ω̄ where the cycle-mean moment vanishes: a start for Newton, None when the motor cannot carry the load."""
    base = float(np.mean(tables.net_phi[:-1]))
    sliding = float(np.mean(tables.sliding[:-1]))
    def mean_moment(w):                   # w: a speed or an array of speeds
        return base + machine.speed_moment(w, sliding)[0]
    top = machine.motor.omega_sync / machine.inertias.gear_ratio if machine.motor.omega_sync else None
    if top is None:                       # linear motor: no-load speed M₀/b, or viscous only
        top = (machine.motor.M0 / machine.motor.b / machine.inertias.gear_ratio if machine.motor.b
               else 1e4)
    grid = np.linspace(top, 1e-9 * top, 400)   # from no-load speed down: the first root is the stable one
    values = mean_moment(grid).tolist()
    for a, b, va, vb in zip(grid[:-1], grid[1:], values[:-1], values[1:]):
        if va <= 0.0 <= vb or vb <= 0.0 <= va:
            return brentq(mean_moment, b, a, xtol=1e-12 * top)
    return None


def cycle_figures(machine: Machine, tables, run: Run, fine: dict | None = None) -> Steady:
    """δ, mean speeds, ε(φ) and the cycle works of the steady solution (``fine``: see extreme_speed)."""
    nodes = slice(0, None, 2)
    J, dJ = tables.J[nodes], tables.dJ[nodes]
    omega = run.omega
    moment = tables.net_phi[nodes] + machine.speed_moment(omega, tables.sliding[nodes])[0]
    epsilon = (moment - 0.5 * dJ * omega**2) / J
    h = float(run.phi[1] - run.phi[0])
    def work(values):
        return float(simpson(values, h))
    drive = tables.drive_phi[nodes] + (machine.speed_moment(omega, np.zeros_like(omega))[0]
                                       if machine.motor.speed_dependent else 0.0)
    viscous = machine.load.beta * omega * tables.sliding[nodes]
    works = {"driving": work(drive), "useful": work(tables.useful[nodes]), "dry_friction": work(tables.dry[nodes]),
             "viscous_friction": work(viscous)}
    works["net"] = works["driving"] - works["useful"] - works["dry_friction"] - works["viscous_friction"]
    k_max, k_min = int(np.argmax(omega)), int(np.argmin(omega))
    fine = {} if fine is None else fine
    sub_step_tables(machine, tables, run, (k_max, k_min), fine)
    w_max = extreme_speed(machine, tables, run, k_max, +1, fine=fine)
    w_min = extreme_speed(machine, tables, run, k_min, -1, fine=fine)
    mean = 0.5 * (w_max + w_min)
    return Steady(run.phi, omega, run.t - run.t[0], epsilon, mean, float((run.phi[-1] - run.phi[0]) / (run.t[-1] - run.t[0])),
                  (w_max - w_min) / mean, abs(works["useful"]) / works["driving"] if works["driving"] > 0 else 0.0,
                  works)


def sub_step_tables(machine: Machine, tables, run: Run, nodes, fine: dict, substeps: int = SUBSTEPS) -> None:
    """Put into ``fine`` the sub-step tables extreme_speed needs around each node k of ``nodes`` that it
    lacks, from one evaluation of the machine on all their angles (element for element the same values)."""
    last = run.phi.size - 1
    wanted = dict.fromkeys((max(k - 1, 0), min(k + 1, last)) for k in nodes)
    missing = [(a, b) for a, b in wanted if a != b and (a, b, substeps) not in fine]
    if not missing:
        return
    grids = [np.linspace(run.phi[a], run.phi[b], 2 * substeps * (b - a) + 1) for a, b in missing]
    joint = machine.tables(np.concatenate(grids))
    start = 0
    for (a, b), grid in zip(missing, grids):
        sub = joint.part(slice(start, start + grid.size))
        start += grid.size
        sub.useful = sub.useful + tables.balancing_moment
        sub.balancing_moment = tables.balancing_moment
        fine[a, b, substeps] = sub


def extreme_speed(machine: Machine, tables, run: Run, k: int, sign: int, substeps: int = SUBSTEPS,
                  fine: dict | None = None) -> float:
    """ω_max (sign +1) or ω_min (−1) between the step nodes around node k: the two steps are integrated
    again with ``substeps`` sub-steps each, and a parabola through the best fine node and its neighbours
    gives the extreme (error ~ (h/substeps)³ instead of the node spacing's h²).

    fine: the tables of the sub-steps already evaluated for these ``tables``, by node pair (a, b); the
    Newton iterations of _level and cycle_figures come back to the same steps with another T₀."""
    last = run.phi.size - 1
    a, b = max(k - 1, 0), min(k + 1, last)
    if a == b:
        return float(run.omega[k])
    fine = {} if fine is None else fine
    if (a, b, substeps) not in fine:
        sub = machine.tables(np.linspace(run.phi[a], run.phi[b], 2 * substeps * (b - a) + 1))
        sub.useful = sub.useful + tables.balancing_moment
        sub.balancing_moment = tables.balancing_moment
        fine[a, b, substeps] = sub
    values = integrate(machine, fine[a, b, substeps], float(run.T[a]), substeps * (b - a)).omega
    j = int(np.argmax(sign * values))
    if 0 < j < values.size - 1:
        left, mid, right = values[j - 1], values[j], values[j + 1]
        curvature = left - 2 * mid + right
        if curvature != 0:
            return float(mid - (right - left) ** 2 / (8 * curvature))
    return float(values[j])


def simpson(values: np.ndarray, h: float) -> float:
    """Composite Simpson over step nodes spaced h (an even number of intervals; trapezoid for the odd tail)."""
    n = values.size - 1
    even = n - n % 2
    total = h / 3 * (values[0] + values[even] + 4 * values[1:even:2].sum() + 2 * values[2:even:2].sum())
    return total + (0.5 * h * (values[even] + values[-1]) if n % 2 else 0.0)


def cumulative_simpson(values: np.ndarray, h: float) -> np.ndarray:
    """∫ from the first node to each step node; values on step and half-step nodes, step h."""
    pieces = h / 6 * (values[:-2:2] + 4 * values[1::2] + values[2::2])
    return np.concatenate([[0.0], np.cumsum(pieces)])


def steady_cycle(machine: Machine, rtol: float = 1e-8, omega_mean: float | None = None,
                 balance: bool = False, deadline: float = math.inf) -> Motion:
    """The periodic solution T(φ₀ + Φ) = T(φ₀), refined until the Richardson estimate meets rtol."""
    started = time.perf_counter()
    method = ("Newton shooting on the cycle map of dT/dφ = M(φ, ω), RK4 in φ" if machine.speed_dependent
              else "energy integral (1.9)–(1.10) by Simpson's rule, mean speed given")
    numerics = Numerics(method=method, rtol=rtol,
                        code="newton_shooting" if machine.speed_dependent else "energy_integral")
    motion = Motion(numerics=numerics)
    per_2pi, previous, T0 = STEPS_START, None, None
    while per_2pi <= STEPS_MAX:
        steps = steps_per_cycle(machine, per_2pi)
        tables = node_tables(machine, steps, balance)
        if not np.isfinite(tables.net_phi).all():
            motion.notices += blocked(tables)
            numerics.message = motion.notices[0].text
            break
        fine = {}                          # sub-step tables of extreme_speed on these nodes
        try:
            if machine.speed_dependent:
                run, T0 = _shoot(machine, tables, steps, T0, numerics)
            else:
                run = _level(machine, tables, steps, omega_mean, fine)
        except NoMotion as stop:
            motion.notices.append(stop.notice)
            numerics.message = stop.notice.text
            break
        numerics.steps = steps
        if previous is not None:
            numerics.error_estimate = float(np.max(np.abs(run.omega[::2] - previous.omega)) / 15 / run.omega.max())
            if numerics.error_estimate <= rtol:
                motion.steady = cycle_figures(machine, tables, run, fine)
                motion.steady.works["balancing_moment"] = tables.balancing_moment
                motion.transient = None
                numerics.energy_residual = abs(motion.steady.works["net"]) / max(motion.steady.works["driving"], 1e-300)
                break
        previous = run
        per_2pi *= 2
        if time.perf_counter() > deadline:
            motion.steady = cycle_figures(machine, tables, run, fine)
            if numerics.error_estimate == 0.0:
                numerics.error_estimate = None     # one level only: nothing to compare with
            numerics.message = (f"stopped at the time budget before reaching rtol = {rtol:g}; the result is the "
                                f"last refinement, with its error estimate")
            break
    else:
        numerics.message = f"the tolerance rtol = {rtol:g} was not reached within {STEPS_MAX} steps per revolution"
    numerics.runtime_ms = 1e3 * (time.perf_counter() - started)
    return motion


def _shoot(machine: Machine, tables, steps: int, T0: float | None, numerics: Numerics):
    """Newton on g(T₀) = T(Φ) − T₀ with g′ = S − 1 from the variational equation."""
    if T0 is None:
        omega = mean_speed_balance(machine, tables)
        if omega is None:
            raise NoMotion("stall_mean", "Stall: the mean resisting moment exceeds the largest mean moment the motor "
                                         "can give at any speed; the machine stops.")
        T0 = 0.5 * tables.J[0] * omega**2
    for _ in range(NEWTON_MAX):
        numerics.iterations += 1
        run = integrate(machine, tables, T0, steps)
        if run.stall_phi is not None:
            raise NoMotion("stall_in_cycle", f"Stall at φ = {np.degrees(run.stall_phi):.1f}°: the kinetic energy runs "
                                             "out within the cycle; there is no steady motion.",
                           phi=float(np.degrees(run.stall_phi)))
        step = (run.T[-1] - T0) / (run.sensitivity - 1.0)
        T0 = max(T0 - step, 0.25 * T0)
        if abs(step) <= 1e-13 * T0:
            return integrate(machine, tables, T0, steps), T0
    raise NoMotion("newton_failed", "Newton's method did not converge on the cycle map.")


def _level(machine: Machine, tables, steps: int, omega_mean: float | None, fine: dict | None = None):
    """φ-only moments: the energy level T₀ at φ₀ for which (ω_max + ω_min)/2 equals the given mean speed."""
    work = cumulative_simpson(tables.net_phi, float(tables.phi[2] - tables.phi[0]))   # A(φ) on the step nodes
    cycle_work = work[-1]
    driving = simpson(tables.drive_phi, float(tables.phi[1] - tables.phi[0]))
    if abs(cycle_work) > 1e-9 * max(abs(driving), 1.0):
        trend = "speeds up" if cycle_work > 0 else "slows down"
        raise NoMotion(f"no_steady_cycle_{trend.split()[0]}", f"No steady cycle: the work over a cycle is "
                       f"{cycle_work:.4g} J, not zero, so the machine {trend} every cycle.", work=cycle_work)
    if omega_mean is None:
        raise NoMotion("needs_mean_speed", "The moments depend on φ alone: every energy level is periodic; give the "
                                           "mean speed to choose one.")
    J = tables.J[::2]
    def mean_of(T0):
        omega = np.sqrt(2 * (T0 + work) / J)
        return 0.5 * (omega.max() + omega.min()) - omega_mean
    lowest = float(np.max(-work))                    # T₀ must keep T = T₀ + A > 0 everywhere
    high = lowest + 0.5 * J.max() * (2 * omega_mean) ** 2 + 1.0
    if mean_of(lowest + 1e-12 * high) > 0:           # even as ω_min → 0 the mean exceeds ω_m: no periodic motion
        stall = float(np.degrees(tables.phi[2 * int(np.argmin(work))]))
        raise NoMotion("stall_in_cycle", f"Stall at φ = {stall:.1f}°: the kinetic energy runs out within the cycle; "
                                         f"there is no steady motion at ω_m = {omega_mean:g} rad/s.", phi=stall)
    T0 = brentq(mean_of, lowest + 1e-12 * high, high, xtol=1e-14 * high)
    for _ in range(4):      # the same condition on the refined extremes: Newton with dω/dT₀ = 1/(Jω)
        run = integrate(machine, tables, T0, steps)
        k_max, k_min = int(np.argmax(run.omega)), int(np.argmin(run.omega))
        if fine is not None:
            sub_step_tables(machine, tables, run, (k_max, k_min), fine)
        w_max = extreme_speed(machine, tables, run, k_max, +1, fine=fine)
        w_min = extreme_speed(machine, tables, run, k_min, -1, fine=fine)
        slope = 0.5 * (1 / (J[k_max] * w_max) + 1 / (J[k_min] * w_min))
        correction = (omega_mean - 0.5 * (w_max + w_min)) / slope
        T0 += correction
        if abs(correction) <= 1e-14 * T0:
            break
    return integrate(machine, tables, T0, steps)


def startup(machine: Machine, omega0: float = 0.0, rtol: float = 1e-6, max_cycles: int = 60,
            balance: bool = False, deadline: float = math.inf) -> Motion:
    """From ω₀ at φ = 0 until the cycle-start energy settles (phase portrait spiralling onto the cycle)."""
    started = time.perf_counter()
    numerics = Numerics(method="RK4 in φ on dT/dφ = M(φ, ω) from the given start", rtol=rtol, code="startup_rk4")
    motion = Motion(numerics=numerics)
    steps = steps_per_cycle(machine, 256)
    tables = node_tables(machine, steps, balance)
    if not np.isfinite(tables.net_phi).all():
        motion.notices += blocked(tables)
        numerics.message = motion.notices[0].text
        return motion
    T0 = 0.5 * tables.J[0] * omega0**2
    if T0 == 0.0 and tables.net_phi[0] + machine.speed_moment(0.0, tables.sliding[0])[0] <= 0.0:
        notice = Notice("cannot_start", "The motor's starting torque does not overcome the resistance at φ = 0: "
                                        "the machine cannot start.")
        numerics.message = notice.text
        motion.notices.append(notice)
        return motion
    pieces, t0, cycle = [], 0.0, machine.cycle()
    for n in range(min(max_cycles, MAX_CYCLES)):
        try:
            run = integrate(machine, tables, T0, steps, t0)
        except RestBudget:                   # only the first cycle starts from rest: nothing to show yet
            notice = Notice("elastic_partial", "The start from rest stopped at the work bound: the motor's "
                                               "characteristic is too steep to follow in time; no start-up is shown.")
            numerics.message = notice.text
            motion.notices.append(notice)
            return motion
        run.phi = run.phi + n * cycle
        pieces.append(run)
        numerics.cycles = n + 1
        if run.stall_phi is not None:
            where = float(np.degrees(run.stall_phi + n * cycle))
            notice = Notice("stall_startup", f"Stall at φ = {where:.1f}°: the machine stops; the load exceeds what "
                                             "the motor gives.", {"phi": where})
            numerics.message = notice.text
            motion.notices.append(notice)
            break
        settled = abs(run.T[-1] - T0) <= rtol * run.T[-1]
        T0, t0 = run.T[-1], run.t[-1]
        if settled:
            numerics.message = f"settled after {n + 1} cycles"
            numerics.message_code, numerics.message_context = "settled", {"cycles": n + 1}
            break
        if time.perf_counter() > deadline:
            numerics.message = f"stopped at the time budget after {n + 1} cycles, not yet periodic"
            break
    else:
        numerics.message = f"not yet periodic after {numerics.cycles} cycles"
    motion.transient = Run(np.concatenate([p.phi for p in pieces]), np.concatenate([p.T for p in pieces]),
                           np.concatenate([p.omega for p in pieces]), np.concatenate([p.t for p in pieces]),
                           pieces[-1].sensitivity, pieces[-1].stall_phi)
    numerics.steps = steps * numerics.cycles
    numerics.error_estimate = _last_cycle_error(machine, pieces[-1], steps, balance)
    numerics.runtime_ms = 1e3 * (time.perf_counter() - started)
    return motion


def _last_cycle_error(machine: Machine, last: Run, steps: int, balance: bool) -> float | None:
    """Richardson estimate on the last cycle: rerun it with half the steps, |ω_h − ω_2h|/15 relative."""
    if last.stall_phi is not None or last.T[0] == 0.0:
        return None
    coarse = integrate(machine, node_tables(machine, steps // 2, balance), float(last.T[0]), steps // 2)
    return float(np.max(np.abs(coarse.omega - last.omega[::2])) / 15 / last.omega.max())
