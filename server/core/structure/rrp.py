"""Class II, kind 2 group RRP (Chaika–Vasylenko §3.1, Fig. 3.3b: the crank-slider's dyad 2–3): link i (rod)
joins the outer joint B to the inner joint C on slider j, which runs along a guide (P, u = e^{iθ_g}) that is
fixed on an earlier link (the frame or a moving one).

    C = P + s u,  |C − B| = a:   t = Re((B − P)ū), h = Im((B − P)ū),  s = t + σ√(a² − h²)
    closes iff |h| ≤ a (limit of assembly: the rod perpendicular to the guide)
    loop P + s u = B + a e_i differentiated (u′ = iθ′_g u, u″ = (iθ″_g − θ′_g²)u):
        s′ u − a θ′_i (i e_i) = B′ − P′ − s u′
        s″ u − a θ″_i (i e_i) = B″ − P″ − 2s′u′ − s u″ − aθ′_i² e_i      (2s′u′: the Coriolis term)
determinant a cos(θ_i − θ_g): zero with the rod perpendicular to the guide.
"""
from __future__ import annotations

import numpy as np

from .group import REGULAR, GroupSolution, Plan, Singular, Slide, carried, chains, rotation, sliding
from .state import Angle, Guide, Point, solve_pair


def solve(b: Point, guide: Guide, length: float, branch: int,
          names: tuple[str, str, str], links: tuple[int, int], singular: Singular = REGULAR) -> GroupSolution:
    """C from B and the guide; ``names`` = (B, C, guide's name); link i = BC (rod), link j = slider at C;
    ``singular``: σ continued through the change points and the analogs near them (group.Singular)."""
    p, g = guide.point, guide.angle
    u = g.unit()
    rel = (b.z - p.z) * np.conj(u)
    radicand = singular.radicand(length**2 - rel.imag**2)
    closes = radicand >= 0
    s = rel.real + branch * singular.flip * np.sqrt(np.where(closes, radicand, np.nan))
    rate = ((b.d1 - p.d1) * np.conj(u) - 1j * g.d1 * rel).imag          # h′, h = Im(rel) B's distance off the guide
    c_z = p.z + s * u
    e_i = (c_z - b.z) / length
    du, ddu = 1j * g.d1 * u, (1j * g.d2 - g.d1**2) * u
    col_s, col_i = u, -1j * length * e_i
    with np.errstate(over="ignore", invalid="ignore"):
        s1, w1 = solve_pair(col_s, col_i, b.d1 - p.d1 - s * du)
        s2, w2 = solve_pair(col_s, col_i, b.d2 - p.d2 - 2 * s1 * du - s * ddu - length * w1**2 * e_i)
    (s1, s2), (w1, w2) = singular.analogs((s1, s2), (w1, w2))
    ang_i = Angle(np.angle(e_i), w1, w2)
    slide = Slide(s, s1, s2)
    c = carried(b, ang_i, c_z)
    nb, nc, ng = names

    def plan() -> Plan:
        under = carried(p, g, c_z)           # the guide's point under the slider (on the guide's link)
        on_guide, on_slider = f"{nc}{guide.link}", f"{nc}{links[1]}"
        vel_b, acc_b = chains(nc, b, nb.lower(), [rotation(nb, nc, b.z, c_z, ang_i)])
        vel_g, acc_g = chains(nc, under, on_guide.lower(), [sliding(on_slider, on_guide, slide, u, g)])
        return Plan([vel_b, vel_g], [acc_b, acc_g])
    return GroupSolution("RRP", {nc: c}, {links[0]: (b, ang_i), links[1]: (c, g)}, {f"{nc}/{ng}": slide},
                         closes, np.cos(ang_i.th - g.th), plan,
                         margins={"rod": ((length - np.abs(rel.imag)) / length, -np.sign(rel.imag) * rate / length)})
