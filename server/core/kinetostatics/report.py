"""The force scene's computation: reactions over a cycle, their iteration, efficiency, and the check of (3.2)."""
from __future__ import annotations

import numpy as np

from ..mechanisms import GeometryError
from .. import errata
from .crank_slider import ForceAnalysis, cross


def efficiency(analysis: ForceAnalysis) -> dict:
    """η = |A_useful|/(|A_useful| + |A_friction|) over the cycle, the second form of Chaika–Vasylenko (3.38).

    A_useful is the work against the piston force, A_friction what the pairs dissipate, each power divided by
    ω₁: f₃₄|N||V_qB| in the guide, M_A|1 − u₂₁| and M_B|u₂₁| in the joints A and B, M_O in the main bearing
    (the relative angular velocities over ω₁).  Both are non-negative, so 0 ≤ η ≤ 1, and η = 1 exactly
    without friction.  A_driving, the work of the balancing moment, is reported beside them; it equals their
    sum when inertia and gravity do no net work over the cycle (constant speed).
    """
    phi, applied, friction = analysis.phi, analysis.applied, analysis.final.friction
    useful = -applied["F_3p"][:, 0] * applied["u31"]                     # power against the piston force / ω₁
    lost = (np.abs(friction["F34"] * applied["u31"]) + friction["M_A"] * np.abs(1 - applied["u21"])
            + friction["M_B"] * np.abs(applied["u21"]) + friction["M_O"])
    driving = analysis.balancing_moment
    if not (np.isfinite(driving).all() and np.isfinite(lost).all()):
        return {"efficiency": None, "work_useful": None, "work_driving": None, "work_friction": None}
    a_useful, a_lost = abs(float(np.trapezoid(useful, phi))), float(np.trapezoid(lost, phi))
    return {"efficiency": 1.0 if a_lost == 0 else a_useful / (a_useful + a_lost),
            "work_useful": a_useful, "work_driving": float(np.trapezoid(driving, phi)), "work_friction": a_lost}


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


def forces_report(analysis: ForceAnalysis, pairs) -> dict:
    """Everything the force scene draws: reactions, applied loads, friction, efficiency (all from the solved
    equilibrium), and the textbook's approximations: their changes, the series' ratio q at each angle and the
    guide's f₃₄|tan ψ| (self-locking where it reaches 1); without "iteration" and "numerics" for an analysis
    made without the approximations (crank_slider.analyse, table=False)."""
    final = analysis.final
    norm = lambda v: np.linalg.norm(v, axis=1)
    angle = lambda v: np.degrees(np.arctan2(v[:, 1], v[:, 0]))
    reactions = {"R12": final.R12, "R23": final.R23, "R41": analysis.R41,
                 "R34": np.stack([final.N * 0.0, final.N], 1)}          # NaN stays NaN in both components
    report = {
        "phi": analysis.phi,
        "points": analysis.points,
        "reactions": reactions,
        "magnitudes": {name: norm(value) for name, value in reactions.items()},
        "directions": {name: angle(value) for name, value in reactions.items()},
        "balancing_moment": analysis.balancing_moment,
        "applied": {k: analysis.applied[k] for k in ("G2", "G3", "F_in2", "F_in3", "F_3p", "M_in2")},
        "friction": {k: final.friction[k] for k in ("M_A", "M_B", "M_O", "F34")},
        "friction_circles": {"O": pairs.f14 * pairs.r14, "A": pairs.f12 * pairs.r12, "B": pairs.f23 * pairs.r23},
        "converged": analysis.converged,
        **efficiency(analysis),
    }
    if analysis.numerics is not None:
        report["iteration"] = {"changes": [a.change for a in analysis.approximations], "ratio": analysis.ratio,
                               "approximations": len(analysis.approximations), "ratios": analysis.ratios,
                               "guide_ratio": analysis.guide_ratio}
        report["numerics"] = analysis.numerics
    return report


