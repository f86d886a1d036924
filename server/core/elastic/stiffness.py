"""Reduced stiffness of an elastic linkage, Eremyants (1.24)–(1.29), (1.33)–(1.34); Drakunov–Tuleshova (2).

The compliances in series reduce to the crank as e = e₁ + e₂λ₁₂² + e₃u₁₃², with λ₁₂ = 1/(l₁ sin θ₁₂)
(θ₁₂ the angle between crank and rod/coupler) and, for the four-bar, u₁₃ = 1/u₃₁ written through
the coupler–rocker angle θ₂₃.  At the dead positions sin θ₁₂ = 0 and e → ∞, so the stiffness is
computed in the finite form (Drakunov–Tuleshova (2))

    c = l₁² S/Δ,   Δ = e₁ l₁² S + e₂ + e₃ l₃² R,   S = sin²θ₁₂,  R = sin²θ₂₃

and dc/dφ = (N′ − cΔ′)/Δ with N = l₁²S, Δ′ = e₁N′ + e₃l₃²R′ (Drakunov–Tuleshova, unnumbered, checked there).
e₁ = L₁/(G I_p1) crank-shaft torsion (rad/(N·m)); e₂ = l₂/(E F₂) rod tension/compression (m/N);
e₃ = L₃/(G I_p3) rocker-shaft torsion (rad/(N·m)).  The crank-slider's sin θ₁₂ is sin(φ − ψ) in the
convention of §2.3 (the textbook's sin(φ + ψ) counts φ from the outer dead centre).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..mechanisms import MECHANISMS


@dataclass(frozen=True)
class Compliances:
    e1: float = 0.0      # crank-shaft torsion, rad/(N·m)
    e2: float = 0.0      # rod (coupler) tension/compression, m/N
    e3: float = 0.0      # rocker-shaft torsion, rad/(N·m) (four-bar)


def link_angles(mechanism: str, values: dict) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """θ₁₂ = crank − rod angle and θ₂₃ = rod − rocker angle (CCW), with their derivatives in φ."""
    return MECHANISMS[mechanism].elastic_angles(values)


def linkage_stiffness(mechanism: str, params: dict, compliances: Compliances, phi: np.ndarray):
    """c(φ) in N·m/rad (module docstring: Eremyants (1.24)–(1.29), (1.33)–(1.34), Drakunov–Tuleshova (2)), dc/dφ and
    the compliance e(φ) = 1/c (inf at the dead positions)."""
    values = MECHANISMS[mechanism].evaluate(params, phi, set()).values | {"phi": phi}
    theta12, d12, theta23, d23 = link_angles(mechanism, values)
    l1, l3 = params["l1"], params.get("l3", 0.0)
    S, dS = np.sin(theta12) ** 2, np.sin(2 * theta12) * d12
    R, dR = np.sin(theta23) ** 2, np.sin(2 * theta23) * d23
    N, dN = l1**2 * S, l1**2 * dS
    delta = compliances.e1 * N + compliances.e2 + compliances.e3 * l3**2 * R
    c = N / delta
    dc = (dN - c * (compliances.e1 * dN + compliances.e3 * l3**2 * dR)) / delta
    with np.errstate(divide="ignore"):
        e = np.where(N > 0, delta / np.where(N > 0, N, 1.0), np.inf)
    return c, dc, e


def bearing_stiffness(load: float, balls: int, r_inner: float, r_outer: float, young: float = 2.1e11,
                      poisson: float = 0.3) -> float:
    """Radial stiffness of a ball bearing under its largest reaction R_m, N/m (Eremyants (1.44)):
    c_n = 3.34 (z k_B)^{2/3} R_m^{1/3}/(1 + ∛(r₁/r₂)),  k_B = 2E√r₁/(3(1 − μ²))."""
    k_b = 2 * young * np.sqrt(r_inner) / (3 * (1 - poisson**2))
    return float(3.34 * (balls * k_b) ** (2 / 3) * load ** (1 / 3) / (1 + (r_inner / r_outer) ** (1 / 3)))
