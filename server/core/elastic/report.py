"""The elastic scenes' computations: build the model from the machine data, integrate, report.

Everything on the mechanism side is tabulated on TABLE_POINTS nodes per turn (closed forms,
vectorised) and kept in the process by what it depends on: J(φ) and c(φ) as cubic Hermite tables
with their exact derivatives, the load M_c(φ) with central-difference slopes (it has kinks at the
dead centres, where the table rounds them over one node spacing).  The rigid machine compared
with runs on the same tables (rigid_start_up).

One deadline per request (request_deadline: REQUEST_BUDGET_S from its start): the run gets TIME_BUDGET_S of it,
its check run at rtol/10 half as much again, and the bearing iteration's rounds whatever is left; every stage
stops at the request's deadline and says so in words (the numerics message, a warning), so that the API marks the
answer partial (X-Partial) instead of running each stage on a budget of its own.
"""
from __future__ import annotations

import math
import threading
import time
from dataclasses import dataclass, field

import numpy as np

from ..dynamics.motors import Motor
from ..dynamics.reduction import Inertias, reduced_inertia
from ..dynamics.resistance import Load, resisting_moment
from ..mechanisms import MECHANISMS, GeometryError, Notice
from ..numerics import Numerics
from . import dop853
from .compiled import MOTOR_KINDS, pack, pack_rigid
from .warm import ready
from .models import Drive, MechanismSide, ThreeMass, TwoMass
from .periodic_table import PeriodicTable
from .simulate import (CHUNKS, MAX_EVALUATIONS, STIFF_RATIO, TIME_BUDGET_S, integrate, stiffness_ratio,
                       work_bound)
from .stiffness import Compliances, bearing_stiffness, link_angles, linkage_stiffness

TABLE_POINTS = 4096
LARGE_TWIST = 0.05       # rad: a linear spring is an idealisation well before this
RIGID_RTOL = 1e-10       # the rigid start-up's tolerance: its error far below the elastic twist's effect
SENSITIVE = 1e-2         # relative error estimate above which the scene says so
MODELS = ("two_mass", "kinematic_drive", "three_mass", "elastic_linkage", "elastic_four_bar")
LINKAGE_STIFFNESS = ("three_mass", "elastic_linkage", "elastic_four_bar")
CHECK_CHUNKS = 23 - 16 + CHUNKS     # the check run restarts its steps at other times than the run (see simulate())
REQUEST_BUDGET_S = 1.5 * TIME_BUDGET_S  # one elastic request, every stage: the run 4 s, its check 2 s (README)


def request_deadline() -> float:
    """The deadline of a request that starts now (time.perf_counter() + REQUEST_BUDGET_S): every stage of the
    request is given this one instant, so their times add up to the request's budget, not to theirs."""
    return time.perf_counter() + REQUEST_BUDGET_S


@dataclass(frozen=True)
class ElasticMachine:
    """A machine with elastic links. The mechanism side is the reduced inertia of `inertias`
    (J1 = the crank); J_motor is the motor side of the first spring."""

    model: str
    mechanism: str
    params: dict
    inertias: Inertias
    load: Load
    motor: Motor
    J_motor: float = 0.0        # kg·m²
    J_middle: float = 0.0       # three-mass: middle mass, kg·m²
    c: float = 0.0              # constant stiffness: the belt (two-mass) or the first spring (three-mass), N·m/rad
    compliances: Compliances = field(default_factory=Compliances)   # elastic linkage, Eremyants (1.24)–(1.34)
    b: float = 0.0              # damping across the spring next to the mechanism, N·m·s/rad
    b1: float = 0.0             # three-mass: damping across the first spring, N·m·s/rad
    speed: float = 0.0          # kinematic drive: prescribed motor-side speed, rad/s
    omega0: float = 0.0         # initial speed of every mass, rad/s
    twist0: float = 0.0         # initial twist of the spring next to the mechanism, rad


