"""The one interface every planar mechanism module implements.

A mechanism is a pure-numeric object: given lengths in metres and crank angles in
radians it returns position functions, the first transfer functions u = ds/dφ and
the second u′ = d²s/dφ² in closed form (Eremyants §2.1), joint coordinates for
drawing, its valid parameter ranges and its special positions.  Nothing here knows
about HTTP or the browser.
"""
from __future__ import annotations

from dataclasses import dataclass, field
import numpy as np

# A friction series whose force passes this many times the load has visibly run away (friction_steps).
DIVERGED = 1e9

TWO_PI = 2.0 * np.pi


class GeometryError(ValueError):
    """Parameters for which the mechanism cannot be assembled or cannot run a full cycle.

    ``field`` names the offending parameter, ``reason`` says why in words (English);
    ``code`` and ``context`` let the interface say the same in Russian or Ukrainian.
    """

    def __init__(self, field: str, reason: str, code: str = "invalid", **context: float | str):
        super().__init__(f"{field}: {reason}")
        self.field = field
        self.reason = reason
        self.code = code
        self.context = context

    def __reduce__(self):
        """Picklable (it crosses from a computing process back to the server)."""
        return _geometry_error, (self.field, self.reason, self.code, self.context)


def _geometry_error(field: str, reason: str, code: str, context: dict) -> GeometryError:
    return GeometryError(field, reason, code, **context)


@dataclass(frozen=True)
class Notice:
    """A warning in words: English ``text``, plus ``code`` and ``context`` for other languages."""

    code: str
    text: str
    context: dict = field(default_factory=dict)


@dataclass(frozen=True)
class ParamSpec:
    """One geometric parameter: name, unit, meaning and the range the scene offers."""

    name: str
    unit: str
    description: str
    default: float
    minimum: float
    maximum: float
    integer: bool = False


@dataclass(frozen=True)
class OutputSpec:
    """One quantity a mechanism can compute, with its unit and meaning."""

    name: str
    unit: str
    description: str


@dataclass(frozen=True)
class SpecialPosition:
    """A special crank angle: dead centre, rocker extreme, change point, smallest μ."""

    kind: str
    phi: float
    description: str
    value: float | None = None

    def as_dict(self) -> dict:
        return {"kind": self.kind, "phi": float(self.phi), "description": self.description,
                "value": None if self.value is None else float(self.value)}


@dataclass
class Evaluation:
    """Everything a mechanism computes at an array of crank angles (SI units)."""

    phi: np.ndarray
    values: dict[str, np.ndarray] = field(default_factory=dict)
    joints: dict[str, np.ndarray] = field(default_factory=dict)
    warnings: list[Notice] = field(default_factory=list)


COMMON_OUTPUTS = (
    OutputSpec("s", "m or rad", "position function of the output link 3 (slider travel or rocker angle)"),
    OutputSpec("u31", "m or 1", "first transfer function u₃₁ = ds/dφ (velocity analog of link 3)"),
    OutputSpec("du31", "m or 1", "second transfer function u′₃₁ = d²s/dφ²"),
    OutputSpec("s2", "m or rad", "position function of the intermediate link 2 (rod/coupler angle or block travel)"),
    OutputSpec("u21", "m or 1", "first transfer function u₂₁ of the intermediate link 2"),
    OutputSpec("du21", "m or 1", "second transfer function u′₂₁ of the intermediate link 2"),
    OutputSpec("chi21", "m", "χ₂₁ = |V_S2|/ω₁, velocity analog of the centre of mass S2 of link 2"),
    OutputSpec("v_s2", "m", "components (x, y) of the velocity analog V_qS2 = dr_S2/dφ"),
    OutputSpec("a_s2", "m", "components (x, y) of the acceleration analog d²r_S2/dφ²"),
    OutputSpec("joints", "m", "joint coordinates (x, y) for drawing the linkage to scale"),
    OutputSpec("special", "rad", "special positions: dead centres, rocker extremes, change points, smallest μ"),
)


def angle_ranges(phi: np.ndarray, mask: np.ndarray) -> list[list[float]]:
    """The stretches of crank angle (degrees, [from, to]) where ``mask`` holds, on an ordered grid."""
    ranges, start = [], None
    for k, inside in enumerate(mask):
        if inside and start is None:
            start = k
        if start is not None and (not inside or k == mask.size - 1):
            end = k if inside else k - 1
            ranges.append([float(np.degrees(phi[start])), float(np.degrees(phi[end]))])
            start = None
    return ranges


def ranges_text(ranges: list[list[float]], decimal: str = ".") -> str:
    """'57.0°–133.0°, 231.0°–307.0°' (with the reader's decimal separator)."""
    return ", ".join(f"{a:.1f}°–{b:.1f}°".replace(".", decimal) for a, b in ranges)


def wrap_angle(phi: float, cycle: float = TWO_PI) -> float:
    """Angle reduced to [0, cycle): within 1e-12 + 1e-5·cycle below the cycle's end is 0 (numpy's isclose with
    atol 1e-12, written out: a scalar's isclose costs more than the special positions' arithmetic)."""
    value = float(np.mod(phi, cycle))
    return 0.0 if abs(value - cycle) <= 1e-12 + 1e-5 * abs(cycle) else value


def point(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Stack coordinates into an (n, 2) array of points."""
    return np.stack(np.broadcast_arrays(np.asarray(x, float), np.asarray(y, float)), axis=-1)
