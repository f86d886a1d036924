"""The two components of a coupler's angular acceleration (Kuleshova–Tokhtar (1)–(4)).

    ε = d/dt (V_A/AP) = ε* + ε**   (1), (2),   ε* = (dV_A/dt)/AP = a_A^τ/AP   (3),
    ε** = V_A·d(1/AP)/dt   (4)

beside the paper's classical method (a), the vector polygon a_B = a_A + a^n_BA + a^τ_BA, ε_AB = a^τ_BA/AB
(``vector_polygon``: an independent route through the velocity and acceleration polygons).

One convention for both mechanisms and for the transfer-function scenes (Eremyants, Fig. 2.2): O at the
origin, the slider's guide along the x axis; φ is measured from that line, φ = 0 with the crank pointing
away from the slider (inner dead centre of the crank-slider), A = OA(−cos φ, sin φ); the angle and the
angular speed of every link are positive in the sense the crank turns (clockwise in the drawing).  AP is
signed, counted from A towards O: positive when P lies on the crank's side of A (the rod turns with the
crank), so that ω_coupler = V_A/AP with V_A = ω·OA in both mechanisms.

Central crank-slider, λ = OA/AB < 1 (the paper's λ; the textbook's l₂/l₁ is 1/λ): B = (−OA cos φ +
AB cos ψ, 0), sin ψ = λ sin φ, ψ the rod's angle in the crank's sense.  P, the instantaneous centre of
AB, is where line OA meets the normal to the guide at B, so

    1/AP = cos φ/(AB cos ψ),   ω_AB = ψ̇ = ω λ cos φ/cos ψ = V_A/AP,
    ε* = ε_OA λ cos φ/cos ψ,   ε** = ω λ(−ω sin φ cos ψ + ω_AB sin ψ cos φ)/cos²ψ.

1/AP is finite everywhere (0 at φ = 90°, 270°, where P goes to infinity); AP itself is never used.
Independent check: ψ̈ = [λ(ε_OA cos φ − ω² sin φ) + ω_AB² sin ψ]/cos ψ from OA sin φ = AB sin ψ.
Elliptic trammel: A the midpoint of BD, B and D in perpendicular guides (B along x, D along y); P is the
fourth corner of the rectangle on O, B, D, P = 2A, so AP = −OA (P beyond A), ε** ≡ 0 and
ω_BD = −ω_OA, ε_BD = −ε_OA (BD turns against the crank).
"""
from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from .numerics import Numerics


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
    """Kuleshova–Tokhtar example 2: ε_AB = ε* + ε** by (3), (4) (module docstring), ψ̈ by the independent route,
    ω_AB, 1/AP and the points O, A, B, P."""
    started = time.perf_counter()
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
    A = np.stack([-length * c, length * s], 1)
    x_b = -length * c + rod * cos_psi
    with np.errstate(divide="ignore", invalid="ignore"):     # P on line OA above B; NaN where P is at infinity
        P = np.stack([x_b, np.where(np.abs(c) > 1e-12, -x_b * s / c, np.nan)], 1)
    P[np.isnan(P[:, 1])] = np.nan
    B = np.stack([x_b, 0 * t], 1)
    return {"t": t, "phi": phi, "omega": w, "epsilon_crank": eps, "psi": np.arcsin(sin_psi), "omega_coupler": w_ab,
            "inv_AP": inv_ap, "epsilon_star": e_star, "epsilon_star2": e_star2, "epsilon": e_star + e_star2,
            "psi_dd": psi_dd, "points": {"O": np.zeros_like(A), "A": A, "B": B, "P": P},
            "polygon": vector_polygon(A, B - A, w, eps, np.ones(t.size, bool), e_star + e_star2),
            "numerics": _numerics(e_star + e_star2, psi_dd, started)}