TABLE_CACHE = 16         # tables of each kind kept per process (a slider family touches one kind at a time)
_tables: dict = {"inertia": {}, "load": {}, "stiffness": {}}
_cache_lock = threading.RLock()        # a server may answer from several threads of one process; re-entered by rigid()


def cached(kind: str, key, compute):
    """The table of `kind` for `key` from this process's cache, computed on a miss (oldest dropped past
    TABLE_CACHE): J(φ) depends only on the mechanism and its inertias, M_c(φ) on the mechanism and its load,
    c(φ) on the mechanism and its compliances, so a slider of one of them tabulates only its own table."""
    with _cache_lock:
        return remembered(_tables[kind], key, compute, TABLE_CACHE)


def remembered(store: dict, key, compute, size: int):
    """store[key], computed on a miss; the oldest entry dropped past `size` (call under _cache_lock)."""
    if key not in store:
        if len(store) >= size:
            store.pop(next(iter(store)))
        store[key] = compute()
    return store[key]


def mechanism_side(machine: ElasticMachine) -> MechanismSide:
    """Periodic tables of J(φ), c(φ), M_c(φ) and S(φ) for the mechanism side on TABLE_POINTS nodes per turn,
    each taken from the process's cache when its machine data were tabulated before."""
    params = tuple(sorted(machine.params.items()))
    period = MECHANISMS[machine.mechanism].cycle(machine.params)
    phi = np.linspace(0.0, period, int(TABLE_POINTS * period / (2 * np.pi)) + 1)
    inertia = cached("inertia", (machine.mechanism, params, machine.inertias),
                     lambda: inertia_table(machine, phi, period))
    load, sliding = cached("load", (machine.mechanism, params, machine.load), lambda: load_tables(machine, phi, period))
    if machine.model in LINKAGE_STIFFNESS:
        stiffness = cached("stiffness", (machine.mechanism, params, machine.compliances),
                           lambda: PeriodicTable(period, *linkage_stiffness(machine.mechanism, machine.params,
                                                                            machine.compliances, phi)[:2]))
    else:
        stiffness = machine.c
    return MechanismSide(inertia, stiffness, load, sliding, machine.load.beta)


def inertia_table(machine: ElasticMachine, phi: np.ndarray, period: float) -> PeriodicTable:
    """J(φ) with its exact J′ of the mechanism side (the crank and the links; J_rotor is not on this side)."""
    side = Inertias(**{**machine.inertias.__dict__, "J_rotor": 0.0})
    inertia = reduced_inertia(machine.mechanism, machine.params, side, phi)
    if not inertia.J.min() > 0:                         # as for the rigid machine: no equation of motion
        raise GeometryError("inertias", "the mechanism side's reduced moment of inertia is zero: give the crank "
                                        "(J1) some inertia", "zero_inertia")
    return PeriodicTable(period, inertia.J, inertia.dJ)


def load_tables(machine: ElasticMachine, phi: np.ndarray, period: float) -> tuple[PeriodicTable, PeriodicTable]:
    """M_c(φ) (useful and dry parts) and the viscous S(φ) = M_viscous/β, with central-difference slopes."""
    moment = resisting_moment(machine.mechanism, machine.params, machine.load, phi, omega=1.0)
    if not np.isfinite(moment.useful + moment.dry).all():
        notice = moment.notices[0] if moment.notices else Notice("singular_position", "the load is undefined")
        raise GeometryError("load", notice.text, notice.code, **notice.context)
    sliding = moment.viscous / machine.load.beta if machine.load.beta else np.zeros_like(phi)
    load = moment.useful + moment.dry
    return PeriodicTable(period, load, periodic_slope(load, period)), PeriodicTable(period, sliding,
                                                                                    periodic_slope(sliding, period))


