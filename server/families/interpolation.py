"""The slider's coordinate (linear or log), the interpolation rule between members (linear, or Lagrange's
cubic on 4 members) and answers as trees of arrays rounded to the family's significant digits
(server/families/family.py, Interpolation)."""
from __future__ import annotations

import math
from bisect import bisect_right

import numpy as np

from ..core.answer import significant
from .accuracy import SIGNIFICANT

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
    each interval's rule (0 the nearer member, 1 linear, 3 cubic; None: every interval linear)."""
    if value <= values[0]:
        return answers[0]
    if value >= values[-1]:
        return answers[-1]
    k = bisect_right(values, value) - 1
    a, b = coordinate(values[k], log), coordinate(values[k + 1], log)
    x = coordinate(value, log)
    if orders is not None and orders[k] == 0:
        return answers[k] if (x - a) / (b - a) < 0.5 else answers[k + 1]
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
