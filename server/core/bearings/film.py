"""Lubricated friction: the Stribeck curve of Chaika–Vasylenko Fig. 2.4 and the fluid-film friction power
(2.15)–(2.19).  SI: μ in Pa·s, ν in m²/s, ω in rad/s, lengths in m, power in W.
"""
from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq

REYNOLDS_TURBULENT = 1000.0        # (2.18): the film is turbulent from Re_ω = 1000 on
BOUNDARY_FRICTION = 0.3            # f ≈ 0.3 in the boundary zone a–b of Fig. 2.4 (§2.3)
# The characteristic λ = μω/p_m where the boundary friction has fallen to 1/e: a standard complement, not in
# the book (Hersey's number μN/P ≈ 15…30 cP·rpm/psi at the transition, McKee; 20 cP·rpm/psi = 3·10⁻⁷).
TRANSITION = 3e-7
FLUID_SHARE = 0.9                  # zone II (fluid) where the film carries 90 % of the friction, our choice


def characteristic(viscosity: float, omega, pressure):
    """Chaika–Vasylenko §2.3: the bearing characteristic λ = μω/p_m (dimensionless)."""
    return viscosity * omega / pressure


def petroff(characteristic_value, relative_clearance: float):
    """The film's friction coefficient f = π·λ·r/h₀: (2.17) with α = 2π, P_f = ω²r³μ·2π·l_z/h₀, divided by the
    friction power of a coefficient f, ω·f·F·r with F = p_m·l_z·2r (Petroff's law); relative_clearance = h₀/r."""
    return math.pi * characteristic_value / relative_clearance


def stribeck(characteristic_value, relative_clearance: float, transition: float = TRANSITION,
             boundary: float = BOUNDARY_FRICTION):
    """f(λ) of Fig. 2.4: the boundary friction fading as the film builds up plus the film's own friction,
    f = f_b·exp(−λ/λ_t) + π·λ·r/h₀.  The book draws the curve and gives f_b ≈ 0.3 and the film's law (2.17);
    the exponential fade and λ_t are a standard illustration (our choice), not the book's."""
    return boundary * np.exp(-np.asarray(characteristic_value) / transition) + petroff(
        np.asarray(characteristic_value), relative_clearance)


def regime_limits(relative_clearance: float, transition: float = TRANSITION,
                  boundary: float = BOUNDARY_FRICTION) -> tuple[float, float]:
    """λ where the boundary zone a–b ends (the contact term has fallen to half of f_b: λ_t·ln 2) and where the
    fluid zone II begins (the film carries FLUID_SHARE of f: f_b·e^(−λ/λ_t) = (1/0.9 − 1)·πλr/h₀, one root, the
    left side falling and the right rising)."""
    first = transition * math.log(2.0)
    gap = lambda lam: boundary * math.exp(-lam / transition) - (1 / FLUID_SHARE - 1) * petroff(lam, relative_clearance)
    high = transition
    while gap(high) > 0:
        high *= 2
    return first, brentq(gap, 0.0, high, xtol=1e-15 * transition, rtol=1e-13)


def regime(characteristic_value: float, limits: tuple[float, float]) -> str:
    """'boundary' (zone a–b), 'mixed' (curve b–c) or 'fluid' (zone II) of Fig. 2.4."""
    if characteristic_value <= limits[0]:
        return "boundary"
    return "mixed" if characteristic_value < limits[1] else "fluid"


def reynolds(omega, radius: float, clearance: float, kinematic_viscosity: float):
    """Chaika–Vasylenko (2.18): Re_ω = V_s·h₀/(2ν) = ω·r·h₀/(2ν) (ν in m²/s here; the book writes mm²/s)."""
    return omega * radius * clearance / (2 * kinematic_viscosity)


def turbulence_factor(reynolds_number):
    """Chaika–Vasylenko (2.19): k_τ = 1 + 0.0525·(0.04·Re_ω)^0.75 for a turbulent film (Re_ω ≥ 1000), 1 below:
    the switch is a jump, k_τ(1000) = 1 + 0.0525·40^0.75 = 1.835."""
    re = np.asarray(reynolds_number, float)
    return np.where(re >= REYNOLDS_TURBULENT, 1 + 0.0525 * (0.04 * re) ** 0.75, 1.0)


def film_power(omega, radius: float, length: float, clearance: float, viscosity: float, wrap: float,
               kinematic_viscosity: float):
    """Chaika–Vasylenko (2.17) laminar, P_f = ω²r³μ·l_z·α/h₀, or (2.19) turbulent, the same times k_τ, chosen by
    Re_ω of (2.18) at each ω.  From (2.16), P_f = ω∫τ·r dA with τ = μωr/h₀ (2.15) over the wrap α·r·l_z
    (the print of (2.16) drops the arm r: ω∫τ dA is a force times an angular speed, W/m)."""
    omega = np.asarray(omega, float)
    re = reynolds(omega, radius, clearance, kinematic_viscosity)
    return omega**2 * radius**3 * viscosity * length * wrap / clearance * turbulence_factor(re), re
