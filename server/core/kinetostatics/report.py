"""The force scene's computation: reactions over a cycle, their iteration, efficiency, and the check of (3.2)."""
from __future__ import annotations

import numpy as np

from .crank_slider import ForceAnalysis, cross


def efficiency(analysis: ForceAnalysis) -> dict:
    """η = |A_useful|/A_driving over the cycle (seed 002 (3.38)), the crank driven at the given speed.

    A_useful is the work against the piston force, A_driving the work of the balancing moment;
    inertia and gravity do no net work over a cycle at constant speed, so A_driving − A_useful is
    what the friction in the pairs consumes.
    """
    phi = analysis.phi
    useful = -analysis.applied["F_3p"][:, 0] * analysis.applied["u31"]       # power against the piston force / ω₁
    driving = analysis.balancing_moment
    if not np.isfinite(driving).all():
        return {"efficiency": None, "work_useful": None, "work_driving": None}
    a_useful, a_driving = float(np.trapezoid(useful, phi)), float(np.trapezoid(driving, phi))
    return {"efficiency": abs(a_useful) / a_driving if a_driving > 0 else None,
            "work_useful": a_useful, "work_driving": a_driving}


def equilibrium_residuals(analysis: ForceAnalysis, k: int = -1) -> dict:
    """Σ forces and Σ moments on the rod and the slider for approximation k (should vanish)."""
    a, p, approx = analysis.applied, analysis.points, analysis.approximations[k]
    n = analysis.phi.size
    rod_force = approx.R12 - approx.R23 + a["G2"] + a["F_in2"]
    rod_moment = (cross(p["B"] - p["A"], -approx.R23) + cross(p["S2"] - p["A"], a["G2"] + a["F_in2"])
                  + a["M_in2"] + approx.friction["M2"])
    slider = (approx.R23 + np.stack([approx.friction["F34"], approx.N], 1) + a["F_3p"] + a["G3"] + a["F_in3"])
    return {"rod_force": np.linalg.norm(rod_force, axis=1), "rod_moment": np.abs(rod_moment),
            "slider_force": np.linalg.norm(slider, axis=1), "size": n}
