"""Composition in order: the input crank, then each group from the elements already placed (Chaika–Vasylenko
§3.1: the kinematic analysis follows the order of attachment; Eremyants §2.1 for the analogs).

    crank:  A = O + l e^{iθ₁},  θ₁ = θ₀ + σφ,  θ′₁ = σ,  θ″₁ = 0
    slider: A = P + s u (a frame guide through P along u = e^{iθ_g}),  A′ = u,  A″ = 0: the generalised
            coordinate is s (``phi`` holds s, m) and every analog is with respect to it
Every group returns its joints, links, slides and the angles where its closure has a real solution; a point
or guide fixed on a link follows the link rigidly (state.on_link).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from . import prp, rpp, rpr, rrp, rrr
from .group import GroupSolution, Slide
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


def solve_group(comp: Composition, group) -> GroupSolution:
    """The group's kind module, given its outer joints and guides as placed so far."""
    j, g = comp.joints, comp.guides
    names = group.outer + group.guides
    if group.kind == "RRR":
        return rrr.solve(j[group.outer[0]], j[group.outer[1]], *group.sizes, group.branch,
                         (group.outer[0], group.outer[1], group.inner), group.links)
    if group.kind == "RRP":
        return rrp.solve(j[group.outer[0]], g[group.guides[0]], group.sizes[0], group.branch,
                         (group.outer[0], group.inner, group.guides[0]), group.links)
    if group.kind == "RPR":
        return rpr.solve(j[group.outer[0]], j[group.outer[1]], group.sizes[0], group.branch,
                         (*names, group.inner), group.links)
    if group.kind == "PRP":
        return prp.solve(g[group.guides[0]], g[group.guides[1]], (group.inner, *names), group.links)
    return rpp.solve(j[group.outer[0]], g[group.guides[0]], group.angle,
                     (group.outer[0], group.inner, group.guides[0], "slot"), group.links)


def compose(linkage: Linkage, phi: np.ndarray) -> Composition:
    """Positions and analogs of every joint, link, guide and slide at ``phi`` (rad), in order of attachment."""
    phi = np.asarray(phi, float)
    n = phi.size
    comp = Composition(phi)
    for name, (x, y) in linkage.joints.items():
        comp.joints[name] = fixed_point(x, y, n)
    for name, ((x, y), angle) in linkage.guides.items():
        comp.guides[name] = Guide(fixed_point(x, y, n), fixed_angle(angle, n), 0)
    crank = linkage.crank
    if isinstance(crank, SliderInput):
        guide = comp.guides[crank.guide]
        unit = guide.angle.unit()
        joint = Point(guide.point.z + phi * unit, unit, np.zeros(n, complex))
        comp.links[crank.link] = (joint, guide.angle)
        comp.joints[crank.joint] = joint
        comp.slides[f"{crank.joint}/{crank.guide}"] = Slide(phi.copy(), np.ones(n), np.zeros(n))
    else:
        pivot = comp.joints[crank.pivot]
        theta = Angle(crank.angle0 + crank.sense * phi, np.full(n, float(crank.sense)), np.zeros(n))
        comp.links[crank.link] = (pivot, theta)
        comp.joints[crank.joint] = on_link(pivot, theta, complex(crank.length))
    attach(comp, crank)
    for group in linkage.groups:
        solution = solve_group(comp, group)
        comp.groups.append(solution)
        comp.joints |= solution.joints
        comp.links |= solution.links
        comp.slides |= solution.slides
        attach(comp, group)
    return comp
