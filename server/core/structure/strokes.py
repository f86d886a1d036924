"""The strokes of loads spread over a stroke: a point's travel along its force line and a rocking link's extreme
angles over the turn, each the least and the largest value of its quantity refined at the stationary points
(masses.with_strokes fills the load diagrams' extremes from them)."""
from __future__ import annotations

import numpy as np

from ..mechanisms.base import GeometryError
from .compose import Composition, compose
from .state import on_link

NO_STROKE = 1e-12         # a travel below this share of the positions' size is no stroke
NEWTON_STEPS = 4          # of the extremes' refinement: quadratic from the 0.5° grid to round-off


def near(theta: np.ndarray, middle: float) -> np.ndarray:
    """θ moved by whole turns into (middle − π, middle + π]."""
    return middle + np.angle(np.exp(1j * (theta - middle)))


def extremes(mechanism, turn: Composition, quantity) -> tuple[float, float]:
    """The least and the largest value of q(φ) over the turn (``quantity``: composition → q, q′, q″): the grid's
    values and the stationary points where q′ changes sign on it, refined by Newton's method φ ← φ − q′/q″
    (as mechanisms/general.reversals)."""
    from ..mechanisms.general import sign_changes
    values, d1, _ = quantity(turn)
    found = [values]
    phi = np.array(sign_changes(turn.phi, d1))
    if phi.size:
        with np.errstate(divide="ignore", invalid="ignore"):
            for _ in range(NEWTON_STEPS):
                _, d1, d2 = quantity(compose(mechanism.linkage, phi))
                phi = np.where(np.isfinite(phi - d1 / d2), phi - d1 / d2, phi)
        found.append(quantity(compose(mechanism.linkage, phi))[0])
    every = np.concatenate(found)
    every = every[np.isfinite(every)]
    return float(every.min()), float(every.max())


def no_stroke(low: float, high: float, size: float) -> bool:
    """Whether a travel from low to high is too small to spread a diagram over."""
    return high - low <= NO_STROKE * max(1.0, size)


def point_stroke(mechanism, turn: Composition, item, where: str) -> tuple[float, float]:
    """q_min, q_max of a point's travel (``item``: a masses.PointForce) along its fixed force line, q = Re(z_P ē), m (GeometryError at ``where``
    where the point does not move along it)."""
    unit = np.exp(1j * item.angle)

    def along(comp):
        origin, angle = comp.links[item.link]
        p = on_link(origin, angle, complex(*item.point))
        return tuple((x * np.conj(unit)).real for x in (p.z, p.d1, p.d2))
    low, high = extremes(mechanism, turn, along)
    if no_stroke(low, high, max(abs(low), abs(high))):
        raise GeometryError(where, f"the point {item.label} does not move along its force line: no stroke to "
                            "spread the load diagram over", "point_no_stroke", name=item.label)
    return low, high


def angle_stroke(mechanism, turn: Composition, link: int, where: str) -> tuple[float, float]:
    """θ_min, θ_max of a rocking link over the turn, rad, both within π of their middle (GeometryError at ``where``
    where the link turns fully or does not turn: no extreme angles)."""
    unwrapped = np.unwrap(turn.links[link][1].th)
    if abs(unwrapped[-1] - unwrapped[0]) > np.pi or np.ptp(unwrapped) <= NO_STROKE:
        raise GeometryError(where, f"link {link} has no extreme angles to spread the load diagram over (it turns "
                            "fully, or not at all); give it a diagram over the crank angle 'phi'", "link_no_stroke",
                            link=link)
    middle = 0.5 * (unwrapped.min() + unwrapped.max())

    def theta(comp):
        angle = comp.links[link][1]
        return near(angle.th, middle), angle.d1, angle.d2
    return extremes(mechanism, turn, theta)
