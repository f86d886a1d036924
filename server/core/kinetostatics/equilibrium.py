"""The friction equilibrium of the dyad 2–3 solved directly: Chaika–Vasylenko §3.1, (3.3) and (3.17)–(3.20)
with the friction loads as unknowns instead of the previous approximation's values.

Only two friction loads reach the dyad's equations: the guide's force F₃₄ and the moment M₂ of the friction
in A and B on the rod.  The reactions are affine in z = (F₃₄, M₂) (``solve_dyad``), and (3.3) gives the
friction from the reactions:
    F₃₄ = −sgn(V_B) f₃₄ |N|,    M₂ = −sgn(ω₂ − ω₁) ρ_A |R₁₂| − sgn(ω₂) ρ_B |R₂₃|,    ρ = f·r (friction circles).
The textbook's successive approximations are the fixed-point iteration z ← G(z).  Its ratio at an angle is
the spectral radius q of J = ∂G/∂z; for the guide alone J = −sgn(V_B) f₃₄ sgn(N) tan ψ and q = f₃₄|tan ψ|,
the ratio of the series in Eremyants' sine and crank-slider iterations (Eremyants (3.24)).

Self-locking is decided from the physics, per angle, by the limit in which the reactions grow without bound
(the loads then negligible beside them): the rod is a two-force member whose line of force is tangent to the
friction circles of A and B as their friction moments require, sin(α − θ) = −ρ_eff/l₂ with
ρ_eff = sgn(ω₂ − ω₁) ρ_A + sgn ω₂ ρ_B, and it must drive the slider along its velocity against the guide's
friction, |R_x| = f₃₄|R_y|.  The slider locks where that line lies within the friction angle of the guide's
normal: f₃₄|tan ψ'| ≥ 1, ψ' the line's angle to the guide (ψ' = ψ, the rod's angle, without friction circles:
the classical f₃₄|tan ψ| ≥ 1), or where the joints' friction turns a line of force past the guide's normal
(|ψ| + δ ≥ 90°, |ρ_eff| ≥ l₂).  There a finite equilibrium does not exist or is not determined by the loads; no driving
moment moves the slider.  The ratio q decides nothing: it says how slowly the textbook's series converges.
Elsewhere z − G(z) = 0 is solved by Newton's method with the generalised Jacobian (|N| and ‖R‖ are
piecewise smooth; where the friction direction switches the branch's one-sided derivative).  Each step
takes the Newton point or the textbook's own step, whichever leaves the smaller change of the reactions
for the next approximation, so the solve never does worse than the textbook.  The error of the reactions
left after a step, relative to |R|, is estimated by the change that step made: a Newton correction bounds
what is left after it (superlinear convergence), a textbook step leaves at most q/(1 − q) of its change;
an angle has converged when that estimate is at most ε_R.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

NEWTON_CAP = 100          # work bound only: an angle still above ε_R after it is reported unconverged, in words
CONTINUATION = 32         # steps of the friction switched on from zero where the direct solve went astray


@dataclass
class Equilibrium:
    """Per angle: the friction z = (F₃₄, M₂), its ratio q, the guide's f₃₄|tan ψ|, the decisions and the error."""

    z: np.ndarray                 # (2, n)
    ratio: np.ndarray             # q, spectral radius of ∂G/∂z at z: the textbook series' ratio
    guide_ratio: np.ndarray       # f₃₄|tan ψ'| (∞ where the line cannot push along the velocity)
    locked: np.ndarray
    converged: np.ndarray
    error: np.ndarray             # relative error estimate of the reactions
    iterations: int


@dataclass
class Dyad:
    """What the friction feedback needs from the dyad at every angle: the rod's direction and the signs of motion."""

    tan_psi: np.ndarray           # AB_y/AB_x
    inverse_length: np.ndarray    # 1/AB_x: ∂R₂₃ᵧ/∂M₂
    slider: np.ndarray            # sgn V_B
    joint_a: np.ndarray           # sgn(ω₂ − ω₁)
    joint_b: np.ndarray           # sgn ω₂


