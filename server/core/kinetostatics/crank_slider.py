"""Kinetostatics of the crank-slider with friction in every pair: seed 002 §3.1, (3.1)–(3.20).

The dyad 2–3 (RRP) first, then the crank; inertia loads by d'Alembert (3.1): F_in = −m a_S,
M_in = −J_S ε.  Unknowns of the dyad: R₁₂ (crank on rod at A), R₂₃ (rod on slider at B) and
the guide's normal reaction N on the slider; five equilibrium equations (rod: ΣF, ΣM_A;
slider: ΣF) solved as one linear system per crank angle, vectorised over φ.  Then the crank:
R₄₁ = R₁₂ − G₁ and the balancing moment from ΣM_O = 0.

Friction (3.3) enters as known loads computed from the previous approximation's reactions:
a force f₃₄|N| against the slider's velocity, and moments f|R|r against the relative rotation
in the revolute pairs A (f₁₂, r₁₂), B (f₂₃, r₂₃) and O (f₁₄, r₁₄) — the friction circles of
radius ρ = f·r.  Approximation 1 has no friction; the iteration stops when the largest
relative change of the reactions falls below ε_R (design step 17(d)); a growing change means
self-locking.  Angles and moments are counter-clockwise internally; the crank turns clockwise in
the drawing (seed 000's convention), so the balancing moment is reported along ω₁.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..dynamics.motors import gas_force
from ..mechanisms import MECHANISMS, Notice
from ..mechanisms.base import angle_ranges, ranges_text

G = 9.81


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
    approximations: list[Approximation] = field(default_factory=list)
    balancing_moment: np.ndarray | None = None    # along ω₁, N·m
    R41: np.ndarray | None = None
    converged: np.ndarray | None = None
    ratio: float | None = None                     # geometric rate of the iteration
    notices: list[Notice] = field(default_factory=list)

    @property
    def final(self) -> Approximation:
        return self.approximations[-1]


def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def motion(params: dict, loads: Loads, phi: np.ndarray) -> tuple[dict, dict]:
    """Positions and the loads applied to each link: gravity, d'Alembert inertia, piston force."""
    mech = MECHANISMS["slider_crank"]
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
        piston = np.stack([-gas_force(loads.gas, params, phi), 0 * phi], axis=1)
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
            max_iterations: int = 60) -> ForceAnalysis:
    """Successive approximations of seed 002 §3.1 over all angles at once."""
    points, applied = motion(params, loads, phi)
    result = ForceAnalysis(phi, points, applied)
    omega1_ccw = -loads.omega                             # the crank turns clockwise
    G1 = np.zeros((phi.size, 2))                          # a balanced crank: its weight acts at O
    none = {"M2": np.zeros(phi.size), "M1": np.zeros(phi.size), "F34": np.zeros(phi.size),
            "M_A": np.zeros(phi.size), "M_B": np.zeros(phi.size), "M_O": np.zeros(phi.size)}
    friction = none
    previous = None
    changes = []
    for _ in range(max_iterations):
        R12, R23, N = solve_dyad(points, applied, friction)
        R41 = R12 - G1
        scale = np.maximum(np.linalg.norm(R12, axis=1), 1e-300)
        change = None if previous is None else np.max(np.linalg.norm(R12 - previous, axis=1) / scale)
        result.approximations.append(Approximation(R12, R23, N, friction, change))
        if change is not None:
            changes.append(change)
            if change < tolerance or not np.isfinite(change) or change > 1e12:
                break
        if not any((pairs.f12, pairs.f23, pairs.f34, pairs.f14)):
            break
        previous = R12
        friction = friction_loads(pairs, applied, R12, R23, N, R41, omega1_ccw)
    per_angle = _per_angle_convergence(result, tolerance)
    result.converged = per_angle
    if len(changes) >= 3:
        tail = [c for c in changes if c > 0]
        if len(tail) >= 3:
            result.ratio = float(np.exp(np.mean(np.diff(np.log(tail[-4:])))))
    final = result.final
    R41 = final.R12 - G1
    result.R41 = R41
    # crank: A×(−R₁₂) + M_b + M_in1 + M_fr on crank = 0 (CCW); report along ω₁ (clockwise)
    ccw = -(cross(points["A"], -final.R12) + applied["M_in1"] + final.friction["M1"])
    result.balancing_moment = -ccw
    if not per_angle.all():
        ranges = angle_ranges(phi, ~per_angle)
        result.notices.append(Notice(
            "kinetostatics_self_locking", f"Self-locking: the successive approximations diverge for φ in "
            f"{ranges_text(ranges)}: friction grows faster than the reactions it comes from.", {"ranges": ranges}))
        for approximation in result.approximations:       # no reaction, no friction where the series diverges
            for name in ("R12", "R23"):
                getattr(approximation, name)[~per_angle] = np.nan
            approximation.N[~per_angle] = np.nan
            for value in approximation.friction.values():
                value[~per_angle] = np.nan
        result.balancing_moment[~per_angle] = np.nan
        result.R41[~per_angle] = np.nan
    return result


def _per_angle_convergence(result: ForceAnalysis, tolerance: float) -> np.ndarray:
    """True where the last two approximations agree to the tolerance (or where there is no friction)."""
    if len(result.approximations) < 2:
        return np.ones(result.phi.size, bool)
    last, before = result.approximations[-1].R12, result.approximations[-2].R12
    change = np.linalg.norm(last - before, axis=1) / np.maximum(np.linalg.norm(last, axis=1), 1e-300)
    return np.isfinite(change) & (change < max(tolerance, 1e-6) * 10)
