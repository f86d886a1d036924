"""Reduction of a general mechanism to its crank (Eremyants (1.1)–(1.5), general form).

Kinetic-energy equality: J(φ) ω²/2 = Σ_k (m_k v_Sk²/2 + J_Sk ω_k²/2) with v_S = z′_S ω, ω_k = θ′_k ω:

    J(φ) = J_const + Σ_k [ m_k (x′_Sk² + y′_Sk²) + J_Sk θ′_k² ],   J_const = J₁ + J_rotor i²
    dJ/dφ = 2 Σ_k [ m_k (x′_Sk x″_Sk + y′_Sk y″_Sk) + J_Sk θ′_k θ″_k ]         (analytic: the second analogs)

Power equality (Chaika–Vasylenko (3.24)): the reduced moment of a force F at a point P is F·z′_P, of a moment M
on link k it is M θ′_k.  As resisting moments (positive against the crank, as M_c):
    a slider force:  M_c = k(φ) P |w|,  w = Re(z′ e^{−iθ_g})      (Eremyants (3.21): M_c = k P_c |u₃₁|)
        (z′ the block's own velocity analog: the power of an external force on the block)
    a point force:   M_c = −Re(F̄ z′_P) = −P p(x) Re(z′_P ē)      (structure/load_kinematics.py)
    a load moment:   M_c = k(φ) M₀ p(x) |θ′|
    gravity:         M_c = Σ_k m_k g y′_Sk          (its work over a cycle is zero)
Each link's and each load's contribution is kept apart.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .compose import Composition
from .load_kinematics import moment_loads, point_loads
from .masses import MassModel, centre_points, slider_loads


@dataclass
class GeneralInertia:
    """J(φ), dJ/dφ (kg·m², kg·m²/rad) and each link's part of J (``parts``) and of dJ (``slopes``)."""

    J: np.ndarray
    dJ: np.ndarray
    parts: dict[str, np.ndarray]
    slopes: dict[str, np.ndarray]


@dataclass
class GeneralLoads:
    """The reduced resisting moment of the loads, N·m, each load apart (``parts``), and the functions whose
    sign changes are its kinks (the velocity analog of every loaded slider and link: k switches there; of every
    point force that acts on the working stroke only; every diagram's breaks)."""

    phi: np.ndarray
    parts: dict[str, np.ndarray]
    switches: list[np.ndarray] = field(default_factory=list)

    @property
    def total(self) -> np.ndarray:
        """M_c(φ) = Σ of the parts: each load reduced by power equality, M = −F·V_q or −M·θ′
        (Chaika–Vasylenko (3.24))."""
        return sum(self.parts.values(), np.zeros(self.phi.shape))


def reduced_inertia(mechanism, comp: Composition, model: MassModel, constant: float,
                    centres: list | None = None) -> GeneralInertia:
    """J(φ) and dJ/dφ of the linkage ``comp`` with the mass model, plus ``constant`` = J₁ + J_rotor i²
    (``centres``: masses.centre_points on ``comp``, to share them)."""
    centres = centres if centres is not None else centre_points(comp, model)
    parts = {"constant": np.full(comp.phi.shape, float(constant))}
    slopes = {"constant": np.zeros(comp.phi.shape)}
    for (s, angle), item in zip(centres, model.links):
        v, a, w, dw = s.d1, s.d2, angle.d1, angle.d2
        parts[f"link {item.link}"] = item.mass * (v.real**2 + v.imag**2) + item.inertia * w**2
        slopes[f"link {item.link}"] = 2 * (item.mass * (v.real * a.real + v.imag * a.imag) + item.inertia * w * dw)
    return GeneralInertia(sum(parts.values()), sum(slopes.values()), parts, slopes)


def reduced_loads(mechanism, comp: Composition, model: MassModel, centres: list | None = None) -> GeneralLoads:
    """M_c(φ) of the slider forces, point forces, load moments and gravity, each apart (keys "force E/ram",
    "force K" (a point force's label), "moment 3", "gravity"; ``centres`` as for ``reduced_inertia``)."""
    n = comp.phi.shape
    parts, switches = {}, []
    for load in slider_loads(comp, model):           # −F·v/ω = k P |w|
        name = f"force {load.force.joint}"
        velocity = comp.links[load.link][0].d1
        parts[name] = parts.get(name, np.zeros(n)) - (np.conj(load.vector) * velocity).real
        switches += load.switches()
    for load in point_loads(comp, model):            # −F·z′_P
        name = f"force {load.force.label}"
        parts[name] = parts.get(name, np.zeros(n)) - (np.conj(load.vector) * load.point.d1).real
        switches += load.switches()
    for load in moment_loads(comp, model):           # −M θ′ = k M₀ p(x) |θ′|
        name = f"moment {load.item.link}"
        parts[name] = parts.get(name, np.zeros(n)) - load.moment * load.rate
        switches += load.switches()
    if model.gravity and any(item.mass for item in model.links):
        centres = centres if centres is not None else centre_points(comp, model)
        parts["gravity"] = model.gravity * sum(item.mass * s.d1.imag for (s, _), item in zip(centres, model.links))
    return GeneralLoads(comp.phi, parts, switches)
