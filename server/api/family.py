"""A slider's family: one endpoint's answer at N values across the slider's range, every other parameter fixed,
so that dragging the slider is a lookup (POST /api/v1/family, the page's family preview).

Members. A member's body is a deep copy of the request with each varied dotted path set to value × factor.
The first members are 9 values evenly spaced from min to max (in log(value) when ``log``), computed coarse to
fine (min, max, the middle, the quarters, ...) so that a family cut short by its time budget still spans the
range. Inner values are rounded to SIGNIFICANT digits before they are computed: the values sent are exact.

Interpolation (the page draws the same): for a value v between members a = answer(v_k) and b = answer(v_k+1),
w = (v − v_k)/(v_k+1 − v_k) (in log(v) when ``log``) and, leaf by leaf,
    number in both                         → (1 − w)·a + w·b,
    arrays of equal length in both         → element by element, by this rule,
    objects in both                        → key by key (the keys of the nearer member), by this rule,
                                             but objects in arrays whose texts differ → the nearer member's,
    null in either                         → null,
    anything else (strings, booleans, arrays of different lengths, a key in one member only)
                                           → the nearer member's leaf (a when w < 1/2, else b).
A refused member's answer is null, so the values between it and its neighbours interpolate to null.
Cubic intervals (``orders``[k] = 3, one rule per interval): the stencil is the 4 members k − 1 … k + 2 (moved
inside the range at its ends: 0 … 3 for the first interval, M − 4 … M − 1 for the last), and a number that all
4 hold at the same place (the same keys, the same array lengths, objects in arrays of the same texts; not
null) is Lagrange's cubic through them in the same coordinate, Σ_i ℓ_i(v)·f_i with
ℓ_i(v) = Π_{j≠i} (v − v_j)/(v_i − v_j); every other leaf follows the rule above (linear, or the nearer
member's).

Refinement. Each interval is drawn by the rule whose error bound is smaller, linear or cubic.
Linear: the error over an interval of width h (in the slider's coordinate) is h²·|f''|/8 for a smooth f;
|f''| at a member is its second divided difference with its two neighbours,
    f''_k ≈ 2·[(f_k+1 − f_k)/h_+ − (f_k − f_k−1)/h_−] / (h_+ + h_−),
largest over each quantity's elements (nulls aside), and an interval's estimate takes the smaller of its two
ends' (an interval beside a jump is not halved for its neighbour's jump; a member at the range's end has no
second difference, its interval takes its other end's); its bound is SAFETY × the estimate. Second
differences read a step of height J between members as J/8 on an even spacing (J/12 beside an interval twice
as wide) and a corner at t from an end as Δs·min(t, h − t)/8 and less, where the chord is off by up to J and
Δs·t(h − t)/h, and halving does not make a step's estimate smaller (an angle found as the argmin on a grid
moves node by node with the value: a staircase). Two terms join the linear estimate and its bound as they
are, without a safety factor (``irregular``): the step the neighbours' slopes leave unexplained,
    u_k = h_k · min |s_k − ŝ_k|,   s_i = (f_i+1 − f_i)/h_i,
ŝ_k the slope of interval k on the line through two other intervals' (midpoint, slope) within 3 of it (the
smallest of these predictions: an interval beside a jump is not blamed for it; zero for a parabola,
O(f‴h³) for a smooth f, J for a step); and, in the bound only, the chord's error were the slope to turn at
one point inside, h_k·a·b/(a + b) with a = s_k − s_k−1, b = s_k+1 − s_k of one sign (exact for a corner
between straight neighbours on any spacing; SAFETY × h²|f''|/8 for a parabola on an even spacing). A
staircase whose steps line up with the members (the same number in every interval) looks like the line
through them: nothing computed from the members sees it.
Cubic: f − p = ω(v)·f[v_0, …, v_3, v] with ω(v) = Π (v − v_i) over the stencil, so the estimate is
max |ω| over the interval times |f[5 members]|, the fourth divided difference (f⁗/24), largest over each
quantity's elements, from the larger of the two 5-member windows holding the stencil (the one at the range's
ends); its bound is CUBIC_SAFETY × the estimate. A jump or a corner near the interval makes the fourth
differences large, but no larger than a smooth bend of the same size does, and a window wider than the
stencil reads a corner inside it diluted (twice as wide: 8× smaller): the cubic overshoots a step by about
its height. So an interval with a step above TOLERANCE / CUBIC_SAFETY that sets a leaf's linear bound, or a
corner (|f''| at its ends over CONCENTRATED × that at the members beyond) whose linear bound is above it, is
drawn linearly, whatever the cubic's estimate. Every computed value is a member: a round computes the
midpoints of every interval whose bound, relative to the quantity's span (see ``widths``), exceeds
TOLERANCE, as one batch, until none does or the family has MAX_MEMBERS members (worst first). An
interval between an answered and a refused value is halved too (the limit is found). No interval narrower
than FINEST_FRACTION of the range is halved: no slider resolves it, and an answer that jumps (an efficiency
that is 0 at zero load and 0.97 just above) or bends at a corner too steep to resolve is named in the message
instead of taking every member. Where the cap or a jump leaves an interval above the tolerance,
numerics.message says between which values and for which quantity, and the error given for an interval the
cap or the time budget left with a bound above the tolerance is that bound, not the estimate; for an interval too narrow to halve the
error given is the change across it, |f(b) − f(a)| / span, if larger than the linear estimate, and the interval
is drawn linearly (a bound wherever f is monotone inside; second differences read a step of height J as J/8).
Arrays on other grids. An array the two members of an interval hold in different shapes (a start-up whose
number of steps moves with the value) has no divided differences there: the page draws the nearer member's
array, on that member's own grid. Its error is then bounded, wherever f is monotone in the value at a fixed
abscissa, by its change across the interval read on a common abscissa (``regridded``: the denser member's curve
read at the other's nodes against every sibling array that increases, φ or t, and the change of its smallest
and largest element); this joins both rules' estimates as it is, without a safety factor, and is halved for
like any other (a start-up that stalls at one value and runs at the next is found as a jump). An array that
one member holds and the other lacks, or holds empty, is drawn from one of them only: it appears (or vanishes)
inside the interval, which is taken as a jump (1 of the span) and halved down to FINEST_FRACTION.

The estimates are computed over all members at once: the members' leaves stacked as rows of one array
(``Stack``: NaN where a member lacks a leaf), the divided differences of every window of 3 and 5 members as
weighted sums of rows, kept across the rounds of refinement (only the windows a new member enters are
computed again).

Checked leaves are floats and arrays of floats outside UNCHECKED (how it was computed, the texts, the
iterations' records of their convergence, the forces' directions in degrees) whose shape is the same at the
members compared; whole numbers (step counters), strings and booleans are not plotted quantities. An object
in an array (a special position) is the same quantity in two members only when its texts agree (its kind):
otherwise the nearer member's object is drawn and nothing is compared.

Stages. ``coarse`` answers the 9 start members at once, unrefined, with the estimate above as its
interpolation error; ``full`` (the default) refines. The members are the same values in both, so a full
family asked right after the coarse one reuses the coarse members (the heavy process's memo,
server/api/family_batch.py).

Fields. A request may name the leaves a preview draws (``fields``: dotted paths into the answer, e.g.
"modal.stiffness", "t", "points"): each member's answer is then pruned to those subtrees (a path keeps the
whole object or array it names) before anything else is done with it, so only they are rounded, checked,
refined for and sent; numbers shown in tables and readouts always come from an exact answer, never from a
family. A path a member does not hold is left out of that member silently: an answer's shape depends on the
values (a stalled machine has no steady cycle) and on its ``outputs``, so a path is not wrong for being
absent at some values. Without ``fields`` every member is the endpoint's whole answer, as before.

Packed (``packed``: true, what the page asks for). An array that is the same in every answered member (a time
grid, a crank-angle grid, the forces a friction coefficient does not change) is sent once, in ``shared``, and
left out of the members: a member's answer is ``shared`` merged with its own, object by object. Every float
array under objects whose quantity has a span (see ``widths``) is sent as {"exp10": e, "order": n,
"deltas": [...]}, the integers k_i = round(x_i / 10^e) as differences along the first axis, column by column:
order 1, d_0 = k_0 and d_i = k_i − k_j with j the last non-null row before i, null where x_i is null
(x_i = 10^e · the sum of the non-null d of its column up to i); order 2 (an array without null, 3 rows or
more), e_0 = d_0, e_1 = d_1, e_i = d_i − d_(i−1): a smooth curve's second differences are a digit or two.
The quantum 10^e is the largest power of ten ≤ PACK_QUANTUM × the leaf's span over
the family (but ≥ 10^−12 of its largest magnitude), so packing moves a value by at most
PACK_QUANTUM/2 = 0.005 % of its span, added to the interpolation error reported. A smooth curve's steps
are a few digits each, where its decimals took eight or nine, and they compress better.

Preview accuracy. A member is drawn only while the slider moves and is never read as a number, so it is
computed to PREVIEW = PREVIEW_FRACTION × TOLERANCE of each drawn quantity's span (endpoints.Preview), not to
its endpoint's own tolerance, where that is far tighter and the answer's shape does not change with it: the
steady cycle's shooting stops earlier (its Richardson levels and the start-up's stay the exact answer's:
motion.steady_cycle says why), the friction equilibrium is solved to PREVIEW_FRICTION × PREVIEW
(endpoints.preview_friction_tolerance). Decisions (stall, self-locking) are made as for the exact answer. The member's
error then adds at most PREVIEW_FRACTION of the tolerance to the interpolation's (tests/
test_preview_accuracy.py checks each endpoint kind against exact answers on random parameters).

The comparison uses the members as sent: every float rounded to SIGNIFICANT digits (NaN and ±inf → null), so
the reported interpolation error includes the rounding the page sees.
"""
from __future__ import annotations

