"""Kinetostatics of the crank-slider with friction in every pair: Chaika–Vasylenko §3.1, (3.1)–(3.20).

The dyad 2–3 (RRP) first, then the crank; inertia loads by d'Alembert (3.1): F_in = −m a_S,
M_in = −J_S ε.  Unknowns of the dyad: R₁₂ (crank on rod at A), R₂₃ (rod on slider at B) and
the guide's normal reaction N on the slider; five equilibrium equations (rod: ΣF, ΣM_A;
slider: ΣF) solved as one linear system per crank angle, vectorised over φ.  Then the crank:
R₄₁ = R₁₂ − G₁ and the balancing moment from ΣM_O = 0.

Friction (3.3): a force f₃₄|N| against the slider's velocity, and moments f|R|r against the relative
rotation in the revolute pairs A (f₁₂, r₁₂), B (f₂₃, r₂₃) and O (f₁₄, r₁₄) — the friction circles of
radius ρ = f·r.  The textbook computes it from the previous approximation's reactions (approximation 1
without friction) until the relative change falls below ε_R (design step 17(d)); near the friction angle
that series converges slowly (ratio f₃₄|tan ψ| → 1).  The answer is therefore the equilibrium solved
directly to ε_R (equilibrium.py: Newton's method; self-locking where the rod's line of force, tangent to the
friction circles, lies within the guide's friction angle, f₃₄|tan ψ'| ≥ 1, or where the equilibrium followed
from zero friction folds); the textbook's approximations are kept as the table the page shows.  Angles and moments are counter-clockwise internally; the crank turns clockwise in
the drawing (Eremyants' convention), so the balancing moment is reported along ω₁.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from ..numerics import Numerics
from ..dynamics.motors import gas_force
from ..mechanisms import SLIDER_CRANK, Notice
from ..mechanisms.base import angle_ranges, ranges_text
from . import equilibrium

G = 9.81
SHOWN_APPROXIMATIONS = 60    # rows of the textbook's table at most; the answer is the direct solve


@dataclass(frozen=True)
class Pairs:
    """Friction coefficients and journal radii (m) of the pairs: O (14), A (12), B (23) revolute, guide (34)."""

    f14: float = 0.0
    f12: float = 0.0
    f23: float = 0.0
    f34: float = 0.0
    r14: float = 0.02
    r12: float = 0.015
    r23: float = 0.01


@dataclass(frozen=True)
class Loads:
    """Masses (kg), inertias (kg·m²), crank motion and the piston force on the slider."""

    m2: float = 0.0
    J_S2: float = 0.0
    m3: float = 0.0
    J1: float = 0.0
    omega: float = 10.0          # crank speed along its rotation, rad/s
    epsilon: float = 0.0         # crank angular acceleration, rad/s²
    force: float = 0.0           # piston force magnitude, N
    return_factor: float = 1.0   # k_p on the return stroke
    gravity: bool = True
    guide_angle: float = 0.0     # α: inclination of the guide, rad (gravity −y when 0)
    gas: object = None           # a piston engine (dynamics.motors.Motor, kind indicator): gas force instead


@dataclass
class Approximation:
    R12: np.ndarray              # (n, 2) N
    R23: np.ndarray
    N: np.ndarray                # (n,) N
    friction: dict               # moments (N·m) and the slider force (N) used in this approximation
    change: float | None


@dataclass
class ForceAnalysis:
    phi: np.ndarray
    points: dict                 # O, A, B, S2 positions (n, 2)
    applied: dict                # gravity, inertia forces and moments, piston force
    approximations: list[Approximation] = field(default_factory=list)   # the textbook's table (shown)
    solution: Approximation | None = None          # the equilibrium solved to ε_R: the answer
    balancing_moment: np.ndarray | None = None    # along ω₁, N·m
    R41: np.ndarray | None = None
    converged: np.ndarray | None = None
    ratios: np.ndarray | None = None               # the series' ratio q at each angle (NaN where it locks)
    guide_ratio: np.ndarray | None = None          # f₃₄|tan ψ| at each angle
    ratio: float | None = None                     # the largest q where it does not lock
    numerics: dict | None = None
    notices: list[Notice] = field(default_factory=list)

    @property
    def final(self) -> Approximation:
        return self.solution


def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """z-component of the plane vector product a × b = a_x b_y − a_y b_x (moments of forces)."""
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def motion(params: dict, loads: Loads, phi: np.ndarray) -> tuple[dict, dict]:
    """Positions and the loads applied to each link: gravity, d'Alembert inertia, piston force."""
    mech = SLIDER_CRANK
    ev = mech.evaluate(params, phi, {"joints"})
    v = ev.values
    w, eps = loads.omega, loads.epsilon
    # accelerations a = ε·(first analog) + ω²·(second analog); CCW angular quantities
    a_s2 = eps * v["v_s2"] + w**2 * v["a_s2"]
    a_b = eps * v["u31"] + w**2 * v["du31"]
    omega2 = -v["u21"] * w
    eps2 = -(v["u21"] * eps + v["du21"] * w**2)
    down = np.array([np.sin(loads.guide_angle), -np.cos(loads.guide_angle)]) * (G if loads.gravity else 0.0)
    k = np.where(v["u31"] * w >= 0, 1.0, loads.return_factor)
    slider_velocity = v["u31"] * w
    if loads.gas is not None:                # the gas pushes the piston towards the crank (−x)
        piston = np.stack([-gas_force(loads.gas, SLIDER_CRANK, params, phi), 0 * phi], axis=1)
    else:                                    # a working machine's load resists the slider's motion
        piston = np.stack([-np.sign(slider_velocity) * k * loads.force, 0 * phi], axis=1)
    applied = {
        "G2": np.tile(loads.m2 * down, (phi.size, 1)), "G3": np.tile(loads.m3 * down, (phi.size, 1)),
        "F_in2": -loads.m2 * a_s2, "F_in3": np.stack([-loads.m3 * a_b, 0 * phi], axis=1),
        "M_in2": -loads.J_S2 * eps2, "M_in1": -loads.J1 * (-eps), "F_3p": piston,
        "omega2": omega2, "slider_velocity": slider_velocity, "u31": v["u31"], "u21": v["u21"],
    }
    points = {"O": ev.joints["O"], "A": ev.joints["A"], "B": ev.joints["B"], "S2": ev.joints["S2"]}
    return points, applied


