"""Wear of the pairs of a general mechanism (Chaika–Vasylenko §4 applied to every pair a structural-group
kinetostatics solves): each revolute pair's two elements and each prismatic pair's slider.

    revolute a–b   δ(β) = a ∫ R_ab |θ′_b − θ′_a| max(cos ψ, 0) dφ,  a = 2·10⁶ k N_c/(π l_z)      (4.12), (4.13)
                   the element on link a taken as the journal (pressed against the force it receives, −R_ab), the
                   one on link b as the bush (pressed where R_ab points); β counter-clockwise on the element's link
    prismatic a–b  δ± = a ∫ |N s′| dφ over the angles pressing side ±,  a = 10⁶ (4/π) k N_c/(l d)       (4.17)
    k = I_s/p_m, p_m = 4 R_m/(π l d) with R_m the cycle mean of |R| (|N|)                               (4.23), (4.24)

The integrals are trapezoids over the kinetostatics' closed grid of n angles (second order; the maximum over β
on a 5° grid).  One set of dimensions for all revolute pairs (pin_diameter, pin_length, I_pin for the journal,
I_bush for the bush) and one for all prismatic pairs (piston_diameter, piston_length, I_piston for the slider);
the guides' wear along their length needs each slider's footprint and is not computed.
"""
from __future__ import annotations

import numpy as np

from .groups.report import label, pair_forces
from .wear import mean_pressure, piston_wear, revolute_wear

BETA = np.radians(np.arange(0, 360, 5))


def _link_angle(comp, link: int, phi: np.ndarray) -> np.ndarray:
    """θ of a link (0 for the frame)."""
    return comp.links[link][1].th if link in comp.links else np.zeros_like(phi)


def general_wear(result, parts: dict, cycles: float) -> dict:
    """The rows of every pair's elements (µm) and the coefficients used; ``result``: a GroupForces."""
    phi, comp = result.phi, result.comp
    reactions, normals, _ = pair_forces(result, result.solution)
    rows = []
    for pair in result.pairs:
        name = label(pair.a, pair.b)
        if pair.kind == "R":
            force = reactions[f"R{name}"]
            p_m = mean_pressure(np.hypot(force[:, 0], force[:, 1]), parts["pin_length"], parts["pin_diameter"])
            for link, journal, intensity, sign in ((pair.a, True, parts["I_pin"], -1.0),
                                                   (pair.b, False, parts["I_bush"], 1.0)):
                k = intensity / p_m if p_m > 0 else 0.0
                wear = revolute_wear(phi, sign * force, np.abs(pair.relative), _link_angle(comp, link, phi), BETA,
                                     k, cycles, parts["pin_length"], journal=journal)
                at = int(np.argmax(wear))
                rows.append({"pair": name, "kind": "R", "link": int(link), "element": "journal" if journal else "bush",
                             "wear": float(wear[at]), "beta": float(np.degrees(BETA[at])), "mean_pressure": p_m,
                             "k": k})
        else:
            normal = normals[f"N{name}"]
            p_m = mean_pressure(normal, parts["piston_length"], parts["piston_diameter"])
            k = parts["I_piston"] / p_m if p_m > 0 else 0.0
            for side in (1, -1):
                rows.append({"pair": name, "kind": "P", "link": int(pair.b), "element": "slider", "side": side,
                             "wear": piston_wear(phi, normal, pair.relative, k, cycles, parts["piston_length"],
                                                 parts["piston_diameter"], side),
                             "mean_pressure": p_m, "k": k})
    return {"pairs_wear": rows, "cycles": cycles,
            "largest": max(rows, key=lambda row: row["wear"]) if rows else None}
