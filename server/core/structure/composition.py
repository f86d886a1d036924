"""Composition in order: the input crank, then each group from the elements already placed (Chaika–Vasylenko
§3.1: the kinematic analysis follows the order of attachment; Eremyants §2.1 for the analogs).

    crank:  A = O + l e^{iθ₁},  θ₁ = θ₀ + σφ,  θ′₁ = σ,  θ″₁ = 0
    slider: A = P + s u (a frame guide through P along u = e^{iθ_g}),  A′ = u,  A″ = 0: the generalised
            coordinate is s (``phi`` holds s, m) and every analog is with respect to it
Every group returns its joints, links, slides and the angles where its closure has a real solution; a point
or guide fixed on a link follows the link rigidly (state.on_link).  Through a group's change points its
assembly σ is continued (change_points.py: σ flips at each, the motion stays smooth); within their
neighbourhoods (|sin| < change_points.SINGULAR_SIN) the analogs are undefined (``at_change_points="null"``:
NaN, for answers at points) or the limit of the continuing motion (``"limit"``, for what is integrated over
the turn: the cubic through the analogs at the neighbourhood's edges, composed with the angles).
"""
from __future__ import annotations

from dataclasses import dataclass, field, fields, replace

import numpy as np

from . import change_point_marks as change_points
from . import prp, rpp, rpr, rrp, rrr
from .group import REGULAR, GroupSolution, Singular, Slide
from .spec import Linkage, SliderInput
from .state import Angle, Guide, Point, fixed_angle, fixed_point, on_link


@dataclass
class Composition:
    """The whole linkage at the crank angles ``phi``."""

    phi: np.ndarray
    joints: dict[str, Point] = field(default_factory=dict)
    links: dict[int, tuple[Point, Angle]] = field(default_factory=dict)
    guides: dict[str, Guide] = field(default_factory=dict)
    slides: dict = field(default_factory=dict)
    groups: list[GroupSolution] = field(default_factory=list)


def attach(comp: Composition, element) -> None:
    """Points and guides the element fixes on its links."""
    for a in element.points:
        origin, angle = comp.links[a.link]
        comp.joints[a.name] = on_link(origin, angle, complex(a.along, a.across))
    for a in element.new_guides:
        origin, angle = comp.links[a.link]
        comp.guides[a.name] = Guide(on_link(origin, angle, complex(a.along, a.across)), angle.shifted(a.angle),
                                    a.link)


def solve_group(comp: Composition, group, singular: Singular = REGULAR) -> GroupSolution:
    """The group's kind module, given its outer joints and guides as placed so far."""
    j, g = comp.joints, comp.guides
    names = group.outer + group.guides
    if group.kind == "RRR":
        return rrr.solve(j[group.outer[0]], j[group.outer[1]], *group.sizes, group.branch,
                         (group.outer[0], group.outer[1], group.inner), group.links, singular)
    if group.kind == "RRP":
        return rrp.solve(j[group.outer[0]], g[group.guides[0]], group.sizes[0], group.branch,
                         (group.outer[0], group.inner, group.guides[0]), group.links, singular)
    if group.kind == "RPR":
        return rpr.solve(j[group.outer[0]], j[group.outer[1]], group.sizes[0], group.branch,
                         (*names, group.inner), group.links, singular)
    if group.kind == "PRP":
        return prp.solve(g[group.guides[0]], g[group.guides[1]], (group.inner, *names), group.links)
    return rpp.solve(j[group.outer[0]], g[group.guides[0]], group.angle,
                     (group.outer[0], group.inner, group.guides[0], "slot"), group.links)


def compose_with(linkage: Linkage, phi: np.ndarray, points: tuple, at_change_points: str,
                 upto: int | None = None) -> Composition:
    """``compose`` with the change points ``points`` (change_points.ChangePoint) and the first ``upto`` groups;
    in "limit" mode the composition runs on the angles and every neighbourhood's two edges, then is cut back."""
    phi = np.asarray(phi, float)
    if at_change_points == "limit" and points and phi.ndim == 1:
        edges = np.array([[cp.phi - cp.half_width, cp.phi + cp.half_width] for cp in points]).ravel()
        whole = _compose(linkage, np.concatenate([phi, edges]), points, "limit", upto, phi.size)
        return cut(whole, phi.size)
    return _compose(linkage, phi, points, at_change_points, upto, phi.size)