def periodic_slope(values: np.ndarray, period: float) -> np.ndarray:
    """Central differences on the closed periodic grid: keeps the table's interpolant C¹ between the
    nodes (a piecewise-linear load would jolt an adaptive solver at every node)."""
    h = period / (values.size - 1)
    inner = values[:-1]
    slope = (np.roll(inner, -1) - np.roll(inner, 1)) / (2 * h)
    return np.append(slope, slope[0])


def reduced_torque(motor: Motor, i: float):
    """ω ↦ (i·M(iω), i²·M′(iω)): the motor seen from the crank, as plain float arithmetic."""
    if motor.kind == "constant":
        return lambda w: (i * motor.M0, 0.0)
    if motor.kind == "linear":
        return lambda w: (i * (motor.M0 - motor.b * i * w), -i * i * motor.b)
    def characteristic(w):
        torque, slope = motor.torque(i * w)
        return i * float(torque), i * i * float(slope)
    return characteristic


def build(machine: ElasticMachine):
    """The first-order model and its initial state: φ = 0, every mass at speed ω₀, the twist next to
    the mechanism θ₀ (a free-vibration start), the others relaxed."""
    side = mechanism_side(machine)
    drive = Drive(reduced_torque(machine.motor, machine.inertias.gear_ratio),
                  machine.speed if machine.model == "kinematic_drive" else None)
    if machine.model == "three_mass":
        model = ThreeMass(machine.J_motor, machine.J_middle, machine.c, machine.b1, side, machine.b, drive)
    else:
        model = TwoMass(machine.J_motor, side, machine.b, drive)
    if machine.motor.kind in MOTOR_KINDS:
        model.compiled = pack(model, machine.motor, machine.inertias.gear_ratio)
    y0 = np.zeros(model.size)
    y0[2] = machine.twist0
    if machine.model == "kinematic_drive":
        y0[3] = machine.speed - machine.omega0        # θ̇ = ω − ω₂
    else:
        y0[1] = machine.omega0
    return model, y0


