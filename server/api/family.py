"""A slider's family: one endpoint's answer at N values across the slider's range, every other parameter fixed,
so that dragging the slider is a lookup (POST /api/v1/family, issue 13).

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

Refinement. The error of linear interpolation over an interval of width h (in the slider's coordinate) is
h²·|f''|/8 for a smooth f; |f''| at a member is its second divided difference with its two neighbours,
    f''_k ≈ 2·[(f_k+1 − f_k)/h_+ − (f_k − f_k−1)/h_−] / (h_+ + h_−),
largest over each quantity's elements (nulls aside), and an interval's estimate takes the smaller of its two
ends' (an interval beside a jump is not halved for its neighbour's jump; a member at the range's end has no
second difference, its interval takes its other end's). Every computed value is a member: a round computes the
midpoints of every interval whose estimate, relative to the quantity's span (see ``widths``), exceeds
TOLERANCE / SAFETY, as one batch, until none does or the family has MAX_MEMBERS members (worst first). An
interval between an answered and a refused value is halved too (the limit is found). No interval narrower
than FINEST_FRACTION of the range is halved: no slider resolves it, and an answer that jumps (an efficiency
that is 0 at zero load and 0.97 just above) or bends at a corner too steep to resolve is named in the message
instead of taking every member. Where the cap or a jump leaves an interval above the tolerance,
numerics.message says between which values and for which quantity; for an interval too narrow to halve the
error given is the change across it, |f(b) − f(a)| / span, if larger than the estimate (a bound wherever f is
monotone inside; second differences read a step of height J as J/8).

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

The comparison uses the members as sent: every float rounded to SIGNIFICANT digits (NaN and ±inf → null), so
the reported interpolation error includes the rounding the page sees.
"""
from __future__ import annotations

import math
import re
import time
from bisect import bisect_right
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from ..core.mechanisms import GeometryError
from .serialise import Answer, significant
from .messages import CommaFloat, DECIMAL_COMMA, ReadableFloat
from ..lessons.scenes import interface_texts

TOLERANCE = 0.005               # 0.5 % of a plotted quantity's span: below a plot's resolution (issue 13)
START_MEMBERS = 9
MAX_MEMBERS = 65                # 8 intervals halved three times over the whole range, at most
FINEST_FRACTION = 1 / 1024      # an interval this narrow (of the range) is not halved: no slider resolves it
TIME_BUDGET_S = 5.0             # wall-clock bound of one family (each member keeps its endpoint's own budget)
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
            step = _step(holder, key)
            holder[step] = holder = (list if isinstance(holder[step], list) else dict)(holder[step])
        holder[_step(holder, last)] = value * item.factor
    return body


def _step(holder, key: str):
    """A dotted path's key as its holder takes it: a list's item by its index ("masses.forces.0.working")."""
    return int(key) if isinstance(holder, list) and key.isdigit() else key


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


def interpolate(a, b, w: float):
    """The contract's rule between two members' leaves a (weight 1 − w) and b (weight w); see the module."""
    if a is None or b is None:
        return None
    if isinstance(a, np.ndarray) and isinstance(b, np.ndarray) and a.shape == b.shape:
        return (1 - w) * a + w * b                      # NaN (null) in either stays NaN (null)
    if _is_number(a) and _is_number(b):
        return (1 - w) * a + w * b
    if isinstance(a, list) and isinstance(b, list) and len(a) == len(b):
        return [interpolate(x, y, w) if texts(x) == texts(y) else (x if w < 0.5 else y) for x, y in zip(a, b)]
    if isinstance(a, dict) and isinstance(b, dict):
        near, far = (a, b) if w < 0.5 else (b, a)
        return {key: (interpolate(a[key], b[key], w) if key in far else value) for key, value in near.items()}
    return a if w < 0.5 else b


def interpolate_family(values: list[float], answers: list, value: float, log: bool):
    """The family's answer at value by the rule (values ascending; outside the range, the end member)."""
    if value <= values[0]:
        return answers[0]
    if value >= values[-1]:
        return answers[-1]
    k = bisect_right(values, value) - 1
    a, b = coordinate(values[k], log), coordinate(values[k + 1], log)
    return interpolate(answers[k], answers[k + 1], (coordinate(value, log) - a) / (b - a))


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