def crank_check(analysis: ForceAnalysis, frictionless: ForceAnalysis, reduced_moment: np.ndarray) -> dict:
    """Chaika–Vasylenko (3.2): the balancing moment against the reduced moment known from dynamics (virtual work),
    as a relative error; with friction it measures friction's share, without it the arithmetic."""
    scale = np.maximum(np.abs(reduced_moment).max(), 1e-300)
    return {"frictionless": float(np.nanmax(np.abs(frictionless.balancing_moment - reduced_moment)) / scale),
            "with_friction": float(np.nanmax(np.abs(analysis.balancing_moment - reduced_moment)) / scale)}


BOOK_WEAR = {"bush_23": 88.0, "pin_23": 36.0, "cylinder": 43.0, "piston": 76.0}   # Chaika–Vasylenko §4.3, µm


def wear_report(analysis: ForceAnalysis, parts: dict, cycles: float) -> dict:
    """Wear of the pin and bush of pair 2–3 (polar, over β), of the piston and along the cylinder.

    parts: pin_diameter, pin_length (l_z23), piston_diameter, piston_length (m) and the wear
    intensities I_s of pin, bush, piston and cylinder; the coefficients k = I_s/p_m (4.24)."""
    from .wear import cylinder_wear, mean_pressure, piston_wear, revolute_wear
    phi = analysis.phi
    values = analysis.applied
    final = analysis.final
    r23 = final.R23                                   # rod on the pin (link 3)
    p23 = mean_pressure(np.linalg.norm(r23, axis=1), parts["pin_length"], parts["pin_diameter"])
    if p23 == 0:                                      # k = I_s/p_m (4.24) needs a pressure
        raise GeometryError("loads", "nothing presses the piston pin: wear needs a load (the piston force, the "
                                     "gas force or the masses)")
    beta = np.radians(np.arange(0, 361, 5))
    rod = analysis.points["B"] - analysis.points["A"]
    rod_angle = np.arctan2(rod[:, 1], rod[:, 0])     # the bush turns with the rod; the pin stays with the piston
    relative = np.abs(values["u21"])                  # |u₂₁ − u₃₁| with the piston not turning (4.9)
    pin = revolute_wear(phi, r23, relative, np.zeros_like(phi), beta, parts["I_pin"] / p23, cycles,
                        parts["pin_length"], journal=True)
    bush = revolute_wear(phi, -r23, relative, rod_angle, beta, parts["I_bush"] / p23, cycles,
                         parts["pin_length"], journal=False)
    normal = final.N
    side = 1 if np.nansum(np.clip(normal, 0, None)) >= np.nansum(np.clip(-normal, 0, None)) else -1
    pressed = np.where(np.sign(normal) == side, np.abs(normal), 0.0)
    p34 = mean_pressure(pressed, parts["piston_length"], parts["piston_diameter"])
    if p34 == 0:
        raise GeometryError("loads", "nothing presses the piston on the cylinder: wear needs a load across the "
                                     "guide")
    u31 = values["u31"]
    x_b = analysis.points["B"][:, 0]
    travel = x_b.max() - x_b                          # piston crown from top dead centre
    stroke = float(travel.max())
    along = np.linspace(0.0, stroke + parts["piston_length"], 121)
    return {
        "beta": beta, "pin": pin, "bush": bush,
        "piston": piston_wear(phi, normal, u31, parts["I_piston"] / p34, cycles, parts["piston_length"],
                              parts["piston_diameter"], side),
        "cylinder_x": along,
        "cylinder": cylinder_wear(phi, normal, u31, travel, along, parts["I_cylinder"] / p34, cycles,
                                  parts["piston_length"], parts["piston_diameter"], side),
        "mean_pressure_23": p23, "mean_pressure_34": p34, "pressed_side": side,
        "book": BOOK_WEAR, "allowed": [150.0, 180.0],
        "errata": [*errata.wear_example(*_crank_and_rod(analysis.points)),
                   errata.piston_pressure(float(np.nanmax(pressed)), parts["piston_length"], parts["piston_diameter"])],
    }


def _crank_and_rod(points: dict) -> tuple[float, float]:
    """l₁ = OA and l₂ = AB from the joints' positions (rigid links: any angle)."""
    return (float(np.hypot(*(points["A"][0] - points["O"][0]))), float(np.hypot(*(points["B"][0] - points["A"][0]))))