def simulate(machine: ElasticMachine, t_end: float, samples: int, rtol: float, method: str = "auto",
             budget_s: float = TIME_BUDGET_S, max_evaluations: int | None = None, with_rigid: bool = True,
             engine: str = "compiled", check: bool = True, deadline: float = math.inf) -> tuple[dict, list]:
    """Time histories, the energy balance and the numerics; the rigid machine's start-up for comparison
    only with_rigid. engine: "compiled" or "scipy" (the reference path, see simulate.integrate). Without the
    check run (check=False, for a caller that reads no error estimate) the error estimate is None.
    The run stops at budget_s, the check run at 1.5·budget_s, both at the request's `deadline` if sooner; a check
    run cut short leaves an error estimate of the part it covers, and says so."""
    ready()
    started = time.perf_counter()
    check_deadline = min(started + 1.5 * budget_s, deadline)
    deadline = min(started + budget_s, deadline)
    model, y0 = build(machine)
    slow = max(2 * np.pi / t_end, machine.speed, no_load_speed(machine))
    ratio, decay, fastest = stiffness_ratio(model, y0, slow)
    chosen = method if method != "auto" else ("Radau" if ratio > STIFF_RATIO else "DOP853")
    times = np.linspace(0.0, t_end, samples)
    atol = absolute_tolerances(machine, model, rtol)
    bound = max_evaluations or work_bound(model, chosen, engine)
    run = integrate(model, y0, t_end, rtol, chosen, times, deadline, atol, bound, engine)
    result = histories(machine, model, run)
    twist_now = result["twist"]
    scale = max(float(np.max(np.abs(twist_now))) if twist_now.size else 0.0, 1e-300)
    estimate, check_notices = None, []
    if check:
        rerun = integrate(model, y0, run.t[-1] if run.t.size else t_end, rtol / 10, chosen,
                          run.t, check_deadline, atol / 10, 2 * bound, engine, CHECK_CHUNKS)
        twist_check = total_twist(machine, rerun.y)
        common = min(twist_now.size, twist_check.size)
        estimate = float(np.max(np.abs(twist_now[:common] - twist_check[:common]), initial=0.0)) / scale
        if not rerun.complete:
            checked = float(rerun.t[-1]) if rerun.t.size else 0.0
            check_notices.append(Notice("elastic_check_partial", f"The check run at ten times tighter tolerance "
                                        f"stopped at its work bound at t = {checked:.4g} s: the error estimate "
                                        "covers the run up to there only.", {"t": checked}))
    numerics = Numerics(
        method=chosen, code="elastic_" + ("implicit" if chosen in ("Radau", "BDF", "LSODA") else "explicit"),
        why_context={"ratio": ratio, "decay": decay, "slow": slow, "fastest": fastest, "threshold": STIFF_RATIO},
        why=(f"stiffness ratio {ratio:.3g}: the fastest decay rate {decay:.4g} 1/s against the "
                                  f"slow rate {slow:.4g} 1/s (fastest |λ| = {fastest:.4g} 1/s) is "
                                  f"{'above' if ratio > STIFF_RATIO else 'below'} {STIFF_RATIO:g}, so an "
                                  f"{'implicit' if chosen in ('Radau', 'BDF', 'LSODA') else 'explicit'} method"
                                  + (" (chosen by the request)" if method != "auto" else "")),
        stiffness_ratio=ratio, rtol=rtol, steps=run.numerics["steps"], rejected=run.numerics["rejected"],
        nfev=run.numerics["nfev"], njev=run.numerics["njev"], nlu=run.numerics["nlu"],
        error_estimate=estimate,
        energy_residual=result.pop("energy_residual"),
        message="; ".join(text for text in (run.numerics["message"], *(n.text for n in check_notices)) if text),
        runtime_ms=1e3 * (time.perf_counter() - started)).as_dict()
    notices = ([] if run.complete else [Notice("elastic_partial", run.numerics["message"])]) + check_notices
    largest = scale if twist_now.size else 0.0
    if largest > LARGE_TWIST:
        near_dead = " (near the dead positions c → 0)" if machine.model in LINKAGE_STIFFNESS else ""
        notices.append(Notice("large_twist_dead" if near_dead else "large_twist",
                              f"The twist reaches {largest:.3g} rad: far beyond the small deformations the linear "
                              f"spring assumes{near_dead}.", {"twist": largest}))
    if estimate is not None and estimate > SENSITIVE:
        notices.append(Notice("sensitive_motion", f"The run at ten times tighter tolerance differs by "
                              f"{100 * numerics['error_estimate']:.2g} % of the largest twist: the details of this "
                              "motion are sensitive; more damping makes them reliable.",
                              {"percent": 100 * numerics["error_estimate"]}))
    result["numerics"] = numerics
    if with_rigid:
        result["rigid"] = rigid(machine, result["t"])
    return result, notices


def no_load_speed(machine: ElasticMachine) -> float:
    """Crank speed where the motor's torque vanishes (0 when there is none): the slow rate's scale."""
    motor, i = machine.motor, machine.inertias.gear_ratio
    if motor.kind == "linear" and motor.b > 0:
        return motor.M0 / motor.b / i
    return motor.omega_sync / i if motor.kind in ("induction", "kloss") else 0.0


def absolute_tolerances(machine: ElasticMachine, model, rtol: float) -> np.ndarray:
    """Per state: angles and speeds to rtol·1e-3; the twists to rtol times a millionth of the static twist
    scale M/c (so a stiff spring's tiny twist keeps its digits); works to rtol·1e-3 J."""
    atol = np.full(model.size, rtol * 1e-3)
    stiffest = max(machine.c, float(np.max(model.side.stiffness.nodes)) if machine.model in LINKAGE_STIFFNESS else 0.0)
    twist_scale = max(machine.load.force * machine.params.get("l1", 1.0), 1.0) / max(stiffest, 1e-300)
    twist_rows = (2, 3, 4, 5) if machine.model == "three_mass" else (2, 3)
    atol[list(twist_rows)] = rtol * 1e-3 * min(twist_scale, 1.0)
    return atol


