"""Class II, kind 1 group RRR (two links i, j; outer joints B on an earlier link, D on an earlier link; inner
joint C): Chaika–Vasylenko §3.1; the diagonal (Zinoviev) method of Eremyants (2.38)–(2.41).

    BC = a, DC = b, d = D − B, L = |d|,  cos α = (a² + L² − b²)/(2aL),  C = B + a e^{i(arg d + σα)}
    closes iff |a − b| ≤ L ≤ a + b   (limit of assembly: the triangle BCD flattens)
    loop B + a e_i = D + b e_j differentiated:   a θ′_i (i e_i) − b θ′_j (i e_j) = D′ − B′
                                                a θ″_i (i e_i) − b θ″_j (i e_j) = D″ − B″ + aθ′_i² e_i − bθ′_j² e_j
determinant a b sin(θ_j − θ_i): zero when BC and DC are in line (dead position).
"""
from __future__ import annotations

import numpy as np

from .group import REGULAR, GroupSolution, Plan, Singular, carried, chains, rotation
from .state import Angle, Point, solve_pair


def solve(b: Point, d: Point, a_len: float, b_len: float, branch: int, names: tuple[str, str, str],
          links: tuple[int, int], singular: Singular = REGULAR) -> GroupSolution:
    """C from B, D; ``names`` = (B, D, C); link i = BC, link j = DC; ``singular``: σ continued through the
    change points and the analogs near them (group.Singular)."""
    diag = d.z - b.z
    length = np.abs(diag)
    with np.errstate(divide="ignore", invalid="ignore"):
        cos_alpha = (a_len**2 + length**2 - b_len**2) / (2 * a_len * length)
        # radicand of sin α factorised: ((a + b)² − L²)(L² − (a − b)²) ≥ 0 where the group closes
        radicand = singular.radicand(((a_len + b_len) ** 2 - length**2) * (length**2 - (a_len - b_len) ** 2))
        closes = radicand >= 0
        alpha = np.arctan2(np.sqrt(np.where(closes, radicand, np.nan)), 2 * a_len * length * cos_alpha)
        rate = (np.conj(diag) * (d.d1 - b.d1)).real / length              # |BD|′
    e_i = np.exp(1j * (np.angle(diag) + branch * singular.flip * alpha))
    c_z = b.z + a_len * e_i
    e_j = (c_z - d.z) / b_len
    th_i, th_j = np.angle(e_i), np.angle(e_j)
    col_i, col_j = 1j * a_len * e_i, -1j * b_len * e_j
    with np.errstate(over="ignore", invalid="ignore"):
        w1, v1 = solve_pair(col_i, col_j, d.d1 - b.d1)
        w2, v2 = solve_pair(col_i, col_j, d.d2 - b.d2 + a_len * w1**2 * e_i - b_len * v1**2 * e_j)
    (w1, w2), (v1, v2) = singular.analogs((w1, w2), (v1, v2))
    ang_i, ang_j = Angle(th_i, w1, w2), Angle(th_j, v1, v2)
    c = carried(b, ang_i, c_z)
    nb, nd, nc = names

    def plan() -> Plan:
        vel_b, acc_b = chains(nc, b, nb.lower(), [rotation(nb, nc, b.z, c_z, ang_i)])
        vel_d, acc_d = chains(nc, d, nd.lower(), [rotation(nd, nc, d.z, c_z, ang_j)])
        return Plan([vel_b, vel_d], [acc_b, acc_d])
    size = a_len + b_len
    margins = {"stretched": ((size - length) / size, -rate / size),
               "folded": ((length - abs(a_len - b_len)) / size, rate / size)}
    return GroupSolution("RRR", {nc: c}, {links[0]: (b, ang_i), links[1]: (d, ang_j)}, {}, closes,
                         np.sin(th_j - th_i), plan, margins=margins)
