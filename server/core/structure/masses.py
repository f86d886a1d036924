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
    a moment on a link: M = −k(φ) M₀ p(x) sign(θ′), k = 1 on the working stroke (σ θ′ ≥ 0), p ≡ 1 without a
        diagram;
    a force at a point P of a link (the tool point of a ram, a press's slide, a crusher's jaw):
        F = P p(x) e, e = e^{iα} fixed or e^{i(θ+α)} turning with the link, zero where it acts on the working
        stroke only and the point moves along e (w = Re(z′_P ē) > 0: the working stroke is where F does
        negative work);
    a load diagram p(x) = P/P_max through points (x_j, p_j), monotone cubic (PCHIP) between them and zero outside
        [x_first, x_last]: over the crank angle (x = φ mod 2π) or over the stroke (x the travel 0…1 from the
        working stroke's start: of a point along its fixed force line from its extreme farthest along e, of a
        link's angle between its extremes);
    gravity: G_k = −m_k g i at S_k;
friction f and pair radius r of the revolute pairs (the friction moment f·R·r, Chaika–Vasylenko §3.1) for the
kinetostatics by groups.  Their reduced moments (power equality) are in ``reduction.py``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace
from functools import lru_cache

import numpy as np
from scipy.interpolate import PchipInterpolator

from ..mechanisms.base import GeometryError
from .compose import Composition, compose
from .state import Angle, Point, on_link
from .strokes import angle_stroke, point_stroke


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


TURN = 2 * np.pi
DIAGRAM_POINTS = 41              # a load diagram's points at most
FARTHEST = 1000.0                # m: a load's point at most this far from its link's origin


@dataclass(frozen=True)
class LoadDiagram:
    """p(x) = P/P_max (0…1) through ``points`` (x_j, p_j), x strictly increasing, monotone cubic (PCHIP) between
    them, zero outside [x_first, x_last].  ``over`` "phi": x is the crank angle φ mod 2π, rad, in [0, 2π];
    "stroke": x is the travel 0…1 from the working stroke's start (structure/masses.py, module docstring)."""

    over: str
    points: tuple[tuple[float, float], ...]

    @property
    def span(self) -> float:
        """The range of x: 2π over the crank angle, 1 over the stroke."""
        return TURN if self.over == "phi" else 1.0

    def at(self, x: np.ndarray) -> np.ndarray:
        """p(x): the monotone cubic inside [x_first, x_last], 0 outside."""
        xs = [a for a, _ in self.points]
        inside = (x >= xs[0]) & (x <= xs[-1])
        return np.where(inside, profile_curve(self.points)(np.clip(x, xs[0], xs[-1])), 0.0)

    def breaks(self) -> list[float]:
        """Where p(x) has a corner or a jump: the inner points (the cubic is only once continuously
        differentiable there) and the ends strictly inside the range of x (p drops to zero there)."""
        xs = [a for a, _ in self.points]
        return xs[1:-1] + [x for x in (xs[0], xs[-1]) if 0.0 < x < self.span]

    def abscissa(self, phi: np.ndarray, travel: np.ndarray | None) -> np.ndarray:
        """x over φ: φ mod 2π over the crank angle, else the stroke's ``travel``."""
        return np.mod(phi, TURN) if self.over == "phi" else travel

    def switches(self, phi: np.ndarray, travel: np.ndarray | None) -> list[np.ndarray]:
        """Functions of φ that change sign at each break: sin((φ − x_j)/2) over the crank angle (zero at
        x_j + 2πn only), x − x_j over the stroke."""
        if self.over == "phi":
            return [np.sin(0.5 * (phi - x)) for x in self.breaks()]
        return [travel - x for x in self.breaks()]


@lru_cache(maxsize=256)
def profile_curve(points: tuple[tuple[float, float], ...]) -> PchipInterpolator:
    """The monotone cubic through a diagram's points (built once per diagram)."""
    return PchipInterpolator([x for x, _ in points], [p for _, p in points])


def diagram_problem(over: str, points) -> tuple[str, str] | None:
    """What is wrong with a load diagram, as (the field: "over" or "points", the reason in words), or None:
    2…DIAGRAM_POINTS points, x strictly increasing within the range (0…1 over the stroke, 0…2π over φ),
    p = P/P_max from 0 to 1."""
    if over not in ("stroke", "phi"):
        return "over", f"'{over}' is neither 'stroke' nor 'phi'"
    span, unit = (1.0, "the stroke's fraction 0…1") if over == "stroke" else (TURN, "the crank angle 0…2π rad")
    if not 2 <= len(points) <= DIAGRAM_POINTS:
        return "points", f"a diagram has 2 to {DIAGRAM_POINTS} points [x, P/P_max], not {len(points)}"
    if not all(len(row) == 2 and all(math.isfinite(v) for v in row) for row in points):
        return "points", "each point is two finite numbers [x, P/P_max]"
    xs, ps = [x for x, _ in points], [p for _, p in points]
    if not all(0.0 <= p <= 1.0 for p in ps):
        return "points", "each point's P/P_max is a number from 0 to 1"
    if not all(0.0 <= x <= span for x in xs):
        return "points", f"each point's x is {unit}"
    if not all(b > a for a, b in zip(xs, xs[1:])):
        return "points", "the points' x must increase strictly from one point to the next"
    return None


@dataclass(frozen=True)
class LinkMoment:
    """A useful load moment on a link, always against the link's rotation: ``working`` M₀ (N·m) on the working
    stroke, k·M₀ on the return; ``sense`` = +1: the working stroke turns the link counter-clockwise.  With a
    ``diagram`` M₀ is its peak, times p(x): over "stroke" x is the link's angle between its extremes θ_min, θ_max
    (``stroke``, filled by with_strokes) from the working stroke's start."""

    link: int
    working: float
    k: float = 1.0
    sense: int = 1
    diagram: LoadDiagram | None = None
    stroke: tuple[float, float] | None = None      # θ_min, θ_max, rad, around their middle (with_strokes)


@dataclass(frozen=True)
class PointForce:
    """A force at a point of a moving link: ``point`` (along, across) in the link's frame (as a centre of mass),
    m; ``magnitude`` P (N; P_max with a diagram); direction e = e^{iα} (``direction`` "fixed": α from +x) or
    e^{i(θ+α)} ("link": α from the link's direction, turning with it); ``acts`` "working": only where the point
    moves against e (the working stroke, where F does negative work), "always": at every angle.  ``name``: a
    label for drawings ("K").  ``stroke``: the point's extremes q_min, q_max along a fixed e, q = Re(z_P ē)
    (with_strokes fills it for a stroke diagram)."""

    link: int
    point: tuple[float, float]
    magnitude: float
    angle: float = 0.0
    direction: str = "fixed"
    acts: str = "working"
    diagram: LoadDiagram | None = None
    name: str | None = None
    stroke: tuple[float, float] | None = None

    @property
    def label(self) -> str:
        """Its name, or "<link>:<along>,<across>"."""
        return self.name or f"{self.link}:{self.point[0]:g},{self.point[1]:g}"


@dataclass(frozen=True)
class MassModel:
    """The mass model and loads of a general mechanism (links not listed are massless)."""

    links: tuple[LinkMass, ...] = ()
    gravity: float = 9.81            # g, m/s², acting along −y
    forces: tuple[SliderForce, ...] = ()
    moments: tuple[LinkMoment, ...] = ()
    friction: float = 0.0            # f in every pair (kinetostatics by groups)
    pair_radius: float = 0.0         # r of the revolute pairs, m
    point_forces: tuple[PointForce, ...] = ()


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


def unknown_link(comp: Composition, link: int, where: str) -> None:
    """Refuse a link number the linkage does not move (GeometryError naming the field)."""
    if link not in comp.links:
        raise GeometryError(where, f"the linkage has no moving link {link} (links: {sorted(comp.links)})",
                            "unknown_link", link=link)


def check_diagram(diagram: LoadDiagram | None, where: str) -> None:
    """Refuse a load diagram ``diagram_problem`` finds wrong, naming its field (``where``.points, .over)."""
    problem = None if diagram is None else diagram_problem(diagram.over, diagram.points)
    if problem:
        raise GeometryError(f"{where}.{problem[0]}", problem[1], "invalid_load_diagram")


def check_places(comp: Composition, model: MassModel) -> None:
    """Refuse a model whose links, sliders, points or diagrams the linkage cannot carry (GeometryError naming
    the field): an unknown or repeated link, an unknown sliding pair, a point farther than FARTHEST from its
    link's origin, a direction or an ``acts`` not known, a wrong diagram, a stroke diagram on a force that turns
    with its link (no fixed line to measure the travel along)."""
    seen = set()
    for i, item in enumerate(model.links):
        unknown_link(comp, item.link, f"masses.links.{i}.link")
        if item.link in seen:
            raise GeometryError(f"masses.links.{i}.link", f"link {item.link} is given twice", "duplicate_link",
                                link=item.link)
        seen.add(item.link)
    for i, item in enumerate(model.moments):
        unknown_link(comp, item.link, f"masses.moments.{i}.link")
        check_diagram(item.diagram, f"masses.moments.{i}.diagram")
    for i, item in enumerate(model.forces):
        pair_of(comp, item.joint, f"masses.forces.{i}.joint")
    for i, item in enumerate(model.point_forces):
        where = f"masses.point_forces.{i}"
        unknown_link(comp, item.link, f"{where}.link")
        if not (len(item.point) == 2 and all(math.isfinite(x) for x in item.point)
                and abs(complex(*item.point)) <= FARTHEST):
            raise GeometryError(f"{where}.point", f"the point [along, across] must be finite numbers of metres, at "
                                f"most {FARTHEST:g} m from the link's origin", "point_too_far")
        if item.direction not in ("fixed", "link"):
            raise GeometryError(f"{where}.direction.kind", f"'{item.direction}' is neither 'fixed' nor 'link'",
                                "invalid_direction")
        if item.acts not in ("working", "always"):
            raise GeometryError(f"{where}.acts", f"'{item.acts}' is neither 'working' nor 'always'", "invalid_acts")
        check_diagram(item.diagram, f"{where}.diagram")
        if item.diagram is not None and item.diagram.over == "stroke" and item.direction == "link":
            raise GeometryError(f"{where}.diagram.over", "a diagram over the stroke needs a fixed direction (the "
                                "travel is measured along a fixed force line); a force turning with its link takes "
                                "a diagram over the crank angle 'phi'", "stroke_diagram_turning")


def check_model(comp: Composition, model: MassModel) -> None:
    """``check_places``, and every stroke diagram's extremes resolved (``with_strokes``)."""
    check_places(comp, model)
    if any(item.diagram is not None and item.stroke is None for item in model.forces) or any(
            item.diagram is not None and item.diagram.over == "stroke" and item.stroke is None
            for item in (*model.moments, *model.point_forces)):
        raise ValueError("a load diagram's stroke is resolved by with_strokes first")


def with_strokes(mechanism, model: MassModel) -> MassModel:
    """The model with every stroke diagram's extremes: a slide's s_min, s_max (its output reversals over the
    turn, refined by Newton's method: mechanisms/general.reversals), a link's θ_min, θ_max, a point's q_min,
    q_max along its force line (strokes.angle_stroke, point_stroke); the places are checked first
    (``check_places``); GeometryError where the slide, link or point does not move back and forth (no stroke to
    spread the diagram over)."""
    unresolved = lambda item: item.diagram is not None and item.diagram.over == "stroke" and item.stroke is None
    if all(force.diagram is None or force.stroke is not None for force in model.forces) and \
            not any(unresolved(item) for item in (*model.moments, *model.point_forces)):
        return model
    from ..mechanisms.general import reversals
    turn = compose(mechanism.linkage, mechanism.turn())
    check_places(turn, model)
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
    moments = tuple(replace(item, stroke=angle_stroke(mechanism, turn, item.link, f"masses.moments.{i}.diagram"))
                    if unresolved(item) else item for i, item in enumerate(model.moments))
    points = tuple(replace(item, stroke=point_stroke(mechanism, turn, item, f"masses.point_forces.{i}.diagram"))
                   if unresolved(item) else item for i, item in enumerate(model.point_forces))
    return replace(model, forces=tuple(forces), moments=moments, point_forces=points)


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