def total_twist(machine: ElasticMachine, y: np.ndarray) -> np.ndarray:
    """The twist between motor and mechanism: θ, or θ₁ + θ₂ of the three masses."""
    return y[2] + y[4] if machine.model == "three_mass" else y[2]


def histories(machine: ElasticMachine, model, run) -> dict:
    """Angles, speeds, twist, its rate, the driving moment and I_n(t) from the state histories."""
    y, t = run.y, run.t
    phi1, w1 = model.motor_state(t, y)
    if machine.model == "kinematic_drive":
        phi2, w2 = machine.speed * t - y[2], machine.speed - y[3]
    else:
        phi2, w2 = y[0], y[1]
    side = model.side
    inertia = side.inertia.evaluate(phi2)[0]
    stiffness = side.stiff_at(phi2)
    spring_near, rate_near = y[2], y[3]
    if machine.model == "kinematic_drive":
        drive = stiffness * spring_near + machine.b * rate_near
    else:
        i = machine.inertias.gear_ratio
        drive = i * machine.motor.torque(i * w1)[0]
    w_in, w_load, w_diss = y[-3], y[-2], y[-1]
    energy = model.energy(t, y)
    residual = w_in - (energy - energy[0]) - w_load - w_diss if t.size else np.zeros(0)
    scale = energy_scale(energy, w_in, w_load, w_diss)
    total_rate = y[3] + y[5] if machine.model == "three_mass" else y[3]
    return {"t": t, "phi_motor": phi1, "omega_motor": w1, "phi": phi2, "omega": w2,
            "twist": total_twist(machine, y), "twist_rate": total_rate, "spring_twist": spring_near, "driving_moment": drive,
            "inertia": inertia, "stiffness": stiffness,
            "work_in": w_in, "work_load": w_load, "work_dissipated": w_diss,
            "energy_residual": float(np.max(np.abs(residual))) / scale if t.size else 0.0}


def energy_scale(energy: np.ndarray, *works: np.ndarray) -> float:
    """The energy the balance W_in = ΔE + W_load + W_diss is measured against: the largest of the machine's
    kinetic + elastic energy over the run and of each work's magnitude (a free vibration does no work, yet
    its energy is the scale of the histories' errors); 1e-300 J only for a machine at rest with no work."""
    if not energy.size:
        return 1e-300
    return max(float(np.max(np.abs(energy))), *(float(np.max(np.abs(w))) for w in works), 1e-300)


RIGID_CACHE = 16
_rigid_runs: dict = {}


def rigid(machine: ElasticMachine, t: np.ndarray) -> dict | None:
    """The rigid machine's start-up (rigid_start_up) on the times t, kept in the process for the rigid machine
    and the times: the sliders of the springs and dampers leave it unchanged."""
    if machine.model == "kinematic_drive" or t.size == 0:
        return None
    key = (machine.mechanism, tuple(sorted(machine.params.items())), machine.inertias, machine.load, machine.motor,
           machine.J_motor + machine.J_middle, t.size, float(t[0]), float(t[-1]))
    with _cache_lock:
        run = remembered(_rigid_runs, key, lambda: rigid_start_up(machine, t), RIGID_CACHE)
    return {name: values.copy() for name, values in run.items()}


