"""Standard drawing scales of the course project's sheets.

A scale is the quantity one millimetre of the drawing stands for: μ_l in m/mm (the textbook's μ_l = l_OA/OA,
the crank's length over the segment OA that draws it), μ_v in (m/s)/mm, μ_a in (m/s²)/mm, μ_F in N/mm.  It is
a standard value μ = m·10ᵏ with m ∈ {1, 2, 2.5, 4, 5} and k whole, the smallest such that the drawing's largest
extent E (in the drawing's units) fits the length L (mm) kept for it: E/μ ≤ L.  The lengths on a sheet of A1:
the plan of positions about 250 mm, a velocity or an acceleration plan about 120 mm, a force plan about 150 mm.
"""
from __future__ import annotations

import math

import numpy as np

STANDARD_MANTISSAS = (1.0, 2.0, 2.5, 4.0, 5.0)
POSITIONS_MM = 250.0
PLAN_MM = 120.0
FORCE_PLAN_MM = 150.0


def standard_scale(extent: float, length_mm: float) -> float | None:
    """The smallest standard μ = m·10ᵏ with extent/μ ≤ length_mm (units per mm); None where there is nothing to
    draw (a zero or not finite extent: every vector of the plan is zero, or undefined)."""
    if not (math.isfinite(extent) and extent > 0 and length_mm > 0):
        return None
    needed = extent / length_mm
    power = math.floor(math.log10(needed))
    candidates = (float(f"{m:g}e{k}") for k in (power - 1, power, power + 1) for m in STANDARD_MANTISSAS)
    return next(value for value in candidates if value * (1 + 1e-12) >= needed)     # 10^(power+1) > needed


def extent(points) -> float:
    """The largest side of the points' bounding box (x, y pairs or complex numbers): what must fit the length."""
    z = np.asarray(points)
    if z.size == 0:
        return 0.0
    if not np.iscomplexobj(z):
        z = z[..., 0] + 1j * z[..., 1]
    z = z[np.isfinite(z)]
    if z.size == 0:
        return 0.0
    return float(max(np.ptp(z.real), np.ptp(z.imag)))


def plan_vertices(equations: list[dict]) -> list[complex]:
    """The points of a velocity or acceleration plan drawn from its pole: the pole and every partial sum of each
    equation's vectors (plans.plans: ``vectors`` with x, y)."""
    points = [0j]
    for equation in equations:
        tip = 0j
        for v in equation["vectors"]:
            tip += complex(v["x"], v["y"])
            points.append(tip)
    return points
