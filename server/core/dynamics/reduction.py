"""Reduced moment of inertia J(φ) and dJ/dφ of a machine, reduced to the crank shaft.

Kinetic-energy equality (Eremyants (1.1)–(1.5), Chaika–Vasylenko (3.22)–(3.23)):

    J(φ) = J_rotor·i² + J₁ + Σ_links [ m_k |V_qSk|² + J_Sk u_k1² ]

with V_qS = dr_S/dφ the velocity analog of a centre of mass, u_k1 = ω_k/ω₁ and
i = ω_motor/ω₁ the transmission ratio.  Differentiating (3.23) (not printed there):

    dJ/dφ = 2 Σ [ m_k V_qSk · V′_qSk + J_Sk u_k1 u′_k1 ]

Both come from the closed-form transfer functions of the kinematics core, so dJ/dφ
is analytic, never a finite difference.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..mechanisms import MECHANISMS


@dataclass(frozen=True)
class Inertias:
    """Masses (kg) and moments of inertia (kg·m²) of the machine's links.

    J1: crank with its shaft and gears, about the crank axis; m2, J_S2: link 2 (rod,
    coupler or block) mass and inertia about its centre of mass S2; m3: slider/yoke
    mass (sine, crank-slider); J3: lever/rocker inertia about its pivot (slotted link,
    four-bar); J_rotor: motor rotor; gear_ratio i = ω_motor/ω_crank.
    """

    J1: float = 0.0
    m2: float = 0.0
    J_S2: float = 0.0
    m3: float = 0.0
    J3: float = 0.0
    J_rotor: float = 0.0
    gear_ratio: float = 1.0


@dataclass
class ReducedInertia:
    """J(φ), dJ/dφ and the contribution of each link (kg·m²)."""

    J: np.ndarray
    dJ: np.ndarray
    parts: dict[str, np.ndarray]

    @property
    def mean(self) -> float:
        """J̄ over a uniform closed grid (trapezoid on a periodic function), Eremyants (3.19)."""
        return float(np.mean(self.J[:-1])) if self.J.size > 1 else float(self.J[0])


def reduced_inertia(mechanism: str, params: dict[str, float], inertias: Inertias,
                    phi: np.ndarray, kinematics=None) -> ReducedInertia:
    """J(φ) and dJ/dφ reduced to the crank by kinetic-energy equality (Eremyants (1.1)–(1.5)), from closed-form
    velocity and acceleration analogs
    (``kinematics``: the mechanism already evaluated at phi, to share one evaluation)."""
    values = (kinematics or MECHANISMS[mechanism].evaluate(params, phi, set())).values
    v, a = values["v_s2"], values["a_s2"]
    constant = inertias.J1 + inertias.J_rotor * inertias.gear_ratio**2
    parts = {"constant": np.full_like(phi, constant),
             "link2_translation": inertias.m2 * np.sum(v * v, axis=1)}
    d_parts = {"link2_translation": 2 * inertias.m2 * np.sum(v * a, axis=1)}
    mech = MECHANISMS[mechanism]
    rotation = mech.link2_rotation
    if rotation:
        u, du = values[rotation], values["d" + rotation]
        parts["link2_rotation"] = inertias.J_S2 * u**2
        d_parts["link2_rotation"] = 2 * inertias.J_S2 * u * du
    link3 = inertias.m3 if mech.link3_translates else inertias.J3
    parts["link3"] = link3 * values["u31"] ** 2
    d_parts["link3"] = 2 * link3 * values["u31"] * values["du31"]
    return ReducedInertia(J=sum(parts.values()), dJ=sum(d_parts.values()), parts=parts)


def textbook_inertia_approximation(mechanism: str, params: dict[str, float], inertias: Inertias,
                                   phi: np.ndarray) -> np.ndarray | None:
    """The textbook's closed forms where it gives them (crank-slider rod mass neglected).

    (Mechanism.textbook_inertia: the crank-slider's (3.36), the sine mechanism's (3.18)); None elsewhere."""
    constant = inertias.J1 + inertias.J_rotor * inertias.gear_ratio**2
    return MECHANISMS[mechanism].textbook_inertia(params, constant, inertias, phi)