import math
import os
import re
import time
from bisect import bisect_right
from dataclasses import dataclass, field
from functools import cached_property
from typing import Callable

import numpy as np

from ..core.interpolation_error import CONCENTRATED, PREDICTORS, divided_differences, irregularities
from ..core.mechanisms import GeometryError
from .serialise import Answer, significant
from .messages import CommaFloat, DECIMAL_COMMA, ReadableFloat
from ..lessons.dotted_paths import path_key
from ..lessons.scenes import interface_texts

TOLERANCE = 0.005               # 0.5 % of a plotted quantity's span: below a plot's resolution
PREVIEW_FRACTION = 1 / 50       # a member's own error, at most this fraction of TOLERANCE (see Preview accuracy)
PREVIEW = PREVIEW_FRACTION * TOLERANCE   # … as a fraction of a drawn quantity's span: 1e-4
START_MEMBERS = 9
MAX_MEMBERS = 65                # 8 intervals halved three times over the whole range, at most
FINEST_FRACTION = 1 / 1024      # an interval this narrow (of the range) is not halved: no slider resolves it
TIME_BUDGET_S = float(os.environ.get("MDL_FAMILY_BUDGET_S", "5"))   # wall-clock bound of one family (each
                                # member keeps its endpoint's own budget); a slow or shared host may give more
SIGNIFICANT = 5                 # significant digits of every float in the family's answer
ROUNDOFF = 1e-12                # below this fraction of its siblings' size a quantity's span is round-off
SAME_KIND = 1e-4                # ... or, inside one object, invisible beside its siblings (see spans)
# Not checked against the bound: how it was computed, the texts, and the reactions' directions in degrees (they
# wrap at ±180°, where no interpolation is right; the page draws the forces from their components).
# The successive approximations of an iteration (the forces' "iteration": changes 1e-1 … 1e-8; the textbook's
# "friction_iteration" at one crank angle: its steps and their limit) are a record of how it converged, read
# as a table and a sentence from the exact answer (readings_view.js), not curves a preview draws.
UNCHECKED = frozenset({"numerics", "study", "warnings", "directions", "iteration", "friction_iteration"})
# An interval is halved while its estimated error exceeds TOLERANCE / SAFETY. The estimate is exact for a
# parabola; for a corner (slopes s and s + Δs meeting inside the interval, at d from an end) the smaller of
# the ends' h²|f''|/8 is Δs·min(d, h − d)/8 against the true Δs·d(h − d)/h: at most 4× too small (d = h/2).
SAFETY = 4
# A cubic interval is halved while its estimate exceeds TOLERANCE / CUBIC_SAFETY. The estimate takes the fourth
# derivative from members around the interval, not inside it: where a curve has a corner inside (|R₃₄| of the
# forces' scene crossing zero as ω changes) it was measured 4.1× too small, and on the elastic transmission's
# motor speed 4.1× as well (0.517 % against a bound of 0.505 % at a factor 4): twice the linear rule's factor.
CUBIC_SAFETY = 8
PACK_QUANTUM = 1e-4            # a packed array's quantum, at most this fraction of its span (see Packed)
MAX_FIELDS = 64                 # dotted paths a family request may name (a scene's previews draw ~5–25)
FIELD = re.compile(r"[A-Za-z0-9_]{1,60}(\.[A-Za-z0-9_]{1,60}){0,7}")     # a dotted path of an answer's keys
COARSE_TO_FINE = (0, 8, 4, 2, 6, 1, 3, 5, 7)    # the order of the first 9 members
STAGES = ("coarse", "full")


@dataclass(frozen=True)
class Vary:
    """One dotted path of the request set to value × factor (factor converts the slider's units to SI)."""

    path: str
    factor: float


def member_body(request: dict, vary: list[Vary], value: float) -> dict:
    """The request with each varied path set to value × factor: new objects along the varied paths, the rest
    shared with the request (read, never written: the endpoints validate a body into models of their own)."""
    body = dict(request)
    for item in vary:
        *keys, last = item.path.split(".")
        holder = body
        for key in keys:
            step = path_key(holder, key)
            holder[step] = holder = (list if isinstance(holder[step], list) else dict)(holder[step])
        holder[path_key(holder, last)] = value * item.factor
    return body


def shared(body):
    """The family body as the response cache keys it: the varied paths' current values left out (every member
    sets them), so that students whose other values agree share one family wherever their slider stands.
    A body that is not a well-formed family request is returned as it is (validation refuses it later)."""
    try:
        varied = member_body(body["request"], [Vary(item["path"], 0.0) for item in body["vary"]], 0.0)
    except (KeyError, TypeError, AttributeError, IndexError):
        return body
    return body | {"request": varied, "stage": body.get("stage", "full")}


def path_exists(request: dict, path: str) -> bool:
    """Whether the dotted path names a number (not a boolean) in the request."""
    holder = request
    for key in path.split("."):
        if isinstance(holder, list) and key.isdigit() and int(key) < len(holder):
            holder = holder[int(key)]
        elif isinstance(holder, dict) and key in holder:
            holder = holder[key]
        else:
            return False
    return isinstance(holder, (int, float)) and not isinstance(holder, bool)


# ---- fields: the leaves a preview draws ------------------------------------------------------------------

Fields = dict      # a trie of dotted paths: key → True (the whole subtree) or a trie of its keys


def field_trie(fields: list[str]) -> Fields:
    """The dotted paths as a trie; a path under another one named whole adds nothing ("modal", "modal.phi")."""
    trie: Fields = {}
    for path in fields:
        *keys, last = path.split(".")
        node = trie
        for key in keys:
            node = node.setdefault(key, {})
            if node is True:
                break
        else:
            node[last] = True
    return trie


def pruned(answer: dict, trie: Fields) -> dict:
    """The answer's subtrees the trie names (each kept whole, not copied); what it does not hold is left out,
    and so is an object of which nothing named is held."""
    kept = {}
    for key, below in trie.items():
        if key not in answer:
            continue
        if below is True:
            kept[key] = answer[key]
        elif isinstance(answer[key], dict):
            inner = pruned(answer[key], below)
            if inner:
                kept[key] = inner
    return kept


def shared_arrays(answers: list) -> tuple[dict, list]:
    """(shared, answers without them): the float arrays under objects that are equal in every answered member
    (NaN equal to NaN), sent once; a member's answer is shared merged with its own (``merged``)."""
    present = [a for a in answers if a is not None]
    common = _common(present) if len(present) > 1 else {}
    if not common:
        return {}, answers
    return common, [None if a is None else _without(a, common) for a in answers]


def _common(trees: list[dict]) -> dict:
    found = {}
    first, others = trees[0], trees[1:]
    for key, value in first.items():
        if key in UNCHECKED:
            continue
        rest = [tree.get(key) for tree in others]
        if isinstance(value, dict) and all(isinstance(other, dict) for other in rest):
            inner = _common([value, *rest])
            if inner:
                found[key] = inner
        elif isinstance(value, np.ndarray) and value.size > 1 and all(
                isinstance(other, np.ndarray) and other.shape == value.shape
                and np.array_equal(other, value, equal_nan=True) for other in rest):
            found[key] = value
    return found


def _without(tree: dict, common: dict) -> dict:
    """The tree without the common leaves (a new object where one is removed below; objects left empty go)."""
    kept = {}
    for key, value in tree.items():
        below = common.get(key)
        if below is None:
            kept[key] = value
        elif isinstance(below, dict):
            inner = _without(value, below)
            if inner:
                kept[key] = inner
    return kept


