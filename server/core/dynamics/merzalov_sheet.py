"""Merzalov's construction on a drawing sheet, Lecture 10 §10.6 and steps 2–5 (L15)–(L24): the scales (mm per
unit: an ordinate y = μ·value) and the diagrams' ordinates in mm at the sheet's positions.

    μ_φ = b/(2π)                  the cycle drawn over the base b (§10.6; printed μ_p, the errata table)
    μ_p = y_pmax/p_max            the indicator diagram's pressure scale                              (L15)
    μ_F = μ_p/S_п                 the gas force drawn with the same ordinates, S_п = πd_п²/4           (L16)
    μ_M                           the moments' scale: the largest |M_д| over the height kept for it
    μ_A = μ_M μ_φ/k₁              graphical integration with the pole distance k₁                      (L19)
    μ_I                           the reduced inertia I_II's scale
    μ_T = 2μ_I/ω_ср²              the I_II diagram read as T_II = I_II ω_ср²/2                           (L20)
    y*_TII = y_TII μ_A/μ_T        T_II moved to the work scale, subtracted from A(φ)'s ordinates        (L21)
    ΔT_Imax = y_ΔTImax/μ_A,  I_I = ΔT_Imax/(ω_ср²[δ])                                                   (L22)
    μ_ω = μ_A I_I ω_ср: the ΔT_I diagram is the Δω diagram in this scale                               (L24)

Each free scale (μ_M, μ_I) is the largest "round" one (1, 2, 2.5, 4, 5 × 10ᵏ mm per unit, the course project's
standard values read the other way) with which its diagram fits its height; the lengths are those of an A1
sheet's diagrams.  The sheet's numbers are the flywheel study's own (report.flywheel): the works A_д, A_с, A,
I_II and ΔT_I = A − I_II ω_ср²/2 on its fine grid, read at the positions by linear interpolation.
"""
from __future__ import annotations

import math

import numpy as np

from ..course_project.scales import standard_scale

BASE_MM = 240.0           # b, the abscissa of one cycle (the errata's DIAGRAM_BASE_MM)
MOMENT_MM = 80.0          # the height kept for the M_д diagram
INERTIA_MM = 60.0         # the height kept for the I_II diagram
PRESSURE_MM = 100.0       # y_pmax of the indicator diagram
POLE_MM = 40.0            # k₁, the pole distance of the graphical integration (30…60 mm)
POSITIONS = 12            # the sheet's positions of the crank, 30° apart


def round_scale(extent: float, length_mm: float) -> float | None:
    """The largest round μ (mm per unit) with extent·μ ≤ length_mm: 1/standard_scale."""
    per_mm = standard_scale(extent, length_mm)
    return None if per_mm is None else 1.0 / per_mm


def merzalov_sheet(phi: np.ndarray, moment: np.ndarray, work_driving: np.ndarray, work_total: np.ndarray,
                   inertia_ii: np.ndarray, omega_mean: float, delta: float, inertia_i: float,
                   indicator: tuple[float, float] | None = None) -> dict:
    """The scales (rows {symbol, equation, value, unit}) and the ordinates (rows per position, mm); ``indicator``:
    (p_max Pa, piston diameter m) of a piston engine's diagram, for μ_p and μ_F."""
    mu_phi = BASE_MM / (2 * np.pi)
    mu_m = round_scale(float(np.max(np.abs(moment))), MOMENT_MM)
    mu_a = mu_m * mu_phi / POLE_MM
    mu_i = round_scale(float(np.max(inertia_ii)), INERTIA_MM)
    mu_t = 2 * mu_i / omega_mean**2
    group_one = work_total - 0.5 * inertia_ii * omega_mean**2
    delta_t = group_one - group_one[0]
    y_swing = float(np.max(delta_t) - np.min(delta_t)) * mu_a
    swing = y_swing / mu_a
    required = swing / (omega_mean**2 * delta)
    mu_w = mu_a * inertia_i * omega_mean
    rows = [{"symbol": "μ_φ", "equation": "§10.6", "value": mu_phi, "unit": "mm_rad"}]
    if indicator is not None:
        p_max, diameter = indicator
        mu_p = PRESSURE_MM / p_max
        rows += [{"symbol": "μ_p", "equation": "(L15)", "value": mu_p * 1e6, "unit": "mm_MPa"},
                 {"symbol": "μ_F", "equation": "(L16)", "value": mu_p / (np.pi * diameter**2 / 4),
                  "unit": "mm_N"}]
    rows += [{"symbol": "μ_M", "equation": "§10.6", "value": mu_m, "unit": "mm_Nm"},
             {"symbol": "k_1", "equation": "(L19)", "value": POLE_MM, "unit": "mm"},
             {"symbol": "μ_A", "equation": "(L19)", "value": mu_a, "unit": "mm_J"},
             {"symbol": "μ_I", "equation": "(L18)", "value": mu_i, "unit": "mm_kgm2"},
             {"symbol": "μ_T", "equation": "(L20)", "value": mu_t, "unit": "mm_J"},
             {"symbol": "y_ΔTImax", "equation": "(L22)", "value": y_swing, "unit": "mm"},
             {"symbol": "ΔT_Imax", "equation": "(L22)", "value": swing, "unit": "J"},
             {"symbol": "I_I", "equation": "(L22)", "value": required, "unit": "kgm2"},
             {"symbol": "μ_ω", "equation": "(L24)", "value": mu_w, "unit": "mm_rad_s"}]
    at = np.arange(POSITIONS + 1) * 2 * np.pi / POSITIONS
    read = lambda values: np.interp(at, phi, values)
    m, a_d, a, i_ii, dt = read(moment), read(work_driving), read(work_total), read(inertia_ii), read(delta_t)
    y_tii = i_ii * mu_i                                   # the I_II diagram is T_II's in μ_T (L20)
    ordinates = [{"position": k, "phi": float(np.degrees(at[k])), "y_M": float(m[k] * mu_m),
                  "y_A_d": float(a_d[k] * mu_a), "y_A_c": float((a_d[k] - a[k]) * -mu_a), "y_A": float(a[k] * mu_a),
                  "y_I": float(y_tii[k]), "y_TII_star": float(y_tii[k] * mu_a / mu_t),      # (L21)
                  "y_dTI": float(dt[k] * mu_a)} for k in range(POSITIONS + 1)]
    return {"scales": rows, "ordinates": ordinates, "drawing": sheet_drawing(ordinates, mu_phi)}


def sheet_drawing(ordinates: list[dict], mu_phi: float) -> dict:
    """What the sheet's drawing needs beyond the ordinates, in mm: the abscissa of each position (x = μ_φ φ),
    the pole P at (−k₁, 0) and the graphical integration's rays (Lecture 10 §10.6, (L19)): over each interval
    between two positions the mean ordinate of M_д, y_Mср = k₁ Δy_Aд/Δx (the integral's chord is parallel to
    the ray from P to (0, y_Mср)), drawn at the interval's middle and carried to the ordinate axis."""
    x = [float(mu_phi * np.radians(row["phi"])) for row in ordinates]
    rays = [{"interval": k + 1, "x_from": x[k], "x_to": x[k + 1],
             "y_mean": POLE_MM * (ordinates[k + 1]["y_A_d"] - ordinates[k]["y_A_d"]) / (x[k + 1] - x[k])}
            for k in range(len(ordinates) - 1)]
    return {"base": BASE_MM, "pole": POLE_MM, "x": x, "rays": rays,
            "heights": {"moment": MOMENT_MM, "inertia": INERTIA_MM}}
