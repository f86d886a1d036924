"""The positions of the kinematics sheet (Chaika–Vasylenko §3.4: the plan of positions at 8, 12 or 24 crank
angles, position 1 at the extreme position that starts the working stroke).

The output that defines the strokes is a slide s (m) or a link's angle θ (rad).  Its extreme positions are the
crank angles where its first analog vanishes, q′(φ) = 0 (Eremyants §2.1: its velocity q′ω₁ is zero there),
bracketed between the sign changes of q′ on a 0.25° grid and found by Brent's method on the closed-form analog.
Two of them split the turn into two strokes; the crank turns through φ_w on the working stroke and φ_i on the
idle one, and the time ratio of the quick return is K = max(φ_w, φ_i)/min(φ_w, φ_i) ≥ 1 (at a constant crank
speed the strokes' times are as their angles).

The working stroke is the one on which the useful loads on the output do the larger resisting work
A = ∫ M_c dφ (M_c their reduced moment, positive against the crank: structure/reduction.reduced_loads,
Chaika–Vasylenko (3.24)); where both strokes take the same work (k = 1) the loads' own sense marks it
(structure/masses.py: the working stroke is σw ≥ 0); without a useful load on the output it is the slower stroke
(the larger crank angle).

The positions are φ_i = φ₀ + 2π(i − 1)/N reduced to [0, 2π), position 1 at φ₀, in the crank's coordinate φ:
the crank's angle is θ₁ = θ₀ + σφ and φ grows with the motion (structure/compose.py).
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass, replace

import numpy as np
from scipy.optimize import brentq

from ..mechanisms.base import GeometryError, angle_ranges, ranges_text
from ..mechanisms.general import GeneralMechanism
from ..structure.compose import Composition, compose
from ..structure.masses import MassModel, pair_of, slider_link, slider_loads, with_strokes
from ..structure.reduction import reduced_loads
from ..structure.spec import SliderInput

TWO_PI = 2.0 * math.pi
POSITION_COUNTS = (8, 12, 24)
TURN_POINTS = 1441          # the turn at 0.25°: the assembly checked, the output's reversals bracketed
ROOT_TOLERANCE = 1e-14      # rad: Brent's bracket at the end (the extremes to ~1e-13 rad)
WORK_NODES = 200            # Gauss–Legendre nodes per stroke for the loads' resisting work
_work_rule = np.polynomial.legendre.leggauss(WORK_NODES)
EQUAL_WORK = 1e-9           # relative: the two strokes take the same work (a load with k = 1)
LINK_NAME = re.compile(r"link\s*(\d{1,2})")


@dataclass(frozen=True)
class Output:
    """The output that defines the strokes: a slide (its pair in Composition.slides, s in m) or a link's angle
    (θ in rad, counter-clockwise from +x); ``link`` carries it (the slider: masses.slider_link, or the link)."""

    kind: str
    name: str
    key: str | int
    link: int

    @property
    def unit(self) -> str:
        return "m" if self.kind == "slide" else "rad"

    def analogs(self, comp: Composition) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(q, q′, q″) over ``comp``'s angles: s, s′, s″ of the slide or θ, θ′, θ″ of the link."""
        if self.kind == "slide":
            s = comp.slides[self.key]
            return s.s, s.d1, s.d2
        angle = comp.links[self.key][1]
        return angle.th, angle.d1, angle.d2

    def as_dict(self) -> dict:
        return {"kind": self.kind, "name": self.name, "unit": self.unit}