def extend(extent: dict[tuple, list[float]], leaves: dict[tuple, np.ndarray]) -> dict[tuple, list[float]]:
    """Merge [min, max] of every element of each leaf (nulls aside) into ``extent``."""
    for path, leaf in leaves.items():
        if leaf.ndim == 0:
            if not math.isfinite(leaf):
                continue
            low = high = float(leaf)
        else:
            finite = leaf[np.isfinite(leaf)]
            if not finite.size:
                continue
            low, high = float(finite.min()), float(finite.max())
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
            continue
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
    side) it is ROUNDOFF: only what is zero but for round-off (~1e-17) is left out."""
    magnitude: dict[tuple, float] = {}
    for path, (low, high) in extent.items():
        magnitude[path[:-1]] = max(magnitude.get(path[:-1], 0.0), abs(low), abs(high))
    return {path: max(high - low, (SAME_KIND if len(path) > 1 else ROUNDOFF) * magnitude[path[:-1]])
            for path, (low, high) in extent.items()}


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


def curvature(left: "Member", centre: "Member", right: "Member", log: bool) -> LeafValues:
    """The largest |f''| at the centre member over the elements of each leaf whose shape the three members
    share: the second divided difference 2·[(f₊ − f₀)/h₊ − (f₀ − f₋)/h₋]/(h₊ + h₋) (nulls aside)."""
    h_minus = coordinate(centre.value, log) - coordinate(left.value, log)
    h_plus = coordinate(right.value, log) - coordinate(centre.value, log)
    if same_layout(left, centre, right):                # every leaf at once
        f_minus, f0, f_plus = left.flat.vector, centre.flat.vector, right.flat.vector
        with np.errstate(invalid="ignore", over="ignore"):
            bend = np.abs((f_plus - f0) / h_plus - (f0 - f_minus) / h_minus) * (2 / (h_plus + h_minus))
        return LeafValues.of(centre.flat, centre.flat.largest(bend))
    found = LeafValues()
    with np.errstate(invalid="ignore", over="ignore"):
        for path, f0 in centre.leaves.items():
            f_minus, f_plus = left.leaves.get(path), right.leaves.get(path)
            if f_minus is None or f_plus is None or f_minus.shape != f0.shape or f_plus.shape != f0.shape:
                continue
            bend = np.abs((f_plus - f0) / h_plus - (f0 - f_minus) / h_minus) * (2 / (h_plus + h_minus))
            found[path] = float(np.fmax.reduce(bend, axis=None, initial=0.0))
    return found


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

    def largest(self, values: np.ndarray) -> np.ndarray:
        """The largest of each leaf's elements of values (≥ 0), nulls aside; 0 where a leaf has none."""
        return np.fmax(np.fmax.reduceat(values, self.starts), 0.0)


class LeafValues(dict):
    """A number per leaf of a member (path → value), and, when computed over the member's Flat at once, the
    same numbers as an array in its layout's order (``array``, ``layout``; else None)."""

    array: np.ndarray | None = None
    layout: tuple | None = None

    @classmethod
    def of(cls, flat: Flat, values: np.ndarray) -> "LeafValues":
        found = cls(zip(flat.paths, values.tolist()))
        found.array, found.layout = values, flat.layout
        return found


def same_layout(*members: "Member") -> bool:
    flats = [member.flat for member in members]
    return all(flat is not None for flat in flats) and all(flat.layout == flats[0].layout for flat in flats[1:])


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

    def size(self) -> int:
        """Bytes the member holds, roughly (its arrays, twice: as leaves and flat, and a little per leaf): the
        memo's measure."""
        return sum(2 * leaf.nbytes + 100 for leaf in self.leaves.values()) + 1000


MemberBatch = Callable[[list[float], float], list[Member]]


# ---- the family -------------------------------------------------------------------------------------------