def solve_dyad(points: dict, applied: dict, friction: dict) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """R₁₂, R₂₃, N from the five equilibrium equations of rod and slider, with friction as known loads.

    Rod: R₁₂ − R₂₃ + G₂ + F_in2 = 0;  (B − A)×(−R₂₃) + (S₂ − A)×(G₂ + F_in2) + M_in2 + M_fr2 = 0.
    Slider: R₂₃ + (0, N) + (F_fr34, 0) + F_3p + G₃ + F_in3 = 0.
    The system is triangular once ordered: the slider's x equation gives R₂₃ₓ, the rod's moment equation
    about A (AB_y R₂₃ₓ − AB_x R₂₃ᵧ = −(AS × rod load + M_in2 + M_fr2)) gives R₂₃ᵧ (AB_x = l₂ cos ψ ≠ 0 for
    λ > 1), the slider's y equation N and the rod's force equation R₁₂: solved in closed form at all angles.
    """
    AB, AS = points["B"] - points["A"], points["S2"] - points["A"]
    rod_load = applied["G2"] + applied["F_in2"]
    slider_load = applied["F_3p"] + applied["G3"] + applied["F_in3"]
    moment = -(cross(AS, rod_load) + applied["M_in2"] + friction["M2"])
    R23 = np.empty_like(rod_load)
    R23[:, 0] = -(slider_load[:, 0] + friction["F34"])
    R23[:, 1] = (AB[:, 1] * R23[:, 0] - moment) / AB[:, 0]
    N = -slider_load[:, 1] - R23[:, 1]
    return R23 - rod_load, R23, N


