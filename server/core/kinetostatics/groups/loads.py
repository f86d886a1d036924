"""The loads on every moving link of a general mechanism (Chaika–Vasylenko (3.1), (3.9)).

d'Alembert's inertia loads (3.1): F_in = −m a_S, M_in = −J_S ε, with a_S = z″_S ω₁² + z′_S ε₁ and
ε = θ″ω₁² + θ′ε₁ from the analogs (the crank's ω₁ > 0 along its rotation, ε₁ its angular acceleration);
the weight G = −m g ĵ at S; the useful loads of the mass model (structure/masses.py): slider forces along their
guides, forces at points of links (structure/load_kinematics.py) and moments on links.  Each load is kept apart, with the
velocity analog of its point (of its link's rotation for a couple), for the free-body diagrams and the power
check; the equilibrium needs per link only the resultant force and its moment about the frame's origin.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...structure.compose import Composition
from ...structure.load_kinematics import moment_loads, point_loads
from ...structure.masses import MassModel, centre_kinematics, slider_loads
from ...structure.state import cross


@dataclass(frozen=True)
class Load:
    """A force F at z on ``link``, or a couple M (``force`` None); ``rate``: the velocity analog z′ of the point
    (complex), or θ′ of the link for a couple.  Arrays over φ."""

    name: str
    link: int
    kind: str                         # gravity, inertia, useful
    z: np.ndarray | None
    force: np.ndarray | None
    moment: np.ndarray | None
    rate: np.ndarray


def link_loads(mechanism, comp: Composition, model: MassModel, omega: float, epsilon: float) -> list[Load]:
    """Every load on every moving link."""
    loads = []
    kin = centre_kinematics(mechanism, model, comp.phi, comp)
    complex_of = lambda xy: xy[0] + 1j * xy[1]
    for row, item in enumerate(model.links):
        z, d1, d2 = complex_of(kin.positions[row]), complex_of(kin.first[row]), complex_of(kin.second[row])
        eps = kin.theta_d2[row] * omega**2 + kin.theta_d1[row] * epsilon
        k = item.link
        loads += [Load(f"G{k}", k, "gravity", z, np.full(z.shape, -1j * model.gravity * item.mass), None, d1),
                  Load(f"F_in{k}", k, "inertia", z, -item.mass * (d2 * omega**2 + d1 * epsilon), None, d1),
                  Load(f"M_in{k}", k, "inertia", None, None, -item.inertia * eps, kin.theta_d1[row])]
    for load in slider_loads(comp, model):
        origin = comp.links[load.link][0]
        loads.append(Load(f"F_{load.force.joint}", load.link, "useful", origin.z, load.vector, None, origin.d1))
    for load in point_loads(comp, model):
        loads.append(Load(f"F_{load.force.label}", load.force.link, "useful", load.point.z, load.vector, None,
                          load.point.d1))
    for load in moment_loads(comp, model):
        loads.append(Load(f"M_{load.item.link}", load.item.link, "useful", None, None, load.moment, load.rate))
    return loads


def resultants(loads: list[Load], links, n: int) -> tuple[dict, dict]:
    """Σ F and Σ M about the origin per link."""
    force = {k: np.zeros(n, complex) for k in links}
    moment = {k: np.zeros(n) for k in links}
    for load in loads:
        if load.force is not None:
            force[load.link] = force[load.link] + load.force
            moment[load.link] = moment[load.link] + cross(load.z, load.force)
        else:
            moment[load.link] = moment[load.link] + load.moment
    return force, moment


def power_moment(loads: list[Load]) -> np.ndarray:
    """The reduced moment of all the loads, along ω₁, by power equality (Chaika–Vasylenko (3.24)) with the
    sign of a balancing moment: M = −Σ (F·z′ + M θ′); the frictionless balancing moment must equal it."""
    total = 0.0
    for load in loads:
        total = total + ((np.conj(load.force) * load.rate).real if load.force is not None
                         else load.moment * load.rate)
    return -total