def merged(shared: dict, own: dict | None) -> dict | None:
    """A member's whole answer from the family's shared arrays and its own leaves (the page does the same)."""
    if own is None:
        return None
    whole = dict(own)
    for key, value in shared.items():
        below = own.get(key)
        whole[key] = merged(value, below if isinstance(below, dict) else {}) if isinstance(value, dict) else value
    return whole


def packed(trees: list, quanta: dict[tuple, int]) -> list:
    """The trees (None: refused) with each float array that has a quantum (path → exponent e) as
    {"exp10": e, "order": n, "deltas": [...]} (see Packed); the arrays of one path and shape are packed together."""
    groups: dict[tuple, list] = {}
    for index, tree in enumerate(trees):
        for path, leaf in _dict_arrays(tree):
            if path in quanta and leaf.ndim and leaf.size > 1:
                groups.setdefault((path, leaf.shape), []).append((index, leaf))
    replaced: dict[tuple, dict] = {}
    for (path, _), found in groups.items():
        exponent = quanta[path]
        for (index, _), steps in zip(found, deltas(np.stack([leaf for _, leaf in found]), exponent)):
            replaced[index, path] = {"exp10": exponent, "order": steps[0], "deltas": steps[1]}
    return [None if tree is None else _replaced(tree, index, replaced) for index, tree in enumerate(trees)]


def _dict_arrays(tree, path: tuple = ()):
    """(path, array) of the arrays reached through objects alone."""
    if isinstance(tree, dict):
        for key, value in tree.items():
            yield from _dict_arrays(value, (*path, key))
    elif isinstance(tree, np.ndarray):
        yield path, tree


def _replaced(tree, index: int, replaced: dict, path: tuple = ()):
    if isinstance(tree, dict):
        return {key: _replaced(value, index, replaced, (*path, key)) for key, value in tree.items()}
    return replaced.get((index, path), tree)


def deltas(x: np.ndarray, exponent: int) -> list[tuple[int, object]]:
    """For each x[m] of the stack: (order, steps) of the integers k = round(x[m] / 10^exponent) along its
    first axis (see Packed): order 2 where x[m] has no null and 3 rows or more (an int array), else order 1
    from the last non-null row of each column (an int array, or nested lists with None where x[m] is NaN)."""
    scaled = x / 10.0 ** exponent if exponent >= 0 else x * 10.0 ** -exponent     # 10^|e| exact to e = 22
    count, rows = x.shape[:2]
    k = np.round(scaled).reshape(count, rows, -1)
    valid = np.isfinite(k)
    last = np.where(valid, np.arange(rows)[None, :, None], -1)
    np.maximum.accumulate(last, axis=1, out=last)                 # the last non-null row at or before i
    before = np.concatenate([np.full((count, 1, k.shape[2]), -1), last[:, :-1]], axis=1)   # ... before i
    known = np.take_along_axis(np.where(valid, k, 0.0), np.maximum(before, 0), axis=1)
    steps = np.where(valid, k - np.where(before >= 0, known, 0.0), 0.0).astype(np.int64)
    whole = valid.reshape(count, -1).all(axis=1)
    second = steps.copy()
    second[:, 2:] -= steps[:, 1:-1]                                # e_i = d_i − d_(i−1) from i = 2 on
    found = []
    for m in range(count):
        if whole[m]:
            found.append((2, second[m].reshape(x.shape[1:])) if rows > 2 else (1, steps[m].reshape(x.shape[1:])))
        else:
            listed = steps[m].astype(object)
            listed[~valid[m]] = None
            found.append((1, listed.reshape(x.shape[1:]).tolist()))
    return found


def quanta(span: dict[tuple, float], extent: dict[tuple, list[float]]) -> dict[tuple, int]:
    """The exponent of each leaf's quantum: 10^e ≤ PACK_QUANTUM × span, and ≥ 10^−12 of its largest magnitude
    (the integers stay exact in a double)."""
    found = {}
    for leaf, width in span.items():
        if width > 0 and math.isfinite(width) and all(isinstance(key, str) for key in leaf):
            exponent = math.floor(math.log10(width * PACK_QUANTUM))
            largest = max(abs(extent[leaf][0]), abs(extent[leaf][1]))
            found[leaf] = max(exponent, math.floor(math.log10(largest)) - 12) if largest > 0 else exponent
    return found


def unpacked(tree):
    """A packed tree's arrays as float arrays again (NaN where null): what the page decodes."""
    if isinstance(tree, dict):
        if tree.keys() == {"exp10", "order", "deltas"}:
            return _summed(tree["deltas"], tree["exp10"], tree["order"])
        return {key: unpacked(value) for key, value in tree.items()}
    return tree


def _summed(steps, exponent: int, order: int) -> np.ndarray:
    d = np.array(steps, dtype=float)                     # None → NaN
    flat = d.reshape(len(d), -1)
    if order == 2:                                       # d_i = d_(i−1) + e_i from i = 2 on: the first differences
        flat = np.concatenate([flat[:1], np.cumsum(flat[1:], axis=0)])
    total = np.cumsum(np.nan_to_num(flat), axis=0)
    values = total / 10.0 ** -exponent if exponent < 0 else total * 10.0 ** exponent
    return np.where(np.isnan(flat), np.nan, values).reshape(d.shape)


# ---- spacing ---------------------------------------------------------------------------------------------

def coordinate(value: float, log: bool) -> float:
    """The coordinate in which members are spaced and interpolated: the value, or its logarithm."""
    return math.log(value) if log else value


def from_coordinate(x: float, log: bool) -> float:
    return math.exp(x) if log else x


def spaced(low: float, high: float, count: int, log: bool) -> list[float]:
    """count values evenly spaced from low to high (in log when ``log``), the ends exact."""
    a, b = coordinate(low, log), coordinate(high, log)
    inner = [_as_sent(from_coordinate(a + (b - a) * k / (count - 1), log), low, high) for k in range(1, count - 1)]
    return [low, *inner, high]


def midpoint(low: float, high: float, log: bool) -> float:
    return _as_sent(from_coordinate((coordinate(low, log) + coordinate(high, log)) / 2, log), low, high)


def _as_sent(value: float, low: float, high: float) -> float:
    """The value to SIGNIFICANT digits (so the member is computed at the value sent), unless that would
    leave the open interval (low, high)."""
    short = rounded(value)
    return short if low < short < high else value


# ---- the interpolation rule -------------------------------------------------------------------------------

def _is_number(x) -> bool:
    return isinstance(x, (int, float)) and not isinstance(x, bool)


def texts(item) -> tuple:
    """The strings of an object (its identity: a special position's kind); () for anything else."""
    return tuple((k, v) for k, v in item.items() if isinstance(v, str)) if isinstance(item, dict) else ()


def interpolate(a, b, w: float, stencil: tuple | None = None):
    """The contract's rule between two members' leaves a (weight 1 − w) and b (weight w); see the module.
    ``stencil`` (trees, weights): the 4 members' leaves of a cubic interval and their Lagrange weights, walked
    alongside (None where the structure parts: that leaf is linear)."""
    if a is None or b is None:
        return None
    trees, weights = stencil if stencil is not None else ((), ())
    if isinstance(a, np.ndarray) and isinstance(b, np.ndarray) and a.shape == b.shape:
        line = (1 - w) * a + w * b                      # NaN (null) in either stays NaN (null)
        if trees and all(isinstance(t, np.ndarray) and t.shape == a.shape for t in trees):
            cubic = sum(weight * t for weight, t in zip(weights, trees))
            return np.where(np.isnan(cubic), line, cubic)          # a null among the 4: linear there
        return line
    if _is_number(a) and _is_number(b):
        if trees and all(_is_number(t) and not math.isnan(t) for t in trees):
            return sum(weight * t for weight, t in zip(weights, trees))
        return (1 - w) * a + w * b
    if isinstance(a, list) and isinstance(b, list) and len(a) == len(b):
        inner = [[t[i] if isinstance(t, list) and len(t) == len(a) and texts(t[i]) == texts(a[i]) else None
                  for t in trees] for i in range(len(a))] if trees else [()] * len(a)
        return [interpolate(x, y, w, (inner[i], weights) if trees and all(t is not None for t in inner[i]) else None)
                if texts(x) == texts(y) else (x if w < 0.5 else y) for i, (x, y) in enumerate(zip(a, b))]
    if isinstance(a, dict) and isinstance(b, dict):
        near, far = (a, b) if w < 0.5 else (b, a)

        def below(key):
            found = [t.get(key) if isinstance(t, dict) else None for t in trees]
            return (found, weights) if trees and all(t is not None for t in found) else None
        return {key: (interpolate(a[key], b[key], w, below(key)) if key in far else value)
                for key, value in near.items()}
    return a if w < 0.5 else b


