"""Equation of motion of the machine: start-up transient and the steady periodic cycle.

Two paths, chosen by what the moments depend on (Eremyants §1.1):
- moments of φ alone: the energy integral (1.9)–(1.12), T = T₀ + ∫(M_д − M_c)dφ by Simpson's
  rule; ω = √(2T/J), t = ∫dφ/ω, ε = (M − ½J′ω²)/J.  A steady cycle exists only when the
  cycle work is zero, and then for any energy level: the caller gives the mean speed.
- moments that depend on ω (linear or induction motor, viscous friction): RK4 on
  dT/dφ = M(φ, ω) and the steady cycle found directly by Newton's method on the cycle map
  P(T₀) = T(φ₀ + Φ), P(T*) = T*, with P′ from the variational equation (shooting).
Accuracy: every kink of the moments is a node (machine.kinks, integrator.kinked_tables), so RK4 keeps its
fourth order on every step; the step is halved until the Richardson estimate of the error of ω(φ) and
t(φ) falls below rtol, with the factor 1/(2^p − 1) of the order p the last three levels show (never less
than fourth order's 1/15). That estimate is reported with the method, steps and run time; the start-up
reports the same estimate for the whole run.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import brentq

from ..mechanisms import Notice
from ..numerics import Numerics, simpson
from .integrator import REST_STEPS, RestBudget, Run, cycles, integrate, kinked_tables
from .machine import Machine, Tables

STEPS_START = 32           # RK4 steps per 2π at the coarsest level
STEPS_MAX = 1 << 15        # per 2π: bounds the work of one request
NEWTON_MAX = 30
SUBSTEPS = 64              # sub-steps per step where extreme_speed integrates again around an extreme
MAX_CYCLES = 200
SHOOTING_STEP = 1e-13      # the shooting's Newton stops at a step this fraction of T₀ (exact answers)
PREVIEW_SHOOTING = 1e-4    # … and a preview's at this fraction of its preview tolerance (T ∝ ω²: far below)
STARTUP_PER_2PI = 256      # RK4 steps per 2π of the start-up, halved until its estimate meets rtol …
STARTUP_MAX_PER_2PI = 4096  # … down to this
FASTEST_FALL = 32          # a start-up level skipped only if even this fall per halving (RK4's is 16) leaves it above rtol
CYCLES_AT_ONCE = 8         # start-up cycles run by one call of the compiled loop (the deadline is checked after each)


class Unresolved(Exception):
    """A level's steps are too long for the motion it follows (see _level); the next level is tried."""


class NoMotion(Exception):
    """The machine has no motion of the kind asked for; ``notice`` says why in words."""

    def __init__(self, code: str, text: str, **context):
        super().__init__(text)
        self.notice = Notice(code, text, context)


@dataclass
class Steady:
    """The steady periodic cycle: ω(φ), t(φ), ε(φ) and its figures of merit."""

    phi: np.ndarray
    omega: np.ndarray
    t: np.ndarray
    epsilon: np.ndarray
    omega_mean: float          # (ω_max + ω_min)/2, Lecture 10 (L3)
    omega_time_mean: float     # cycle angle / cycle time
    delta: float               # (ω_max − ω_min)/ω_mean
    efficiency: float | None   # A_useful/(A_useful + A_losses) over the cycle, Chaika–Vasylenko (3.38); see efficiency()
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
    """φ-dependent tables on the uniform step and half-step nodes of one cycle (the flywheel's grid).

    balance: add the constant crank moment that makes the cycle work of the φ-dependent
    moments zero on these very nodes (the driven machine of a piston engine, M_c = A_д/Φ).
    Made once per machine, steps and balance (machine.memo: members of a family sharing one machine, the
    flywheel's error estimate); no caller changes a Tables once made.
    """
    key = ("node_tables", steps, balance)
    if key not in machine.memo:
        machine.memo[key] = _node_tables(machine, steps, balance)
    return machine.memo[key]


def _node_tables(machine: Machine, steps: int, balance: bool) -> Tables:
    tables = machine.tables(np.linspace(0.0, machine.cycle(), 2 * steps + 1))
    if balance:   # Simpson on all nodes is the quadrature RK4 applies to moments of φ alone
        tables.balancing_moment = simpson(tables.net_phi, float(tables.phi[1] - tables.phi[0])) / machine.cycle()
        tables.useful = tables.useful + tables.balancing_moment
    return tables


