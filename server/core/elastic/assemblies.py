"""The elastic four-bar's two assemblies side by side, Drakunov–Tuleshova (2), (4), (9), (10).

For the '+' and the '−' sign of (4) (the two closures of the loop (3)), over one turn of the crank:

    I_n(φ₁)  = I₁ + I₃u₃₁²,            I_n′ = 2I₃u₃₁u₃₁′                               (9)
    c_n(φ₁)  = l₁²sin²(φ₁ − φ₂)/Δ,     Δ = e₁l₁²sin²(φ₁ − φ₂) + e₂ + e₃l₃²sin²(φ₂ − φ₃)   (2)
    c_n′     = [l₁²sin 2(φ₁ − φ₂)(1 − u₂₁) − c_nΔ′]/Δ                    (unnumbered in the paper)

with u₃₁ of (8) in its corrected sign and u₃₁′ of (10).  The mechanism's own closed forms give u₃₁, u₃₁′
(the reduction of the inertias) and the linkage stiffness gives c_n, c_n′; the coupler's inertia is left out,
as in the paper (the request's inertias are I₁ = J1 and I₃ = J3 alone).
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..dynamics.reduction import reduced_inertia
from ..mechanisms import MECHANISMS
from .stiffness import linkage_stiffness

OUTPUT = "assemblies"                                    # the name of this answer among an elastic request's outputs
ASSEMBLIES = {"assembly_1": 1.0, "assembly_2": -1.0}     # the answer's key → the sign of (4)
CURVES = ("inertia", "inertia_slope", "stiffness", "stiffness_slope")   # I_n, I_n′, c_n, c_n′ of each assembly
POINTS = 361                                             # 1° of crank angle


def assembly_curves(machine, phi: np.ndarray | None = None) -> dict:
    """{"phi": φ₁, "assembly_1": {curve: values}, "assembly_2": {…}} for the elastic machine's mechanism, inertias
    and compliances (SI: kg·m², kg·m²/rad, N·m/rad, N·m/rad²), at the crank angles phi (rad; by default one cycle
    in POINTS points)."""
    if phi is None:
        phi = np.linspace(0.0, MECHANISMS[machine.mechanism].cycle(machine.params), POINTS)
    inertias = replace(machine.inertias, J_rotor=0.0)    # the rotor is I_d, on the other side of the spring
    answer = {"phi": phi}
    for name, sign in ASSEMBLIES.items():
        params = machine.params | {"assembly": sign}
        inertia = reduced_inertia(machine.mechanism, params, inertias, phi)
        stiffness, slope, _ = linkage_stiffness(machine.mechanism, params, machine.compliances, phi)
        answer[name] = dict(zip(CURVES, (inertia.J, inertia.dJ, stiffness, slope)))
    if machine.mechanism == "four_bar":             # the linkage's Grashof class with its inequality
        from ..mechanisms.four_bar import grashof_row
        p = machine.params
        answer["grashof"] = [grashof_row(p["l0"], p["l1"], p["l2"], p["l3"])]
    return answer
