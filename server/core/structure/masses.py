"""Mass properties and loads of a general mechanism, and the kinematics of its centres of mass.

Every moving link k carries a mass m_k at its centre of mass S_k, fixed on the link in the link's own frame
(the frame the linkage's ``points`` use: from the link's origin joint along its angle θ_k, u along, v to the
left), and its moment of inertia J_Sk about S_k.  Rigid-body kinematics (Eremyants §2.1):

    z_S = z_O + w e^{iθ},   z′_S = z′_O + iθ′ w e^{iθ},   z″_S = z″_O + (iθ″ − θ′²) w e^{iθ},   w = u + iv

Loads (Eremyants ch. 3: the useful load resists the motion, k on the return stroke):
    a force on a slider, along its guide: F = −k(φ) P sign(w) e^{iθ_g} at the slider's joint, w = Re(z′ e^{−iθ_g})
        the velocity analog along the guide; k = 1 on the working stroke (σ w ≥ 0), k on the return;
    or a useful-load diagram, as the indicator diagram of a piston (Lecture 10 (L15)–(L16)): P(x) = P_max p(x)
        with p given at equally spaced positions x = 0…1 of the slider's stroke H (x from the start of the
        working stroke), one row for the working and one for the return stroke, between them by monotone
        (PCHIP) interpolation; F = −P(x) sign(w) e^{iθ_g};
    a moment on a link: M = −k(φ) M₀ sign(θ′), k = 1 on the working stroke (σ θ′ ≥ 0);
    gravity: G_k = −m_k g i at S_k;
friction f and pair radius r of the revolute pairs (the friction moment f·R·r, Chaika–Vasylenko §3.1) for the
kinetostatics by groups.  Their reduced moments (power equality) are in ``reduction.py``.
"""
from __future__ import annotations

from dataclasses import dataclass, replace
from functools import lru_cache

import numpy as np
from scipy.interpolate import PchipInterpolator

from ..mechanisms.base import GeometryError
from .compose import Composition, compose
from .state import Angle, Point, on_link


@dataclass(frozen=True)
class LinkMass:
    """One moving link: ``link`` as numbered in the linkage (1 = the input crank); mass m (kg); centre S in the
    link's own frame (along, across), m; inertia J_S about S (kg·m²)."""

    link: int
    mass: float
    centre: tuple[float, float] = (0.0, 0.0)
    inertia: float = 0.0


@dataclass(frozen=True)
class SliderForce:
    """A useful load on a slider, along its guide, always against the slider's motion: ``working`` P (N) on the
    working stroke, k·P on the return stroke (the textbook's k).  ``joint``: the sliding pair as named in the
    ``slides`` output ("E/ram"), or the slider's joint alone ("E") where it slides along one guide only.
    ``sense`` = +1: the working stroke is the motion along the guide's direction, −1 against it."""

    joint: str
    working: float
    k: float = 1.0
    sense: int = 1
    diagram: tuple[tuple[float, ...], tuple[float, ...]] | None = None   # p(x) of the working, the return stroke
    stroke: tuple[float, float] | None = None      # the slide's extremes s_min, s_max (with_strokes fills it)


@dataclass(frozen=True)
class LinkMoment:
    """A useful load moment on a link, always against the link's rotation: ``working`` M₀ (N·m) on the working
    stroke, k·M₀ on the return; ``sense`` = +1: the working stroke turns the link counter-clockwise."""

    link: int
    working: float
    k: float = 1.0
    sense: int = 1


@dataclass(frozen=True)
class MassModel:
    """The mass model and loads of a general mechanism (links not listed are massless)."""

    links: tuple[LinkMass, ...] = ()
    gravity: float = 9.81            # g, m/s², acting along −y
    forces: tuple[SliderForce, ...] = ()
    moments: tuple[LinkMoment, ...] = ()
    friction: float = 0.0            # f in every pair (kinetostatics by groups)
    pair_radius: float = 0.0         # r of the revolute pairs, m


@dataclass(frozen=True)
class CentreKinematics:
    """Centres of mass and link angles over φ, in the order of ``links``: positions, first and second analogs
    as (L, 2, N) arrays of (x, y); θ, θ′, θ″ as (L, N)."""

    links: tuple[int, ...]
    positions: np.ndarray
    first: np.ndarray
    second: np.ndarray
    theta: np.ndarray
    theta_d1: np.ndarray
    theta_d2: np.ndarray


