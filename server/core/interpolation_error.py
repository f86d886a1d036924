"""What the second differences of a sampled curve do not see, compiled with numba: the family engine's
``irregular`` (server/families/family.py, where the measures and their reasons are given) over every element of the
members' stacked answers, each element's measures reduced at once to the largest of its leaf; and the divided
differences of ``family.divided`` likewise.

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
operation, is in tests/test_interpolation_error.py; the two agree to rounding. numpy made a temporary of the
whole stack for each of the nine predictor pairs: for an equation-of-motion family of 65 members × 83 000
elements (start-up curves) 1.5 s, here about 50 ms; a transfer-function stack of 30 × 6 200, 4.6 → 2.3 ms
(bench/results/family_engine.md).
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


@njit(cache=True, error_model="numpy")
def _fmax(held, new):
    """np.fmax: the larger, NaN passed over (NaN only when both are)."""
    return new if held != held or new > held else held


@njit(cache=True, error_model="numpy")
def _held(rows, m, low, high):
    """Whether member m has a number among columns low … high − 1 (a leaf it holds)."""
    for e in range(low, high):
        if rows[m, e] == rows[m, e]:
            return True
    return False


@njit(cache=True, error_model="numpy")
def irregularities(x, rows, starts, predictors, concentrated, safety):
    """(changes, steps, corners, kinked), each (M − 1, L): interval by leaf, the largest of the leaf's elements
    (the leaf of columns starts[l] … starts[l+1] − 1). ``rows`` (M, E), M ≥ 2: with fewer than 4 members no
    predictor pair, inner interval or member beyond is there, and only the changes are numbers; ``safety`` the
    linear rule's factor on a curvature (family.SAFETY).

    Interval by interval: the steps over the columns of the leaves both members hold (runs of adjacent leaves), one
    pass per predictor pair, which the compiler vectorises; then leaf by leaf, a leaf one of the interval's
    members lacks (every slope NaN) answered at once."""
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
    bend = np.full((count, width), np.nan)                  # |f″| at each member
    for m in range(1, count - 1):
        sum_h = h[m - 1] + h[m]
        for e in range(width):
            bend[m, e] = abs(2 * (slope[m, e] - slope[m - 1, e]) / sum_h)
    ends = np.empty(leaves + 1, np.int64)
    ends[:leaves] = starts
    ends[leaves] = width
    held = np.empty((count, leaves), np.bool_)
    for m in range(count):
        for leaf in range(leaves):
            held[m, leaf] = _held(rows, m, ends[leaf], ends[leaf + 1])
    pairs = predictors.shape[0]
    first = np.empty(pairs, np.int64)
    second = np.empty(pairs, np.int64)
    weight = np.empty(pairs)
    least = np.empty(width)
    seen = np.empty(width, np.bool_)
    run_start = np.empty(leaves, np.int64)
    run_end = np.empty(leaves, np.int64)
    for k in range(count - 1):
        valid = 0                                           # the predictor pairs inside the range
        for p in range(pairs):
            a, b = predictors[p, 0], predictors[p, 1]
            if k + a >= 0 and k + b <= count - 2:
                first[valid], second[valid] = k + a, k + b
                weight[valid] = (middle[k] - middle[k + a]) / (middle[k + b] - middle[k + a])
                valid += 1
        inside = 1 <= k <= count - 3
        h_k = h[k]
        runs = 0                                            # the columns of the leaves both members hold, as
        for leaf in range(leaves):                          # runs of adjacent leaves
            if held[k, leaf] and held[k + 1, leaf]:
                if runs > 0 and run_end[runs - 1] == ends[leaf]:
                    run_end[runs - 1] = ends[leaf + 1]
                else:
                    run_start[runs], run_end[runs] = ends[leaf], ends[leaf + 1]
                    runs += 1
        for r in range(runs):           # slices from 0: indices the compiler knows are not negative vectorise
            low, high = run_start[r], run_end[r]
            mine, lows, found = slope[k, low:high], least[low:high], seen[low:high]
            lows[:] = np.inf
            found[:] = False
            for q in range(valid):
                w = weight[q]
                s_i, s_j = slope[first[q], low:high], slope[second[q], low:high]
                for e in range(high - low):
                    off = abs(mine[e] - (s_i[e] + (s_j[e] - s_i[e]) * w)) * h_k
                    number = off == off                     # numpy's fmin: NaN passed over
                    found[e] = found[e] or number
                    lows[e] = min(lows[e], off) if number else lows[e]
        for leaf in range(leaves):
            low, high = ends[leaf], ends[leaf + 1]
            if not (held[k, leaf] and held[k + 1, leaf]):   # every slope NaN: no change, step or kink; corner 0
                if inside:
                    corners[k, leaf] = 0.0
                continue
            before, after, mine = rows[k, low:high], rows[k + 1, low:high], slope[k, low:high]
            change = np.nan
            step = np.nan
            lows, found = least[low:high], seen[low:high]
            for e in range(high - low):
                change = _fmax(change, abs(after[e] - before[e]))
                if found[e]:
                    step = _fmax(step, lows[e])
            changes[k, leaf] = change
            steps[k, leaf] = step
            if not inside:              # no corner, and no kink: nothing beyond to compare the ends' bends with
                continue
            left, right = slope[k - 1, low:high], slope[k + 1, low:high]
            ends_0, ends_1 = bend[k, low:high], bend[k + 1, low:high]
            beyond_0, beyond_1 = bend[k - 1, low:high], bend[k + 2, low:high]
            corner = np.nan
            kink = np.nan
            for e in range(high - low):
                a = mine[e] - left[e]
                b = right[e] - mine[e]
                corner = _fmax(corner, h_k * a * b / (a + b) if a * b > 0 else 0.0)
                inner = _fmax(ends_0[e], ends_1[e])
                beyond = _fmax(beyond_0[e], beyond_1[e])
                # numpy's nan_to_num(beyond, nan=inf) × CONCENTRATED: no bound where beyond is NaN or inf
                if beyond == beyond and beyond != np.inf and inner > concentrated * beyond:
                    kink = _fmax(kink, safety * inner * (h_k * h_k / 8))
            corners[k, leaf] = corner
            kinked[k, leaf] = kink
    return changes, steps, corners, kinked


@njit(cache=True, error_model="numpy")
def divided_differences(rows, first, weights, starts, ends):
    """(K, L): for window j (members first[j] … first[j] + n) and leaf l (columns starts[l] … ends[l] − 1), the
    largest over the leaf's elements of |Σ_i weights[j, i]·f_first[j]+i|, the divided difference of order n
    when weights[j, i] = 1/Π_{m≠i}(x_i − x_m) (family.divided); NaN elements passed over as numpy's fmax does,
    NaN where the leaf has no number in the window. The sum in the order i = 0 … n, as numpy summed rows."""
    windows, width = weights.shape
    leaves = starts.size
    found = np.full((windows, leaves), np.nan)
    total = np.empty((ends - starts).max() if leaves else 0)
    for j in range(windows):
        for leaf in range(leaves):
            low, high = starts[leaf], ends[leaf]
            sums = total[:high - low]
            row = rows[first[j], low:high]
            for e in range(high - low):
                sums[e] = weights[j, 0] * row[e]
            for i in range(1, width):
                row = rows[first[j] + i, low:high]
                w = weights[j, i]
                for e in range(high - low):
                    sums[e] += w * row[e]
            largest = np.nan
            for e in range(high - low):
                largest = _fmax(largest, abs(sums[e]))
            found[j, leaf] = largest
    return found


def warm_up() -> float:
    """Compile (or load from the disk cache) ``irregularities`` and ``divided_differences``; seconds."""
    started = time.perf_counter()
    irregularities(np.arange(5.0), np.zeros((5, 2)), np.array([0, 1], np.int64), PREDICTORS, CONCENTRATED, 4.0)
    divided_differences(np.zeros((5, 2)), np.array([0, 1], np.int64), np.ones((2, 3)), np.array([0, 1], np.int64),
                        np.array([1, 2], np.int64))
    return time.perf_counter() - started
