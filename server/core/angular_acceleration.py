"""The two components of a coupler's angular acceleration (seed 001, Kuleshova & Tokhtar 2007).

    ε = d/dt (V_A/AP) = ε* + ε**,   ε* = (dV_A/dt)/AP = a_A^τ/AP,   ε** = V_A·d(1/AP)/dt      (1)–(4)

Central crank-slider, λ = OA/AB < 1 (the paper's λ; the textbook's l₂/l₁ is 1/λ): O at the origin,
A = OA(cos φ, sin φ), B on the x axis, sin ψ = λ sin φ.  P, the instantaneous centre of AB, is where
line OA meets the normal to the guide at B, so (signed)

    1/AP = cos φ/(AB cos ψ),   ω_AB = ω λ cos φ/cos ψ = V_A/AP,
    ε* = ε_OA λ cos φ/cos ψ,   ε** = ω λ(−ω sin φ cos ψ + ω_AB sin ψ cos φ)/cos²ψ.

1/AP is finite everywhere (0 at φ = 90°, 270°, where P goes to infinity); AP itself is never used.
Independent check: ψ̈ = [λ(ε_OA cos φ − ω² sin φ) + ω_AB² sin ψ]/cos ψ from OA sin φ = AB sin ψ.
Elliptic trammel: A the midpoint of BD, B and D in perpendicular guides; P is the fourth corner of the
rectangle on O, B, D, so AP = OA, ε** ≡ 0 and ε_BD = −ε_OA (BD turns the other way).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq


@dataclass(frozen=True)
class CrankLaw:
    """φ(t) of the crank: constant speed ω₀, uniform acceleration ε₀, or ω = ω₀(1 + a sin νt)."""

    kind: str = "constant"
    omega0: float = np.pi / 6
    epsilon0: float = 0.0
    amplitude: float = 0.0
    frequency: float = 1.0
    phi0: float = 0.0

    def at(self, t: np.ndarray):
        """φ, ω, ε at times t (s)."""
        t = np.asarray(t, float)
        if self.kind == "accelerating":
            return (self.phi0 + self.omega0 * t + 0.5 * self.epsilon0 * t**2, self.omega0 + self.epsilon0 * t,
                    np.full_like(t, self.epsilon0))
        if self.kind == "harmonic":
            nu, a = self.frequency, self.amplitude
            return (self.phi0 + self.omega0 * (t + a * (1 - np.cos(nu * t)) / nu),
                    self.omega0 * (1 + a * np.sin(nu * t)), self.omega0 * a * nu * np.cos(nu * t))
        return self.phi0 + self.omega0 * t, np.full_like(t, self.omega0), np.zeros_like(t)

    def turn_time(self) -> float:
        """Time for one full turn of the crank from φ₀."""
        target = self.phi0 + 2 * np.pi
        high = 2 * np.pi / self.omega0
        while self.at(high)[0] < target:
            high *= 2
        return brentq(lambda t: float(self.at(t)[0]) - target, 0.0, high, xtol=1e-14)


def crank_slider(lam: float, length: float, law: CrankLaw, t: np.ndarray) -> dict:
    """Components of ε_AB, ψ̈ by the independent route, ω_AB, 1/AP and the points O, A, B, P."""
    phi, w, eps = law.at(t)
    s, c = np.sin(phi), np.cos(phi)
    sin_psi = lam * s
    cos_psi = np.sqrt(1 - sin_psi**2)
    rod = length / lam
    inv_ap = c / (rod * cos_psi)
    w_ab = w * lam * c / cos_psi
    e_star = eps * lam * c / cos_psi
    e_star2 = w * lam * (-w * s * cos_psi + w_ab * sin_psi * c) / cos_psi**2
    psi_dd = (lam * (eps * c - w**2 * s) + w_ab**2 * sin_psi) / cos_psi
    A = np.stack([length * c, length * s], 1)
    B = np.stack([length * c + rod * cos_psi, 0 * t], 1)
    with np.errstate(divide="ignore", invalid="ignore"):
        distance = np.where(np.abs(inv_ap) > 1e-12, 1 / inv_ap, np.nan)      # signed AP; NaN where P is at infinity
    P = A + distance[:, None] * np.stack([c, s], 1)
    return {"t": t, "phi": phi, "omega": w, "epsilon_crank": eps, "psi": np.arcsin(sin_psi), "omega_coupler": w_ab,
            "inv_AP": inv_ap, "epsilon_star": e_star, "epsilon_star2": e_star2, "epsilon": e_star + e_star2,
            "psi_dd": psi_dd, "points": {"O": np.zeros_like(A), "A": A, "B": B, "P": P}}


def trammel(length: float, law: CrankLaw, t: np.ndarray) -> dict:
    """Elliptic trammel with OA = AB = AD: AP = OA, ε* = ε_OA·OA/AP, ε** = 0, ε_BD = −ε_OA (signed)."""
    phi, w, eps = law.at(t)
    c, s = np.cos(phi), np.sin(phi)
    A = np.stack([length * c, length * s], 1)
    return {"t": t, "phi": phi, "omega": w, "epsilon_crank": eps, "omega_coupler": -w,
            "inv_AP": np.full_like(t, 1 / length), "epsilon_star": -eps, "epsilon_star2": np.zeros_like(t),
            "epsilon": -eps, "psi_dd": -eps,
            "points": {"O": np.zeros_like(A), "A": A, "B": np.stack([2 * length * c, 0 * t], 1),
                       "D": np.stack([0 * t, 2 * length * s], 1), "P": 2 * A}}
