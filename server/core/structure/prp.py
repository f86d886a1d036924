"""Class II, kind 4 group PRP: slider i on guide 1 (P₁, u₁) and slider j on guide 2 (P₂, u₂), hinged together
at the inner joint C (Chaika–Vasylenko §3.1; Artobolevsky's kind 4).

    C = P₁ + s₁u₁ = P₂ + s₂u₂:   s₁u₁ − s₂u₂ = P₂ − P₁ (linear: one assembly)
    closes iff the guides are not parallel (u₁ × u₂ ≠ 0)
    s′₁u₁ − s′₂u₂ = P′₂ − P′₁ + s₂u′₂ − s₁u′₁
    s″₁u₁ − s″₂u₂ = P″₂ − P″₁ + 2s′₂u′₂ + s₂u″₂ − 2s′₁u′₁ − s₁u″₁       (2s′u′: Coriolis of each slider)
"""
from __future__ import annotations

import numpy as np

from .group import GroupSolution, Plan, Slide, carried, chains, sliding
from .state import Guide, Point, solve_pair


def solve(first: Guide, second: Guide, names: tuple[str, str, str], links: tuple[int, int]) -> GroupSolution:
    """C from the two guides; ``names`` = (C, guide 1, guide 2); links (slider on guide 1, slider on guide 2)."""
    p1, p2, g1, g2 = first.point, second.point, first.angle, second.angle
    u1, u2 = g1.unit(), g2.unit()
    du1, du2 = 1j * g1.d1 * u1, 1j * g2.d1 * u2
    ddu1, ddu2 = (1j * g1.d2 - g1.d1**2) * u1, (1j * g2.d2 - g2.d1**2) * u2
    s_1, s_2 = solve_pair(u1, -u2, p2.z - p1.z)
    v_1, v_2 = solve_pair(u1, -u2, p2.d1 - p1.d1 + s_2 * du2 - s_1 * du1)
    a_1, a_2 = solve_pair(u1, -u2, p2.d2 - p1.d2 + 2 * v_2 * du2 + s_2 * ddu2 - 2 * v_1 * du1 - s_1 * ddu1)
    c_z = p1.z + s_1 * u1
    c = Point(c_z, p1.d1 + v_1 * u1 + s_1 * du1, p1.d2 + a_1 * u1 + 2 * v_1 * du1 + s_1 * ddu1)
    nc, n1, n2 = names
    slide1, slide2 = Slide(s_1, v_1, a_1), Slide(s_2, v_2, a_2)

    def plan() -> Plan:
        steps = []
        for guide, slide, unit, link in ((first, slide1, u1, links[0]), (second, slide2, u2, links[1])):
            under = carried(guide.point, guide.angle, c_z)
            steps.append(chains(nc, under, f"{nc}{guide.link}".lower(),
                                [sliding(f"{nc}{link}", f"{nc}{guide.link}", slide, unit, guide.angle)]))
        return Plan([v for v, _ in steps], [a for _, a in steps])
    crossing = np.sin(g2.th - g1.th)
    return GroupSolution("PRP", {nc: c}, {links[0]: (c, g1), links[1]: (c, g2)},
                         {f"{nc}/{n1}": slide1, f"{nc}/{n2}": slide2}, crossing != 0, crossing, plan)