def trammel(length: float, law: CrankLaw, t: np.ndarray) -> dict:
    """Kuleshova–Tokhtar example 1, the elliptic trammel with OA = AB = AD: AP = −OA, ε* = ε_OA·OA/AP = −ε_OA,
    ε** = 0 (signed as above)."""
    started = time.perf_counter()
    phi, w, eps = law.at(t)
    c, s = np.cos(phi), np.sin(phi)
    A = np.stack([-length * c, length * s], 1)
    psi_dd = -eps                                    # the angle of BD in the crank's sense is −φ (+ const)
    B, D = np.stack([-2 * length * c, 0 * t], 1), np.stack([0 * t, 2 * length * s], 1)
    along_x = np.abs(c) >= np.abs(s)    # the better conditioned guide: B's (y = 0) or D's (x = 0)
    return {"t": t, "phi": phi, "omega": w, "epsilon_crank": eps, "omega_coupler": -w,
            "inv_AP": np.full_like(t, -1 / length), "epsilon_star": -eps, "epsilon_star2": np.zeros_like(t),
            "epsilon": -eps, "psi_dd": psi_dd,
            "points": {"O": np.zeros_like(A), "A": A, "B": B, "D": D, "P": 2 * A},
            "polygon": vector_polygon(A, np.where(along_x[:, None], B - A, D - A), w, eps, along_x, -eps),
            "numerics": _numerics(-eps, psi_dd, started)}


def vector_polygon(A: np.ndarray, r: np.ndarray, w: np.ndarray, eps: np.ndarray, along_x: np.ndarray,
                   decomposed: np.ndarray) -> dict:
    """Kuleshova–Tokhtar's method (a), the velocity and acceleration polygons of the coupler from its pole A
    (crank O→A turning clockwise at ω, ε; r = the coupler's point B − A, B on the guide y = 0 where
    ``along_x``, else on the guide x = 0), in counter-clockwise components θ̇₂, θ̈₂ of the coupler:

        V_B = V_A + ω₂ k × r,   a_B = a_A + a^n_BA + a^τ_BA,   a^n_BA = −ω₂² r,   a^τ_BA = θ̈₂ k × r,
        a_A = −ε k × OA − ω² OA   (the crank's clockwise ω, ε),

    the guide's normal component of V_B and a_B zero gives ω₂ and θ̈₂; ε_AB = a^τ_BA/AB, returned in the
    crank's sense (clockwise positive) as every angular quantity here, with |a^n_BA|, |a^τ_BA| in m/s² and
    ``difference``, the largest |ε_AB − (ε* + ε**)| against the decomposition (1)–(4) (``decomposed``), s⁻²."""
    k_cross = lambda v: np.stack([-v[:, 1], v[:, 0]], 1)   # noqa: E731  (k × v in the plane)
    v_a = -w[:, None] * k_cross(A)
    a_a = -eps[:, None] * k_cross(A) - (w**2)[:, None] * A
    normal = np.where(along_x, 1, 0)           # the component the guide forbids: y for B on y = 0, x for x = 0
    pick = lambda v: np.where(normal == 1, v[:, 1], v[:, 0])   # noqa: E731
    kr = k_cross(r)
    w2 = -pick(v_a) / pick(kr)
    theta_dd = (pick((w2**2)[:, None] * r) - pick(a_a)) / pick(kr)
    length = np.hypot(r[:, 0], r[:, 1])
    return {"epsilon": -theta_dd, "a_n_BA": w2**2 * length, "a_tau_BA": np.abs(theta_dd) * length,
            "omega": -w2, "difference": float(np.max(np.abs(-theta_dd - decomposed))) if A.size else 0.0}


def _numerics(epsilon: np.ndarray, psi_dd: np.ndarray, started: float) -> dict:
    """Closed forms at each instant; the error estimate is the largest relative difference between the
    two routes, ε* + ε** and ψ̈ (rounding only: both are exact)."""
    scale = float(np.max(np.abs(psi_dd))) if psi_dd.size else 0.0
    difference = float(np.max(np.abs(epsilon - psi_dd))) if psi_dd.size else 0.0
    return Numerics(method="closed forms at each instant: ε* + ε** from 1/AP, checked against ψ̈ from "
                           "OA sin φ = AB sin ψ; the error estimate is their largest relative difference",
                    code="angular_closed_forms", steps=int(epsilon.size),
                    runtime_ms=1e3 * (time.perf_counter() - started),
                    error_estimate=difference / scale if scale > 0 else difference).as_dict()