@dataclass
class Family:
    """The members computed so far, ascending in value, and the spans of their leaves."""

    log: bool
    finest: float
    members: list[Member] = field(default_factory=list)
    extent: dict[tuple, list[float]] = field(default_factory=dict)
    _curvatures: dict[float, tuple] = field(default_factory=dict)   # value → (neighbours' values, curvature)
    _errors: dict[tuple, dict] = field(default_factory=dict)  # the 4 members' values → absolute error by leaf
    _spans: tuple = (None, None)                    # the span dict last asked, and its arrays by layout

    def add(self, member: Member) -> None:
        extend_member(self.extent, member)
        self.members.insert(bisect_right([m.value for m in self.members], member.value), member)

    @property
    def values(self) -> list[float]:
        return [m.value for m in self.members]

    def width(self, k: int) -> float:
        """The width of interval k (members k and k + 1) in the slider's coordinate."""
        return coordinate(self.members[k + 1].value, self.log) - coordinate(self.members[k].value, self.log)

    def curvature(self, k: int) -> LeafValues | None:
        """|f''| at member k (None at the range's ends and beside a refused member), kept until a neighbour
        changes."""
        if k == 0 or k == len(self.members) - 1 or any(self.members[j].answer is None for j in (k - 1, k, k + 1)):
            return None
        left, centre, right = self.members[k - 1:k + 2]
        kept = self._curvatures.get(centre.value)
        if kept is None or kept[0] != (left.value, right.value):
            kept = ((left.value, right.value), curvature(left, centre, right, self.log))
            self._curvatures[centre.value] = kept
        return kept[1]

    def estimate(self, k: int, span: dict[tuple, float]) -> tuple[float, tuple]:
        """Interval k's estimated interpolation error relative to the span, and the leaf where it is largest:
        h²/8 times the smaller of its two ends' largest |f''| (the one end that has it at the range's ends); 1 (100 %) between an answered and a refused member (the limit is to be found), 0
        between two refused; infinite when neither end has a second difference (no neighbour to take it with)."""
        a, b = self.members[k], self.members[k + 1]
        if a.answer is None or b.answer is None:
            return (0.0 if a.answer is None and b.answer is None else 1.0), ()
        found = self.errors(k)
        if found is None:
            return math.inf, ()
        if found.layout is not None:                    # every leaf at once
            widths_ = self._span_array(span, a.flat)
            with np.errstate(divide="ignore", invalid="ignore"):
                error = np.where(found.array == 0, 0.0, np.where(widths_ > 0, found.array / widths_, 1.0))
            worst = int(np.argmax(error))
            return (float(error[worst]), a.flat.paths[worst]) if error[worst] > 0 else (0.0, ())
        worst, where = 0.0, ()
        for path, largest in found.items():
            width = span.get(path, 0.0)
            error = 0.0 if not largest else largest / width if width > 0 else 1.0
            if error > worst:
                worst, where = error, path
        return worst, where

    def _span_array(self, span: dict[tuple, float], flat: Flat) -> np.ndarray:
        """The span of each leaf of the layout, as an array (kept while the same span dict is asked)."""
        if self._spans[0] is not span:
            self._spans = (span, {})
        kept = self._spans[1].get(flat.layout)
        if kept is None:
            kept = self._spans[1][flat.layout] = np.array([span.get(path, 0.0) for path in flat.paths])
        return kept

    def errors(self, k: int) -> LeafValues | None:
        """Interval k's estimated largest |interpolation − exact| by leaf (absolute), kept until a member
        that enters it changes; None when neither end has a second difference."""
        around = tuple(self.members[j].value if 0 <= j < len(self.members) else None for j in range(k - 1, k + 3))
        if around in self._errors:
            return self._errors[around]
        a, b = self.members[k], self.members[k + 1]
        ends = [c for c in (self.curvature(k), self.curvature(k + 1)) if c is not None]
        found = None
        if ends and same_layout(a, b) and all(c.layout is not None and c.layout == a.flat.layout for c in ends):
            smallest = ends[0].array if len(ends) == 1 else np.minimum(ends[0].array, ends[1].array)
            found = LeafValues.of(a.flat, smallest * (self.width(k) ** 2 / 8))
        elif ends:
            scale = self.width(k) ** 2 / 8
            found = LeafValues()
            for path, leaf in a.leaves.items():
                other = b.leaves.get(path)
                bends = [c[path] for c in ends if path in c]
                if other is None or other.shape != leaf.shape or not bends:
                    continue        # another grid at each end: the nearer member's curve, not interpolated
                found[path] = min(bends) * scale
        self._errors[around] = found
        return found

    def change(self, k: int, span: dict[tuple, float]) -> tuple[float, tuple]:
        """The largest |f(b) − f(a)| / span over interval k's leaves, and where: for an interval too narrow to
        halve, a bound of the interpolation error wherever f is monotone inside it (f and the chord both lie
        between f(a) and f(b)), which a jump's second differences understate (a step of height J reads J/8)."""
        worst, where = 0.0, ()
        if same_layout(self.members[k], self.members[k + 1]):
            a, b = self.members[k].flat, self.members[k + 1].flat
            for path, largest in zip(a.paths, a.largest(np.abs(b.vector - a.vector)).tolist()):
                if span.get(path) and largest / span[path] > worst:
                    worst, where = largest / span[path], path
            return worst, where
        a, b = self.members[k].leaves, self.members[k + 1].leaves
        with np.errstate(invalid="ignore"):
            for path, leaf in a.items():
                other = b.get(path)
                if other is None or other.shape != leaf.shape or not span.get(path):
                    continue
                error = float(np.fmax.reduce(np.abs(other - leaf), axis=None, initial=0.0)) / span[path]
                if error > worst:
                    worst, where = error, path
        return worst, where

    def halvable(self, k: int) -> bool:
        return self.width(k) > self.finest * (1 + 1e-9)


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
    while stage == "full" and not cut:
        span = widths(family.extent)
        scores = sorted(((family.estimate(k, span)[0], k) for k in range(len(family.members) - 1)
                         if family.halvable(k)), reverse=True)
        halve = [k for score, k in scores if score > TOLERANCE / SAFETY][:MAX_MEMBERS - len(family.members)]
        if not halve:
            break
        values = [midpoint(family.members[k].value, family.members[k + 1].value, log) for k in halve]
        computed = members(values, deadline)
        for member in computed:
            family.add(member)
        cut = len(computed) < len(values)
    return _answer(family, lang, cut, started, stage, pack)