def cycle_tables(machine: Machine, kinks: np.ndarray, per_2pi: int, balance: bool = False) -> Tables:
    """φ-dependent tables of one cycle with every kink on a node: between consecutive kinks (and the cycle's
    ends) an even number of uniform steps, about per_2pi per 2π. The counts of a level are those of
    STEPS_START times per_2pi/STEPS_START, so each level's nodes are every other node of the next (Richardson).
    Made once per machine and level (the steady cycle, the start-up and their estimates share levels); no
    caller changes a Tables once made.

    balance: add the constant crank moment that makes the cycle work of the φ-dependent moments zero with
    the quadrature RK4 applies to them on these nodes (the driven machine of a piston engine, M_c = A_д/Φ)."""
    key = ("cycle_tables", kinks.tobytes(), per_2pi, balance)
    if key not in machine.memo:
        machine.memo[key] = _cycle_tables(machine, kinks, per_2pi, balance)
    return machine.memo[key]


def _cycle_tables(machine: Machine, kinks: np.ndarray, per_2pi: int, balance: bool) -> Tables:
    cycle = machine.cycle()
    edges = np.concatenate([[0.0], kinks[kinks > 0], [cycle]])
    base = steps_per_cycle(machine, STEPS_START)
    counts = 2 * np.maximum(1, np.ceil(np.diff(edges) * base / (2 * cycle) - 1e-9)).astype(int)
    closed = bool(kinks.size) and kinks[0] == 0.0
    sided = np.concatenate([[closed], np.ones(edges.size - 2, bool), [closed]])
    tables = kinked_tables(machine, edges, counts * max(1, per_2pi // STEPS_START), sided)
    if balance:
        tables.balancing_moment = float(step_integral(tables, tables.net_phi)[-1]) / cycle
        tables.useful = tables.useful + tables.balancing_moment
    return tables


def step_integral(tables: Tables, values: np.ndarray) -> np.ndarray:
    """∫ values dφ from the first node to each step node, by Simpson's rule on each step's three nodes: the
    quadrature RK4 applies to a right-hand side of φ alone (Eremyants (1.9))."""
    start = tables.step_nodes[:-1]
    h = tables.phi[start + 2] - tables.phi[start]
    return np.concatenate([[0.0], np.cumsum(h / 6 * (values[start] + 4 * values[start + 1] + values[start + 2]))])


def pair_simpson(values: np.ndarray, phi: np.ndarray) -> float:
    """∫ values dφ over step nodes phi by Simpson's rule on consecutive pairs of steps (three-point rule for
    unequal steps; a trapezoid for an odd last step). cycle_tables' segments have even counts, so no pair
    straddles a kink."""
    n = values.size - 1
    i = np.arange(0, n - n % 2, 2)
    h0, h1 = phi[i + 1] - phi[i], phi[i + 2] - phi[i + 1]
    f0, f1, f2 = values[i], values[i + 1], values[i + 2]
    total = float(np.sum((h0 + h1) / 6 * ((2 - h1 / h0) * f0 + (h0 + h1) ** 2 / (h0 * h1) * f1 + (2 - h0 / h1) * f2)))
    return total + (0.5 * float(phi[-1] - phi[-2]) * float(values[-2] + values[-1]) if n % 2 else 0.0)


def steps_per_cycle(machine: Machine, per_2pi: int) -> int:
    return int(per_2pi * round(machine.cycle() / (2 * np.pi)))


def mean_speed_balance(machine: Machine, tables: Tables) -> float | None:
    """ω̄ where the cycle-mean moment vanishes: a start for Newton, None when the motor cannot carry the load.
    Searched from twice the no-load speed down: where the static moments' mean does not resist (no useful load,
    the weights' mean zero up to round-off, or loads that drive), the balance lies at or above the no-load speed,
    where the motor brakes; the first root met going down is the stable one."""
    cycle = float(tables.phi[-1] - tables.phi[0])
    base = float(step_integral(tables, tables.net_phi)[-1]) / cycle
    sliding = float(step_integral(tables, tables.sliding)[-1]) / cycle
    def mean_moment(w):                   # w: a speed or an array of speeds
        return base + machine.speed_moment(w, sliding)[0]
    top = machine.motor.omega_sync / machine.inertias.gear_ratio if machine.motor.omega_sync else None
    if top is None:                       # linear motor: no-load speed M₀/b, or viscous only
        top = (machine.motor.M0 / machine.motor.b / machine.inertias.gear_ratio if machine.motor.b
               else 1e4)
    grid = np.linspace(2 * top, 1e-9 * top, 800)
    values = mean_moment(grid).tolist()
    for a, b, va, vb in zip(grid[:-1], grid[1:], values[:-1], values[1:]):
        if va <= 0.0 <= vb or vb <= 0.0 <= va:
            return brentq(mean_moment, b, a, xtol=1e-12 * top)
    return None


def efficiency(machine: Machine, works: dict[str, float]) -> float | None:
    """η = A_useful/A_driving over the steady cycle (Chaika–Vasylenko (3.38)), with A_driving = A_useful + A_losses:
    over a periodic cycle the kinetic energy returns to its value, so the driving work is the useful work
    plus the work of friction (the quadrature's difference from the driving work integrated directly is
    the reported energy residual). Without friction (f = 0, β = 0) the losses are zero and η = 1 exactly,
    by construction; with friction the losses are ≥ 0 and η ≤ 1. None where η has no meaning: a useful
    work below zero (a balancing moment that drives) or losses below zero (the textbook's printed formulas,
    with which friction helps on the return stroke)."""
    if machine.lossless:
        return 1.0
    losses = works["dry_friction"] + works["viscous_friction"]
    if works["useful"] < 0 or losses < 0:
        return None
    return works["useful"] / (works["useful"] + losses) if works["useful"] + losses > 0 else 1.0


def no_efficiency(steady: Steady) -> list[Notice]:
    """Why η is not given, in words (none when it is)."""
    if steady.efficiency is not None:
        return []
    useful, losses = steady.works["useful"], steady.works["dry_friction"] + steady.works["viscous_friction"]
    return [Notice("efficiency_undefined", f"η is not given: over the cycle the useful work is {useful:.4g} J and the "
                   f"work of friction {losses:.4g} J; with one of them below zero (the textbook's printed formulas let "
                   "friction help the crank on the return stroke; a balancing moment can drive) their ratio is no "
                   "efficiency.", {"useful": useful, "losses": losses})]


def energy_residual(works: dict[str, float]) -> float:
    """|A_driving − A_useful − A_losses| over the sum of their magnitudes (≤ 1; 0 when nothing does work)."""
    turnover = abs(works["driving"]) + abs(works["useful"]) + abs(works["dry_friction"]) + abs(works["viscous_friction"])
    return abs(works["net"]) / turnover if turnover > 0 else 0.0


def cycle_figures(machine: Machine, tables: Tables, run: Run, fine: dict | None = None) -> Steady:
    """δ, mean speeds, ε(φ) and the cycle works of the steady solution (``fine``: see extreme_speed)."""
    nodes = tables.step_nodes
    omega = run.omega
    J, dJ = tables.J[nodes], tables.dJ[nodes]
    moment = tables.net_phi[nodes] + machine.speed_moment(omega, tables.sliding[nodes])[0]
    epsilon = (moment - 0.5 * dJ * omega**2) / J
    def work(values):
        return pair_simpson(values, run.phi)
    drive = tables.drive_phi[nodes] + (machine.speed_moment(omega, np.zeros_like(omega))[0]
                                       if machine.motor.speed_dependent else 0.0)
    viscous = machine.load.beta * omega * tables.sliding[nodes]
    def work_phi(values):          # a moment of φ alone, each step's own three nodes: a jump at a kink is kept
        return float(step_integral(tables, values)[-1])
    works = {"driving": work(drive) if machine.motor.speed_dependent else work_phi(tables.drive_phi),
             "useful": work_phi(tables.useful), "dry_friction": work_phi(tables.dry), "viscous_friction": work(viscous)}
    works["net"] = works["driving"] - works["useful"] - works["dry_friction"] - works["viscous_friction"]
    k_max, k_min = int(np.argmax(omega)), int(np.argmin(omega))
    fine = {} if fine is None else fine
    w_max = extreme_speed(machine, tables, run, k_max, +1, fine=fine)
    w_min = extreme_speed(machine, tables, run, k_min, -1, fine=fine)
    mean = 0.5 * (w_max + w_min)
    return Steady(run.phi, omega, run.t - run.t[0], epsilon, mean, float((run.phi[-1] - run.phi[0]) / (run.t[-1] - run.t[0])),
                  (w_max - w_min) / mean, efficiency(machine, works), works)


def extreme_speed(machine: Machine, tables: Tables, run: Run, k: int, sign: int, substeps: int = SUBSTEPS,
                  fine: dict | None = None) -> float:
    """ω_max (sign +1) or ω_min (−1) between the step nodes around node k: the two steps are integrated
    again with ``substeps`` sub-steps each, and a parabola through the best fine node and its neighbours
    gives the extreme (error ~ (h/substeps)³ instead of the node spacing's h²). A kink on node k stays a
    node of the sub-steps, and an extreme on it (ω with a corner) is that node's value, no parabola.

    fine: the sub-step tables already evaluated for these ``tables``, by node pair (a, b); the Newton
    iterations of _level and cycle_figures come back to the same steps with another T₀."""
    last = run.phi.size - 1
    a, b = max(k - 1, 0), min(k + 1, last)
    if a == b:
        return float(run.omega[k])
    kinked = tables.kink_nodes if tables.kink_nodes is not None else np.zeros(last + 1, bool)
    fine = {} if fine is None else fine
    if (a, b, substeps) not in fine:
        pieces = [a, k, b] if kinked[k] and a < k < b else [a, b]
        edges = run.phi[pieces]
        sub = kinked_tables(machine, edges, substeps * np.diff(pieces), kinked[pieces])
        sub.useful = sub.useful + tables.balancing_moment
        sub.balancing_moment = tables.balancing_moment
        fine[a, b, substeps] = sub
    sub = fine[a, b, substeps]
    values = integrate(machine, sub, float(run.T[a]), substeps * (b - a)).omega
    j = int(np.argmax(sign * values))
    if 0 < j < values.size - 1 and not (kinked[k] and j == substeps * (k - a)):
        left, mid, right = values[j - 1], values[j], values[j + 1]
        curvature = left - 2 * mid + right
        if curvature != 0:
            return float(mid - (right - left) ** 2 / (8 * curvature))
    return float(values[j])


def richardson(differences: list[float]) -> float:
    """The error of the finer of the last two levels from the largest differences between successive levels,
    d_n = max|y_h − y_2h|: d_n/(2^p − 1) with 2^p = d_{n−1}/d_n the order the levels show, taken between
    2 (first order) and 16 (RK4's fourth: never a smaller estimate than d_n/15)."""
    ratio = differences[-2] / differences[-1] if len(differences) > 1 and differences[-1] > 0 else 16.0
    return differences[-1] / (min(max(ratio, 2.0), 16.0) - 1.0)


def level_difference(fine: Run, coarse: Run) -> float:
    """max over the coarse nodes of |ω_h − ω_2h|/ω_max and |t_h − t_2h|/t_end (t from the run's start)."""
    omega = np.max(np.abs(fine.omega[::2] - coarse.omega)) / fine.omega.max()
    span = fine.t[-1] - fine.t[0]
    t = np.max(np.abs((fine.t[::2] - fine.t[0]) - (coarse.t - coarse.t[0]))) / span if span > 0 else 0.0
    return float(max(omega, t))


def steady_cycle(machine: Machine, rtol: float = 1e-8, omega_mean: float | None = None,
                 balance: bool = False, deadline: float = math.inf, preview: float | None = None) -> Motion:
    """The periodic solution T(φ₀ + Φ) = T(φ₀), refined until the Richardson estimate meets rtol: the
    estimate (``richardson``) of three levels at least, so that the order they show is known.

    ``preview`` (a family member drawn only while a slider moves, never read as a number): the shooting's
    Newton stops at PREVIEW_SHOOTING × preview of T₀ (None: the exact answer, bit for bit as without it). The
    levels stay the exact answer's: a member at a coarser level than its neighbours' is interpolated node by
    node with them, and where the kinks move with the slider, node k is another angle in each member; the
    family's estimate does not see that (bench/family_grid_check.py: previews at coarser levels put 3 more of
    the scene's 33 families off by 0.9–4.4 % of a span where they claimed 0.1 %)."""
    started = time.perf_counter()
    method = ("Newton shooting on the cycle map of dT/dφ = M(φ, ω), RK4 in φ" if machine.speed_dependent
              else "energy integral (1.9)–(1.10) by Simpson's rule, mean speed given")
    numerics = Numerics(method=method, rtol=rtol,
                        code="newton_shooting" if machine.speed_dependent else "energy_integral")
    motion = Motion(numerics=numerics)
    kinks = machine.kinks()
    per_2pi, previous, T0, differences = STEPS_START, None, None, []
    while per_2pi <= STEPS_MAX:
        tables = cycle_tables(machine, kinks, per_2pi, balance)
        steps = tables.starts.size
        if not np.isfinite(tables.net_phi).all():
            motion.notices += blocked(tables)
            numerics.tell(motion.notices[0])
            break
        fine = {}                          # sub-step tables of extreme_speed on these nodes
        try:
            if machine.speed_dependent:
                run, T0 = _shoot(machine, tables, steps, T0, numerics,
                                 SHOOTING_STEP if preview is None else max(SHOOTING_STEP, PREVIEW_SHOOTING * preview))
            else:
                run = _level(machine, tables, steps, omega_mean, fine)
        except NoMotion as stop:
            motion.notices.append(stop.notice)
            numerics.tell(stop.notice)
            break
        except Unresolved:              # the levels' differences start again from the next, finer one
            previous, differences = None, []
            per_2pi *= 2
            continue
        numerics.steps = steps
        if previous is not None:
            differences.append(level_difference(run, previous))
            numerics.error_estimate = richardson(differences)
            if len(differences) > 1 and numerics.error_estimate <= rtol:
                motion.steady = cycle_figures(machine, tables, run, fine)
                motion.steady.works["balancing_moment"] = tables.balancing_moment
                motion.transient = None
                numerics.energy_residual = energy_residual(motion.steady.works)
                motion.notices += no_efficiency(motion.steady)
                break
        previous = run
        per_2pi *= 2
        if time.perf_counter() > deadline:
            motion.steady = cycle_figures(machine, tables, run, fine)   # one level only: no estimate (None)
            numerics.energy_residual = energy_residual(motion.steady.works)
            motion.notices += no_efficiency(motion.steady)
            numerics.message = (f"stopped at the time budget before reaching rtol = {rtol:g}; the result is the "
                                f"last refinement, with its error estimate")
            break
    else:
        numerics.message = f"the tolerance rtol = {rtol:g} was not reached within {STEPS_MAX} steps per revolution"
    if motion.steady is None:
        numerics.error_estimate = None              # no result, nothing estimated
    numerics.runtime_ms = 1e3 * (time.perf_counter() - started)
    return motion


def _shoot(machine: Machine, tables: Tables, steps: int, T0: float | None, numerics: Numerics,
           tolerance: float = 1e-13):
    """Newton on g(T₀) = T(Φ) − T₀ with g′ = S − 1 from the variational equation, until a step is below
    ``tolerance`` × T₀ (quadratic convergence: the next step's error is far below that)."""
    if T0 is None:
        omega = mean_speed_balance(machine, tables)
        if omega is None:
            raise NoMotion("stall_mean", "Stall: the mean resisting moment exceeds the largest mean moment the motor "
                                         "can give at any speed; the machine stops.")
        T0 = 0.5 * tables.J[0] * omega**2
    for _ in range(NEWTON_MAX):
        numerics.iterations = (numerics.iterations or 0) + 1
        run = integrate(machine, tables, T0, steps)
        if run.stall_phi is not None:
            raise NoMotion("stall_in_cycle", f"Stall at φ = {np.degrees(run.stall_phi):.1f}°: the kinetic energy runs "
                                             "out within the cycle; there is no steady motion.",
                           phi=float(np.degrees(run.stall_phi)))
        slope = run.sensitivity - 1.0
        step = (run.T[-1] - T0) / slope if slope != 0.0 else math.copysign(math.inf, T0 - run.T[-1])
        T0 = min(max(T0 - step, 0.25 * T0), 4.0 * T0)      # a step by a factor 4 at most either way
        if abs(step) <= tolerance * T0:
            return integrate(machine, tables, T0, steps), T0
    raise NoMotion("newton_failed", "Newton's method did not converge on the cycle map.")


def _level(machine: Machine, tables: Tables, steps: int, omega_mean: float | None, fine: dict | None = None):
    """φ-only moments: the energy level T₀ at φ₀ for which (ω_max + ω_min)/2 equals the given mean speed."""
    work = step_integral(tables, tables.net_phi)       # A(φ) on the step nodes
    cycle_work = work[-1]
    driving = step_integral(tables, tables.drive_phi)[-1]
    if abs(cycle_work) > 1e-9 * max(abs(driving), 1.0):
        trend = "speeds up" if cycle_work > 0 else "slows down"
        raise NoMotion(f"no_steady_cycle_{trend.split()[0]}", f"No steady cycle: the work over a cycle is "
                       f"{cycle_work:.4g} J, not zero, so the machine {trend} every cycle.", work=cycle_work)
    if omega_mean is None:
        raise NoMotion("needs_mean_speed", "The moments depend on φ alone: every energy level is periodic; give the "
                                           "mean speed to choose one.")
    nodes = tables.step_nodes
    J = tables.J[nodes]
    def mean_of(T0):
        omega = np.sqrt(2 * (T0 + work) / J)
        return 0.5 * (omega.max() + omega.min()) - omega_mean
    def stall(phi: float) -> NoMotion:
        at = float(np.degrees(phi))
        return NoMotion("stall_in_cycle", f"Stall at φ = {at:.1f}°: the kinetic energy runs out within the cycle; "
                                          f"there is no steady motion at ω_m = {omega_mean:g} rad/s.", phi=at)

    def run_from(T0: float) -> Run:
        """The run over the cycle. One whose energy runs out inside a step, where the nodes' A(φ) kept T₀ + A above
        zero, is a step too long for the slowest point of the cycle (an RK4 stage overshooting the dip), not a
        stall: the next level decides, and at STEPS_MAX it is the stall."""
        run = integrate(machine, tables, T0, steps)
        if run.stall_phi is not None:
            raise (stall(run.stall_phi) if 2 * steps > STEPS_MAX else Unresolved())
        return run
    lowest = float(np.max(-work))                    # T₀ must keep T = T₀ + A > 0 everywhere
    high = lowest + 0.5 * J.max() * (2 * omega_mean) ** 2 + 1.0
    if mean_of(lowest + 1e-12 * high) > 0:           # even as ω_min → 0 the mean exceeds ω_m: no periodic motion
        raise stall(tables.phi[nodes[int(np.argmin(work))]])
    T0 = brentq(mean_of, lowest + 1e-12 * high, high, xtol=1e-14 * high)
    for _ in range(4):      # the same condition on the refined extremes: Newton with dω/dT₀ = 1/(Jω)
        run = run_from(T0)
        k_max, k_min = int(np.argmax(run.omega)), int(np.argmin(run.omega))
        w_max = extreme_speed(machine, tables, run, k_max, +1, fine=fine)
        w_min = extreme_speed(machine, tables, run, k_min, -1, fine=fine)
        slope = 0.5 * (1 / (J[k_max] * w_max) + 1 / (J[k_min] * w_min))
        correction = (omega_mean - 0.5 * (w_max + w_min)) / slope
        T0 += correction
        if abs(correction) <= 1e-14 * T0:
            break
    return run_from(T0)


def startup(machine: Machine, omega0: float = 0.0, rtol: float = 1e-6, max_cycles: int = 60,
            balance: bool = False, deadline: float = math.inf) -> Motion:
    """From ω₀ at φ = 0 until the cycle-start energy settles to rtol (phase portrait spiralling onto the cycle);
    the error estimate covers the whole run (``startup_error``), and the step is halved until it meets rtol
    (rtol = 0: never settles, one run of max_cycles at STARTUP_PER_2PI)."""
    started = time.perf_counter()
    numerics = Numerics(method="RK4 in φ on dT/dφ = M(φ, ω) from the given start", rtol=rtol, code="startup_rk4")
    motion = Motion(numerics=numerics)
    kinks = machine.kinks()
    tables = cycle_tables(machine, kinks, STARTUP_PER_2PI, balance)
    if not np.isfinite(tables.net_phi).all():
        motion.notices += blocked(tables)
        numerics.tell(motion.notices[0])
        return motion
    T0 = 0.5 * tables.J[0] * omega0**2
    if T0 == 0.0 and tables.net_phi[0] + machine.speed_moment(0.0, tables.sliding[0])[0] <= 0.0:
        notice = Notice("cannot_start", "The motor's starting torque does not overcome the resistance at φ = 0: "
                                        "the machine cannot start.")
        numerics.tell(notice)
        motion.notices.append(notice)
        return motion
    per_2pi, done = STARTUP_PER_2PI, None
    bound_stopped = False          # a time or work bound stopped a finer level (else: met rtol, or the finest)
    while True:                    # halve the step until the estimate meets rtol (rtol = 0: one fixed run)
        try:
            pieces, settled = _cycles(machine, tables, T0, max_cycles, rtol, deadline)
        except RestBudget:
            if done is None:       # only the first cycle starts from rest: nothing to show yet
                notice = Notice("elastic_partial", "The start from rest stopped at the work bound: the motor's "
                                                   "characteristic is too steep to follow in time; no start-up is shown.")
                numerics.tell(notice)
                motion.notices.append(notice)
                return motion
            bound_stopped = True
            break
        done = pieces, settled, startup_error(machine, kinks, pieces, balance, per_2pi), per_2pi
        estimate = done[2]
        if rtol <= 0 or estimate is None or estimate <= rtol or 2 * per_2pi > STARTUP_MAX_PER_2PI:
            break
        if time.perf_counter() > deadline:
            bound_stopped = True
            break
        per_2pi = next_level(per_2pi, estimate, rtol)
        tables = cycle_tables(machine, kinks, per_2pi, balance)
    pieces, settled, estimate, per_2pi = done
    numerics.cycles = len(pieces)
    if pieces[-1].stall_phi is not None:
        where = float(np.degrees(pieces[-1].stall_phi))
        notice = Notice("stall_startup_from", f"Stall at φ = {where:.1f}° on the start-up from ω₀ = {omega0:g} rad/s: "
                        "started this way, the machine comes to rest because the load takes more work than the motor "
                        "gives. This concerns the start-up only: a steady cycle, if one is shown, is the motion of the "
                        "machine once it runs.", {"phi": where, "omega0": float(omega0)})
        numerics.message, numerics.message_code, numerics.message_context = notice.text, notice.code, notice.context
        motion.notices.append(notice)
    elif settled:
        numerics.message = f"settled after {len(pieces)} cycles"
        numerics.message_code, numerics.message_context = "settled", {"cycles": len(pieces)}
    elif len(pieces) < min(max_cycles, MAX_CYCLES):
        numerics.message = f"stopped at the time budget after {len(pieces)} cycles, not yet periodic"
        numerics.message_code, numerics.message_context = "startup_time_budget", {"cycles": len(pieces)}
    else:
        numerics.message = f"not yet periodic after {len(pieces)} cycles"
        numerics.message_code, numerics.message_context = "startup_not_periodic", {"cycles": len(pieces)}
    motion.transient = Run(np.concatenate([p.phi for p in pieces]), np.concatenate([p.T for p in pieces]),
                           np.concatenate([p.omega for p in pieces]), np.concatenate([p.t for p in pieces]),
                           pieces[-1].sensitivity, pieces[-1].stall_phi)
    numerics.steps = sum(p.phi.size - 1 for p in pieces)
    numerics.error_estimate = estimate
    if rtol > 0 and estimate is not None and estimate > rtol:
        above_rtol(numerics, estimate, per_2pi, bound_stopped)
    numerics.runtime_ms = 1e3 * (time.perf_counter() - started)
    return motion


def next_level(per_2pi: int, estimate: float, rtol: float) -> int:
    """The start-up's next level: the step halved, and halved again past every level whose estimate could not
    meet rtol even if it fell by FASTEST_FALL per halving (fourth order falls by 2⁴ = 16; a Richardson estimate
    seen falling faster than 32× is pre-asymptotic), never past STARTUP_MAX_PER_2PI. A skipped level is one the
    halving would have run and left, so the answer is that of the level the halving would end at, with less work:
    e.g. the linear motor with b = 0.05 and rtol 10⁻⁸ falls 2.5–4.5× per level, 256 → 4096 at once."""
    while 2 * per_2pi < STARTUP_MAX_PER_2PI and estimate / FASTEST_FALL > rtol:
        per_2pi, estimate = 2 * per_2pi, estimate / FASTEST_FALL
    return 2 * per_2pi


def above_rtol(numerics: Numerics, estimate: float, per_2pi: int, bound_stopped: bool) -> None:
    """The start-up's message ends with its estimate above rtol and why no finer level was run: the finest level
    (STARTUP_MAX_PER_2PI, a result in full) or a time or work bound that stopped the next one (a partial result,
    as its words say: server/api/answering.py reads them). A start-up stopped at the time budget within its
    cycles says so already."""
    rtol = numerics.rtol
    numerics.message += f"; the error estimate {estimate:.2g} is above rtol = {rtol:g} at {per_2pi} steps per 2π"
    code = f"{numerics.message_code}_above_rtol"
    if numerics.message_code != "startup_time_budget":
        numerics.message += (" (a finer level was stopped by the time budget or the work bound)" if bound_stopped
                             else " (the finest level)")
        code += "_bound" if bound_stopped else ""
    numerics.message_code = code
    numerics.message_context = {**numerics.message_context, "estimate": estimate, "rtol": rtol,
                                "per_2pi": per_2pi}


def _cycles(machine: Machine, tables: Tables, T0: float, max_cycles: int, rtol: float | None,
            deadline: float = math.inf, first: int = 0, t0: float = 0.0) -> tuple[list[Run], bool]:
    """Cycle after cycle from T₀, t₀ at step node ``first`` of the first cycle until a stall, the cycle-start
    energy settling to rtol (None: run all max_cycles), max_cycles or the deadline; the runs with φ and t
    continued, and whether it settled."""
    pieces, cycle, steps, total = [], machine.cycle(), tables.starts.size, min(max_cycles, MAX_CYCLES)
    ahead: list[Run] = []                  # cycles run already (integrator.cycles: CYCLES_AT_ONCE at a time)
    for n in range(total):
        if n == 0:                         # from rest, or from node ``first``
            run = integrate(machine, tables, T0, steps, t0, first=first)
        else:
            if not ahead:
                ahead = cycles(machine, tables, T0, t0, steps, min(CYCLES_AT_ONCE, total - n), rtol)
            run = ahead.pop(0)
        run.phi = run.phi + n * cycle
        if run.stall_phi is not None:
            run.stall_phi += n * cycle
        pieces.append(run)
        if run.stall_phi is not None:
            break
        settled = rtol is not None and abs(run.T[-1] - run.T[0]) <= rtol * run.T[-1]
        T0, t0 = run.T[-1], run.t[-1]
        if settled:
            return pieces, True
        if time.perf_counter() > deadline:
            break
    return pieces, False


def startup_error(machine: Machine, kinks: np.ndarray, pieces: list[Run], balance: bool, per_2pi: int) -> float | None:
    """Richardson estimate of the whole start-up: the same run over as many cycles with half and a quarter of
    the steps, and ``richardson`` of the largest differences at the shared nodes (ω relative to its largest
    value, t to the run's duration). A start from rest is shared: the coarser runs start where its DOP853
    steps end (integrator.leave_rest, at rtol 1e-11), so the estimate covers every RK4 step. None when there
    is no RK4 step, or the run stalls: towards the stop ω ∝ √(φ_s − φ) is not smooth in φ and no estimate of
    a fixed order holds there (the stall's angle is the answer then)."""
    first = REST_STEPS if pieces[0].T[0] == 0.0 else 0
    if pieces[-1].stall_phi is not None or (pieces[0].T.size <= first + 1 and len(pieces) == 1):
        return None
    levels = [(pieces, 0)]
    for factor in (2, 4):
        try:
            tables = cycle_tables(machine, kinks, per_2pi // factor, balance)
            levels.append((_cycles(machine, tables, float(pieces[0].T[first]), len(pieces), None,
                                   first=first // factor, t0=float(pieces[0].t[first]))[0], first // factor))
        except RestBudget:
            return None
    omega_max = max(float(p.omega.max()) for p in pieces)
    duration = pieces[-1].t[-1] - pieces[0].t[0]
    differences = []
    for (coarse, c_first), (fine, f_first) in ((levels[2], levels[1]), (levels[1], levels[0])):
        reach = coarse[-1].phi[-1] + 2 * np.max(np.diff(coarse[-1].phi), initial=0.0)
        if len(coarse) < len(fine) or reach < fine[-1].phi[-1]:
            return None
        omega, t = 0.0, 0.0
        for n, (c, f) in enumerate(zip(coarse, fine)):
            offset = 2 * c_first - f_first if n == 0 else 0
            k = min(c.phi.size, f.phi[offset::2].size)
            omega = max(omega, float(np.max(np.abs(f.omega[offset::2][:k] - c.omega[:k]))))
            t = max(t, float(np.max(np.abs(f.t[offset::2][:k] - c.t[:k]))))
        differences.append(max(omega / omega_max, t / duration if duration > 0 else 0.0))
    return richardson(differences)
