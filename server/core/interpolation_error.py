"""What the second differences of a sampled curve do not see, compiled with numba: the family engine's
``irregular`` (server/api/family.py, where the three measures and their reasons are given) over every element of
the members' stacked answers in one loop, each element's measures reduced at once to the largest of its leaf.

The members are x_0 < … < x_M−1 with rows f_m (one column per element of every leaf), h_k = x_k+1 − x_k and
s_k = (f_k+1 − f_k)/h_k the slope over interval k. For interval k and every element:

    changes   |f_k+1 − f_k|;
    steps     h_k · min over the predictor pairs (i, j) of |s_k − (s_i + (s_j − s_i)(c_k − c_i)/(c_j − c_i))|,
              c the intervals' midpoints, the pairs PREDICTORS within the range;
    corners   h_k·a·b/(a + b) where a = s_k − s_k−1 and b = s_k+1 − s_k have one sign, else 0 (inner intervals);
    kinked    safety·h_k²/8·max(|f″_k|, |f″_k+1|) where that larger curvature is more than CONCENTRATED times the
              larger one at the members beyond (k − 1, k + 2), else none; f″_m = 2(s_m − s_m−1)/(h_m−1 + h_m).

NaN (an element a member lacks, a refused member's row) is passed over as numpy's fmin and fmax pass it: a
leaf with no number anywhere in an interval reads NaN. The numpy reference of the same arithmetic, operation for
operation, is in tests/test_interpolation_error.py; the two agree to rounding. The loop visits each element once
per interval with its seven neighbouring slopes in cache, where numpy made a temporary of the whole stack for
each of the nine predictor pairs: for an equation-of-motion family of 65 members × 83 000 elements (start-up
curves), 1.5 s became a few tens of milliseconds (bench/results/family_engine.md).
"""
from __future__ import annotations

import time

import numpy as np
from numba import njit

# The slope of interval k predicted from two other intervals k + a, k + b (a < b), the line through their
# (midpoint, slope) read at interval k's midpoint (exact for a parabola, whose chord's slope is f′ at the
# chord's midpoint): every pair within 3 intervals of k and 3 of each other, so that a pair clear of one other
# step is there even beside the range's end (an interval two from the end beside a step).
PREDICTORS = np.array([(a, b) for a in (-3, -2, -1, 1, 2) for b in (-2, -1, 1, 2, 3) if a < b and b - a <= 3],
                      np.int64)
CONCENTRATED = 4.0      # |f″| at an interval's ends this many times that beyond them: a corner there


@njit(cache=True)
def _fmax(held, new):
    """np.fmax: the larger, NaN passed over (NaN only when both are)."""
    return new if held != held or new > held else held


@njit(cache=True)
def _bend(slope, h, m, e):
    """|f″| at member m, 2|s_m − s_m−1|/(h_m−1 + h_m); NaN at the range's ends."""
    if m < 1 or m > h.size - 1:
        return np.nan
    return abs(2 * (slope[m, e] - slope[m - 1, e]) / (h[m - 1] + h[m]))


