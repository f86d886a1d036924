"""Change points of a linkage's groups, found from the geometry: where a group's loop flattens (its Jacobian
singular) while the crank moves *through* that angle, the group assembling on both sides.

A group that flattens is at the edge of its closure: RRR at |BD| = BC + CD or |BC − CD| (the triangle BCD
stretched or folded), RRP at the distance of B from the guide = BC (the rod across the guide), RPR at |BD| = e
(the slot tangent).  Its margin f (that distance's gap to the edge, over the group's size) is ≥ 0 where it
closes.  Crossing zero (a simple zero) is a limit of assembly; touching zero at a minimum (a double zero:
f = 0 and f′ = 0 at one angle) is a change point.  For a four-bar this is the Grashof equality s + l = p + q:
the diagonal BD runs between |l₀ − l₁| and l₀ + l₁, and one of its extremes equals l₂ + l₃ or |l₂ − l₃| (Eremyants
(2.45)–(2.47)); a parallelogram has two, at φ = 0 and 180°.

Found on the crank's turn: the minima of f are bracketed by the sign of f′ (from the closed-form analogs of
the group's outer joints) on a 0.5° grid and bisected to round-off; a minimum with f ≤ ``EQUALITY`` (1e-9,
the four-bar's tolerance of the Grashof equality) is a change point.  Slider inputs and the PRP and RPP
groups (which flatten only with parallel guides) are not searched.

At a change point the two assemblies σ = ±1 of the group meet; the motion goes on along the *other* σ
(the analytic continuation: the root of the margin's double zero changes sign), which keeps every angle
continuous and every analog bounded, a parallelogram a parallelogram.  So the student's σ holds from the start
of the turn to the first change point, and flips at each (``signs``).

The analogs there are 0/0 quotients of the loop's Jacobian, whose round-off grows as ε·κ² for the first and
ε·κ³ for the second (κ ≈ 1/|sin| of the angle between the group's links, its condition number; measured on a
parallelogram: θ″ off by 6·10⁻⁴ at 10⁻⁴ rad from the change point, by 1 at 10⁻⁵).  The change point's
neighbourhood is where ε·κ³ > 10⁻⁶, |sin| < ``SINGULAR_SIN`` = (ε/10⁻⁶)^⅓ ≈ 6·10⁻⁴ (about ±0.035° on a
parallelogram); there the analogs are not sent (null, with a sentence naming the angle), and where a
quantity is integrated over the turn they are the limit of the continuing motion, the cubic through the
analogs and their derivatives at the neighbourhood's edges (error ~ h⁴, h the half-width).
"""
from __future__ import annotations

import numpy as np

from .spec import Linkage, SliderInput
# the marks the composition reads, and the names read from here (change_points.offset, ...)
from .change_point_marks import (EQUALITY, GRID, MAX_HALF_WIDTH, SECOND_ANALOG_ERROR, SINGULAR_SIN, STEPS,  # noqa: F401
                                 TURN, ChangePoint, near, offset, per_turn, signs)
from .composition import compose_with


def find(linkage: Linkage) -> tuple[ChangePoint, ...]:
    """Every group's change points, in order of attachment (each group's σ continued through the earlier ones');
    cached on the linkage (it is immutable)."""
    cached = linkage.__dict__.get("_change_points")
    if cached is not None:
        return cached
    points: tuple[ChangePoint, ...] = ()
    if not isinstance(linkage.crank, SliderInput):
        grid = np.linspace(0.0, TURN, GRID)
        with np.errstate(all="ignore"):      # at a change point not yet known the analogs are 0/0 (inf, NaN)
            for k in range(len(linkage.groups)):
                turn = compose_with(linkage, grid, points, "null", upto=k + 1)
                points += _group_points(linkage, k, turn, points)
    object.__setattr__(linkage, "_change_points", points)
    return points


def _group_points(linkage: Linkage, k: int, turn, points) -> tuple[ChangePoint, ...]:
    """Group k's change points: minima of its margins bracketed on the grid (kept only where the margin there is
    within |f′|·step of zero: it may reach zero within the step), bisected together on the sign of f′."""
    step = turn.phi[1] - turn.phi[0]
    brackets = []
    for edge, (f, df) in margins(turn.groups[k]).items():
        d, value = df[:-1], f[:-1]                            # the grid's last point is its first again
        after, next_value = np.roll(d, -1), np.roll(value, -1)
        reach = np.maximum(np.abs(d), np.abs(after)) * step + EQUALITY
        low_enough = np.minimum(value, next_value) <= reach
        for i in np.flatnonzero((d <= 0) & (after > 0) & low_enough):
            brackets.append((edge, turn.phi[i]))
    if not brackets:
        return ()
    low = np.array([at for _, at in brackets])
    high = low + step
    for _ in range(STEPS):
        middle = 0.5 * (low + high)
        fine = margins(compose_with(linkage, middle, points, "null", upto=k + 1).groups[k])
        rising = np.array([fine[edge][1][i] > 0 for i, (edge, _) in enumerate(brackets)])
        low, high = np.where(rising, low, middle), np.where(rising, middle, high)
    at = 0.5 * (low + high)
    fine = margins(compose_with(linkage, at, points, "null", upto=k + 1).groups[k])
    found = []
    for i, (edge, _) in enumerate(brackets):
        if abs(fine[edge][0][i]) <= EQUALITY:
            where = float(np.mod(at[i], TURN))
            where = 0.0 if min(where, TURN - where) < 1e-12 else where
            found.append(ChangePoint(k, where, _half_width(linkage, k, where, points), edge))
    return tuple(sorted(found, key=lambda cp: cp.phi))


def _half_width(linkage: Linkage, k: int, at: float, points) -> float:
    """The smallest h (on a ×1.25 ladder from 10⁻⁶ rad) at which |sin| of group k reaches SINGULAR_SIN on both
    sides of the change point, at most 1°."""
    ladder = 1e-6 * 1.25 ** np.arange(70)
    ladder = ladder[ladder <= MAX_HALF_WIDTH]
    both = compose_with(linkage, np.concatenate([at - ladder, at + ladder]), points, "null", upto=k + 1)
    det = np.abs(both.groups[k].determinant)
    fine = np.flatnonzero((det[:ladder.size] >= SINGULAR_SIN) & (det[ladder.size:] >= SINGULAR_SIN))
    return float(ladder[fine[0]]) if fine.size else float(MAX_HALF_WIDTH)


def margins(group) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """A group's margins to the edge of its closure with their derivatives (``group.margins``)."""
    return group.margins or {}