def dyad(points: dict, applied: dict, omega1_ccw: float) -> Dyad:
    """The rod's tan ψ = AB_y/AB_x, 1/AB_x and the signs of V_B, ω₂ − ω₁, ω₂ that orient the friction
    loads f·N, f·R·r of Chaika–Vasylenko (3.3) at every angle."""
    AB = points["B"] - points["A"]
    return Dyad(AB[:, 1] / AB[:, 0], 1.0 / AB[:, 0], np.sign(applied["slider_velocity"]),
                np.sign(applied["omega2"] - omega1_ccw), np.sign(applied["omega2"]))


def locking_ratio(pairs, d: Dyad) -> np.ndarray:
    """f₃₄|tan ψ'| of the rod's line of force tangent to the friction circles (module docstring); 0 at the dead
    centres (V_B = 0: no guide friction).  The rod's equation has two lines, at θ − δ and θ + π + δ
    (sin δ = ρ_eff/l₂); while |θ| + |δ| < 90° (|tan ψ tan δ| < 1) exactly one of them drives the slider along
    its velocity, tan ψ' = (tan ψ + τ_s)/(1 − tan ψ τ_s) with τ_s = −sgn(V_B) tan δ.  Where the joints' friction
    turns a line past the guide's normal (|θ| + |δ| ≥ 90°, or |ρ_eff| ≥ l₂) the friction circles alone
    wedge the rod: ∞."""
    rho = d.joint_a * pairs.f12 * pairs.r12 + d.joint_b * pairs.f23 * pairs.r23
    sine = rho * np.abs(d.inverse_length) * np.sqrt(1 / (1 + d.tan_psi**2))        # ρ_eff/l₂
    with np.errstate(invalid="ignore", divide="ignore"):
        tau = -d.slider * sine / np.sqrt(1 - sine**2)
        pushes = (np.abs(sine) < 1) & (np.abs(d.tan_psi * tau) < 1)
        ratio = np.where(pushes, pairs.f34 * np.abs(d.tan_psi + tau) / (1 - d.tan_psi * tau), np.inf)
    return np.where(d.slider == 0, 0.0, ratio)