def interpolate_family(values: list[float], answers: list, value: float, log: bool, orders: list[int] | None = None):
    """The family's answer at value by the rule (values ascending; outside the range, the end member); orders:
    each interval's rule (1 linear, 3 cubic; None: every interval linear)."""
    if value <= values[0]:
        return answers[0]
    if value >= values[-1]:
        return answers[-1]
    k = bisect_right(values, value) - 1
    a, b = coordinate(values[k], log), coordinate(values[k + 1], log)
    x = coordinate(value, log)
    stencil = None
    if orders is not None and orders[k] == 3:
        first = int(stencils(len(values))[k])
        trees = answers[first:first + 4]
        if all(t is not None for t in trees):
            nodes = np.array([coordinate(v, log) for v in values[first:first + 4]])
            stencil = (trees, lagrange(nodes, x).tolist())
    return interpolate(answers[k], answers[k + 1], (x - a) / (b - a), stencil)


# ---- answers as trees of arrays ---------------------------------------------------------------------------

def as_tree(answer, sent: bool = True):
    """A member's answer with every array of numbers (and nulls) as a float ndarray, null → NaN, and (when
    ``sent``) each float rounded to SIGNIFICANT digits as sent (all arrays in one vectorised pass). Arrays of
    whole numbers alone stay lists (interpolated element by element all the same)."""
    tree = _arrays(answer)
    if not sent:
        return tree
    found: list[np.ndarray] = []
    _float_arrays(tree, found)
    flat = rounded_array(np.concatenate([a.ravel() for a in found])) if found else np.empty(0)
    parts = np.split(flat, np.cumsum([a.size for a in found])[:-1]) if found else []
    return _sent(tree, iter(part.reshape(a.shape) for part, a in zip(parts, found)))


def _arrays(answer):
    """The answer with its arrays of numbers as float ndarrays (non-finite → NaN), floats as floats."""
    if isinstance(answer, dict):
        return {key: _arrays(value) for key, value in answer.items()}
    if isinstance(answer, np.ndarray) and answer.dtype.kind != "f":
        return answer.tolist()
    if isinstance(answer, (list, tuple, np.ndarray)):
        array = answer.astype(float) if isinstance(answer, np.ndarray) else _numeric_array(answer)
        if array is None:
            return list(answer) if _flat(answer) else [_arrays(x) for x in answer]
        return np.where(np.isfinite(array), array, np.nan)
    if isinstance(answer, (float, np.floating)):
        return float(answer)
    return answer


def _flat(items) -> bool:
    """Whether a list holds no number to round nor anything nested: flags, counters, texts (sent as they are)."""
    return set(map(type, items)) <= PLAIN


def _float_arrays(tree, found: list) -> None:
    """The tree's float arrays in walk order."""
    if isinstance(tree, dict):
        for value in tree.values():
            _float_arrays(value, found)
    elif isinstance(tree, list) and not _flat(tree):
        for value in tree:
            _float_arrays(value, found)
    elif isinstance(tree, np.ndarray):
        found.append(tree)


def _sent(tree, arrays):
    """The tree with each float array taken from ``arrays`` (rounded, in walk order), each float rounded."""
    if isinstance(tree, dict):
        return {key: _sent(value, arrays) for key, value in tree.items()}
    if isinstance(tree, list):
        return tree if _flat(tree) else [_sent(value, arrays) for value in tree]
    if isinstance(tree, np.ndarray):
        return next(arrays)
    if isinstance(tree, float):
        return rounded(tree)
    return tree


NUMBERS = frozenset({float, int, type(None)})
PLAIN = frozenset({bool, int, str, type(None)})


def _numeric_array(items: list) -> np.ndarray | None:
    """The list as a float array if it is a (nested, rectangular) array of numbers and nulls with a float, or
    of nulls alone (a curve undefined at every angle, interpolated element by element like any other)."""
    kinds = {type(x) for x in items}
    if kinds == {list}:                                  # a table: its rows' elements decide
        kinds = {type(y) for x in items for y in x}
        if kinds == {list}:
            rows = [_numeric_array(x) for x in items]
            if any(row is None for row in rows) or len({row.shape for row in rows}) != 1:
                return None
            return np.stack(rows)
    if not kinds <= NUMBERS or not (float in kinds or kinds == {type(None)}):     # whole numbers: counters
        return None
    try:
        return np.array(items, dtype=float)
    except ValueError:                                   # ragged rows
        return None


def rounded(x: float) -> float | None:
    """x to SIGNIFICANT digits; NaN and ±inf → None (sent as null)."""
    return float(f"{x:.{SIGNIFICANT}g}") if math.isfinite(x) else None


def rounded_array(x: np.ndarray) -> np.ndarray:
    """Each element to SIGNIFICANT digits (serialise.significant: exact powers of ten keep the shortest decimal
    form), non-finite → NaN (null); the few elements where 10^|k| is no longer exact (below 1e-17 or from
    1e26 on) are formatted one by one."""
    x = np.where(np.isfinite(x), x, np.nan)
    result = significant(x, SIGNIFICANT)
    with np.errstate(invalid="ignore"):
        magnitude = np.abs(x)
        far = (magnitude > 0) & ((magnitude < 1e-17) | (magnitude >= 1e26))
    if far.any():
        result[far] = [float(f"{value:.{SIGNIFICANT}g}") for value in x[far]]
    return result


# ---- checked leaves, spans and the estimated error of interpolation ----------------------------------------

def checked_leaves(tree, path: tuple = ()):
    """(path, float or float array) of each plotted quantity: floats outside UNCHECKED. An object in an array
    is named by its index and its texts, (index, texts): another kind at that index is another quantity."""
    if isinstance(tree, dict):
        for key, value in tree.items():
            if key not in UNCHECKED:
                yield from checked_leaves(value, (*path, key))
    elif isinstance(tree, list):                        # of objects, tables, or flags and counters (skipped)
        for index, value in enumerate(tree):
            if isinstance(value, dict):
                yield from checked_leaves(value, (*path, (index, texts(value))))
            elif isinstance(value, (list, np.ndarray, float)):
                yield from checked_leaves(value, (*path, index))
    elif isinstance(tree, np.ndarray) or isinstance(tree, float):
        yield path, tree


def flatten(tree) -> dict[tuple, np.ndarray]:
    """Each checked leaf of a member's tree as a float array (a number as a 0-d array), by path: the
    family's arithmetic works on these, once per member."""
    return {path: np.asarray(leaf, float) for path, leaf in checked_leaves(tree)}


def quantity(path: tuple) -> str:
    """The dotted name of a leaf's path, as the message gives it (an object in an array by its index)."""
    return ".".join(str(part[0] if isinstance(part, tuple) else part) for part in path)


NO_NUMBER = (math.inf, -math.inf)   # the extent of a leaf without a number (null wherever held): no span


def extend(extent: dict[tuple, list[float]], leaves: dict[tuple, np.ndarray]) -> dict[tuple, list[float]]:
    """Merge [min, max] of every element of each leaf (nulls aside) into ``extent``; a leaf with no number
    (a flywheel's speed without the flywheel where the machine would stall) is held as NO_NUMBER."""
    for path, leaf in leaves.items():
        finite = np.atleast_1d(leaf)[np.isfinite(np.atleast_1d(leaf))]
        low, high = (float(finite.min()), float(finite.max())) if finite.size else NO_NUMBER
        known = extent.setdefault(path, [low, high])
        known[0], known[1] = min(known[0], low), max(known[1], high)
    return extent


def extend_member(extent: dict[tuple, list[float]], member: "Member") -> dict[tuple, list[float]]:
    """extend by a member's leaves, every leaf at once when it has them flat."""
    flat = member.flat
    if flat is None:
        return extend(extent, member.leaves)
    lows, highs = np.fmin.reduceat(flat.vector, flat.starts).tolist(), np.fmax.reduceat(flat.vector, flat.starts).tolist()
    for path, low, high in zip(flat.paths, lows, highs):
        if low != low:                                  # NaN: no element of the leaf is a number
            low, high = NO_NUMBER
        known = extent.setdefault(path, [low, high])
        known[0], known[1] = min(known[0], low), max(known[1], high)
    return extent


def ranges(answer, into: dict[tuple, list[float]] | None = None) -> dict[tuple, list[float]]:
    """[min, max] of every element of each checked leaf of the answer (nulls aside), merged into ``into``."""
    return extend({} if into is None else into, flatten(answer))


