"""Class II, kind 5 group RPP (the sine mechanism's dyad, Eremyants §2.2): block i hinged at the outer joint B
slides in a slot of link j; link j slides along a guide (P, u = e^{iθ_g}) of an earlier link.  The slot makes
the fixed angle α with the guide and passes through link j's reference point R = P + s_j u.

    B = P + s_j u + s_i v,  v = e^{iα}u:   linear in (s_j, s_i), one assembly; sin α ≠ 0
    s′_j u + s′_i v = B′ − P′ − (s_j u′ + s_i v′)                          (u′ = iθ′_g u, v′ = iθ′_g v)
    s″_j u + s″_i v = B″ − P″ − 2(s′_j u′ + s′_i v′) − (s_j u″ + s_i v″)   (the 2s′u′ terms: Coriolis)
Both links turn with the guide's link: θ_j = θ_g, θ_i = θ_g + α.
"""
from __future__ import annotations

import numpy as np

from .group import GroupSolution, Plan, Slide, carried, chains, sliding
from .state import Guide, Point, solve_pair


def solve(b: Point, guide: Guide, alpha: float, names: tuple[str, str, str, str],
          links: tuple[int, int]) -> GroupSolution:
    """``names`` = (B, R, guide, slot); links (block i at B, slotted link j)."""
    p, g = guide.point, guide.angle
    slot = g.shifted(alpha)
    u, v = g.unit(), slot.unit()
    turn1, turn2 = 1j * g.d1, 1j * g.d2 - g.d1**2
    s_j, s_i = solve_pair(u, v, b.z - p.z)
    v_j, v_i = solve_pair(u, v, b.d1 - p.d1 - turn1 * (s_j * u + s_i * v))
    a_j, a_i = solve_pair(u, v, b.d2 - p.d2 - 2 * turn1 * (v_j * u + v_i * v) - turn2 * (s_j * u + s_i * v))
    r = Point(p.z + s_j * u, p.d1 + v_j * u + s_j * turn1 * u, p.d2 + a_j * u + 2 * v_j * turn1 * u + s_j * turn2 * u)
    nb, nr, ng, ns = names
    along_guide, in_slot = Slide(s_j, v_j, a_j), Slide(s_i, v_i, a_i)

    def plan() -> Plan:
        on_block, on_slot, on_guide = f"{nb}{links[0]}", f"{nb}{links[1]}", f"{nb}{guide.link}"
        back = Slide(-s_i, -v_i, -a_i)         # the slotted link's point relative to the block
        vel_b, acc_b = chains(on_slot, b, nb.lower(), [sliding(on_slot, on_block, back, v, g)])
        vel_g, acc_g = chains(on_slot, carried(p, g, b.z), on_guide.lower(),
                              [sliding(on_slot, on_guide, along_guide, u, g)])
        return Plan([vel_b, vel_g], [acc_b, acc_g], {on_slot: carried(r, g, b.z)})
    return GroupSolution("RPP", {nr: r}, {links[0]: (b, slot), links[1]: (r, g)},
                         {f"{nr}/{ng}": along_guide, f"{nb}/{ns}": in_slot},
                         np.full(b.z.shape, True), np.full(b.z.shape, np.sin(alpha)), plan)