@dataclass(frozen=True)
class SliderLoad:
    """A slider force resolved on the composed linkage: the link it acts on, its point z (with analogs), the
    guide's unit vector e^{iθ_g} and the velocity analog along it, w = Re(z′ e^{−iθ_g})."""

    force: SliderForce
    link: int
    point: np.ndarray        # complex z of the application point over φ
    unit: np.ndarray         # complex e^{iθ_g} over φ
    along: np.ndarray        # w, m (velocity analog along the guide)
    travel: np.ndarray       # x: the slide's position over its stroke from the working stroke's start, 0…1

    @property
    def working_stroke(self) -> np.ndarray:
        """Whether the slider is on its working stroke (σw ≥ 0)."""
        return self.force.sense * self.along >= 0

    @property
    def magnitude(self) -> np.ndarray:
        """|F|, N: k(φ)P (k = 1 on the working stroke), or P_max p(x) of the stroke's diagram."""
        if self.force.diagram is None:
            return np.where(self.working_stroke, 1.0, self.force.k) * self.force.working
        working, back = (diagram_curve(points)(self.travel) for points in self.force.diagram)
        return self.force.working * np.where(self.working_stroke, working, back)

    @property
    def vector(self) -> np.ndarray:
        """The force on the slider, complex F_x + iF_y, N: −|F| sign(w) e^{iθ_g}."""
        return -self.magnitude * np.sign(self.along) * self.unit

    def switches(self) -> list[np.ndarray]:
        """Where the reduced moment has a corner: the reversal (w = 0), and a diagram's inner points (the
        monotone cubic is only once continuously differentiable there)."""
        if self.force.diagram is None:
            return [self.along]
        inner = [self.travel - j / (len(points) - 1) for points in self.force.diagram for j in range(1, len(points) - 1)]
        return [self.along] + inner


@lru_cache(maxsize=64)
def diagram_curve(points: tuple[float, ...]) -> PchipInterpolator:
    """p(x) over x = 0…1 through a diagram's equally spaced points (built once per diagram)."""
    return PchipInterpolator(np.linspace(0.0, 1.0, len(points)), points)


def slider_link(comp: Composition, pair: str) -> int:
    """The link that slides in ``pair``: the one of its group whose frame runs along the guide (RRP: the slider;
    PRP: the first or second block; RPP: the slotted link on the guide, or the block in the slot; RPR: the
    block), i.e. whose origin is the sliding point."""
    for group in comp.groups:
        keys = list(group.slides)
        if pair in keys:
            links = list(group.links)
            order = {"RRP": [links[1]], "PRP": links, "RPP": [links[1], links[0]], "RPR": [links[0]]}[group.kind]
            return order[keys.index(pair)]
    raise KeyError(pair)


def pair_of(comp: Composition, joint: str, where: str) -> str:
    """The sliding pair a force names: its exact name in ``slides``, or the one pair of that joint."""
    if joint in comp.slides:
        return joint
    found = [name for name in comp.slides if name.split("/")[0] == joint]
    if len(found) != 1:
        known = ", ".join(sorted(comp.slides)) or "none"
        reason = "slides in more than one pair: name the pair" if found else "is no sliding pair of this linkage"
        raise GeometryError(where, f"'{joint}' {reason} (pairs: {known})", "unknown_slider", joint=joint)
    return found[0]


def check_model(comp: Composition, model: MassModel) -> None:
    """Refuse a model whose links or sliders the linkage does not have (GeometryError naming the field)."""
    seen = set()
    for i, item in enumerate(model.links):
        if item.link not in comp.links:
            raise GeometryError(f"masses.links.{i}.link", f"the linkage has no moving link {item.link} "
                                f"(links: {sorted(comp.links)})", "unknown_link", link=item.link)
        if item.link in seen:
            raise GeometryError(f"masses.links.{i}.link", f"link {item.link} is given twice", "duplicate_link",
                                link=item.link)
        seen.add(item.link)
    for i, item in enumerate(model.moments):
        if item.link not in comp.links:
            raise GeometryError(f"masses.moments.{i}.link", f"the linkage has no moving link {item.link} "
                                f"(links: {sorted(comp.links)})", "unknown_link", link=item.link)
    for i, item in enumerate(model.forces):
        pair_of(comp, item.joint, f"masses.forces.{i}.joint")
        if item.diagram is not None and item.stroke is None:
            raise ValueError("a load diagram's stroke is resolved by with_strokes first")