def rigid_start_up(machine: ElasticMachine, t: np.ndarray) -> dict:
    """The rigid machine's start from rest at φ = 0 on the times t: J(φ)ω̇ + ½J′(φ)ω² = M_д(ω) − M_c(φ, ω)
    (Lagrange's equation of the machine reduced to the crank, in time), J(φ) the mechanism side's table plus the
    motor-side masses J_motor (+ J_middle) turning with it, by the compiled DOP853 at RIGID_RTOL in one call
    (regular at ω = 0, unlike dT/dφ). Past a stall (ω back to zero after leaving rest: the load wins; or a start
    the motor cannot make) the rigid machine stands, and φ, ω are NaN (null in the answer) from there on."""
    model = pack_rigid(mechanism_side(machine), machine.J_motor + machine.J_middle, machine.motor,
                       machine.inertias.gear_ratio)
    states = np.full((2, t.size), np.nan)
    dop853.chunk(model.kind, model.p, model.tab, float(t[0]), float(t[-1]), np.zeros(2), RIGID_RTOL,
                 np.full(2, RIGID_RTOL * 1e-2), np.ascontiguousarray(t, dtype=float), states,
                 MAX_EVALUATIONS["compiled"])
    stalled = np.flatnonzero(~(states[1, 1:] > 0.0))          # NaN past a work bound counts as not moving
    if stalled.size:
        states[:, stalled[0] + 1:] = np.nan
    return {"phi": states[0], "omega": states[1]}


def modal(machine: ElasticMachine, points: int = 361) -> dict:
    """Over one turn: c(φ), e(φ), natural frequency √(c(J_m + J)/(J_m J)) and damping ratio
    ζ = b/(2√(c J_eq)), J_eq = J_m J/(J_m + J) (the two masses of Drakunov–Tuleshova (1))."""
    side = mechanism_side(machine)
    period = side.inertia.period
    phi = np.linspace(0.0, period, points)
    J = side.inertia.evaluate(phi)[0]
    c = side.stiff_at(phi)
    c = np.where(c <= 1e-12 * c.max(), 0.0, c)          # the dead positions: round-off of sin²θ₁₂ is zero
    J_eq = machine.J_motor * J / (machine.J_motor + J)
    with np.errstate(divide="ignore"):
        compliance = np.where(c > 1e-12 * c.max(), 1 / np.where(c > 0, c, 1.0), np.inf)
        zeta = np.where(c > 0, machine.b / (2 * np.sqrt(np.where(c > 0, c, 1.0) * J_eq)), np.inf)   # null in JSON
    return {"phi": phi, "stiffness": c, "compliance": compliance, "natural_frequency": np.sqrt(c / J_eq),
            "damping_ratio": zeta, "inertia": J}


@dataclass(frozen=True)
class Bearing:
    """Ball bearings in joints B and C (Eremyants §1.4): z balls, race radii r₁, r₂ (m), E (Pa), μ."""

    balls: int = 9
    r_inner: float = 0.01
    r_outer: float = 0.011
    young: float = 2.1e11
    poisson: float = 0.3


def rod_force(machine: ElasticMachine, phi: np.ndarray, twist: np.ndarray) -> np.ndarray:
    """Axial force of the rod from the spring moment: F = l₁ sin θ₁₂ · θ/Δ (finite at the dead positions)."""
    values = MECHANISMS[machine.mechanism].evaluate(machine.params, np.mod(phi, 2 * np.pi), set()).values
    theta12 = link_angles(machine.mechanism, values | {"phi": phi})[0]
    S = np.sin(theta12) ** 2
    l1 = machine.params["l1"]
    delta = machine.compliances.e1 * l1**2 * S + machine.compliances.e2
    return l1 * np.sin(theta12) * twist / delta


