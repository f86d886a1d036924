"""The reduced moment of all loads on the crank-slider by virtual work (power equality, Chaika–Vasylenko (3.24)).

M = −Σ(F·V_q + M·u) over gravity, d'Alembert inertia loads and the piston force, along ω₁:
the balancing moment of the frictionless kinetostatics must equal it at every angle.
"""
from __future__ import annotations

import numpy as np

from ..mechanisms import SLIDER_CRANK


def reduced_moment(params: dict, applied: dict, phi: np.ndarray) -> np.ndarray:
    """M = −Σ(F·V_q + M·u), power equality (Chaika–Vasylenko (3.24)): the forces G₂ + F_in2 with V_qS2, the
    slider's F_3p + G₃ + F_in3 with u₃₁, and the couples M_in2, M_in1 with the rod's and the crank's turning
    analogs −u₂₁, −1 (couples counted counter-clockwise, the crank turning clockwise)."""
    v = SLIDER_CRANK.evaluate(params, phi, set()).values
    return -(np.sum((applied["G2"] + applied["F_in2"]) * v["v_s2"], 1)
             + (applied["F_3p"][:, 0] + applied["G3"][:, 0] + applied["F_in3"][:, 0]) * v["u31"]
             + applied["M_in2"] * (-v["u21"]) + applied["M_in1"] * (-1.0))