@dataclass(frozen=True)
class StrokePositions:
    """The sheet's positions: the output, position 1 at ``phi0`` (the working stroke's start, or typed), the N
    crank angles and which of them lie on the working stroke, the strokes' extreme angles and spans (rad), the
    output at the working stroke's start and end, the rule that chose the working stroke, and the useful loads'
    resisting work on the working and the idle stroke (J; None without a load on the output)."""

    output: Output
    phi0: float
    typed: bool
    phi: np.ndarray
    working: np.ndarray
    working_stroke: tuple[float, float]
    spans: tuple[float, float]
    extremes: tuple[float, float]
    rule: str
    works: tuple[float, float] | None

    @property
    def count(self) -> int:
        return self.phi.size

    @property
    def time_ratio(self) -> float:
        """K = the slower stroke's crank angle / the quicker one's (≥ 1)."""
        return max(self.spans) / min(self.spans)

    @property
    def stroke(self) -> float:
        """The output's stroke H (m) or swing (rad) between its extremes."""
        start, end = self.extremes
        return abs(end - start) if self.output.kind == "slide" else abs(math.remainder(end - start, TWO_PI))

    @property
    def other_extreme(self) -> dict:
        """The working stroke's end, the textbook's extra position k′: k is the last position before it."""
        end = self.working_stroke[1]
        after = int(math.floor(float(wrapped(end - self.phi0)) * self.count / TWO_PI + 1e-9)) % self.count + 1
        return {"label": f"{after}′", "after": after, "phi": end}

    def as_dict(self) -> dict:
        """The answer's ``positions`` (rad, m; plain floats and lists)."""
        start, end = self.working_stroke
        return {"count": self.count, "phi0": self.phi0, "start": "typed" if self.typed else "extreme",
                "output": self.output.as_dict(), "phi": self.phi.tolist(), "working": self.working.tolist(),
                "strokes": {"working": [start, end], "idle": [end, start]},
                "spans": {"working": self.spans[0], "idle": self.spans[1]}, "time_ratio": self.time_ratio,
                "rule": self.rule,
                "works": None if self.works is None else {"working": self.works[0], "idle": self.works[1]},
                "extremes": {"start": self.extremes[0], "end": self.extremes[1], "stroke": self.stroke,
                             "unit": self.output.unit},
                "other_extreme": self.other_extreme}


def wrapped(phi):
    """φ reduced to [0, 2π) (np.mod may round a tiny negative angle up to 2π itself)."""
    value = np.mod(phi, TWO_PI)
    return np.where(value >= TWO_PI, 0.0, value)


def full_turn(mechanism: GeneralMechanism, points: int = TURN_POINTS) -> Composition:
    """The linkage composed over the crank's turn; GeometryError where the crank cannot turn fully: a slider
    input (linkage.input.kind), or a group (linkage.groups.k) that cannot be assembled at some angles (its limits
    of assembly) or passes a dead position (its determinant changes sign: its links come in line)."""
    linkage = mechanism.linkage
    if isinstance(linkage.crank, SliderInput):
        raise GeometryError("linkage.input.kind", "the course project takes a crank as the input link (its cycle "
                            "is the crank's turn)", "slider_input_kinematics_only", what="the course project")
    comp = compose(linkage, np.linspace(0.0, TWO_PI, points))
    for k, group in enumerate(comp.groups):
        if not group.closes.all():
            ranges = ranges_text(angle_ranges(comp.phi, ~group.closes))
            raise GeometryError(f"linkage.groups.{k}", f"the crank cannot turn fully: the {group.kind} group cannot "
                                f"be assembled at φ = {ranges}", "crank_not_full_turn", group=k, ranges=ranges)
        det = group.determinant
        flips = np.flatnonzero(np.sign(det[:-1]) * np.sign(det[1:]) < 0)
        if flips.size:
            at = float(np.degrees(comp.phi[flips[0]]))
            raise GeometryError(f"linkage.groups.{k}", f"the crank cannot turn fully: the {group.kind} group passes "
                                f"a dead position (its links in line) near φ = {at:.1f}°", "crank_dead_position",
                                group=k, phi=at)
    return comp


def slide_output(comp: Composition, pair: str) -> Output:
    return Output("slide", pair, pair, slider_link(comp, pair))


def link_output(link: int) -> Output:
    return Output("link", f"link {link}", link, link)


def loaded_link_output(comp: Composition, link: int) -> Output:
    """The output of a link with a point force: its slide where it slides without turning (a ram on a frame
    guide), else its angle."""
    if not np.any(comp.links[link][1].d1):
        for pair in comp.slides:
            if slider_link(comp, pair) == link:
                return slide_output(comp, pair)
    return link_output(link)