def friction_loads(pairs: Pairs, applied: dict, R12, R23, N, R41, omega1_ccw: float) -> dict:
    """Friction from the previous reactions (3.3): against the relative motion in each pair."""
    relative_a = applied["omega2"] - omega1_ccw          # rod relative to crank at A
    m_a = pairs.f12 * np.linalg.norm(R12, axis=1) * pairs.r12
    m_b = pairs.f23 * np.linalg.norm(R23, axis=1) * pairs.r23
    m_o = pairs.f14 * np.linalg.norm(R41, axis=1) * pairs.r14
    on_rod = -np.sign(relative_a) * m_a - np.sign(applied["omega2"]) * m_b
    on_crank = np.sign(relative_a) * m_a - np.sign(omega1_ccw) * m_o
    return {"M2": on_rod, "M1": on_crank, "M_A": m_a, "M_B": m_b, "M_O": m_o,
            "F34": -np.sign(applied["slider_velocity"]) * pairs.f34 * np.abs(N)}


def analyse(params: dict, loads: Loads, pairs: Pairs, phi: np.ndarray, tolerance: float = 1e-9,
            shown: int = SHOWN_APPROXIMATIONS, table: bool = True) -> ForceAnalysis:
    """The friction equilibrium at every angle, solved to ε_R (equilibrium.solve), and the textbook's successive
    approximations of Chaika–Vasylenko §3.1 beside it: the first ``shown`` of them, or fewer if they reach ε_R.
    ``table`` False: without the approximations and the numerics that describe them (approximations empty,
    numerics None), for a caller that reads neither (the wear; a family's preview of the forces)."""
    clock = time.perf_counter()
    points, applied = motion(params, loads, phi)
    result = ForceAnalysis(phi, points, applied)
    omega1_ccw = -loads.omega                             # the crank turns clockwise
    solved = equilibrium.solve(points, applied, pairs, omega1_ccw, tolerance, solve_dyad)
    locked = solved.locked
    result.approximations = (textbook_approximations(points, applied, pairs, omega1_ccw, tolerance, shown, locked)
                             if table else [])
    R12, R23, N = solve_dyad(points, applied, {"F34": solved.z[0], "M2": solved.z[1]})
    friction = friction_loads(pairs, applied, R12, R23, N, R12, omega1_ccw)   # R₄₁ = R₁₂ (balanced crank)
    R12, R23, N = solve_dyad(points, applied, friction)                        # in equilibrium with that friction
    result.solution = Approximation(R12, R23, N, friction, None)
    result.R41 = R12.copy()
    # crank: A×(−R₁₂) + M_b + M_in1 + M_fr on crank = 0 (CCW); report along ω₁ (clockwise)
    result.balancing_moment = -cross(points["A"], R12) + applied["M_in1"] + friction["M1"]
    result.converged = solved.converged
    result.ratios = np.where(locked, np.nan, solved.ratio)
    result.guide_ratio = solved.guide_ratio
    rough = any((pairs.f12, pairs.f23, pairs.f34, pairs.f14))
    result.ratio = float(np.max(solved.ratio[~locked])) if rough and (~locked).any() else None
    if locked.any():
        ranges = angle_ranges(phi, locked)
        result.notices.append(Notice(
            "kinetostatics_self_locking", f"Self-locking for φ in {ranges_text(ranges)}: the connecting rod's line "
            "of force lies within the guide's friction angle (f₃₄·|tan ψ′| ≥ 1), so no force on the slider moves it "
            "there.", {"ranges": ranges}))
        for approximation in (*result.approximations, result.solution):   # no reaction, no friction where it locks
            for value in (approximation.R12, approximation.R23, approximation.N, *approximation.friction.values()):
                value[locked] = np.nan
        result.balancing_moment[locked] = np.nan
        result.R41[locked] = np.nan
    unconverged = ~locked & ~solved.converged
    if unconverged.any():
        ranges = angle_ranges(phi, unconverged)
        reached = float(np.max(solved.error[unconverged]))
        result.notices.append(Notice(
            "kinetostatics_not_converged", f"The equilibrium with friction reached a relative error of "
            f"{reached:.2g}, not ε_R = {tolerance:.2g}, for φ in {ranges_text(ranges)}: rounding or the work bound "
            f"stopped it; the values there carry that error.",
            {"reached": reached, "tolerance": float(tolerance), "ranges": ranges}))
    result.numerics = numerics(result, solved, tolerance, rough, time.perf_counter() - clock) if table else None
    return result


