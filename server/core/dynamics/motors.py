"""Driving moment M_д(φ, ω) of the motor, reduced to the crank shaft (ω in rad/s of the crank).

With the transmission ratio i = ω_motor/ω₁ a motor torque M(ω_m) at ω_m = iω reduces
to i·M(iω) (power equality, Eremyants (1.17)).  Characteristics:

    constant     M = M₀
    linear       M = M₀ − b ω_m                                      Eremyants §3.1
    induction    M = M_н (ω_с − ω_m)/(ω_с − ω_н)  (stable branch, linearised)  Lecture 10 (L30)
    kloss        M = 2M_к/(s/s_к + s_к/s),  s = (ω_с − ω_m)/ω_с      standard addition, not in the lecture
    indicator    M = −p(x) A_p u₃₁ of the crank-slider's piston        Lecture 10 (L15)–(L17)
    table        M_P(φ₁) at the crank, a free law given as points (φ_j, M_j) over one turn, linear between
                 them and periodic (the last point joins the first)   Chaika–Vasylenko §3.4, step 9

The indicator diagram gives p/p_max at 11 equally spaced piston positions x/H from top dead
centre for the expansion and the compression stroke; p between them by monotone (PCHIP)
interpolation.  φ = 0 is the inner (bottom) dead centre: a two-stroke cycle compresses on
0…π and expands on π…2π; a four-stroke cycle then exhausts and draws in at zero gauge pressure.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np
from scipy.interpolate import PchipInterpolator

from ..mechanisms import MECHANISMS

KINDS = ("constant", "linear", "induction", "kloss", "indicator", "table")
TABLE_POINTS = (2, 361)         # a free law M_P(φ₁): at least 2 points, at most one a degree
INDICATOR_POINTS = 11


def polytropic_diagram(clearance: float = 0.1, exponent: float = 1.3,
                       p_ratio_intake: float = 0.1 / 4.4) -> tuple[list[float], list[float]]:
    """An assumed, plausible indicator diagram (p/p_max) of expansion and compression over x/H = 0…1."""
    x = np.linspace(0.0, 1.0, INDICATOR_POINTS)
    expansion = (clearance / (clearance + x)) ** exponent
    compression = p_ratio_intake * ((1 + clearance) / (clearance + x)) ** exponent
    return expansion.round(4).tolist(), compression.round(4).tolist()


@dataclass(frozen=True)
class Motor:
    """Motor characteristic; torques in N·m and speeds in rad/s at the motor shaft."""

    kind: str = "constant"
    M0: float = 0.0                 # constant / linear: stall torque
    b: float = 0.0                  # linear: slope, N·m·s/rad
    M_nominal: float = 0.0          # induction: nominal torque M_н
    omega_nominal: float = 0.0      # induction: nominal speed ω_н
    omega_sync: float = 0.0         # induction, kloss: synchronous speed ω_с
    M_max: float = 0.0              # kloss: breakdown torque M_к
    s_critical: float = 0.1         # kloss: critical slip s_к
    p_max: float = 0.0              # indicator: maximum cylinder pressure, Pa
    piston_diameter: float = 0.0    # indicator: m
    expansion: tuple[float, ...] = field(default_factory=lambda: tuple(polytropic_diagram()[0]))
    compression: tuple[float, ...] = field(default_factory=lambda: tuple(polytropic_diagram()[1]))
    strokes: int = 2                # indicator: 2 or 4 strokes per cycle
    table_phi: tuple[float, ...] = ()     # table: crank angles φ_j in [0, 2π), increasing, rad
    table_moment: tuple[float, ...] = ()  # table: M_P(φ_j) at the crank shaft, N·m

    @property
    def speed_dependent(self) -> bool:
        return self.kind in ("linear", "induction", "kloss")

    def cycle(self) -> float:
        return 2 * np.pi * (self.strokes // 2) if self.kind == "indicator" else 2 * np.pi

    def max_torque(self) -> float:
        """The largest torque the characteristic offers at the motor shaft (for the stall check)."""
        if self.kind in ("constant", "linear"):
            return self.M0
        if self.kind == "induction":
            return self.M_nominal * self.omega_sync / (self.omega_sync - self.omega_nominal)
        if self.kind == "kloss":
            return self.M_max
        if self.kind == "table":
            return max(self.table_moment)
        return np.inf

    def torque(self, w):
        """Motor-shaft torque M and its slope dM/dω_m at motor speed ω_m (float or array):
        linear M₀ − bω (Eremyants §3.1), induction linearised (Lecture 10 (L30)),
        Kloss 2M_к/(s/s_к + s_к/s) (a standard addition)."""
        if self.kind == "constant":
            return self.M0 + 0 * w, 0 * w
        if self.kind == "linear":
            return self.M0 - self.b * w, -self.b + 0 * w
        if self.kind == "induction":
            slope = -self.M_nominal / (self.omega_sync - self.omega_nominal)
            return slope * (w - self.omega_sync), slope + 0 * w
        if self.kind == "kloss":
            s, sk = (self.omega_sync - w) / self.omega_sync, self.s_critical
            denominator = s * s + sk * sk
            torque = 2 * self.M_max * s * sk / denominator
            return torque, -2 * self.M_max * sk * (sk * sk - s * s) / denominator**2 / self.omega_sync
        raise ValueError(f"the {self.kind} motor has no speed characteristic")


def driving_moment(motor: Motor, mechanism: str, params: dict[str, float], phi: np.ndarray,
                   omega: np.ndarray | float, gear_ratio: float = 1.0, kinematics=None) -> np.ndarray:
    """M_д at crank angles φ and crank speed ω, reduced to the crank shaft (N·m): i·M(iω) (Eremyants (1.17)) or the
    indicator moment (Lecture 10 (L17)); ``kinematics``: the
    mechanism already evaluated at phi, to share one evaluation."""
    if motor.kind == "table":
        return table_moment(motor, phi)
    if motor.kind != "indicator":
        return gear_ratio * motor.torque(gear_ratio * np.asarray(omega, float) + 0 * phi)[0]
    return indicator_moment(motor, mechanism, params, phi, kinematics)


@lru_cache(maxsize=64)
def diagram_curve(ratios: tuple[float, ...]) -> PchipInterpolator:
    """p/p_max over x/H = 0…1 through the diagram's equally spaced points (built once per diagram)."""
    return PchipInterpolator(np.linspace(0.0, 1.0, INDICATOR_POINTS), ratios)