def named_output(comp: Composition, output: str) -> Output:
    """A sliding pair by its name ("E/ram", or its joint "E" where it slides in one pair) or a link ("link 3")."""
    match = LINK_NAME.fullmatch(output.strip())
    if match and int(match[1]) in comp.links:
        return link_output(int(match[1]))
    if not match:
        pairs = [pair for pair in comp.slides if output in (pair, pair.split("/")[0])]
        if len(pairs) == 1:
            return slide_output(comp, pairs[0])
    known = ", ".join(sorted(comp.slides)) or "none"
    links = ", ".join(f"link {k}" for k in sorted(comp.links))
    raise GeometryError("output", f"'{output}' is no output of this linkage: name a sliding pair ({known}) or a "
                        f"moving link ({links})", "unknown_output", output=output)


def find_output(mechanism: GeneralMechanism, comp: Composition, model: MassModel | None,
                output: str | None) -> Output:
    """``output`` by name; or, with None, the first output carrying a useful load (a slider force's slide, a point
    force's link, a load moment's link), else the last group's (last) slide, else its last link's angle."""
    if output is not None:
        return named_output(comp, output)
    model = model or MassModel()
    for i, force in enumerate(model.forces):
        if force.working > 0:
            return slide_output(comp, pair_of(comp, force.joint, f"masses.forces.{i}.joint"))
    for force in model.point_forces:
        if force.link in comp.links:
            return loaded_link_output(comp, force.link)
    for moment in model.moments:
        if moment.working > 0 and moment.link in comp.links:
            return link_output(moment.link)
    groups = mechanism.linkage.groups
    if not groups:
        return link_output(mechanism.linkage.crank.link)
    if comp.groups[-1].slides:
        return slide_output(comp, list(comp.groups[-1].slides)[-1])
    return link_output(groups[-1].links[1])


def reversal_angles(mechanism: GeneralMechanism, turn: Composition, output: Output) -> list[float]:
    """Crank angles in [0, 2π) where the output's q′ changes sign: bracketed by the grid of ``turn`` (between two
    points, or about a point where q′ is zero up to round-off), then Brent's method on q′(φ) composed at one angle,
    to ROOT_TOLERANCE."""
    phi, d1 = turn.phi[:-1], output.analogs(turn)[1][:-1]          # the grid's last point is its first again
    step = phi[1] - phi[0]
    sign = np.where(np.abs(d1) <= 1e-12 * np.max(np.abs(d1), initial=0.0), 0.0, np.sign(d1))
    after, before = np.roll(sign, -1), np.roll(sign, 1)
    brackets = [(phi[k], phi[k] + step) for k in np.flatnonzero(sign * after < 0)]
    brackets += [(phi[k] - step, phi[k] + step) for k in np.flatnonzero((sign == 0) & (before * after < 0))]

    def analog(x: float) -> float:
        return float(output.analogs(compose(mechanism.linkage, np.array([x])))[1][0])

    return sorted(float(wrapped(brentq(analog, a, b, xtol=ROOT_TOLERANCE, rtol=4 * np.finfo(float).eps)))
                  for a, b in brackets)


def output_loads(mechanism: GeneralMechanism, comp: Composition, model: MassModel | None,
                 output: Output) -> MassModel | None:
    """The useful loads on the output's link alone (no masses, so no weights), or None where it carries none."""
    if model is None:
        return None
    forces = tuple(f for i, f in enumerate(model.forces) if f.working > 0 and slider_link(
        comp, pair_of(comp, f.joint, f"masses.forces.{i}.joint")) == output.link)
    moments = tuple(m for m in model.moments if m.working > 0 and m.link == output.link)
    extra = {}
    if hasattr(model, "point_forces"):
        extra["point_forces"] = tuple(p for p in model.point_forces if p.link == output.link)
    if not (forces or moments or extra.get("point_forces")):
        return None
    return with_strokes(mechanism, replace(model, links=(), forces=forces, moments=moments, **extra))