def _answer(family: Family, lang: str, cut: bool, started: float, stage: str,
            pack: bool = False) -> tuple[dict, bool]:
    """The answer of the contract, and whether it is partial (cut at the time budget, or a member is)."""
    span = widths(family.extent)
    members = family.members
    estimates = {k: family.estimate(k, span) for k in range(len(members) - 1)}
    answered = {k: found for k, found in estimates.items()
                if members[k].answer is not None and members[k + 1].answer is not None and math.isfinite(found[0])}
    for k, found in answered.items():
        if stage == "full" and not family.halvable(k) and found[0] > TOLERANCE:    # a jump: say how large
            answered[k] = max(found, family.change(k, span))
    error = max((score for score, _ in answered.values()), default=None)
    if pack and error is not None:
        error += PACK_QUANTUM / 2                             # packing moves a value by at most this / span
    texts = interface_texts(lang)
    number = CommaFloat if lang in DECIMAL_COMMA else ReadableFloat
    sentences = []
    if cut:
        sentences.append(texts["family_time_budget"].format(seconds=number(TIME_BUDGET_S), points=len(members)))
    worst: dict[str, tuple[float, int, tuple]] = {}          # the worst interval left above the tolerance, by why
    if stage == "full":
        for k, (score, where) in answered.items():
            if score > TOLERANCE:
                why = ("family_unresolved" if not family.halvable(k) else
                       None if cut else "family_cap_unmet")    # cut short: the budget, said above
                if why and score > worst.get(why, (0.0,))[0]:
                    worst[why] = (score, k, where)
        for k in range(1, len(members) - 1):
            if members[k].answer is None and members[k - 1].answer is not None and members[k + 1].answer is not None:
                worst.setdefault("family_refused_inside", (math.inf, k - 1, ()))
    for why, (score, k, where) in worst.items():
        a, b = members[k].value, members[k + 2 if why == "family_refused_inside" else k + 1].value
        sentences.append(texts[why].format(
            low=number(rounded(a)), high=number(rounded(b)), cap=MAX_MEMBERS, tolerance=number(100 * TOLERANCE),
            error=number(rounded(100 * score)) if math.isfinite(score) else score, quantity=quantity(where)))
    partial = [m.value for m in members if m.partial]
    if partial:
        shown = ", ".join(f"{number(rounded(v)):g}" for v in partial[:8]) + (", …" if len(partial) > 8 else "")
        sentences.append(texts["family_partial_members"].format(count=len(partial), values=shown))
    method = texts[f"family_method_{stage}_{'log' if family.log else 'linear'}"].format(
        start=START_MEMBERS, tolerance=number(100 * TOLERANCE), safety=SAFETY, cap=MAX_MEMBERS)
    answers = [m.answer for m in members]
    if pack:
        common, answers = shared_arrays(answers)
        exponents = quanta(span, family.extent)
        common, *answers = packed([common, *answers], exponents)
    return {
        "values": [rounded(m.value) for m in members],
        **({"shared": common} if pack else {}),
        "answers": answers,
        "errors": [m.error for m in members],
        "interpolation_error": rounded(error) if error is not None else None,
        "tolerance": TOLERANCE,
        "numerics": {"method": method, "stage": stage, "points": len(members), "checked": len(members),
                     "runtime_ms": rounded(1e3 * (time.perf_counter() - started)), "message": " ".join(sentences)},
    }, cut or bool(partial)