@njit(cache=True)
def irregularities(x, rows, starts, predictors, concentrated, safety):
    """(changes, steps, corners, kinked), each (M − 1, L): interval by leaf, the largest of the leaf's elements (the
    leaf of columns starts[l] … starts[l+1] − 1). ``rows`` (M, E) with M ≥ 4 and L ≥ 1; ``safety`` the linear
    rule's factor on a curvature (family.SAFETY)."""
    count, width = rows.shape
    leaves = starts.size
    changes = np.full((count - 1, leaves), np.nan)
    steps = np.full((count - 1, leaves), np.nan)
    corners = np.full((count - 1, leaves), np.nan)
    kinked = np.full((count - 1, leaves), np.nan)
    h = np.empty(count - 1)
    middle = np.empty(count - 1)
    for k in range(count - 1):
        h[k] = x[k + 1] - x[k]
        middle[k] = (x[k] + x[k + 1]) / 2
    slope = np.empty((count - 1, width))
    for k in range(count - 1):
        for e in range(width):
            slope[k, e] = (rows[k + 1, e] - rows[k, e]) / h[k]
    ends = np.empty(leaves + 1, np.int64)
    ends[:leaves] = starts
    ends[leaves] = width
    pairs = predictors.shape[0]
    valid = np.zeros(pairs, np.bool_)
    weight = np.zeros(pairs)
    for k in range(count - 1):
        for p in range(pairs):
            a, b = predictors[p, 0], predictors[p, 1]
            valid[p] = k + a >= 0 and k + b <= count - 2
            if valid[p]:
                weight[p] = (middle[k] - middle[k + a]) / (middle[k + b] - middle[k + a])
        inside = 1 <= k <= count - 3
        for leaf in range(leaves):
            change = np.nan
            step = np.nan
            corner = np.nan
            kink = np.nan
            for e in range(ends[leaf], ends[leaf + 1]):
                s = slope[k, e]
                change = _fmax(change, abs(rows[k + 1, e] - rows[k, e]))
                if s != s:              # an element a member of the interval lacks: no step, no kink, corner 0
                    if inside:
                        corner = _fmax(corner, 0.0)
                    continue
                least = np.nan
                for p in range(pairs):
                    if valid[p]:
                        si = slope[k + predictors[p, 0], e]
                        off = abs(s - (si + (slope[k + predictors[p, 1], e] - si) * weight[p])) * h[k]
                        if least != least or off < least:
                            least = off
                step = _fmax(step, least)
                if inside:
                    a = s - slope[k - 1, e]
                    b = slope[k + 1, e] - s
                    corner = _fmax(corner, h[k] * a * b / (a + b) if a * b > 0 else 0.0)
                    beyond = _fmax(_bend(slope, h, k - 1, e), _bend(slope, h, k + 2, e))
                    # numpy's nan_to_num(beyond, nan=inf) × CONCENTRATED: no bound where beyond is NaN or inf
                    limit = concentrated * beyond if beyond == beyond and beyond != np.inf else np.inf
                else:
                    limit = np.inf
                inner = _fmax(_bend(slope, h, k, e), _bend(slope, h, k + 1, e))
                if inner > limit:
                    kink = _fmax(kink, safety * inner * (h[k] * h[k] / 8))
            changes[k, leaf] = change
            steps[k, leaf] = step
            corners[k, leaf] = corner
            kinked[k, leaf] = kink
    return changes, steps, corners, kinked


@njit(cache=True)
def divided_differences(rows, first, weights, starts, ends):
    """(K, L): for window j (members first[j] … first[j] + n) and leaf l (columns starts[l] … ends[l] − 1), the
    largest over the leaf's elements of |Σ_i weights[j, i]·f_first[j]+i|, the divided difference of order n
    when weights[j, i] = 1/Π_{m≠i}(x_i − x_m) (family.divided); NaN elements passed over as numpy's fmax does,
    NaN where the leaf has no number in the window. The sum in the order i = 0 … n, as numpy summed rows."""
    windows, width = weights.shape
    leaves = starts.size
    found = np.full((windows, leaves), np.nan)
    for j in range(windows):
        for leaf in range(leaves):
            largest = np.nan
            for e in range(starts[leaf], ends[leaf]):
                total = weights[j, 0] * rows[first[j], e]
                for i in range(1, width):
                    total += weights[j, i] * rows[first[j] + i, e]
                largest = _fmax(largest, abs(total))
            found[j, leaf] = largest
    return found


def warm_up() -> float:
    """Compile (or load from the disk cache) ``irregularities`` and ``divided_differences``; seconds."""
    started = time.perf_counter()
    irregularities(np.arange(5.0), np.zeros((5, 2)), np.array([0, 1], np.int64), PREDICTORS, CONCENTRATED, 4.0)
    divided_differences(np.zeros((5, 2)), np.array([0, 1], np.int64), np.ones((2, 3)), np.array([0, 1], np.int64),
                        np.array([1, 2], np.int64))
    return time.perf_counter() - started