def stroke_work(mechanism: GeneralMechanism, loads: MassModel, start: float, span: float) -> float:
    """The loads' resisting work A = ∫ M_c dφ (J) over the stroke from ``start`` through ``span`` by
    Gauss–Legendre quadrature (M_c is smooth inside a stroke: k switches at its ends, the reversals)."""
    x, w = _work_rule
    comp = compose(mechanism.linkage, start + (x + 1) * span / 2)
    return float(w @ reduced_loads(mechanism, comp, loads).total * span / 2)


def marked_working(comp: Composition, loads: MassModel) -> bool | None:
    """Whether the loads' own sense marks ``comp``'s one angle as their working stroke (σw ≥ 0, σθ′ ≥ 0)."""
    if loads.forces:
        return bool(slider_loads(comp, loads)[0].working_stroke[0])
    if loads.moments:
        moment = loads.moments[0]
        return bool(moment.sense * comp.links[moment.link][1].d1[0] >= 0)
    return None


def working_first(mechanism: GeneralMechanism, turn: Composition, model: MassModel | None, output: Output,
                  strokes: list[tuple[float, float]]) -> tuple[bool, str, tuple[float, float] | None]:
    """Whether the first of the two ``strokes`` (start, span) is the working one, by which rule, and the loads'
    resisting work on each (module docstring)."""
    loads = output_loads(mechanism, turn, model, output)
    if loads is not None:
        works = tuple(stroke_work(mechanism, loads, *stroke) for stroke in strokes)
        largest = max(abs(w) for w in works)
        if largest > 0 and abs(works[0] - works[1]) > EQUAL_WORK * largest:
            return works[0] > works[1], "resisting_work", works
        start, span = strokes[0]
        mark = marked_working(compose(mechanism.linkage, np.array([start + span / 2])), loads)
        if largest > 0 and mark is not None:
            return mark, "load_sense", works
    return strokes[0][1] >= strokes[1][1], "slower_stroke", None


def position_angles(phi0: float, count: int) -> np.ndarray:
    """φ_i = φ₀ + 2π(i − 1)/N reduced to [0, 2π), i = 1…N."""
    return wrapped(phi0 + TWO_PI * np.arange(count) / count)


def stroke_positions(mechanism: GeneralMechanism, model: MassModel | None = None, count: int = 12,
                     start: float | None = None, output: str | None = None) -> StrokePositions:
    """The sheet's N positions (module docstring): ``start`` None puts position 1 at the working stroke's start,
    a number puts it at φ₀ = start (rad).  GeometryError naming ``positions``, ``start``, ``output`` or the group
    that keeps the crank from turning fully."""
    if count not in POSITION_COUNTS:
        raise GeometryError("positions", "the kinematics sheet takes 8, 12 or 24 positions of the crank",
                            "position_count", count=str(count))
    if start is not None and not (isinstance(start, (int, float)) and math.isfinite(start)):
        raise GeometryError("start", "φ₀ is a finite angle in rad, or null for the extreme position that starts "
                            "the working stroke", "not_finite")
    turn = full_turn(mechanism)
    out = find_output(mechanism, turn, model, output)
    roots = reversal_angles(mechanism, turn, out)
    if len(roots) != 2:
        reason = (f"does not reverse over the turn: it has no stroke (it turns fully or stands still)" if not roots
                  else f"reverses {len(roots)} times per turn: more than one stroke per turn, where the working and "
                  "the idle stroke need exactly two extreme positions")
        raise GeometryError("output", f"the output {out.name} {reason}; name another output", "output_strokes",
                            output=out.name, reversals=len(roots))
    a, b = roots
    strokes = [(a, b - a), (b, TWO_PI - (b - a))]
    first, rule, works = working_first(mechanism, turn, model, out, strokes)
    (begin, span), (end, idle) = strokes if first else strokes[::-1]
    values = out.analogs(compose(mechanism.linkage, np.array([begin, end])))[0]
    phi0 = begin if start is None else float(wrapped(start))
    phi = position_angles(phi0, count)
    offset = wrapped(phi - begin)
    offset = np.where(offset > TWO_PI - 1e-9, 0.0, offset)
    return StrokePositions(out, phi0, start is not None, phi, offset < span - 1e-9, (begin, end), (span, idle),
                           (float(values[0]), float(values[1])), rule,
                           None if works is None else (works if first else works[::-1]))