def widths(extent: dict[tuple, list[float]]) -> dict[tuple, float]:
    """The width each checked leaf's interpolation error is measured against: its span, max − min of every
    element of the leaf over all members (refused members and nulls aside), but at least a fraction of the
    largest magnitude among the leaf and its siblings. Inside an object (the works of a cycle, a harmonic
    series: quantities of one kind, drawn side by side) the fraction is SAME_KIND: the net work of a steady
    cycle, zero but for the solver's residual (~1e-7 of the driving work), is invisible beside the driving
    work and is not a curve to resolve. At the answer's top level (quantities of different units side by
    side) it is ROUNDOFF: only what is zero but for round-off (~1e-17) is left out. A leaf that is null
    wherever a member holds it has width 0: nothing of it is drawn, but it is a leaf of the family all the
    same (every checked leaf of every member has a width)."""
    magnitude: dict[tuple, float] = {}
    for path, (low, high) in extent.items():
        if low <= high:
            magnitude[path[:-1]] = max(magnitude.get(path[:-1], 0.0), abs(low), abs(high))
    return {path: max(high - low, (SAME_KIND if len(path) > 1 else ROUNDOFF) * magnitude[path[:-1]])
            if low <= high else 0.0 for path, (low, high) in extent.items()}


def spans(answers: list) -> dict[tuple, float]:
    """widths over the members (None: refused)."""
    extent: dict[tuple, list[float]] = {}
    for answer in answers:
        if answer is not None:
            ranges(answer, extent)
    return widths(extent)


def _leaf(tree, path: tuple):
    for key in path:
        if isinstance(key, tuple):                      # an object in an array: the same kind, or nothing
            key, kind = key
            if not isinstance(tree, list) or key >= len(tree) or texts(tree[key]) != kind:
                return None
        try:
            tree = tree[key]
        except (KeyError, IndexError, TypeError):
            return None
    return tree


# ---- members ----------------------------------------------------------------------------------------------

def refusal(error: Exception) -> dict:
    """{code, message} of a member refused as HTTP would refuse it (the 422's detail)."""
    if isinstance(error, GeometryError):
        return {"code": error.code, "message": f"{error.field}: {error.reason}"}
    first = error.errors()[0]
    where = ".".join(str(part) for part in first["loc"])
    return {"code": first["type"], "message": f"{where}: {first['msg']}" if where else first["msg"]}


@dataclass(frozen=True)
class Flat:
    """A member's checked leaves as one vector, for the arithmetic of the whole member at once: the leaves'
    paths and shapes (its layout: members of the same layout are compared element for element), where each
    leaf starts in the vector, and the vector."""

    layout: tuple
    paths: tuple
    starts: np.ndarray
    vector: np.ndarray

    @classmethod
    def of(cls, leaves: dict[tuple, np.ndarray]) -> "Flat | None":
        """None for no leaves or an empty one (no element to reduce)."""
        if not leaves or any(leaf.size == 0 for leaf in leaves.values()):
            return None
        sizes = [leaf.size for leaf in leaves.values()]
        return cls(tuple((path, leaf.shape) for path, leaf in leaves.items()), tuple(leaves),
                   np.cumsum([0, *sizes[:-1]]), np.concatenate([leaf.ravel() for leaf in leaves.values()]))


@dataclass
class Member:
    """One value of the family: its answer as sent (a tree of rounded arrays; None where refused), the
    refusal, whether a bound cut it short, and its checked leaves flattened."""

    value: float
    answer: dict | None
    error: dict | None
    partial: bool
    leaves: dict[tuple, np.ndarray] = field(default_factory=dict)
    flat: Flat | None = None                            # the leaves as one vector (made from them if not given)

    @classmethod
    def of(cls, value: float, outcome: Answer | Exception, fields: Fields | None = None) -> "Member":
        """The member from the endpoint's Answer (pruned to ``fields`` first, if given), or from its refusal
        (ValidationError, GeometryError)."""
        if isinstance(outcome, Exception):
            return cls(value, None, refusal(outcome), False)
        tree = as_tree(outcome.payload if fields is None else pruned(outcome.payload, fields))
        return cls(value, tree, None, outcome.partial, flatten(tree))

    def __post_init__(self):
        if self.flat is None and self.leaves:
            self.flat = Flat.of(self.leaves)

    @cached_property
    def kinds(self) -> frozenset:
        """The (path, shape) of each leaf that has elements."""
        return frozenset((path, leaf.shape) for path, leaf in self.leaves.items() if leaf.size)

    @cached_property
    def placed(self) -> tuple[np.ndarray, list[tuple[tuple, int, int]]]:
        """The leaves end to end (the flat vector, where there is one) and each leaf's ((path, shape), where it
        starts, size) in it."""
        sizes = [leaf.size for leaf in self.leaves.values()]
        starts = np.cumsum([0, *sizes[:-1]]).tolist() if sizes else []
        vector = self.flat.vector if self.flat is not None else \
            np.concatenate([leaf.ravel() for leaf in self.leaves.values()]) if sizes else np.zeros(0)
        return vector, [((path, leaf.shape), start, leaf.size)
                        for (path, leaf), start in zip(self.leaves.items(), starts)]

    def size(self) -> int:
        """Bytes the member holds, roughly (its arrays, twice: as leaves and flat, and a little per leaf): the
        memo's measure."""
        return sum(2 * leaf.nbytes + 100 for leaf in self.leaves.values()) + 1000


MemberBatch = Callable[[list[float], float], list[Member]]


# ---- the members stacked: every member's leaves as one row --------------------------------------------------

@dataclass(frozen=True)
class Stack:
    """The members' checked leaves stacked, one row per member (M × E): the columns are the elements of every
    (path, shape) that two neighbouring answered members hold, in the order first met; NaN where a member
    lacks that leaf (or holds it in another shape: another quantity), where it is null, and in a refused
    member's row. ``starts`` says where each leaf's columns begin, ``paths`` names them (a path may come
    twice, in two shapes). A (path, shape) that no two neighbours hold has no difference of any order across
    members (every one takes two neighbours at least): it has no columns (a start-up curve whose length
    moves with the value would otherwise bring as many columns as it has lengths, all but NaN; ``regridded``
    bounds it)."""

    x: np.ndarray               # (M,) the members' coordinates (value, or its log)
    answered: np.ndarray        # (M,) bool
    paths: tuple
    starts: np.ndarray
    rows: np.ndarray            # (M, E)
    layout: tuple               # ((path, shape), ...): the columns' leaves
    held: tuple | None = None   # per member, the indices of the leaves it holds (None: every member all)

    @classmethod
    def of(cls, members: list[Member], log: bool) -> "Stack":
        x = np.array([coordinate(m.value, log) for m in members])
        answered = np.array([m.answer is not None for m in members])
        flats = [m.flat for m in members if m.answer is not None]
        if _one_layout(flats, answered.sum()):
            layout, paths, starts, width = flats[0].layout, flats[0].paths, flats[0].starts, flats[0].vector.size
            rows = np.full((len(members), width), np.nan)
            for index, member in enumerate(members):
                if member.answer is not None:
                    rows[index] = member.flat.vector
            return cls(x, answered, paths, starts, rows, layout)
        kinds = [m.kinds if m.answer is not None else frozenset() for m in members]
        paired = set().union(*(a & b for a, b in zip(kinds[:-1], kinds[1:])))
        columns: dict[tuple, int] = {}                      # (path, shape) → its first column
        width = 0
        for member in members:
            for path, leaf in member.leaves.items():
                if (path, leaf.shape) in paired and (path, leaf.shape) not in columns:
                    columns[path, leaf.shape] = width
                    width += leaf.size
        rows = np.full((len(members), width), np.nan)
        order = {leaf: index for index, leaf in enumerate(columns)}
        held = []
        for index, member in enumerate(members):
            mine = []
            runs: list[list[int]] = []      # [from, to, size]: leaves adjacent both in the member and in the columns
            vector, places = member.placed
            for key, position, size in places:
                first = columns.get(key)
                if first is None:
                    continue
                mine.append(order[key])
                if runs and runs[-1][0] + runs[-1][2] == position and runs[-1][1] + runs[-1][2] == first:
                    runs[-1][2] += size
                else:
                    runs.append([position, first, size])
            for position, first, size in runs:
                rows[index, first:first + size] = vector[position:position + size]
            held.append(frozenset(mine))
        return cls(x, answered, tuple(path for path, _ in columns), np.array(list(columns.values()), int), rows,
                   tuple(columns), tuple(held))

    def common_to_any(self, windows: list) -> tuple | None:
        """The indices of the leaves that every member of at least one of the windows holds, ascending (None:
        all, one layout)."""
        if self.held is None:
            return None
        return tuple(sorted(set().union(*(frozenset.intersection(*(self.held[m] for m in window))
                                           for window in windows))))

    def largest(self, values: np.ndarray) -> np.ndarray:
        """(K, L): the largest of each leaf's elements of values (K, E), nulls aside; NaN where it has none."""
        if not self.paths:
            return np.zeros((len(values), 0))
        return np.fmax.reduceat(values, self.starts, axis=1)

    def spans(self, span: dict[tuple, float]) -> np.ndarray:
        return np.array([span.get(path, 0.0) for path in self.paths])


