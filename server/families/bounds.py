"""The estimated error of interpolation and its bound: checked leaves and their spans, the members stacked as
rows, divided differences, the cubic's error, steps and corners (server/families/family.py, Refinement)."""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property
from typing import Callable

import numpy as np

from ..core.answer import Answer
from ..core.interpolation_error import CONCENTRATED, PREDICTORS, divided_differences, irregularities
from ..core.mechanisms import GeometryError
from .accuracy import CUBIC_SAFETY, ROUNDOFF, SAFETY, SAME_KIND, TOLERANCE, UNCHECKED
from .bodies import Fields, pruned
from .interpolation import as_tree, coordinate, stencils, texts

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