def textbook_approximations(points: dict, applied: dict, pairs: Pairs, omega1_ccw: float, tolerance: float,
                            shown: int, locked: np.ndarray) -> list[Approximation]:
    """Approximation 1 without friction, then friction from the previous reactions (3.3), until the largest
    relative change of R₁₂ over the angles that do not lock is below ε_R (design step 17(d)) or ``shown``
    approximations stand in the table (or the table has run away where the series' ratio q ≥ 1)."""
    n = points["A"].shape[0]
    friction = {key: np.zeros(n) for key in ("M2", "M1", "F34", "M_A", "M_B", "M_O")}
    rough = any((pairs.f12, pairs.f23, pairs.f34, pairs.f14))
    free = ~locked
    table, previous = [], None
    with np.errstate(over="ignore", invalid="ignore"):
        while len(table) < (shown if rough else 1):
            R12, R23, N = solve_dyad(points, applied, friction)
            change = None
            if previous is not None:
                scale = np.maximum(np.linalg.norm(R12[free], axis=1), 1e-300)
                change = float(np.max(np.linalg.norm(R12[free] - previous[free], axis=1) / scale, initial=0.0))
            table.append(Approximation(R12, R23, N, friction, change))
            if change is not None and (change < tolerance or not change < 1e12):    # done, or visibly run away
                break
            previous = R12
            friction = friction_loads(pairs, applied, R12, R23, N, R12, omega1_ccw)
    return table


def approximations_outcome(approximations: list, ratio: float | None, tolerance: float,
                           rough: bool) -> tuple[str, dict, str]:
    """(message code, its context, the sentence): how much of the textbook's series of successive approximations
    the table shows: all of it down to ε_R, a series whose ratio is ≥ 1 somewhere (it does not converge there),
    or its first terms, with the n ≈ ln ε_R / ln q + 1 it would need at the ratio q (Chaika–Vasylenko §3.3)."""
    shown = len(approximations)
    ratio = ratio or 0.0
    last = approximations[-1].change
    if not rough or (last is not None and last < tolerance):
        return ("approximations_complete", {"shown": shown},
                f"the table shows all {shown} successive approximations down to ε_R")
    if ratio >= 1:
        return ("approximations_diverge", {"shown": shown, "ratio": ratio},
                f"the textbook's series has the ratio {ratio:.3g} ≥ 1 at some angles and does not converge there, "
                f"though the mechanism does not lock; the table shows {shown} approximations; the reactions come "
                f"from Newton's solve")
    needed = int(np.ceil(np.log(tolerance) / np.log(ratio))) + 1 if 0 < ratio < 1 else shown
    return ("approximations_truncated", {"shown": shown, "needed": needed, "ratio": ratio},
            f"the table shows the first {shown} successive approximations; at the ratio {ratio:.3g} the series "
            f"needs about {needed} to reach ε_R; the reactions come from Newton's solve")


def numerics(result: ForceAnalysis, solved, tolerance: float, rough: bool, seconds: float) -> dict:
    """How the reactions were found: the direct solve, its error, and how much of the textbook's series is shown."""
    free = ~solved.locked
    error = float(np.max(solved.error[free], initial=0.0))
    code, context, message = approximations_outcome(result.approximations, result.ratio, tolerance, rough)
    return Numerics(
        method="Newton's method on the friction equilibrium (the friction of (3.3) as unknowns), safeguarded by "
               "the textbook's step; the textbook's successive approximations shown beside it",
        rtol=float(tolerance), code="kinetostatics_newton", message_code=code, message_context=context,
        iterations=solved.iterations, runtime_ms=1e3 * seconds, error_estimate=error if rough else 0.0,
        message=message).as_dict()
