"""A family's answers packed for sending: the arrays every member shares sent once, arrays as integer steps of
a quantum (server/families/family.py, Packed)."""
from __future__ import annotations

import math

import numpy as np

from .accuracy import PACK_QUANTUM, UNCHECKED


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