def _one_layout(flats: list, answered: int) -> bool:
    """Whether every answered member holds the same leaves in the same shapes (a row is its flat vector)."""
    return (len(flats) == answered > 0 and all(flat is not None for flat in flats)
            and all(flat.layout == flats[0].layout for flat in flats[1:]))


def relative(errors: np.ndarray, widths_: np.ndarray) -> np.ndarray:
    """errors (K, L) per leaf as fractions of the leaves' spans: 0 where nothing is estimated (NaN) or the
    error is 0, 1 (100 %) where a leaf with no span has one."""
    with np.errstate(divide="ignore", invalid="ignore"):
        found = np.where(widths_ > 0, errors / widths_, 1.0)
    return np.where(np.isnan(errors) | (errors == 0), 0.0, found)


def divided(stack: Stack, order: int, kept: dict) -> np.ndarray:
    """(M − order, L): the largest |f[x_j, …, x_j+order]| of each leaf, the divided difference of order
    ``order`` over members j … j + order (f″/2 for order 2, f⁗/24 for order 4); NaN where a refusal is among
    them. A window computed before (the same members) is taken from ``kept``."""
    count, width = len(stack.x), order + 1
    found = np.full((max(count - order, 0), len(stack.paths)), np.nan)
    if count < width:
        return found
    whole = np.convolve(stack.answered.astype(int), np.ones(width, int), "valid") == width
    keys = [(order, *stack.x[j:j + width].tolist()) for j in range(count - order)]
    new = [j for j in range(count - order) if whole[j] and keys[j] not in kept]
    if new:
        first = np.array(new)
        nodes = stack.x[first[:, None] + np.arange(width)]                       # (K, order + 1)
        # f[x_0 … x_n] = Σ_i f_i / Π_{j≠i} (x_i − x_j): one weighted sum of rows per member of the window
        gaps = nodes[:, :, None] - nodes[:, None, :]
        gaps[:, np.arange(width), np.arange(width)] = 1.0
        weights = 1.0 / np.prod(gaps, axis=2)
        # only the leaves that all members of some window hold: elsewhere the difference is NaN anyway (a
        # start-up curve whose length changes with the value would fill most columns with NaN)
        leaves = stack.common_to_any([range(j, j + width) for j in new])
        chosen = np.arange(len(stack.paths)) if leaves is None else np.array(leaves, np.int64)
        found_rows = np.full((len(new), len(stack.paths)), np.nan)
        if chosen.size:                 # one compiled loop over the windows' elements, leaf by leaf
            ends = np.append(stack.starts[1:], stack.rows.shape[1]).astype(np.int64)
            found_rows[:, chosen] = divided_differences(
                np.ascontiguousarray(stack.rows, float), first.astype(np.int64), weights,
                stack.starts[chosen].astype(np.int64), ends[chosen])
        for j, row in zip(new, found_rows):
            kept[keys[j]] = (stack.layout, row)
    for j in range(count - order):
        if whole[j]:
            layout, row = kept[keys[j]]
            found[j] = row if layout == stack.layout else _moved(row, layout, stack.layout, kept)
    return found


def _moved(row: np.ndarray, before: tuple, after: tuple, kept: dict) -> np.ndarray:
    """A window's values per leaf of the layout ``before`` in the layout ``after`` (the leaves neighbours hold,
    which change as members are added): NaN for a leaf new to it, which not all of the window's members hold;
    a leaf ``after`` lacks is one they do not all hold either (they are still neighbours), NaN in ``row``."""
    where = kept.get((before, after))
    if where is None:
        index = {leaf: i for i, leaf in enumerate(after)}
        where = kept[before, after] = np.array([index.get(leaf, -1) for leaf in before], int)
    moved = np.full(len(after), np.nan)
    moved[where[where >= 0]] = row[where >= 0]
    return moved


def curvatures(stack: Stack, kept: dict) -> np.ndarray:
    """(M, L): the largest |f″| of each leaf at each member, the second divided difference with its two
    neighbours 2·[(f₊ − f₀)/h₊ − (f₀ − f₋)/h₋]/(h₊ + h₋) (twice the divided difference); NaN rows at the
    range's ends and beside a refusal."""
    found = np.full((len(stack.x), len(stack.paths)), np.nan)
    if len(stack.x) >= 3:
        found[1:-1] = 2 * divided(stack, 2, kept)
    return found


def stencils(count: int) -> np.ndarray:
    """(M − 1,) the first of the 4 members whose cubic interpolates interval k: k − 1, moved inside the range
    at its ends (0 for the first interval, M − 4 for the last)."""
    return np.clip(np.arange(count - 1) - 1, 0, max(count - 4, 0))


def lagrange(nodes: np.ndarray, x: float) -> np.ndarray:
    """The weights of the cubic through the 4 nodes at x: ℓ_i(x) = Π_{j≠i} (x − x_j)/(x_i − x_j)."""
    weights = np.ones(4)
    for i in range(4):
        for j in range(4):
            if j != i:
                weights[i] *= (x - nodes[j]) / (nodes[i] - nodes[j])
    return weights


OMEGA_SAMPLES = np.linspace(0.0, 1.0, 65)


def cubic_errors(stack: Stack, kept: dict) -> np.ndarray:
    """(M − 1, L): interval k's estimated largest |cubic − exact| by leaf, max over the interval of
    |Π (x − x_i)| over its 4 stencil nodes times |f[5 members]|, the fourth divided difference, the larger
    of the two 5-member windows around the stencil (the one window at the range's ends): a bend or a corner
    that one window straddles is not hidden by the other; NaN where a stencil member or both windows hold a
    refusal, and for families of fewer than 5 members."""
    x, count = stack.x, len(stack.x)
    found = np.full((count - 1, len(stack.paths)), np.nan)
    if count < 5:
        return found
    windows = divided(stack, 4, kept)                  # (M − 4, L): window j = members j … j + 4
    first = stencils(count)
    left = np.where((first - 1 >= 0)[:, None], windows[np.maximum(first - 1, 0)], np.nan)
    right = np.where((first + 4 <= count - 1)[:, None], windows[np.minimum(first, count - 5)], np.nan)
    fourth = np.fmax(left, right)
    nodes = x[first[:, None] + np.arange(4)]                                    # (M − 1, 4)
    t = x[:-1, None] + np.diff(x)[:, None] * OMEGA_SAMPLES                       # (M − 1, S)
    omega = np.abs(np.prod(t[:, :, None] - nodes[:, None, :], axis=2)).max(axis=1)
    stencil_answered = np.all(stack.answered[first[:, None] + np.arange(4)], axis=1)
    found = fourth * omega[:, None]
    found[~stencil_answered] = np.nan
    return found


@dataclass(frozen=True)
class Irregular:
    """(M − 1, L) each, by interval and leaf (the largest of the leaf's elements): what the second differences
    at an interval's ends do not see (see ``irregular``)."""

    changes: np.ndarray     # |f(b) − f(a)| across the interval
    steps: np.ndarray       # u_k: the step the neighbours' slopes do not explain
    corners: np.ndarray     # the chord's error were the slope to change at one point inside
    kinked: np.ndarray      # the linear bound of elements whose curvature sits at the interval alone


def irregular(stack: Stack) -> Irregular:
    """Interval k's departures from a smooth f at the members' spacing, from the slopes s_i = (f_i+1 − f_i)/h_i
    of it and its neighbours, element by element, then the largest of each leaf's elements:
    steps     u_k = h_k · min |s_k − ŝ_k|, ŝ_k the slope predicted from two other intervals (PREDICTORS), the
              smallest of the predictions there are (an interval beside a jump predicts from the side away
              from it: it is not blamed for its neighbour's step). Zero for a parabola and O(f‴h³) for a smooth
              f; for a step of height J between members inside smooth neighbours it is J whatever the spacing,
              where h²|f″|/8 reads J·h/(4(h + h₋)) (J/8 on an even spacing, J/12 beside an interval twice as
              wide) and halving does not make it smaller (an argmin on a grid: a touching point moving node by
              node as the value changes);
    corners   h_k·a·b/(a + b), a = s_k − s_k−1, b = s_k+1 − s_k of one sign: the chord's largest error were f
              two straight lines meeting inside the interval (slopes s_k−1 and s_k+1, at the point that makes
              the chord's slope s_k), on any spacing; for a parabola on an even spacing (a = b = f″h) it is
              f″h²/2, SAFETY × h²f″/8. The ends' second differences read a corner at t from an end as
              Δs·min(t, h − t)/8 on an even spacing and less beside wider neighbours: up to 8× and more below
              the corner's Δs·t(h − t)/h;
    kinked    SAFETY·h²/8 × the larger |f″| at the interval's ends, for the elements where that is more than
              CONCENTRATED × the larger |f″| at the members beyond (k − 1 and k + 2): a bend at the interval
              alone, a corner, which the cubic's fourth differences over 5 members read diluted (a window
              twice as wide as the cubic's 4 members reads a corner 8× smaller), not a smooth curvature, which
              is the same at neighbouring members.
    NaN where the members are not there (fewer than 4, refusals, the range's ends for the corners); and the
    change |f(b) − f(a)| across each interval. Computed element by element in one compiled loop
    (server/core/interpolation_error.py)."""
    return Irregular(*irregularities(np.ascontiguousarray(stack.x, float), np.ascontiguousarray(stack.rows, float),
                                     np.asarray(stack.starts, np.int64), PREDICTORS, CONCENTRATED, float(SAFETY)))


