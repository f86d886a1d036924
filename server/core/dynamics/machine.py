"""A machine: motor → transmission ratio i → mechanism with its masses, load and friction.

The equation of motion of the one-mass model reduced to the crank (Eremyants (1.13), (3.22)):

    J(φ) ε + ½ J′(φ) ω² = M_д(φ, ω) − M_c(φ, ω),   or with T = Jω²/2:   dT/dφ = M_д − M_c

Every φ-dependent quantity is tabulated once per parameter change on the integration
nodes (vectorised over φ); what depends on ω is the motor's speed characteristic and the
viscous friction β ω S(φ), evaluated in the integration loop.

The φ-dependent moments are smooth except at a few angles, the kinks: an output's reversal (the load's k
switches and |u₃₁| has a corner), a friction term's own corner, an indicator diagram's change of stroke and
its inner points, a stroke limiter's jump. A fixed-step Runge–Kutta step across one is only first or
second order, and the Richardson estimate that assumes fourth order is then optimistic (RK4 across a
corner of the load gave 12× the estimated error). ``Machine.kinks`` finds them as the zeros of the
functions the load, the motor and the mechanism name (``switching``), so that the integrator can put
every one on a node.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..mechanisms import MECHANISMS, Notice
from .brackets import own_rows, refine_zeros
from .kept import Kept
from .motors import Motor, driving_moment, indicator_switches, table_moment, table_switches
from .reduction import Inertias, reduced_inertia
from .resistance import Load, resisting_moment


KINK_SCAN = 4096      # samples per turn on which the switching functions are scanned for sign changes
KINK_MERGE = 1e-12    # rad: kinks closer than this are one (the refinement leaves them ~1e-15 apart)
KINKS_KEPT = 512       # machines' kinks kept per process (a slider's family shares them: see Machine.kinks)
_kinks_found = Kept(KINKS_KEPT)


def read_only(array: np.ndarray) -> np.ndarray:
    """The array, made read-only (it is kept and shared across requests)."""
    array.flags.writeable = False
    return array


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
    starts: np.ndarray | None = None    # the node where each step starts (None: 2k, one uniform run of steps)
    kink_nodes: np.ndarray | None = None  # which step nodes are kinks (None: none)

    def part(self, nodes: slice) -> Tables:
        """The tables on a slice of the nodes (of a uniform run of steps)."""
        return Tables(self.phi[nodes], self.J[nodes], self.dJ[nodes], self.drive_phi[nodes], self.useful[nodes],
                      self.dry[nodes], self.sliding[nodes], self.notices, self.balancing_moment)

    @property
    def step_nodes(self) -> np.ndarray:
        """Indices of the step nodes: where each step starts, and the last node. A step runs over the nodes
        s, s + 1 (half step), s + 2; at a kink the next step starts on a node of its own, at the same angle,
        with the values from its own side."""
        starts = np.arange(0, self.phi.size - 1, 2) if self.starts is None else self.starts
        return np.append(starts, self.phi.size - 1)

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
    # what one answer asks of the machine more than once (its kinks, a level's tables), kept for the machine's
    # life: the steady cycle, the start-up and their error estimates share levels
    memo: dict = field(default_factory=dict, compare=False, repr=False)

    @property
    def speed_dependent(self) -> bool:
        """True when a moment depends on ω: then the ODE path; otherwise the energy integral."""
        return self.motor.speed_dependent or self.load.beta > 0

    @property
    def lossless(self) -> bool:
        """No friction of any kind (the load's f and β zero, its friction terms the consistent ones): the driving
        work over a steady cycle is the useful work, η = 1 by construction."""
        return self.load.f == 0 and self.load.beta == 0 and self.load.convention == "consistent"

    def cycle(self) -> float:
        return max(MECHANISMS[self.mechanism].cycle(self.params), self.motor.cycle())

    def linkage_notices(self) -> list[Notice]:
        """What the motion and the flywheel say of the linkage itself (a general mechanism's change points)."""
        return []

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
        elif self.motor.kind == "table":                # M_P(φ₁) given at the crank: no gear to reduce it by
            drive = table_moment(self.motor, phi)
        else:
            drive = np.zeros_like(phi)
        sliding = resisting.viscous / self.load.beta if self.load.beta else np.zeros_like(phi)
        return Tables(phi, inertia.J, inertia.dJ, drive, resisting.useful, resisting.dry, sliding,
                      resisting.notices)

    def switching(self, phi: np.ndarray) -> np.ndarray:
        """The functions whose sign changes are the kinks of the φ-dependent moments, one row each: the
        load's (resistance.py: u₃₁ and the arguments of its friction terms) and an indicator diagram's."""
        kinematics = MECHANISMS[self.mechanism].evaluate(self.params, phi, set())
        rows = resisting_moment(self.mechanism, self.params, self.load, phi, 1.0, kinematics).switches
        if self.motor.kind == "indicator":
            rows = rows + indicator_switches(MECHANISMS[self.mechanism], self.params, phi, kinematics)
        if self.motor.kind == "table":
            rows = rows + table_switches(self.motor, phi)
        return np.array(rows)

    def kinks(self) -> np.ndarray:
        """The kinks in [0, Φ), sorted (``find_kinks``; read-only). They depend on the mechanism, the load and
        whether an indicator diagram drives it, not on the masses or the motor's speeds: machines that differ
        only there (a slider's family over J, ω or a motor's torque) share them, the last KINKS_KEPT kept."""
        return _kinks_found.kept(self.kinks_key(), lambda: read_only(self.find_kinks()))

    def kinks_key(self) -> tuple:
        """What the kinks depend on (``kinks``)."""
        return (self.mechanism, tuple(sorted(self.params.items())), self.load, self.motor.kind == "indicator",
                self.motor.table_phi, self.cycle())

    def jumps(self) -> list[float]:
        """The mechanism's jumps (a stroke limiter), rad."""
        return MECHANISMS[self.mechanism].jumps(self.params)

    def find_kinks(self) -> np.ndarray:
        """The kinks in [0, Φ), sorted: the mechanism's jumps and every sign change of ``switching`` over the
        cycle, bracketed on KINK_SCAN samples per turn and refined, all brackets at once, to a few doubles
        (brackets.refine_zeros). A kink within KINK_MERGE of another or of the cycle's ends is that one."""
        cycle = self.cycle()
        phi = np.linspace(0.0, cycle, KINK_SCAN * math.ceil(cycle / (2 * np.pi) - 1e-9) + 1)
        values = self.switching(phi)
        with np.errstate(invalid="ignore"):
            rows, cols = np.nonzero((values[:, :-1] * values[:, 1:] < 0) | (values[:, :-1] == 0))
        found = refine_zeros(lambda index, at: own_rows(self.switching(at.ravel()), rows[index], at.shape),
                             phi[cols], phi[cols + 1], values[rows, cols], values[rows, cols + 1])
        found = np.concatenate([found, self.jumps()])
        found = np.sort(np.where((found <= KINK_MERGE) | (found >= cycle - KINK_MERGE), 0.0, found))
        return found[np.append(True, np.diff(found) > KINK_MERGE)] if found.size else found

    def speed_moment(self, omega: float, sliding: float) -> tuple[float, float]:
        """ω-dependent moment and its derivative ∂/∂ω: i·M(iω) of the motor minus β ω S(φ)."""
        i = self.inertias.gear_ratio
        moment, slope = -self.load.beta * omega * sliding, -self.load.beta * sliding
        if self.motor.speed_dependent:
            torque, torque_slope = self.motor.torque(i * omega)
            moment += i * torque
            slope += i * i * torque_slope
        return moment, slope
