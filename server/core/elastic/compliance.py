"""Compliances of the elastic linkage from the parts' dimensions and materials, Eremyants (1.16), (1.24)–(1.25),
(1.37).

    e_shaft = L/(G I_p),  I_p = π d⁴/32   (torsion of a round shaft, rad/(N·m))
    e_rod   = l/(E F),    F = π d²/4      (tension–compression of a round rod, m/N)

A compliance on a shaft that turns u = ω_D/ω_L times as fast as the crank shaft L (the motor shaft behind a
gear of ratio u) reduces to the crank as e_D/u²: the same twist energy M_D²e_D/2 with M_D = M_L/u gives
M_L²(e_D/u²)/2.  Eremyants (1.16) and (1.37) print e_D·u² with the same u as (1.15) and (1.17) [erratum];
both are computed and the corrected one is used:

    e₁ = e_L + e_D/u²   (corrected),    e₁ = e_L + e_D·u²   (as printed).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errata import row


@dataclass(frozen=True)
class Dimensions:
    shaft_length: float          # L of the crank shaft, m
    shaft_diameter: float        # d of the crank shaft, m
    rod_length: float            # l of the rod (coupler), m
    rod_diameter: float          # d₂ of the rod's round section, m
    motor_shaft_length: float    # L_D of the motor shaft, m (0: none)
    motor_shaft_diameter: float  # d_D, m
    ratio: float                 # u = ω_D/ω_L, the gear ratio between the motor shaft and the crank shaft
    shear_modulus: float = 8.0e10   # G, Pa (steel)
    young: float = 2.1e11           # E, Pa (steel)


def shaft_compliance(length: float, diameter: float, shear_modulus: float) -> float:
    """e = L/(G I_p) with I_p = πd⁴/32, rad/(N·m) (Eremyants (1.24))."""
    return length / (shear_modulus * np.pi * diameter**4 / 32)


def rod_compliance(length: float, diameter: float, young: float) -> float:
    """e = l/(E F) with F = πd²/4, m/N (Eremyants (1.25))."""
    return length / (young * np.pi * diameter**2 / 4)


def reduced_to_crank(compliance: float, ratio: float) -> tuple[float, float]:
    """A compliance on a shaft turning u times as fast as the crank, reduced to the crank: (corrected e/u²,
    as printed in Eremyants (1.16), (1.37) e·u²)."""
    return compliance / ratio**2, compliance * ratio**2


def compliance_report(d: Dimensions) -> dict:
    """e₁ (the crank shaft and the motor shaft reduced to it) and e₂ (the rod) from the dimensions, each part,
    and the erratum of (1.16)/(1.37) as a row: the printed e₁ beside the corrected one."""
    e_crank = shaft_compliance(d.shaft_length, d.shaft_diameter, d.shear_modulus)
    e_motor = (shaft_compliance(d.motor_shaft_length, d.motor_shaft_diameter, d.shear_modulus)
               if d.motor_shaft_length > 0 else 0.0)
    corrected, printed = reduced_to_crank(e_motor, d.ratio)
    e2 = rod_compliance(d.rod_length, d.rod_diameter, d.young)
    return {"e_crank_shaft": e_crank, "e_motor_shaft": e_motor, "e_motor_reduced": corrected,
            "polar_moment": np.pi * d.shaft_diameter**4 / 32, "rod_area": np.pi * d.rod_diameter**2 / 4,
            "e1": e_crank + corrected, "e2": e2, "ratio": d.ratio,
            "errata": [row("compliance_reduction", "eremyants", "(1.16), (1.37)", e_crank + printed,
                           e_crank + corrected, "rad_Nm")]}
