"""How an answer was computed, declared once (like scipy's OdeResult), and the two quadrature helpers
every dynamic result shares: the parabola-vertex extremum of a sampled curve and Simpson's rule.

``Numerics`` is what every computed answer carries under ``numerics``; the API declares the same fields
once as a response model (server/api/schemas.py, ``NumericsModel``).  A field a method has no use for
stays None and reads "—" on the page.

Parabola vertex: through the best node y₀ and its neighbours y₋, y₊ (spacing h) the parabola's vertex is

    y* = y₀ − (y₊ − y₋)²/(8(y₋ − 2y₀ + y₊)),

which lowers the error of the extreme value from O(h²) of the nodes to O(h³) for a smooth curve.
Composite Simpson:  ∫ ≈ h/3 [y₀ + 4y₁ + 2y₂ + … + 4y_{n−1} + y_n]  (error O(h⁴) on a smooth integrand).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, fields

import numpy as np


@dataclass
class Numerics:
    """Method, why it was chosen, the tolerance asked, the work done and the error, in one declared form.

    method: what was computed and how, in words; why: why this method (stiffness, smoothness);
    rtol: relative tolerance asked; steps, rejected: accepted and rejected steps (or grid intervals);
    nfev, njev, nlu: evaluations of the right-hand side, of the Jacobian, LU decompositions;
    iterations: iterations of an outer loop (shooting, root finding, successive approximations);
    cycles: cycles integrated (a start-up, a steady-cycle shooting); stiffness_ratio: the largest
    ratio of the eigenvalues' magnitudes (elastic models); converged: whether the iteration met its
    tolerance (None where nothing iterates); runtime_ms: wall-clock time; error_estimate: estimated
    relative error of the result (≥ 0), None where there is nothing to compare with;
    energy_residual: |net work over the run| / driving work (≥ 0, ≤ 1 where meaningful);
    message: how it ended, in words.  code, message_code, message_context, why_context: the keys the
    interface uses to say method, message and why in the reader's language.
    """

    method: str
    code: str = ""
    why: str | None = None
    rtol: float | None = None
    steps: int | None = None
    rejected: int | None = None
    nfev: int | None = None
    njev: int | None = None
    nlu: int | None = None
    iterations: int | None = None
    cycles: int | None = None
    stiffness_ratio: float | None = None
    converged: bool | None = None
    runtime_ms: float | None = None
    error_estimate: float | None = None
    energy_residual: float | None = None
    message: str = ""
    message_code: str = ""
    message_context: dict = field(default_factory=dict)
    why_context: dict = field(default_factory=dict)

    def tell(self, notice) -> None:
        """End with a warning's words (a mechanisms.Notice): its text, and its code and context, so that
        the interface says it in the reader's language as it says the warning."""
        self.message, self.message_code, self.message_context = notice.text, notice.code, notice.context

    def as_dict(self) -> dict:
        """Every field, numbers as plain Python numbers; a non-finite number becomes None and is said in
        the message (an answer never carries NaN or infinity)."""
        result, said = {}, []
        for item in fields(self):
            value = getattr(self, item.name)
            if isinstance(value, (float, np.floating)):
                value = float(value)
                if not math.isfinite(value):
                    said.append(f"{item.name} is not a finite number")
                    value = None
            elif isinstance(value, np.integer):
                value = int(value)
            elif isinstance(value, np.bool_):
                value = bool(value)
            result[item.name] = value
        if said:
            result["message"] = "; ".join(filter(None, [result["message"], *said]))
        return result


def parabola_extremum(values: np.ndarray, sign: int = 1, periodic: bool = True,
                      allowed: np.ndarray | None = None) -> float:
    """Largest (sign +1) or smallest (−1) value of a smooth sampled curve, refined by the vertex of the
    parabola through the best node and its two neighbours (formula in the module docstring).

    periodic: a closed grid over one cycle (last node = first), the neighbours wrap around; otherwise an
    extreme at an end node is that node's value.  allowed: a mask over the nodes restricting the search;
    where a neighbour lies outside it the node's value is kept.  A curvature of the wrong sign (a kink,
    a plateau) keeps the node's value too.
    """
    return parabola_vertex(values, sign, periodic, allowed)[0]


def parabola_vertex(values: np.ndarray, sign: int = 1, periodic: bool = True,
                    allowed: np.ndarray | None = None) -> tuple[float, float]:
    """parabola_extremum's value and where it lies: the node index of the vertex, k + (y₋ − y₊)/(2(y₋ − 2y₀ + y₊)),
    within half a node of the best node k (y₀ is the largest of the three); k itself wherever the value is the
    node's. On a periodic grid the position lies in [−½, n − ½) for the n distinct nodes."""
    y = sign * np.asarray(values, float)
    if periodic:
        y = y[:-1]
        if allowed is not None:
            allowed = np.asarray(allowed, bool)[:-1]
    n = y.size
    k = int(np.argmax(y if allowed is None else np.where(allowed, y, -np.inf)))
    if not periodic and k in (0, n - 1):
        return float(sign * y[k]), float(k)
    before, after = (k - 1) % n, (k + 1) % n
    if allowed is not None and not (allowed[before] and allowed[after]):
        return float(sign * y[k]), float(k)
    left, mid, right = y[before], y[k], y[after]
    curvature = left - 2 * mid + right
    if not curvature < 0:
        return float(sign * mid), float(k)
    best = mid - (right - left) ** 2 / (8 * curvature)
    return float(sign * best), k + float((left - right) / (2 * curvature))


def simpson(values: np.ndarray, h: float) -> float:
    """Composite Simpson over nodes spaced h (an even number of intervals; trapezoid for an odd tail)."""
    n = values.size - 1
    even = n - n % 2
    total = h / 3 * (values[0] + values[even] + 4 * values[1:even:2].sum() + 2 * values[2:even:2].sum())
    return total + (0.5 * h * (values[even] + values[-1]) if n % 2 else 0.0)


def cumulative_simpson(values: np.ndarray, h: float) -> np.ndarray:
    """∫ from the first node to each step node; values on step and half-step nodes, step h."""
    pieces = h / 6 * (values[:-2:2] + 4 * values[1::2] + values[2::2])
    return np.concatenate([[0.0], np.cumsum(pieces)])