def limit(phi: np.ndarray, n: int, points: tuple, k: int, near: np.ndarray):
    """The analogs (x′, x″) of group k within its change points' neighbourhoods from their values at the edges
    (composed at phi[n + 2m], phi[n + 2m + 1] for the m-th change point): x′ the cubic Hermite through x′ and
    x″ at both edges, x″ the straight line (the continuing motion's limit, error O(h⁴) and O(h²))."""
    def fill(d1: np.ndarray, d2: np.ndarray):
        d1, d2 = d1.copy(), d2.copy()
        for m, cp in enumerate(points):
            if cp.group != k:
                continue
            a, b, h = n + 2 * m, n + 2 * m + 1, cp.half_width
            inside = np.flatnonzero(near[:n] & (np.abs(change_points.offset(phi[:n], cp.phi)) < h))
            t = (change_points.offset(phi[inside], cp.phi) + h) / (2 * h)
            span = 2 * h
            h00, h10, h01, h11 = 2 * t**3 - 3 * t**2 + 1, t**3 - 2 * t**2 + t, -2 * t**3 + 3 * t**2, t**3 - t**2
            d1[inside] = h00 * d1[a] + h10 * span * d2[a] + h01 * d1[b] + h11 * span * d2[b]
            d2[inside] = (1 - t) * d2[a] + t * d2[b]
        return d1, d2
    return fill


def cut(comp: Composition, n: int) -> Composition:
    """The composition at its first n angles (the rest were the neighbourhoods' edges)."""
    def first(value):
        if isinstance(value, np.ndarray):
            return value[:n] if value.ndim else value
        if isinstance(value, tuple):
            return tuple(first(v) for v in value)
        if isinstance(value, dict):
            return {key: first(v) for key, v in value.items()}
        if hasattr(value, "__dataclass_fields__") and not isinstance(value, type):
            return replace(value, **{f.name: first(getattr(value, f.name)) for f in fields(value)
                                     if f.init and not callable(getattr(value, f.name))})
        return value
    return Composition(comp.phi[:n], first(comp.joints), first(comp.links), first(comp.guides), first(comp.slides),
                       [first(group) for group in comp.groups])


def _compose(linkage: Linkage, phi: np.ndarray, points: tuple, mode: str, upto: int | None, n: int) -> Composition:
    """The composition proper (see compose_with)."""
    n_all = phi.size
    comp = Composition(phi)
    for name, (x, y) in linkage.joints.items():
        comp.joints[name] = fixed_point(x, y, n_all)
    for name, ((x, y), angle) in linkage.guides.items():
        comp.guides[name] = Guide(fixed_point(x, y, n_all), fixed_angle(angle, n_all), 0)
    crank = linkage.crank
    if isinstance(crank, SliderInput):
        guide = comp.guides[crank.guide]
        unit = guide.angle.unit()
        joint = Point(guide.point.z + phi * unit, unit, np.zeros(n_all, complex))
        comp.links[crank.link] = (joint, guide.angle)
        comp.joints[crank.joint] = joint
        comp.slides[f"{crank.joint}/{crank.guide}"] = Slide(phi.copy(), np.ones(n_all), np.zeros(n_all))
    else:
        pivot = comp.joints[crank.pivot]
        theta = Angle(crank.angle0 + crank.sense * phi, np.full(n_all, float(crank.sense)), np.zeros(n_all))
        comp.links[crank.link] = (pivot, theta)
        comp.joints[crank.joint] = on_link(pivot, theta, complex(crank.length))
    attach(comp, crank)
    for k, group in enumerate(linkage.groups[:upto]):
        singular = REGULAR
        near = change_points.near(points, k, phi)
        if near is not None:
            if mode == "limit":
                near[n:] = False                      # the edges themselves are regular
            singular = Singular(change_points.signs(points, k, phi), near,
                                limit(phi, n, points, k, near) if mode == "limit" else None)
        solution = solve_group(comp, group, singular)
        comp.groups.append(solution)
        comp.joints |= solution.joints
        comp.links |= solution.links
        comp.slides |= solution.slides
        attach(comp, group)
    return comp
