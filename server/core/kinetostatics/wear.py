"""Expected wear of the pairs, Archard-type linear in p·V (Chaika–Vasylenko §4, (4.1)–(4.24)).

Revolute pair j/j+1 under a rotating reaction R (cosine pressure, |ψ| ≤ π/2 in contact):
    δ_j(β) = a_j ∫ R |u_j1 − u_{j+1,1}| cos ψ_j dφ,   ψ_j = φ_j + β − γ*,   a_j = 2·10⁶ k_j n_c/(π l_z)   (4.12), (4.13)
    [(4.6)–(4.11) are lost in the print; reconstructed from (4.12)–(4.13), Fig. 4.2 and the example]
Piston (cylindrical slider) and cylinder, the pressed side only:
    δ₃ = a₃ ∫ |R₃₄ V_qB| dφ,  a₃ = 10⁶ b k₃ n_c/(l_p d_p), b = 4/π                            (4.17), (4.19)
    δ₄(X) = a₄ ∫_{piston over X} |R₃₄ V_qB| dφ,  a₄ = 10⁶ d k₄ n_c/(l_p d_p), d = 4/π        (4.18)
Wear coefficients from the wear intensities: k = I_s/p_m, p_m = 4 R_m/(π l d) (4.23), (4.24).
Wear in micrometres; integrals by the trapezoidal rule as in the book's program ISNKPKPM.

Under a constant load (Chaika–Vasylenko §4.1, Figs 4.1 and 4.3), in SI (wear in metres):
    δ₂ = δ₂,max cos ψ (4.1),  p = p_max cos ψ (4.2),  F_e = 2∫₀^{π/2} p_max l_z r cos²ψ dψ = p_max l_z r π/2 (4.3),
    p_max = 2F_e/(π l_z r) (4.4),  p = 2F_e cos ψ/(π l_z r) (4.5),  zero where |ψ| > π/2 (out of contact);
    δ₃,c = 2H_B k₃ p (4.14),  δ₄,c = S k₄ p (4.15) with the friction path S(X) of a guide point per cycle.
"""
from __future__ import annotations

import numpy as np


def mean_pressure(reaction: np.ndarray, length: float, diameter: float) -> float:
    """p_m = 4 R_m/(π l d) with R_m the mean of |R| over the cycle samples (4.23)."""
    return 4 * float(np.mean(np.abs(reaction))) / (np.pi * length * diameter)


def revolute_wear(phi: np.ndarray, reaction: np.ndarray, relative_rate: np.ndarray, link_angle: np.ndarray,
                  beta: np.ndarray, k: float, cycles: float, length: float, journal: bool) -> np.ndarray:
    """δ(β) in µm over the points β (rad) of one element of a revolute pair, Chaika–Vasylenko (4.12)–(4.13).

    reaction: (n, 2) force the mating element exerts on this one; relative_rate: |u_j1 − u_{j+1,1}|;
    link_angle: the element's angle in the frame (its points turn with it); journal: a pin is pressed on
    the side facing against the force (γ* = γ + π), a bush on the side the force points to (γ* = γ).
    In contact where ψ wrapped to (−π, π] has |ψ| ≤ π/2, i.e. where cos ψ ≥ 0: the cosine pressure max(cos ψ, 0)."""
    gamma = np.arctan2(reaction[:, 1], reaction[:, 0]) + (np.pi if journal else 0.0)
    contact = np.maximum(np.cos(link_angle[None, :] + beta[:, None] - gamma[None, :]), 0.0)
    integrand = np.linalg.norm(reaction, axis=1)[None, :] * relative_rate[None, :] * contact
    a = 2e6 * k * cycles / (np.pi * length)
    return a * np.trapezoid(integrand, phi, axis=1)


def piston_wear(phi: np.ndarray, normal: np.ndarray, velocity_analog: np.ndarray, k: float, cycles: float,
                length: float, diameter: float, side: int = 1) -> float:
    """δ₃ (µm) of the piston's side pressed when sign(R₃₄) = side (4.17), b = 4/π."""
    pressed = np.where(np.sign(normal) == side, np.abs(normal * velocity_analog), 0.0)
    return 1e6 * (4 / np.pi) * k * cycles / (length * diameter) * float(np.trapezoid(pressed, phi))


def cylinder_wear(phi: np.ndarray, normal: np.ndarray, velocity_analog: np.ndarray, travel: np.ndarray,
                  points: np.ndarray, k: float, cycles: float, length: float, diameter: float, side: int = 1) -> np.ndarray:
    """δ₄(X) (µm) along the cylinder: a point X (from the top-dead-centre end of the piston's path) wears
    while the piston, occupying [s, s + l_p] in that coordinate, covers it (4.18), d = 4/π."""
    pressed = np.where(np.sign(normal) == side, np.abs(normal * velocity_analog), 0.0)
    covered = (points[:, None] >= travel[None, :]) & (points[:, None] <= travel[None, :] + length)
    a = 1e6 * (4 / np.pi) * k * cycles / (length * diameter)
    return a * np.trapezoid(np.where(covered, pressed[None, :], 0.0), phi, axis=1)


def cosine_law(peak, psi):
    """δ₂(ψ) = δ₂,max cos ψ (4.1) and p(ψ) = p_max cos ψ (4.2) on the loaded half |ψ| ≤ π/2, zero beyond it."""
    return np.asarray(peak) * np.maximum(np.cos(psi), 0.0)


def peak_pressure(force, length, radius):
    """p_max = 2F_e/(π l_z r) (4.4), Pa, for the force F_e (N) on a journal of radius r and length l_z (m)."""
    return 2 * np.asarray(force) / (np.pi * length * radius)


def cosine_pressure(force, length, radius, psi):
    """p(ψ) = 2F_e cos ψ/(π l_z r) (4.5), Pa, zero out of contact (|ψ| > π/2)."""
    return cosine_law(peak_pressure(force, length, radius), psi)


def pressure_resultant(peak, length, radius):
    """F_e = 2∫₀^{π/2} p_max l_z r cos²ψ dψ = p_max l_z r π/2 (4.3), N: the load the cosine pressure carries."""
    return np.asarray(peak) * length * radius * np.pi / 2


def slider_wear(k, pressure, stroke, cycles=1.0):
    """δ₃ = n_c·2H_B k₃ p (4.14), m: a slider under a uniform pressure p slides 2H_B per cycle."""
    return cycles * 2 * stroke * k * np.asarray(pressure)


def guide_path(x, slider_length, stroke):
    """The friction path S per cycle of a guide point X (m, from the guide's top-dead-centre end) under a slider
    of length l_p with stroke H_B, reconstructed from Fig. 4.3 (the print reads S = 0 at the ends, l_p at D₄,
    2l_p on K₄M₄): S = 2·(length of the travel over which the slider covers X)
    = 2·(min(X, H_B) − max(X − l_p, 0)), zero outside [0, H_B + l_p]."""
    x = np.asarray(x, float)
    return 2 * np.clip(np.minimum(x, stroke) - np.maximum(x - slider_length, 0.0), 0.0, None)


def guide_wear(k, pressure, path, cycles=1.0):
    """δ₄ = n_c·S k₄ p (4.15), m: a guide point slid over a distance S per cycle under the pressure p."""
    return cycles * np.asarray(path) * k * np.asarray(pressure)
