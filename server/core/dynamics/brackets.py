"""Zeros of functions of the crank angle, each bracketed by a sign change on a scan, refined all at once.

The kinks of a machine (machine.py, general_machine.py) are the sign changes of switching functions: velocity
analogs, normal forces. Some are simple zeros, some are not: at a symmetric dead point a relative velocity can
cross zero with zero slope (a zero of odd multiplicity), and a load that switches with the sense of motion jumps
through zero. Regula falsi and its Illinois variant (Dahlquist & Björck, Numerical Methods, §6.2.3) fall back to
halving the bracket there, one evaluation per halving: some forty-five evaluations from a scan's interval
(2π/4096) to a few doubles. Here each pass evaluates, in one call, ``sections`` points inside every open bracket:
the false-position point of its ends, its two neighbours a (sections − 2)²-th of the bracket away, and
sections − 3 equally spaced points; the bracket becomes the first pair of neighbours with a sign change. A simple
zero lies between the false-position point and a neighbour after a pass or two (3–4 passes in all); any other
zero, or a jump, still loses at least a factor sections − 2 of its bracket per pass (at most 10 passes with 34
points, 18 with 8). Evaluating the switching functions costs mostly the call (composing the linkage, setting up
the friction solve: ~0.3 and ~1 ms), little per angle (~0.5 and ~9 µs), so the passes, not the points, are what
is saved: machine.py takes SECTIONS points a pass, the normal forces' friction solve 8
(general_machine.NORMAL_SECTIONS).

The passes end when every bracket is at most a few doubles wide (``ulps``), holds an exact zero, or has no sign
change left between finite values (no equilibrium at a point: NaN); each pass shrinks every open bracket, so
they end: at most log(width / ulp) / log(sections − 2) + 2 passes.
"""
from __future__ import annotations

from collections.abc import Callable

import numpy as np

SECTIONS = 34           # points evaluated inside each open bracket per pass (cheap switching functions)


def ulps(low: np.ndarray, high: np.ndarray) -> np.ndarray:
    """A few doubles at the bracket: the width at which a zero is located as well as the angle can be."""
    return 4 * np.spacing(np.maximum(np.abs(low), np.abs(high)))


def own_rows(values: np.ndarray, rows: np.ndarray, shape: tuple[int, int]) -> np.ndarray:
    """Each bracket's own function at its points: ``values`` (functions × brackets·points, bracket k's points
    in columns k·points … (k+1)·points − 1, ``shape`` (brackets, points)) read at its function ``rows[k]``."""
    count, points = shape
    return values.reshape(values.shape[0], count, points)[rows, np.arange(count), :]


def refine_zeros(f: Callable[[np.ndarray, np.ndarray], np.ndarray], low: np.ndarray, high: np.ndarray,
                 f_low: np.ndarray, f_high: np.ndarray, sections: int = SECTIONS) -> np.ndarray:
    """One zero (or a jump through zero) of f per bracket [low, high], f of opposite signs (or zero) at its ends.

    f(index, angles) takes the indices of some brackets and angles of shape (len(index), points), each row
    inside its bracket, and returns each bracket's function there (NaN where it has no value). Each zero is the
    bracket's midpoint once it is a few doubles wide, the point where f is exactly zero, or, where no sign
    change between finite values is left, the bracket's midpoint as it stands."""
    low, high = np.array(low, float), np.array(high, float)
    f_low, f_high = np.array(f_low, float), np.array(f_high, float)
    high = np.where(f_low == 0, low, high)
    low = np.where(f_high == 0, high, low)
    while True:
        open_ = np.flatnonzero((high - low > ulps(low, high)) & (f_low * f_high < 0))
        if not open_.size:
            return 0.5 * (low + high)
        a, b, fa, fb = low[open_], high[open_], f_low[open_], f_high[open_]
        w = b - a
        inner = a[:, None] + w[:, None] * (np.arange(1, sections - 2) / (sections - 2))[None, :]
        falsi = (a * fb - b * fa) / (fb - fa)
        falsi = np.where((falsi > a) & (falsi < b), falsi, 0.5 * (a + b))
        near = w / (sections - 2) ** 2
        neighbours = np.clip(falsi - near, a, b), np.clip(falsi + near, a, b)
        points = np.sort(np.column_stack([inner, falsi, *neighbours]), axis=1)
        values = np.asarray(f(open_, points), float)
        x = np.column_stack([a, points, b])
        y = np.column_stack([fa, values, fb])
        change = (y[:, :-1] * y[:, 1:] < 0) | (y[:, :-1] == 0)
        first = np.argmax(change, axis=1)
        found = change[np.arange(first.size), first]
        rows = np.arange(first.size)
        new_low, new_high = x[rows, first], x[rows, first + 1]
        new_f_low, new_f_high = y[rows, first], y[rows, first + 1]
        zero = new_f_low == 0
        new_high, new_f_high = np.where(zero, new_low, new_high), np.where(zero, 0.0, new_f_high)
        shrank = found & (new_high - new_low < b - a)
        # a bracket with no sign change left between finite values (NaN inside) stays as it is, closed (fa, fa)
        low[open_] = np.where(shrank, new_low, a)
        high[open_] = np.where(shrank, new_high, b)
        f_low[open_] = np.where(shrank, new_f_low, fa)
        f_high[open_] = np.where(shrank, new_f_high, fa)
