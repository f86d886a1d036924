"""Fixed-step RK4 in the crank angle for the energy form of the equation of motion.

    dT/dφ = F(φ, T) = M_φ(φ) + M_ω(ω, φ),   ω = √(2T/J(φ))         Eremyants (1.9), (1.13)
    dS/dφ = ∂F/∂T · S,   ∂F/∂T = (∂M_ω/∂ω)/(J ω)                       variational equation

The nodes are fixed in φ, so every φ-dependent quantity is tabulated in one vectorised
call on the step and half-step nodes; the loop does scalar arithmetic only.  When F does
not depend on T (moments of φ alone) the scheme is Simpson's rule applied to the energy
integral (1.9): T(φ) = T₀ + ∫ (M_д − M_c) dφ.  Time follows from dt = dφ/ω (1.11) by
Simpson's rule per step.  A start from rest is singular in t (ω ∝ √(φ − φ₀)); that first
step is integrated in time instead, where the equation is regular.

The moments have kinks (machine.py): the nodes are uniform between them and every kink is a node
(``kinked_tables``), so each step sees a smooth right-hand side and RK4 keeps its fourth order; at a
kink the step after it starts on a node of its own, evaluated just inside its side (KINK_SIDE), so that
a jump of the moment (a reversal with friction, an indicator diagram's change of stroke) is taken from
the side each step lies on.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp

from . import compiled as motor_kernel
from . import dop853
from .machine import Machine, Tables


COMPILED = True   # default path: the numba loops (compiled.py, dop853.py); False: the Python/scipy reference
REST_STEPS = 16   # steps integrated in time after a start from rest: T ≈ aφ − cφ^{3/2} is not smooth in φ there
REST_REACH = 1.0   # the compiled path's table reaches this many times the nodes' span past the last node
REST_BUDGET_S = 1.0   # wall time for those steps at most (milliseconds usually; a very steep motor is stiff in time)


class RestBudget(Exception):
    """Leaving rest took longer than REST_BUDGET_S of wall time."""


KINK_SIDE = 4e-12        # rad: a kink's node is evaluated this far inside the step's own side (> KINK_MERGE)


def kinked_tables(machine: Machine, edges: np.ndarray, counts: np.ndarray, sided: np.ndarray) -> Tables:
    """Tables on the step and half-step nodes of the segments between consecutive ``edges``, counts[i]
    uniform steps in segment i. Each segment has nodes of its own, so an inner edge has two, one per side;
    sided[i]: edge i is a kink, its nodes are evaluated KINK_SIDE inside their segments (Tables.kink_nodes
    marks those step nodes)."""
    nodes, angles, starts, first = [], [], [], 0
    for i, (a, b, n) in enumerate(zip(edges[:-1], edges[1:], counts)):
        segment = np.linspace(a, b, 2 * n + 1)
        nodes.append(segment)
        inside = segment.copy()
        inside[0] += KINK_SIDE if sided[i] else 0.0
        inside[-1] -= KINK_SIDE if sided[i + 1] else 0.0
        angles.append(inside)
        starts.append(first + 2 * np.arange(n))
        first += 2 * n + 1
    inside, kinks = np.concatenate(angles), edges[sided]
    both = machine.tables(np.concatenate([inside, kinks]))     # the kinks themselves too: a singular position?
    tables = both.part(slice(0, inside.size))
    tables.phi = np.concatenate(nodes)
    tables.starts = np.concatenate(starts)
    tables.kink_nodes = np.zeros(tables.starts.size + 1, bool)
    tables.kink_nodes[np.concatenate([[0], np.cumsum(counts)])] = sided
    for kink in kinks[~np.isfinite(both.net_phi[inside.size:])]:    # undefined on the kink: not beside it either
        tables.dry = np.where(tables.phi == kink, np.nan, tables.dry)
    return tables


REST_NODES = 32          # Chebyshev nodes of the table of J, J′, M(φ), S(φ) over the start from rest
REST_TABLE_RTOL = 1e-12  # the table is used only if it matches direct evaluation between its nodes this well


class RestTable:
    """J, J′, the φ-moment and S(φ) over [a, b] for the start from rest: direct evaluation, or, when it
    reproduces direct evaluation between its nodes to REST_TABLE_RTOL, the polynomial through the
    Chebyshev points x_j = cos(jπ/N) in barycentric form (weights (−1)^j, halved at the ends; Berrut &
    Trefethen 2004, (5.4)). DOP853 calls the right-hand side at one angle at a time; a mechanism evaluated at
    one angle costs as much as at a hundred, so one vectorised table replaces about a hundred evaluations.
    A moment with a kink or a jump inside the interval (an indicator diagram's corner, dry friction at a
    reversal) fails the check and is evaluated directly."""

    def __init__(self, machine: Machine, a: float, b: float):
        self.machine, self.a, self.b = machine, a, b
        j = np.arange(REST_NODES + 1)
        self.nodes = 0.5 * (a + b) + 0.5 * (b - a) * np.cos(np.pi * j / REST_NODES)
        self.weights = (-1.0) ** j * np.where((j == 0) | (j == REST_NODES), 0.5, 1.0)
        middles = 0.5 * (self.nodes[1:] + self.nodes[:-1])        # where the interpolation error is largest
        both = self.direct(np.concatenate([self.nodes, middles]))  # one vectorised evaluation of the machine
        self.values, at_middles = both[:REST_NODES + 1], both[REST_NODES + 1:]
        terms = self.weights / (middles[:, None] - self.nodes[None, :])
        error = np.abs((terms @ self.values) / terms.sum(axis=1)[:, None] - at_middles)
        scale = np.max(np.abs(self.values), axis=0) + 1e-300
        self.tabulated = bool(np.all(error <= REST_TABLE_RTOL * scale))

    def direct(self, phi: np.ndarray) -> np.ndarray:
        """Columns J, J′, M(φ), S(φ) from the machine itself."""
        tables = self.machine.tables(phi)
        return np.stack([tables.J, tables.dJ, tables.net_phi, tables.sliding], axis=1)

    def at(self, phi: float) -> np.ndarray:
        """J, J′, M(φ), S(φ) at one angle: from the table inside [a, b] when it passed, else direct."""
        if not (self.tabulated and self.a <= phi <= self.b):
            return self.direct(np.array([phi]))[0]
        difference = phi - self.nodes
        if not difference.all():
            return self.values[np.argmin(np.abs(difference))]
        terms = self.weights / difference
        return (terms @ self.values) / terms.sum()


def leave_rest(machine: Machine, phi: np.ndarray, t0: float,
               compiled: bool | None = None) -> tuple[list[float], list[float]]:
    """T and t at the step nodes ``phi`` after a start from rest at phi[0]: J ω̇ = M − ½J′ω², φ̇ = ω
    in time, regular at ω = 0 (unlike dT/dφ, whose solution has a φ^{3/2} term), by scipy's DOP853.
    The φ-dependent parts come from a RestTable over the steps and a little past them (DOP853's stages
    may look ahead of the last node). Raises RestBudget past REST_BUDGET_S of wall time (a very steep
    motor crawls off in tiny steps).

    compiled: the same DOP853 compiled (dop853.py; default ``COMPILED``) on a table reaching REST_REACH
    past the last node, when that table applies and no stage leaves it; else scipy's solve_ivp, the
    reference path."""
    motor_kernel.warm_up()                  # compiled before the clock starts (once per process)
    deadline = time.perf_counter() + REST_BUDGET_S
    span = float(phi[-1] - phi[0])
    if COMPILED if compiled is None else compiled:
        wide = RestTable(machine, float(phi[0]), float(phi[-1]) + REST_REACH * span)
        if wide.tabulated:
            speed, kind, params = motor_kernel.speed_parameters(machine)
            t_first, omega_first = np.empty(phi.size - 1), np.empty(phi.size - 1)
            outcome = dop853.leave_rest(wide.nodes, wide.weights, np.ascontiguousarray(wide.values), wide.a, wide.b,
                                        speed, kind, params, np.ascontiguousarray(phi[1:], dtype=np.float64),
                                        _time_bound(machine, wide, phi), 1e-11, 1e-14, deadline, t_first, omega_first)
            if outcome == dop853.OUT_OF_TIME:
                raise RestBudget
            if outcome == dop853.DONE:
                return _passings(machine, phi, t0, t_first[:, None], omega_first[:, None])
    table = RestTable(machine, float(phi[0]), float(phi[-1] + 0.25 * (phi[-1] - phi[0])))

    def rhs(_, y):
        if time.perf_counter() > deadline:
            raise RestBudget
        J, dJ, moment, sliding = table.at(y[0])
        if machine.speed_dependent:
            moment += machine.speed_moment(y[1], sliding)[0]
        return [y[1], (moment - 0.5 * dJ * y[1] ** 2) / J]

    def passing(node):
        def event(_, y):
            return y[0] - node
        event.terminal = node == phi[-1]
        return event

    def stalls(_, y):                 # back to rest after leaving it: the load wins
        return y[1]
    stalls.terminal, stalls.direction = True, -1
    solution = solve_ivp(rhs, (0.0, _time_bound(machine, table, phi)), [phi[0], 0.0], method="DOP853", rtol=1e-11,
                         atol=1e-14, events=[passing(node) for node in phi[1:]] + [stalls])
    return _passings(machine, phi, t0, solution.t_events[:-1], [y[:, 1] if y.size else y for y in solution.y_events[:-1]])


def _time_bound(machine: Machine, table: RestTable, phi: np.ndarray) -> float:
    """The end of the time interval: 20 × the time to cover the nodes at the starting acceleration, + 1 s."""
    J, _, moment, sliding = table.at(float(phi[0]))
    if machine.speed_dependent:
        moment += machine.speed_moment(0.0, sliding)[0]
    start = machine.tables(phi[:1])
    scale = math.sqrt(2 * (phi[-1] - phi[0]) * start.J[0] / max(abs(moment / J) * start.J[0], 1e-300))
    return 20 * scale + 1.0


def _passings(machine: Machine, phi: np.ndarray, t0: float, times, speeds) -> tuple[list[float], list[float]]:
    """T and t at the nodes passed, contiguous from the start, from each node's passing times and speeds
    (NaN or none: not passed; the first passing counts)."""
    reached = [k for k, t in enumerate(times) if t.size and np.isfinite(t[0]) and speeds[k][0] > 0]
    reached = reached[:next((n for n, k in enumerate(reached) if k != n), len(reached))]   # contiguous from the start
    omega = np.array([float(speeds[k][0]) for k in reached])
    J = machine.tables(phi[1:len(reached) + 1]).J
    return (0.5 * J * omega**2).tolist(), [t0 + float(times[k][0]) for k in reached]


@dataclass
class Run:
    """T, ω, t at the step nodes; S = dT(end)/dT₀; where the run stopped if it stalled."""

    phi: np.ndarray
    T: np.ndarray
    omega: np.ndarray
    t: np.ndarray
    sensitivity: float
    stall_phi: float | None = None


def integrate(machine: Machine, tables: Tables, T0: float, steps: int, t0: float = 0.0,
              compiled: bool | None = None, first: int = 0) -> Run:
    """Integrate over the ``steps`` steps of ``tables`` (Tables.step_nodes: a step over nodes s, s + 1, s + 2)
    from T₀ at step node ``first`` (0: the first node; a start from rest only there).

    compiled: the numba loop of compiled.py (default, ``COMPILED``) or the plain Python loop below, the
    reference the compiled one is tested against (tests/test_motion_compiled.py)."""
    phi = tables.phi
    kernel = loop_tables(tables)
    index, starts = kernel[0], kernel[1]
    T_nodes, t_nodes = np.empty(steps + 1), np.empty(steps + 1)
    T_nodes[first], t_nodes[first] = T0, t0
    stall, count, S, start = None, first + 1, 1.0, first
    if T0 == 0.0 and first == 0:
        first = min(REST_STEPS, steps)
        T_rest, t_rest = leave_rest(machine, phi[index[:first + 1]], t0, compiled)
        count = len(T_rest) + 1
        T_nodes[1:count], t_nodes[1:count] = T_rest, t_rest
        if len(T_rest) < first:            # came to rest again before the first few steps
            stall, first = float(phi[index[len(T_rest)]]), steps
    if first < steps:
        loop = _steps_compiled if (COMPILED if compiled is None else compiled) else _steps_python
        count, S, stall_node = loop(machine, tables, starts, T_nodes, t_nodes, first, steps)
        stall = float(phi[stall_node]) if stall_node >= 0 else None
    T_arr = T_nodes[start:count]
    J_nodes = tables.J[index[start:count]]
    return Run(phi=phi[index[start:count]], T=T_arr, omega=np.sqrt(2 * T_arr / J_nodes),
               t=t_nodes[start:count].copy(), sensitivity=S, stall_phi=stall)


def loop_tables(tables: Tables) -> tuple:
    """(step node indices, step starts, φ, J, M_φ, S) as the loops take them (contiguous float64, int64), made
    once per Tables: a start-up integrates the same tables cycle after cycle, the shooting iteration after
    iteration. Kept on the Tables with the arrays they were made from, and made again if one of those was
    replaced since (a balancing moment added to ``useful`` after the tables were made)."""
    sources = (tables.phi, tables.J, tables.drive_phi, tables.useful, tables.dry, tables.sliding, tables.starts)
    held = tables.__dict__.get("_loop_tables")
    if held is None or any(a is not b for a, b in zip(held[0], sources)):
        index = tables.step_nodes
        held = (sources, (index, np.ascontiguousarray(index[:-1], dtype=np.int64),
                          np.ascontiguousarray(tables.phi, dtype=np.float64),
                          np.ascontiguousarray(tables.J, dtype=np.float64),
                          np.ascontiguousarray(tables.net_phi, dtype=np.float64),
                          np.ascontiguousarray(tables.sliding, dtype=np.float64)))
        tables.__dict__["_loop_tables"] = held
    return held[1]


def _steps_compiled(machine: Machine, tables: Tables, starts, T_nodes, t_nodes, first: int, steps: int):
    if "speed_parameters" not in machine.memo:
        machine.memo["speed_parameters"] = motor_kernel.speed_parameters(machine)
    speed, kind, params = machine.memo["speed_parameters"]
    _, _, phi, J, net_phi, sliding = loop_tables(tables)
    return motor_kernel.rk4_steps(phi, J, net_phi, sliding, starts, speed, kind, params, T_nodes, t_nodes, first,
                                  steps)


def cycles(machine: Machine, tables: Tables, T0: float, t0: float, steps: int, count: int,
           rtol: float | None) -> list[Run]:
    """Up to ``count`` whole cycles of ``tables`` from T₀ > 0, t₀ at the first node, each from the last one's end,
    stopping after a stall or the cycle whose start energy settles to rtol (None: never), as that many
    ``integrate`` calls give them (φ of each from the tables' first node): the compiled loop runs them at once
    (compiled.rk4_cycles), the reference one by one."""
    if not COMPILED:
        runs = []
        for _ in range(count):
            run = integrate(machine, tables, T0, steps, t0)
            runs.append(run)
            if run.stall_phi is not None or (rtol is not None and abs(run.T[-1] - run.T[0]) <= rtol * run.T[-1]):
                break
            T0, t0 = run.T[-1], run.t[-1]
        return runs
    if "speed_parameters" not in machine.memo:
        machine.memo["speed_parameters"] = motor_kernel.speed_parameters(machine)
    speed, kind, params = machine.memo["speed_parameters"]
    index, starts, phi, J, net_phi, sliding = loop_tables(tables)
    T_out, t_out = np.empty((count, steps + 1)), np.empty((count, steps + 1))
    counts, S, stalls = np.zeros(count, np.int64), np.zeros(count), np.zeros(count, np.int64)
    done = motor_kernel.rk4_cycles(phi, J, net_phi, sliding, starts, speed, kind, params, float(T0), float(t0), steps,
                                   count, 0.0 if rtol is None else float(rtol), rtol is not None, T_out, t_out, counts,
                                   S, stalls)
    runs = []
    for n in range(done):
        filled = int(counts[n])
        T_arr = T_out[n, :filled]
        runs.append(Run(phi=tables.phi[index[:filled]], T=T_arr, omega=np.sqrt(2 * T_arr / tables.J[index[:filled]]),
                        t=t_out[n, :filled].copy(), sensitivity=float(S[n]),
                        stall_phi=float(tables.phi[stalls[n]]) if stalls[n] >= 0 else None))
    return runs


def _steps_python(machine: Machine, tables: Tables, starts, T_nodes, t_nodes, first: int, steps: int):
    """The reference loop: steps first … steps−1 from node ``first``, step k over the nodes starts[k] + 0, 1, 2;
    fills the following nodes and returns (nodes filled, S = dT(end)/dT₀, stall node index or −1)."""
    phi = tables.phi.tolist()
    J = tables.J.tolist()
    base = tables.net_phi.tolist()
    sliding = tables.sliding.tolist()
    speed = machine.speed_dependent
    speed_moment = machine.speed_moment

    def rate(j: int, T: float) -> tuple[float, float]:
        omega = math.sqrt(2.0 * T / J[j]) if T > 0.0 else 0.0
        if not speed:
            return base[j], 0.0
        moment, slope = speed_moment(omega, sliding[j])
        return base[j] + moment, (slope / (J[j] * omega) if omega > 0.0 else 0.0)

    S, T, t = 1.0, float(T_nodes[first]), float(t_nodes[first])
    stall, count = -1, first + 1
    for k in range(first, steps):
        j = int(starts[k])
        h = phi[j + 2] - phi[j]
        f1, g1 = rate(j, T)
        f2, g2 = rate(j + 1, T + 0.5 * h * f1)
        f3, g3 = rate(j + 1, T + 0.5 * h * f2)
        f4, g4 = rate(j + 2, T + h * f3)
        T_new = T + h * (f1 + 2 * f2 + 2 * f3 + f4) / 6
        if T_new <= 0.0 or min(T + 0.5 * h * f1, T + 0.5 * h * f2) < 0.0:
            stall = j
            break
        if T > 0.0 and 0.5 * (T + T_new) + h * (f1 - f4) / 8 <= 0.0:   # T(φ) touches zero inside the step
            stall = j + 1
            break
        s1 = g1 * S
        s2 = g2 * (S + 0.5 * h * s1)
        s3 = g3 * (S + 0.5 * h * s2)
        s4 = g4 * (S + h * s3)
        S += h * (s1 + 2 * s2 + 2 * s3 + s4) / 6
        w0 = math.sqrt(2 * T / J[j])
        w1 = math.sqrt(2 * T_new / J[j + 2])
        if w0 == 0.0:           # leaving rest: T grows linearly, ∫dφ/ω = 2h/ω(h)
            t += 2 * h / w1
        else:                   # Simpson, with T at mid-step from the cubic Hermite interpolant
            T_mid = 0.5 * (T + T_new) + h * (f1 - f4) / 8
            w_half = math.sqrt(2 * max(T_mid, 0.0) / J[j + 1])
            t += h * (1 / w0 + 4 / w_half + 1 / w1) / 6
        T = T_new
        T_nodes[count], t_nodes[count] = T, t
        count += 1
    return count, S, stall