def with_strokes(mechanism, model: MassModel) -> MassModel:
    """The model with every load diagram's slide extremes s_min, s_max (the slide's output reversals over the
    turn, refined by Newton's method: mechanisms/general.reversals); GeometryError where that slide does not
    move (no stroke to spread the diagram over)."""
    if all(force.diagram is None or force.stroke is not None for force in model.forces):
        return model
    from ..mechanisms.general import reversals
    turn = compose(mechanism.linkage, mechanism.turn())
    extremes = reversals(mechanism.linkage, turn)
    forces = []
    for i, force in enumerate(model.forces):
        if force.diagram is not None and force.stroke is None:
            pair = pair_of(turn, force.joint, f"masses.forces.{i}.joint")
            values = [sp.value for sp in extremes if sp.slide == pair]
            if len(values) < 2 or max(values) - min(values) <= 1e-12 * max(1.0, max(np.abs(values))):
                raise GeometryError(f"masses.forces.{i}.diagram", f"the slide {pair} has no stroke to spread the "
                                    "load diagram over (it does not reverse)", "diagram_no_stroke", joint=pair)
            force = replace(force, stroke=(float(min(values)), float(max(values))))
        forces.append(force)
    return replace(model, forces=tuple(forces))


def centre_points(comp: Composition, model: MassModel) -> list[tuple[Point, Angle]]:
    """Each listed link's centre of mass S (z, z′, z″ complex over φ) and the link's angle, in model order."""
    out = []
    for item in model.links:
        origin, angle = comp.links[item.link]
        out.append((on_link(origin, angle, complex(*item.centre)), angle))
    return out


def centre_kinematics(mechanism, model: MassModel, phi: np.ndarray,
                      comp: Composition | None = None) -> CentreKinematics:
    """Positions and analogs of every listed link's centre of mass, and its angle with θ′, θ″, at ``phi``
    (``comp``: the linkage already composed there, to share it)."""
    comp = comp if comp is not None else compose(mechanism.linkage, np.asarray(phi, float))
    n = comp.phi.size
    rows = centre_points(comp, model)
    planar = lambda part: np.stack([np.stack([getattr(s, part).real, getattr(s, part).imag]) for s, _ in rows]) \
        if rows else np.zeros((0, 2, n))
    flat = lambda part: np.stack([getattr(a, part) for _, a in rows]) if rows else np.zeros((0, n))
    return CentreKinematics(tuple(item.link for item in model.links), planar("z"), planar("d1"), planar("d2"),
                            flat("th"), flat("d1"), flat("d2"))


def slider_loads(comp: Composition, model: MassModel) -> list[SliderLoad]:
    """Every slider force resolved on ``comp``: its link, point, direction and velocity analog along the guide."""
    out = []
    for i, force in enumerate(model.forces):
        pair = pair_of(comp, force.joint, f"masses.forces.{i}.joint")
        link = slider_link(comp, pair)
        origin, angle = comp.links[link]
        unit = angle.unit()
        travel = np.zeros(comp.phi.shape)
        if force.diagram is not None:
            low, high = force.stroke
            s = comp.slides[pair].s
            travel = np.clip(((s - low) if force.sense > 0 else (high - s)) / (high - low), 0.0, 1.0)
        out.append(SliderLoad(force, link, origin.z, unit, (origin.d1 * np.conj(unit)).real, travel))
    return out


def moment_strokes(comp: Composition, model: MassModel) -> list[tuple[LinkMoment, np.ndarray, np.ndarray]]:
    """Every load moment with θ′ of its link and the moment on the link, −k M₀ sign(θ′) (N·m, CCW positive)."""
    out = []
    for item in model.moments:
        d1 = comp.links[item.link][1].d1
        k = np.where(item.sense * d1 >= 0, 1.0, item.k)
        out.append((item, d1, -k * item.working * np.sign(d1)))
    return out