def feedback(pairs, d: Dyad, R12: np.ndarray, R23: np.ndarray, N: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """G(z) from the reactions it produced, (3.3), and J = ∂G/∂z (2, 2, n) by the chain rule through solve_dyad:
    ∂R/∂F₃₄ = (−1, −tan ψ), ∂R/∂M₂ = (0, 1/AB_x) for R₁₂ and R₂₃, ∂N/∂F₃₄ = tan ψ, ∂N/∂M₂ = −1/AB_x."""
    rho_a, rho_b = pairs.f12 * pairs.r12, pairs.f23 * pairs.r23
    t, c = d.tan_psi, d.inverse_length
    norm_a, norm_b = np.linalg.norm(R12, axis=1), np.linalg.norm(R23, axis=1)
    G = np.stack([-d.slider * pairs.f34 * np.abs(N), -d.joint_a * rho_a * norm_a - d.joint_b * rho_b * norm_b])

    def unit(R, norm):
        safe = np.where(norm > 0, norm, 1.0)
        return np.where(norm > 0, R[:, 0] / safe, 0.0), np.where(norm > 0, R[:, 1] / safe, 0.0)

    ax, ay = unit(R12, norm_a)
    bx, by = unit(R23, norm_b)
    guide = -d.slider * pairs.f34 * np.sign(N)
    J = np.array([[guide * t, -guide * c],
                  [-d.joint_a * rho_a * (-ax - t * ay) - d.joint_b * rho_b * (-bx - t * by),
                   -d.joint_a * rho_a * c * ay - d.joint_b * rho_b * c * by]])
    return G, J


def spectral_radius(J: np.ndarray) -> np.ndarray:
    """max |λ| of the 2 × 2 matrices J[:, :, k]: real pair from the trace and determinant, else √det."""
    half = (J[0, 0] + J[1, 1]) / 2
    det = J[0, 0] * J[1, 1] - J[0, 1] * J[1, 0]
    disc = half**2 - det
    root = np.sqrt(np.abs(disc))
    return np.where(disc >= 0, np.maximum(np.abs(half + root), np.abs(half - root)), np.sqrt(np.abs(det)))


def newton_step(J: np.ndarray, residual: np.ndarray) -> np.ndarray:
    """Δ solving (I − J)Δ = G(z) − z; NaN where I − J is singular."""
    a, b, c, d = 1 - J[0, 0], -J[0, 1], -J[1, 0], 1 - J[1, 1]
    det = a * d - b * c
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.stack([(d * residual[0] - b * residual[1]) / det, (a * residual[1] - c * residual[0]) / det])


def reaction_change(d: Dyad, dz: np.ndarray) -> np.ndarray:
    """|ΔR₁₂| = |ΔR₂₃| for a change dz of the friction: ΔR = (−dF₃₄, −tan ψ dF₃₄ + dM₂/AB_x)."""
    return np.hypot(dz[0], -d.tan_psi * dz[0] + d.inverse_length * dz[1])


def solve(points: dict, applied: dict, pairs, omega1_ccw: float, tolerance: float, solve_dyad) -> Equilibrium:
    """z with z = G(z) at every angle where the mechanism does not lock (module docstring).

    Where the solve lands on an equilibrium with det(I − J) ≤ 0, it is not the one the mechanism reaches as its
    friction grows from zero (that branch keeps det > 0; a root with det < 0 implies others beside it): the
    friction is then switched on in CONTINUATION steps, each solved from the last.  If the branch folds on the
    way (det(I − J) reaches 0) or no equilibrium continues it, the reactions it needs run away: self-locking."""
    d = dyad(points, applied, omega1_ccw)
    n = d.tan_psi.size
    guide_ratio = locking_ratio(pairs, d)
    locked = guide_ratio >= 1

    def evaluate(z, share):
        R12, R23, N = solve_dyad(points, applied, {"F34": z[0], "M2": z[1]})
        G, J = feedback(pairs, d, R12, R23, N)
        scale = np.maximum(np.maximum(np.linalg.norm(R12, axis=1), np.linalg.norm(R23, axis=1)), np.abs(N))
        return share * G, share * J, scale

    def iterate(z, share, todo):
        G, J, scale = evaluate(z, share)
        error = np.full(n, np.inf)
        steps = 0
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
            while True:
                active = todo & ~(error <= tolerance) & np.isfinite(z).all(0)
                if not active.any() or steps >= NEWTON_CAP:
                    break
                steps += 1
                step = newton_step(J, G - z)
                usable = np.isfinite(step).all(0)
                candidates = [z + np.where(usable, step, 0.0), G]          # Newton's point, the textbook's step
                left = [reaction_change(d, evaluate(c, share)[0] - c) for c in candidates]
                newton = usable & (left[0] <= np.where(np.isfinite(left[1]), left[1], np.inf))
                chosen = np.where(newton, candidates[0], candidates[1])
                moved = reaction_change(d, chosen - z)
                q = spectral_radius(J)
                z = np.where(active, chosen, z)
                G, J, scale = evaluate(z, share)
                moved /= np.where(scale > 0, scale, 1.0)
                # a Newton correction bounds the error left after it (superlinear convergence); a textbook step
                # leaves at most q/(1 − q) of its own size
                estimate = np.where(newton, moved, np.where(q < 1, moved * q / (1 - q), np.inf))
                error = np.where(active, np.where(np.isfinite(estimate), estimate, np.inf), error)
        determinant = (1 - J[0, 0]) * (1 - J[1, 1]) - J[0, 1] * J[1, 0]
        return z, error, determinant, spectral_radius(J), steps

    full = np.ones(n)
    z, error, determinant, ratio, iterations = iterate(np.zeros((2, n)), full, ~locked)
    astray = ~locked & ~(determinant > 0)
    if astray.any():
        followed, lost = np.zeros((2, n)), np.zeros(n, bool)
        for share in np.linspace(0, 1, CONTINUATION + 1)[1:]:
            followed, followed_error, followed_det, followed_ratio, steps = iterate(followed, share * full,
                                                                                   astray & ~lost)
            iterations += steps
            lost |= astray & ~((followed_error <= tolerance) & (followed_det > 0))
        kept = astray & ~lost
        z, error, ratio = np.where(kept, followed, z), np.where(kept, followed_error, error), \
            np.where(kept, followed_ratio, ratio)
        locked = locked | lost
    converged = ~locked & (error <= tolerance)
    return Equilibrium(z, ratio, guide_ratio, locked, converged, error, iterations)