@dataclass
class Assessment:
    """Each interval's rule (1 linear, 3 cubic), its estimated error relative to the spans, the leaf where it
    is largest, and its bound (the estimate times the rule's safety factor, compared with TOLERANCE)."""

    orders: list[int]
    scores: list[float]
    where: list[tuple]
    bounds: list[float]
    linear: list[tuple[float, tuple]]       # the linear rule's estimate and its leaf, whichever rule is chosen


def assess(stack: Stack, span: dict[tuple, float], kept: dict, drawn: list | None = None) -> Assessment:
    """Every interval at once (see the module, Refinement): the linear estimate h²/8 times the smaller of the
    ends' |f''|, the cubic one from the fourth divided differences, and the rule whose bound is smaller.
    Between an answered and a refused member: 1 (the limit is to be found), between two refused: 0; where
    neither end has a second difference: infinite. ``kept``: divided differences computed before (divided)."""
    count = len(stack.x)
    widths_ = stack.spans(span)
    bends = curvatures(stack, kept)
    h = np.diff(stack.x)
    ends = np.fmin(bends[:-1], bends[1:]) * (h ** 2 / 8)[:, None]
    odd = irregular(stack)
    steps = odd.changes                                 # |f(b) − f(a)| of every leaf over every interval
    # a leaf both ends hold but neither has a second difference for (its neighbours hold it in another shape,
    # a start-up curve whose length changes with the value): the change across, a bound where f is monotone
    bent_only = relative(np.where(np.isnan(ends), steps, ends), widths_)
    jumps = relative(odd.steps, widths_)                # a step the neighbours' slopes do not explain, as it is
    corners = relative(odd.corners, widths_)            # a corner inside, as it is
    # the linear rule's estimate (the ends' curvature, exact for a parabola on any spacing; a step as it is)
    # and its bound: the safety factor on the curvature, none on a step or a corner measured as it is (on a
    # spacing that grows, the corner term reads a parabola up to (h₋ + h)/2h times its SAFETY × estimate)
    linear = np.maximum(bent_only, jumps)
    linear_bound = np.maximum(np.maximum(SAFETY * bent_only, jumps), corners)
    fourth = cubic_errors(stack, kept)
    has_cubic = ~np.isnan(fourth).all(axis=1)
    cubic = np.where(np.isnan(fourth), linear, relative(fourth, widths_))   # a leaf the stencil lacks: linear
    bent = np.zeros(count, bool)                        # members with a second difference (answered neighbours)
    bent[1:-1] = stack.answered[:-2] & stack.answered[1:-1] & stack.answered[2:]
    known = bent[:-1] | bent[1:]
    orders, scores, where, bounds, linears = [], [], [], [], []
    # a step (or a corner) sets the linear bound of a leaf in the interval: a cubic through a step overshoots
    # by about the step (0.87 of it measured), and its fourth differences read a step as they read a smooth
    # bend (the ratio u_k / (f[5 members]·max|ω|) is ~14 for both), so the interval is drawn linearly, where
    # the step bounds the chord's error; a step below TOLERANCE / CUBIC_SAFETY (a smooth curve's inflection,
    # where f″ and so the second differences vanish) is left to the cubic, whose overshoot is as small. A
    # corner (odd.kinked) above that size is drawn linearly too: the cubic's estimate reads it diluted.
    kinked = relative(odd.kinked, widths_)
    stepped = (((jumps > SAFETY * bent_only) & (jumps > TOLERANCE / CUBIC_SAFETY))
               | (kinked > TOLERANCE / CUBIC_SAFETY)).any(axis=1) if linear.size else np.zeros(count - 1, bool)
    lin_worst = linear_bound.argmax(axis=1) if linear.size else None
    cub_worst = cubic.argmax(axis=1) if cubic.size else None
    for k in range(count - 1):
        a, b = stack.answered[k], stack.answered[k + 1]
        if not (a and b):
            score = 0.0 if not (a or b) else 1.0
            orders.append(1), scores.append(score), where.append(()), bounds.append(score)
            linears.append((score, ()))
            continue
        lin = (float(linear[k, lin_worst[k]]), stack.paths[lin_worst[k]]) if linear.size else (0.0, ())
        lin_bound = float(linear_bound[k, lin_worst[k]]) if linear.size else 0.0
        if not known[k]:
            lin, lin_bound = (math.inf, ()), math.inf
        linears.append(lin)
        order, (score, path), bound = 1, lin, lin_bound
        if has_cubic[k] and cubic.size and not stepped[k]:
            cub = (float(cubic[k, cub_worst[k]]), stack.paths[cub_worst[k]])
            if cub[0] * CUBIC_SAFETY < lin_bound:
                order, (score, path), bound = 3, cub, cub[0] * CUBIC_SAFETY
        if drawn is not None and drawn[k][0] > score:     # a leaf drawn from the nearer member: its change
            score, path = drawn[k]
        if drawn is not None and drawn[k][0] > lin[0]:
            linears[-1] = drawn[k]
        orders.append(order), scores.append(score), where.append(path if score > 0 else ())
        bounds.append(max(bound, score))
    return Assessment(orders, scores, where, bounds, linears)


# ---- the family -------------------------------------------------------------------------------------------

@dataclass
class Family:
    """The members computed so far, ascending in value, and the extents of their leaves."""

    log: bool
    finest: float
    members: list[Member] = field(default_factory=list)
    extent: dict[tuple, list[float]] = field(default_factory=dict)
    kept: dict = field(default_factory=dict)        # divided differences by layout and members (divided)
    drawn: dict = field(default_factory=dict)       # (value, value) → regridded of the interval between them

    def add(self, member: Member) -> None:
        extend_member(self.extent, member)
        self.members.insert(bisect_right([m.value for m in self.members], member.value), member)

    @property
    def values(self) -> list[float]:
        return [m.value for m in self.members]

    def width(self, k: int) -> float:
        """The width of interval k (members k and k + 1) in the slider's coordinate."""
        return coordinate(self.members[k + 1].value, self.log) - coordinate(self.members[k].value, self.log)

    def halvable(self, k: int) -> bool:
        return self.width(k) > self.finest * (1 + 1e-9)

    def assess(self) -> tuple[Stack, dict[tuple, float], Assessment]:
        stack, span = Stack.of(self.members, self.log), widths(self.extent)
        pairs = list(zip(self.members[:-1], self.members[1:]))
        for a, b in pairs:
            if (a.value, b.value) not in self.drawn:
                self.drawn[a.value, b.value] = regridded(a, b, span)
        return stack, span, assess(stack, span, self.kept, [self.drawn[a.value, b.value] for a, b in pairs])


def regridded(a: Member, b: Member, span: dict[tuple, float]) -> tuple[float, tuple]:
    """The largest change across an interval, relative to its span, of the arrays its two members hold in
    different shapes, and where ((0, ()) if none). The page draws the nearer member's array there, on its own
    grid (a start-up whose length moves with the value), so the change is a bound of what is drawn wherever f
    is monotone in the value at a fixed abscissa, as for a jump (see change): on a common abscissa,
    |f_b(x) − f_a(x)| at the sparser member's nodes inside the range both cover, the denser member's curve
    read there linearly, for every sibling array (the same object) of the array's length in both that increases (φ, t:
    what it is plotted against); and, for an array that is not itself an abscissa, the change of its smallest
    and largest element (a start-up that stalls at one value and runs at the other). Where an abscissa ends
    (a start-up stops at the whole revolution where its convergence test is met, one revolution more or less
    from value to value) is not compared: its curve against the others' abscissae is, where both are drawn.
    An array one member holds (a number in it) and the other does not, or holds empty (the motor's operating
    point that exists from some value on), appears inside the interval: 1, a jump, found by halving."""
    if a.answer is None or b.answer is None:
        return 0.0, ()
    worst = (0.0, ())
    for path in [*a.leaves, *(p for p in b.leaves if p not in a.leaves)]:
        f, g = a.leaves.get(path), b.leaves.get(path)
        if f is not None and g is not None and f.shape == g.shape:
            continue            # one shape in both: the stack compares it element by element
        held = [x is not None and bool(np.isfinite(x).any()) for x in (f, g)]
        if held[0] != held[1]:
            if worst[0] < 1.0:          # drawn from one member only, it appears (or vanishes) inside: a jump
                worst = (1.0, path)
            continue
        if not held[0]:                 # in neither
            continue
        found = 0.0 if _increasing(f) and _increasing(g) else max(abs(np.nanmin(f) - np.nanmin(g)),
                                                                  abs(np.nanmax(f) - np.nanmax(g)))
        if f.ndim == 1 and g.ndim == 1:
            theirs = dict(abscissae(b.leaves, path, g.size))
            for name, x in abscissae(a.leaves, path, f.size):
                if name in theirs:
                    found = max(found, _apart(*sorted([(x, f), (theirs[name], g)], key=_density)))
        width = span.get(path, 0.0)
        share = found / width if width > 0 else (1.0 if found > 0 else 0.0)
        if share > worst[0]:
            worst = (float(share), path)
    return worst