def gas_force(motor: Motor, mechanism, params: dict[str, float], phi: np.ndarray, kinematics=None) -> np.ndarray:
    """Gas force on the crank-slider's piston, N, from the indicator diagram (Lecture 10 (L15)–(L16)):
    p/p_max interpolated over the piston travel from top dead centre; it pushes towards the crank."""
    x = mechanism.piston_travel(params, phi, kinematics)
    expansion = diagram_curve(motor.expansion)(x)
    compression = diagram_curve(motor.compression)(x)
    phase = np.mod(phi, motor.cycle()) / np.pi                  # stroke number 0, 1, (2, 3)
    ratio = np.select([phase < 1, phase < 2], [compression, expansion], 0.0)
    return motor.p_max * ratio * np.pi * motor.piston_diameter**2 / 4


def indicator_moment(motor: Motor, mechanism: str, params: dict[str, float], phi: np.ndarray,
                     kinematics=None) -> np.ndarray:
    """M_д = F·V_qC·cos(F, V) with F = p A_p on the piston (Lecture 10 (L17)); gas pushes towards the crank."""
    mech = MECHANISMS[mechanism]
    if not mech.piston:
        raise ValueError("an indicator diagram drives a crank-slider (piston engine) only")
    kinematics = kinematics or mech.evaluate(params, phi, set())
    return -gas_force(motor, mech, params, phi, kinematics) * kinematics.values["u31"]


def indicator_switches(mechanism, params: dict[str, float], phi: np.ndarray, kinematics=None) -> list[np.ndarray]:
    """Functions whose sign changes are where the gas moment has a jump or a corner: a change of stroke
    (φ a multiple of π, sin φ = 0: the other branch of the diagram) and the diagram's inner points
    x/H = 0.1 … 0.9 (the monotone cubic is only once continuously differentiable there)."""
    x = mechanism.piston_travel(params, phi, kinematics)
    return [np.sin(phi)] + [x - j / (INDICATOR_POINTS - 1) for j in range(1, INDICATOR_POINTS - 1)]


def table_moment(motor: Motor, phi: np.ndarray) -> np.ndarray:
    """A free law M_P(φ₁) (Chaika–Vasylenko §3.4, step 9: the driving moment of the transient regime given as a
    function of the crank angle), at the crank shaft, N·m: linear between the table's points, periodic over
    one turn (from the last point back to the first at φ₀ + 2π)."""
    return np.interp(np.mod(np.asarray(phi, float), 2 * np.pi), motor.table_phi, motor.table_moment,
                     period=2 * np.pi)


def table_switches(motor: Motor, phi: np.ndarray) -> list[np.ndarray]:
    """Functions whose sign changes are the corners of a free law M_P(φ₁): sin((φ − φ_j)/2) changes sign at
    φ_j alone within a turn."""
    return [np.sin((np.asarray(phi, float) - node) / 2) for node in motor.table_phi]
