"""The reduced moment of all loads on the crank-slider by virtual work (power equality, seed 002 (3.24)).

M = −Σ(F·V_q + M·u) over gravity, d'Alembert inertia loads and the piston force, along ω₁:
the balancing moment of the frictionless kinetostatics must equal it at every angle.
"""
from __future__ import annotations

import numpy as np

from ..mechanisms import SLIDER_CRANK


def reduced_moment(params: dict, applied: dict, phi: np.ndarray) -> np.ndarray:
    v = SLIDER_CRANK.evaluate(params, phi, set()).values
    return -(np.sum((applied["G2"] + applied["F_in2"]) * v["v_s2"], 1)
             + (applied["F_3p"][:, 0] + applied["G3"][:, 0] + applied["F_in3"][:, 0]) * v["u31"]
             + applied["M_in2"] * (-v["u21"]) + applied["M_in1"] * (-1.0))
