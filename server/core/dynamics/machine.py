"""A machine: motor → transmission ratio i → mechanism with its masses, load and friction.

The equation of motion of the one-mass model reduced to the crank (seed 000 (1.13), (3.22)):

    J(φ) ε + ½ J′(φ) ω² = M_д(φ, ω) − M_c(φ, ω),   or with T = Jω²/2:   dT/dφ = M_д − M_c

Every φ-dependent quantity is tabulated once per parameter change on the integration
nodes (vectorised over φ); what depends on ω is the motor's speed characteristic and the
viscous friction β ω S(φ), evaluated in the integration loop.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..mechanisms import MECHANISMS, Notice
from .motors import Motor, driving_moment
from .reduction import Inertias, reduced_inertia
from .resistance import Load, resisting_moment


@dataclass
class Tables:
    """φ-dependent parts of the equation of motion on a set of nodes (SI units)."""

    phi: np.ndarray
    J: np.ndarray
    dJ: np.ndarray
    drive_phi: np.ndarray      # M_д part that depends on φ only (indicator engine), N·m
    useful: np.ndarray         # useful resisting moment, N·m
    dry: np.ndarray            # dry-friction moment, N·m
    sliding: np.ndarray        # S(φ): viscous moment is β ω S(φ)
    notices: list[Notice]
    balancing_moment: float = 0.0   # constant crank moment added to balance the cycle work, N·m

    def part(self, nodes: slice) -> Tables:
        """The tables on a slice of the nodes."""
        return Tables(self.phi[nodes], self.J[nodes], self.dJ[nodes], self.drive_phi[nodes], self.useful[nodes],
                      self.dry[nodes], self.sliding[nodes], self.notices, self.balancing_moment)

    @property
    def net_phi(self) -> np.ndarray:
        """M_д,φ − M_c,φ: everything that does not depend on ω."""
        return self.drive_phi - self.useful - self.dry


@dataclass(frozen=True)
class Machine:
    mechanism: str
    params: dict
    inertias: Inertias
    load: Load
    motor: Motor

    @property
    def speed_dependent(self) -> bool:
        """True when a moment depends on ω: then the ODE path; otherwise the energy integral."""
        return self.motor.speed_dependent or self.load.beta > 0

    def cycle(self) -> float:
        return max(MECHANISMS[self.mechanism].cycle(self.params), self.motor.cycle())

    def tables(self, phi: np.ndarray) -> Tables:
        """The tables at phi from one evaluation of the mechanism there."""
        kinematics = MECHANISMS[self.mechanism].evaluate(self.params, phi, set())
        inertia = reduced_inertia(self.mechanism, self.params, self.inertias, phi, kinematics)
        resisting = resisting_moment(self.mechanism, self.params, self.load, phi, 1.0, kinematics)
        if self.motor.kind == "indicator":
            drive = driving_moment(self.motor, self.mechanism, self.params, phi, 0.0, self.inertias.gear_ratio,
                                   kinematics)
        elif self.motor.kind == "constant":
            drive = np.full_like(phi, self.motor.M0 * self.inertias.gear_ratio)
        else:
            drive = np.zeros_like(phi)
        sliding = resisting.viscous / self.load.beta if self.load.beta else np.zeros_like(phi)
        return Tables(phi, inertia.J, inertia.dJ, drive, resisting.useful, resisting.dry, sliding,
                      resisting.notices)

    def speed_moment(self, omega: float, sliding: float) -> tuple[float, float]:
        """ω-dependent moment and its derivative ∂/∂ω: i·M(iω) of the motor minus β ω S(φ)."""
        i = self.inertias.gear_ratio
        moment, slope = -self.load.beta * omega * sliding, -self.load.beta * sliding
        if self.motor.speed_dependent:
            torque, torque_slope = self.motor.torque(i * omega)
            moment += i * torque
            slope += i * i * torque_slope
        return moment, slope
