"""Class II, kind 3 group RPR, the slotted link (кулисная группа; Chaika–Vasylenko §3.1, Eremyants §2.4):
block i is hinged at the outer joint B and slides in the slot of lever j, which turns about the outer joint D.
The slot runs at the offset e from D (e = 0: through D).

    B = D + (s + ie) e_j:   |B − D|² = s² + e²,  s = σ√(|B − D|² − e²),  θ_j = arg(B − D) − arg(s + ie)
    closes iff |B − D| ≥ |e|
    differentiated (B_j: the lever's point under the block):
        s′ e_j + θ′_j i(s + ie) e_j = B′ − D′
        s″ e_j + θ″_j i(s + ie) e_j = B″ − D″ − 2s′θ′_j i e_j + θ′_j²(s + ie) e_j      (2s′θ′_j i e_j: Coriolis)
determinant s: zero where the block passes over the lever's pivot (e = 0) or the slot is tangent (e ≠ 0).
With e = 0 and B on D (|B − D| at round-off, 1e-9 of the joints' distance from the origin) the slot may point any way: the lever's
angle is not determined by the closure (arg of round-off noise).  Those angles are singular (determinant 0, the
lever's angle and every analog undefined); a group whose B stays on D over the whole turn is refused
(general.py), since its lever is then free.
The block turns with the lever (θ_i = θ_j); plan: v_B3 = v_B2 + v_B3B2 = v_D + v_B3D, and
a_B3 = a_B2 + a^k_B3B2 + a^r_B3B2 = a_D + a^n_B3D + a^τ_B3D with a^k_B3B2 = 2ω₂ × v_B3B2.
"""
from __future__ import annotations

import numpy as np

from .group import REGULAR, GroupSolution, Plan, Singular, Slide, carried, chains, rotation, sliding
from .state import Angle, Point, solve_pair


def solve(b: Point, d: Point, offset: float, branch: int, names: tuple[str, str, str],
          links: tuple[int, int], singular: Singular = REGULAR) -> GroupSolution:
    """Lever angle and block slide from B, D; ``names`` = (B, D, slide name); links (block i, lever j);
    ``singular``: σ continued through the change points and the analogs near them (group.Singular)."""
    diag = b.z - d.z
    size = max(float(np.max(np.abs(b.z), initial=0.0)), float(np.max(np.abs(d.z), initial=0.0)))
    undetermined = np.abs(diag) <= 1e-9 * size if offset == 0 else np.zeros(diag.shape, bool)
    diag = np.where(undetermined, np.nan, diag)
    radicand = singular.radicand(np.abs(diag) ** 2 - offset**2)
    closes = (radicand >= 0) | undetermined
    s = branch * singular.flip * np.sqrt(np.where(closes, radicand, np.nan))
    arm = s + 1j * offset
    e_j = np.exp(1j * (np.angle(diag) - np.angle(arm)))
    col_s, col_t = e_j, 1j * arm * e_j
    with np.errstate(over="ignore", invalid="ignore"):
        s1, w1 = solve_pair(col_s, col_t, b.d1 - d.d1)
        s2, w2 = solve_pair(col_s, col_t, b.d2 - d.d2 - 2j * s1 * w1 * e_j + w1**2 * arm * e_j)
    (s1, s2), (w1, w2) = singular.analogs((s1, s2), (w1, w2))
    lever = Angle(np.angle(e_j), w1, w2)
    slide = Slide(s, s1, s2)
    nb, nd, name = names

    def plan() -> Plan:
        on_block, on_lever = f"{nb}{links[0]}", f"{nb}{links[1]}"
        back = Slide(-s, -s1, -s2)            # the lever's point relative to the block
        vel_b, acc_b = chains(on_lever, b, nb.lower(), [sliding(on_lever, on_block, back, e_j, lever)])
        vel_d, acc_d = chains(on_lever, d, nd.lower(), [rotation(nd, on_lever, d.z, b.z, lever)])
        return Plan([vel_b, vel_d], [acc_b, acc_d], {on_lever: carried(d, lever, b.z)})
    with np.errstate(divide="ignore", invalid="ignore"):
        det = np.where(undetermined, 0.0, s / np.abs(arm))
        length = np.abs(diag)
        margins = None if offset == 0 else {
            "slot": ((length - abs(offset)) / abs(offset), (np.conj(diag) * (b.d1 - d.d1)).real / length / abs(offset))}
    return GroupSolution("RPR", {}, {links[0]: (b, lever), links[1]: (d, lever)}, {name: slide}, closes, det, plan,
                         undetermined, margins)