def bearing_iteration(machine: ElasticMachine, bearing: Bearing, t_end: float, samples: int, rtol: float,
                      tolerance: float = 1e-3, max_rounds: int = 12, deadline: float | None = None) -> dict:
    """Successive approximations of Eremyants §1.4: rigid bearings → R_m → c_n (1.44) → e = e₁ + (e₂ + 2/c_n)λ₁₂²
    (1.43) → R_m again: the fixed point R = g(R). Each round is one run (no check run: only R_m is read).
    Convergence is decided from the iteration's own contraction q = |R_{k+1} − R_k|/|R_k − R_{k−1}|: for q < 1
    the fixed point lies within q/(1 − q)·|R_{k+1} − R_k| of R_{k+1} (Banach), and the rounds stop when that
    bound and the last change are within ``tolerance``·R. q ≥ 1 in two successive rounds: the approximations
    do not contract, and the answer says so in words (message, with message_code and message_context for the
    other languages, as bearing_notice reads them); so it does when the rounds run out first, and when the
    request's `deadline` (request_deadline() when None) comes first, which a round cut short by it (its rod force
    from part of the run) does not count towards."""
    rounds, current, changes = [], machine, []
    deadline = request_deadline() if deadline is None else deadline
    outcome = {"rounds": rounds, "converged": False, "message": "", "message_code": "", "message_context": {}}
    while len(rounds) < max_rounds:
        if time.perf_counter() >= deadline:
            return outcome | _out_of_time(rounds)
        result, _ = simulate(current, t_end, samples, rtol, with_rigid=False, check=False, deadline=deadline)
        if result["numerics"]["message"] and time.perf_counter() >= deadline:
            return outcome | _out_of_time(rounds)   # this round's run was cut by the deadline: not a round
        if not result["t"].size:                    # stopped at the work bound before any sample: no rod force
            break
        load = float(np.max(np.abs(rod_force(current, result["phi"], result["twist"]))))
        stiffness = bearing_stiffness(load, bearing.balls, bearing.r_inner, bearing.r_outer, bearing.young,
                                      bearing.poisson)
        if rounds:
            changes.append(abs(load - rounds[-1]["R_m"]))
        rounds.append({"R_m": load, "c_n": stiffness, "e2_total": current.compliances.e2})
        if len(changes) >= 2:
            ratio = changes[-1] / max(changes[-2], 1e-300)
            if ratio < 1 and max(changes[-1], ratio / (1 - ratio) * changes[-1]) <= tolerance * load:
                return outcome | {"converged": True, "ratio": ratio, "limit": {"R_m": load, "c_n": stiffness}}
            if ratio >= 1 and len(changes) >= 3 and changes[-2] >= changes[-3]:
                return outcome | {"ratio": ratio, "message_code": "bearings_not_contracting",
                                  "message_context": {"ratio": ratio},
                                  "message": f"The successive approximations of the bearing stiffness do not contract "
                                             f"(each change of R_m is {ratio:.3g} times the previous one): they do "
                                             "not converge."}
        elif changes and changes[-1] == 0.0:        # the bearings change nothing the run can see
            return outcome | {"converged": True, "limit": {"R_m": load, "c_n": stiffness}}
        joints = 2.0 / stiffness                    # e_B + e_C, two equal bearings
        current = ElasticMachine(**{**machine.__dict__, "compliances": Compliances(
            machine.compliances.e1, machine.compliances.e2 + joints, machine.compliances.e3)})
    if not rounds:
        return outcome | {"message_code": "bearings_no_run", "message": "The run stopped at its work bound before "
                          "its first sample: no rod force, so no bearing stiffness."}
    change = changes[-1] / rounds[-1]["R_m"] if changes and rounds[-1]["R_m"] > 0 else math.nan
    return outcome | {"message_code": "bearings_unconverged", "message_context": {"rounds": len(rounds),
                                                                                 "percent": 100 * change},
                      "message": f"The successive approximations of the bearing stiffness stopped after {len(rounds)} "
                                 f"rounds (the rounds or the time allowed ran out), the last change of R_m "
                                 f"{100 * change:.2g} %: not converged."}


def _out_of_time(rounds: list) -> dict:
    """The bearing iteration's words when the request's deadline stopped it (the API marks the answer partial)."""
    return {"message_code": "bearings_time_budget", "message_context": {"rounds": len(rounds)},
            "message": f"The successive approximations of the bearing stiffness stopped at the request's time budget "
                       f"after {len(rounds)} complete rounds: not converged."}


def bearing_notice(outcome: dict) -> list[Notice]:
    """The iteration's message as a notice (none when it converged)."""
    if not outcome["message"]:
        return []
    return [Notice(outcome["message_code"], outcome["message"], outcome["message_context"])]
