"""How the point forces and the load moments of a general mechanism move with it (structure/masses.py): each
load resolved on the composed linkage, and the strokes their diagrams are spread over.

A force F at a point P of link k (P fixed in the link's frame at w = along + i·across, Eremyants §2.1):

    z_P = z_O + w e^{iθ},   z′_P = z′_O + iθ′ w e^{iθ};   e = e^{iα} (fixed) or e^{i(θ+α)} (turning with the link)
    F = P p(x) e,   zero where it acts on the working stroke only and w_e = Re(z′_P ē) > 0

(the working stroke: the point moves against e, F does negative work).  Its reduced moment by power equality
(Chaika–Vasylenko (3.24)), as a resisting moment: M_c = −Re(F̄ z′_P) = −P p(x) w_e.  A load moment on link k:
M = −k(φ) M₀ p(x) sign(θ′), M_c = −M θ′ = k M₀ p(x) |θ′|.

A stroke diagram's x: a point's travel along its fixed e, q = Re(z_P ē), from its extreme farthest along e
(the working stroke's start), x = (q_max − q)/(q_max − q_min); a link's angle between its extremes from the
working stroke's start, x = (θ − θ_min)/(θ_max − θ_min) (σ = +1: the working stroke turns it counter-clockwise)
or (θ_max − θ)/(θ_max − θ_min) (σ = −1).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .compose import Composition
from .masses import LinkMoment, MassModel, PointForce
from .state import Point, on_link
from .strokes import near


@dataclass(frozen=True)
class PointLoad:
    """A point force resolved over φ: its point (z_P, z′_P), the unit vector e, the velocity analog along it
    w_e = Re(z′_P ē) (m) and a stroke diagram's x (None without one)."""

    force: PointForce
    point: Point
    unit: np.ndarray
    along: np.ndarray
    phi: np.ndarray
    travel: np.ndarray | None

    @property
    def vector(self) -> np.ndarray:
        """F = P p(x) e (complex F_x + iF_y, N), zero where it acts on the working stroke only and w_e > 0
        (and at w_e = 0, where its power is zero either way)."""
        f = self.force
        size = np.full(self.along.shape, float(f.magnitude)) if f.diagram is None else \
            f.magnitude * f.diagram.at(f.diagram.abscissa(self.phi, self.travel))
        if f.acts == "working":
            size = np.where(self.along < 0, size, 0.0)
        return size * self.unit

    def switches(self) -> list[np.ndarray]:
        """Where its reduced moment has a corner or a jump: the reversal along e (w_e = 0) where it acts on the
        working stroke only, and its diagram's breaks."""
        rows = [self.along] if self.force.acts == "working" else []
        return rows + ([] if self.force.diagram is None else self.force.diagram.switches(self.phi, self.travel))


@dataclass(frozen=True)
class MomentLoad:
    """A load moment resolved over φ: its link's θ′ (``rate``) and a stroke diagram's x (None without one)."""

    item: LinkMoment
    rate: np.ndarray
    phi: np.ndarray
    travel: np.ndarray | None

    @property
    def moment(self) -> np.ndarray:
        """M = −k(φ) M₀ p(x) sign(θ′), N·m, counter-clockwise positive; k = 1 on the working stroke (σθ′ ≥ 0)."""
        item = self.item
        k = np.where(item.sense * self.rate >= 0, 1.0, item.k)
        shape = 1.0 if item.diagram is None else item.diagram.at(item.diagram.abscissa(self.phi, self.travel))
        return -k * item.working * shape * np.sign(self.rate)

    def switches(self) -> list[np.ndarray]:
        """The link's reversal (θ′ = 0: k switches, |θ′| has a corner) and its diagram's breaks."""
        diagram = self.item.diagram
        return [self.rate] + ([] if diagram is None else diagram.switches(self.phi, self.travel))


def force_unit(item: PointForce, theta: np.ndarray) -> np.ndarray:
    """e over φ: e^{iα}, or e^{i(θ+α)} for a force turning with its link."""
    return np.exp(1j * (item.angle + (theta if item.direction == "link" else 0.0)))


def point_loads(comp: Composition, model: MassModel) -> list[PointLoad]:
    """Every point force resolved on ``comp`` (its stroke diagram's extremes resolved by masses.with_strokes)."""
    out = []
    for item in model.point_forces:
        origin, angle = comp.links[item.link]
        point = on_link(origin, angle, complex(*item.point))
        unit = force_unit(item, angle.th)
        travel = None
        if item.diagram is not None and item.diagram.over == "stroke":
            low, high = item.stroke
            travel = np.clip((high - (point.z * np.conj(unit)).real) / (high - low), 0.0, 1.0)
        out.append(PointLoad(item, point, unit, (point.d1 * np.conj(unit)).real, comp.phi, travel))
    return out


def moment_loads(comp: Composition, model: MassModel) -> list[MomentLoad]:
    """Every load moment resolved on ``comp`` (its stroke diagram's extremes resolved by masses.with_strokes)."""
    out = []
    for item in model.moments:
        angle = comp.links[item.link][1]
        travel = None
        if item.diagram is not None and item.diagram.over == "stroke":
            low, high = item.stroke
            theta = near(angle.th, 0.5 * (low + high))
            travel = np.clip(((theta - low) if item.sense > 0 else (high - theta)) / (high - low), 0.0, 1.0)
        out.append(MomentLoad(item, angle.d1, comp.phi, travel))
    return out