def abscissae(leaves: dict[tuple, np.ndarray], path: tuple, size: int) -> list[tuple[str, np.ndarray]]:
    """(name, x) of every sibling of the leaf at ``path`` that can be its abscissa: an array of ``size``
    elements, no null, increasing; by name (the same names in two members pair up)."""
    return [(other[-1], x) for other, x in leaves.items()
            if other[:-1] == path[:-1] and other != path and x.shape == (size,) and _increasing(x)]


def _increasing(x: np.ndarray) -> bool:
    """Whether x is a 1-d array without null that increases (an abscissa; a node may come twice: the
    integrator's grids hold each kink of the moments at both of its sides)."""
    return (x.ndim == 1 and x.size > 1 and bool(np.all(np.isfinite(x))) and bool(np.all(np.diff(x) >= 0))
            and x[-1] > x[0])


def _density(curve: tuple[np.ndarray, np.ndarray]) -> float:
    """Nodes per unit of a curve's abscissa."""
    x = curve[0]
    return x.size / (x[-1] - x[0])


def _apart(sparse: tuple[np.ndarray, np.ndarray], dense: tuple[np.ndarray, np.ndarray]) -> float:
    """The largest |g(x) − f(x)| at the nodes x of the sparser curve (x, f) inside the denser one's grid, the
    denser curve g read there linearly (the sparser one read between its nodes would add its own chord's
    error, not a change with the value); 0 if none."""
    (x, f), (grid, g) = sparse, dense
    inside = (x >= grid[0]) & (x <= grid[-1])
    if not inside.any():
        return 0.0
    off = np.abs(np.interp(x[inside], grid, g) - f[inside])
    return float(np.nanmax(off)) if np.isfinite(off).any() else 0.0


def change(stack: Stack, span: dict[tuple, float], k: int) -> tuple[float, tuple]:
    """Interval k's largest |f(b) − f(a)| / span over its leaves, and where: for an interval too narrow to
    halve, a bound of the linear interpolation's error wherever f is monotone inside it (f and the chord both
    lie between f(a) and f(b)), which a jump's second differences understate (a step of height J reads J/8)."""
    with np.errstate(invalid="ignore"):
        found = relative(stack.largest(np.abs(stack.rows[k + 1:k + 2] - stack.rows[k:k + 1])), stack.spans(span))[0]
    if not found.size:
        return 0.0, ()
    worst = int(found.argmax())
    return float(found[worst]), stack.paths[worst]


def build(members: MemberBatch, low: float, high: float, log: bool, lang: str = "en",
          stage: str = "full", pack: bool = False) -> tuple[dict, bool]:
    """The family's answer (see the module) and whether it is partial. members(values, deadline) gives the
    members at values, in order, stopping early (a shorter list) once the deadline has passed. ``pack``:
    sent packed (see the module: shared arrays once, arrays as integer steps)."""
    started = time.perf_counter()
    deadline = started + TIME_BUDGET_S
    family = Family(log, (coordinate(high, log) - coordinate(low, log)) * FINEST_FRACTION)
    first = spaced(low, high, START_MEMBERS, log)
    order = [first[index] for index in COARSE_TO_FINE]
    for member in members(order[:2], math.inf) + members(order[2:], deadline):   # min and max always
        family.add(member)
    cut = len(family.members) < START_MEMBERS
    assessed = family.assess()
    while stage == "full" and not cut:
        bounds = assessed[2].bounds
        scores = sorted(((bound, k) for k, bound in enumerate(bounds) if family.halvable(k)), reverse=True)
        halve = [k for bound, k in scores if bound > TOLERANCE][:MAX_MEMBERS - len(family.members)]
        if not halve:
            break
        values = [midpoint(family.members[k].value, family.members[k + 1].value, log) for k in halve]
        computed = members(values, deadline)
        for member in computed:
            family.add(member)
        cut = len(computed) < len(values)
        assessed = family.assess()
    return _answer(family, assessed, lang, cut, started, stage, pack)


def _answer(family: Family, assessed: tuple, lang: str, cut: bool, started: float, stage: str,
            pack: bool = False) -> tuple[dict, bool]:
    """The answer of the contract, and whether it is partial (cut at the time budget, or a member is)."""
    stack, span, assessment = assessed
    members = family.members
    orders, scores, where = list(assessment.orders), list(assessment.scores), list(assessment.where)
    answered = [k for k in range(len(members) - 1)
                if members[k].answer is not None and members[k + 1].answer is not None and math.isfinite(scores[k])]
    for k in answered:
        if stage != "full" or assessment.bounds[k] <= TOLERANCE:
            continue
        if not family.halvable(k):
            orders[k] = 1                                     # a jump: drawn linearly, and said how large
            scores[k], where[k] = max(assessment.linear[k], change(stack, span, k))
        else:                                                 # left above the tolerance (the cap, the time
            scores[k] = max(scores[k], assessment.bounds[k])  # budget): its bound, not the estimate, holds
    error = max((scores[k] for k in answered), default=None)
    if pack and error is not None:
        error += PACK_QUANTUM / 2                             # packing moves a value by at most this / span
    texts = interface_texts(lang)
    number = CommaFloat if lang in DECIMAL_COMMA else ReadableFloat
    sentences = []
    if cut:
        sentences.append(texts["family_time_budget"].format(seconds=number(TIME_BUDGET_S), points=len(members)))
    worst: dict[str, tuple[float, int, tuple]] = {}          # the worst interval left above the tolerance, by why
    if stage == "full":
        for k in answered:
            if scores[k] > TOLERANCE:
                why = ("family_unresolved" if not family.halvable(k) else
                       None if cut else "family_cap_unmet")    # cut short: the budget, said above
                if why and scores[k] > worst.get(why, (0.0,))[0]:
                    worst[why] = (scores[k], k, where[k])
        for k in range(1, len(members) - 1):
            if members[k].answer is None and members[k - 1].answer is not None and members[k + 1].answer is not None:
                worst.setdefault("family_refused_inside", (math.inf, k - 1, ()))
    for why, (score, k, path) in worst.items():
        a, b = members[k].value, members[k + 2 if why == "family_refused_inside" else k + 1].value
        sentences.append(texts[why].format(
            low=number(rounded(a)), high=number(rounded(b)), cap=MAX_MEMBERS, tolerance=number(100 * TOLERANCE),
            error=number(rounded(100 * score)) if math.isfinite(score) else score, quantity=quantity(path)))
    partial = [m.value for m in members if m.partial]
    if partial:
        shown = ", ".join(f"{number(rounded(v)):g}" for v in partial[:8]) + (", …" if len(partial) > 8 else "")
        sentences.append(texts["family_partial_members"].format(count=len(partial), values=shown))
    method = texts[f"family_method_{stage}_{'log' if family.log else 'linear'}"].format(
        start=START_MEMBERS, tolerance=number(100 * TOLERANCE), safety=SAFETY, cap=MAX_MEMBERS)
    method += texts["family_method_cubic"].format(safety=CUBIC_SAFETY, tolerance=number(100 * TOLERANCE))
    method += texts["family_method_steps"] + (texts["family_method_left"] if stage == "full" else "")
    answers = [m.answer for m in members]
    if pack:
        common, answers = shared_arrays(answers)
        exponents = quanta(span, family.extent)
        common, *answers = packed([common, *answers], exponents)
    return {
        "values": [rounded(m.value) for m in members],
        "orders": orders,
        **({"shared": common} if pack else {}),
        "answers": answers,
        "errors": [m.error for m in members],
        "interpolation_error": rounded(error) if error is not None else None,
        "tolerance": TOLERANCE,
        "numerics": {"method": method, "stage": stage, "points": len(members), "checked": len(members),
                     "runtime_ms": rounded(1e3 * (time.perf_counter() - started)), "message": " ".join(sentences)},
    }, cut or bool(partial)
