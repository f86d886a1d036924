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
    null in either                         → null,
    anything else (strings, booleans, arrays of different lengths, a key in one member only)
                                           → the nearer member's leaf (a when w < 1/2, else b).
A refused member's answer is null, so the values between it and its neighbours interpolate to null.

Refinement. Each interval's midpoint is computed exactly and compared with the interpolation there; the
interval is halved (the midpoint becomes a member) while the largest |interpolation − exact| / span of a
checked leaf exceeds TOLERANCE (spans: see ``spans``), worst intervals first, at most MAX_MEMBERS members.
Checked leaves are floats and arrays of floats outside ``numerics``, ``study`` and ``warnings`` (whole numbers
such as step counters, strings and booleans are not plotted quantities) whose shape is the same at both ends
and at the midpoint. An interval between an answered and a refused value is halved too (the limit is found),
and so is one whose midpoint is refused. No interval narrower than FINEST_FRACTION of the range is halved:
no slider resolves it, and an answer that jumps (an efficiency that is 0 at zero load and 0.97 just above)
or bends at a corner too steep to resolve is named in the message instead of taking every member. Where the cap or a jump leaves an interval above the
tolerance, numerics.message says between which values and for which quantity.

The comparison uses the members as sent: every float rounded to SIGNIFICANT digits (NaN and ±inf → null), so
the reported interpolation error includes the rounding the page sees.
"""
from __future__ import annotations

import copy
import math
import time
from bisect import bisect_right
from dataclasses import dataclass, field
from typing import Callable

import numpy as np
from pydantic import ValidationError

from ..core.mechanisms import GeometryError
from .serialise import Answer
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
UNCHECKED = frozenset({"numerics", "study", "warnings", "directions"})
COARSE_TO_FINE = (0, 8, 4, 2, 6, 1, 3, 5, 7)    # the order of the first 9 members


@dataclass(frozen=True)
class Vary:
    """One dotted path of the request set to value × factor (factor converts the slider's units to SI)."""

    path: str
    factor: float


def member_body(request: dict, vary: list[Vary], value: float) -> dict:
    """The request with each varied path set to value × factor (a deep copy: the request is shared)."""
    body = copy.deepcopy(request)
    for item in vary:
        *keys, last = item.path.split(".")
        holder = body
        for key in keys:
            holder = holder[key]
        holder[last] = value * item.factor
    return body


def shared(body):
    """The family body as the response cache keys it: the varied paths' current values left out (every member
    sets them), so that students whose other values agree share one family wherever their slider stands.
    A body that is not a well-formed family request is returned as it is (validation refuses it later)."""
    try:
        varied = member_body(body["request"], [Vary(item["path"], 0.0) for item in body["vary"]], 0.0)
    except (KeyError, TypeError, AttributeError, IndexError):
        return body
    return body | {"request": varied}


def path_exists(request: dict, path: str) -> bool:
    """Whether the dotted path names a number (not a boolean) in the request."""
    holder = request
    for key in path.split("."):
        if not isinstance(holder, dict) or key not in holder:
            return False
        holder = holder[key]
    return isinstance(holder, (int, float)) and not isinstance(holder, bool)


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


def interpolate(a, b, w: float):
    """The contract's rule between two members' leaves a (weight 1 − w) and b (weight w); see the module."""
    if a is None or b is None:
        return None
    if isinstance(a, np.ndarray) and isinstance(b, np.ndarray) and a.shape == b.shape:
        return (1 - w) * a + w * b                      # NaN (null) in either stays NaN (null)
    if _is_number(a) and _is_number(b):
        return (1 - w) * a + w * b
    if isinstance(a, list) and isinstance(b, list) and len(a) == len(b):
        return [interpolate(x, y, w) for x, y in zip(a, b)]
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
    ``sent``) each float rounded to SIGNIFICANT digits as sent. Arrays of whole numbers alone stay lists
    (interpolated element by element all the same)."""
    if isinstance(answer, dict):
        return {key: as_tree(value, sent) for key, value in answer.items()}
    if isinstance(answer, np.ndarray) and answer.dtype.kind != "f":
        return answer.tolist()
    if isinstance(answer, (list, tuple, np.ndarray)):
        array = answer.astype(float) if isinstance(answer, np.ndarray) else _numeric_array(answer)
        if array is None:
            return [as_tree(x, sent) for x in answer]
        return rounded_array(array) if sent else np.where(np.isfinite(array), array, np.nan)
    if isinstance(answer, (float, np.floating)):
        return rounded(float(answer)) if sent else float(answer)
    return answer


NUMBERS = frozenset({float, int, type(None)})


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
    """Each element to SIGNIFICANT digits, non-finite → NaN (null). Scaling by an exact power of ten
    (multiply by 10^k, 0 ≤ k ≤ 22; divide by 10^−k, −22 ≤ k < 0) keeps the shortest decimal form of each
    result; the few elements further from 1 (below 1e-18 or above 1e26) are formatted one by one."""
    x = np.where(np.isfinite(x), x, np.nan)
    magnitude = np.abs(x)
    with np.errstate(divide="ignore", invalid="ignore"):
        exponent = np.floor(np.log10(np.where(magnitude > 0, magnitude, 1.0)))
    k = SIGNIFICANT - 1 - exponent
    scale = 10.0 ** np.clip(np.abs(k), 0, 22)
    with np.errstate(over="ignore", invalid="ignore"):
        result = np.where(k >= 0, np.round(x * scale) / scale, np.round(x / scale) * scale)
    far = np.abs(k) > 22
    if far.any():
        result[far] = [float(f"{value:.{SIGNIFICANT}g}") for value in x[far]]
    return result


# ---- spans and the error of interpolation -----------------------------------------------------------------

def checked_leaves(tree, path: tuple = ()):
    """(path, float or float array) of each plotted quantity: floats outside numerics, study and warnings."""
    if isinstance(tree, dict):
        for key, value in tree.items():
            if key not in UNCHECKED:
                yield from checked_leaves(value, (*path, key))
    elif isinstance(tree, list):
        for index, value in enumerate(tree):
            yield from checked_leaves(value, (*path, index))
    elif isinstance(tree, np.ndarray) or isinstance(tree, float):
        yield path, tree


def ranges(answer, into: dict[tuple, list[float]] | None = None) -> dict[tuple, list[float]]:
    """[min, max] of every element of each checked leaf of the answer (nulls aside), merged into ``into``."""
    into = {} if into is None else into
    for path, leaf in checked_leaves(answer):
        finite = leaf[np.isfinite(leaf)] if isinstance(leaf, np.ndarray) else np.asarray([leaf])
        if finite.size:
            low, high = float(finite.min()), float(finite.max())
            known = into.setdefault(path, [low, high])
            known[0], known[1] = min(known[0], low), max(known[1], high)
    return into


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
        try:
            tree = tree[key]
        except (KeyError, IndexError, TypeError):
            return None
    return tree


def differences(approx, exact, ends: tuple = ()) -> dict[tuple, float]:
    """max |approx − exact| of each checked leaf of exact. Nulls on either side are not compared, nor a leaf
    whose shape differs between the interval's ends (``ends``) or from exact: the page draws the nearer
    member's curve there (a steady cycle refined to more steps, a start-up that settles a cycle sooner), a
    curve on its own grid, not an interpolation."""
    found = {}
    for path, leaf in checked_leaves(exact):
        guess = _leaf(approx, path)
        if guess is None or not isinstance(guess, (float, np.ndarray)) or any(
                np.shape(x) != np.shape(leaf) for x in (guess, *(_leaf(end, path) for end in ends))):
            continue
        with np.errstate(invalid="ignore"):
            difference = np.abs(np.asarray(guess, float) - np.asarray(leaf, float))
        found[path] = float(np.max(difference, initial=0.0, where=np.isfinite(difference)))
    return found


def deviation(found: dict[tuple, float], span: dict[tuple, float]) -> tuple[float, tuple]:
    """The largest difference / span over the leaves, and that leaf's path; a difference where the span is
    zero (out of nothing) counts 100 %."""
    worst, where = 0.0, ()
    for path, difference in found.items():
        width = span.get(path, 0.0)
        error = 0.0 if not difference else difference / width if width > 0 else 1.0
        if error > worst:
            worst, where = error, path
    return worst, where


# ---- members that are refused or partial ------------------------------------------------------------------

def refusal(error: Exception) -> dict:
    """{code, message} of a member refused as HTTP would refuse it (the 422's detail)."""
    if isinstance(error, GeometryError):
        return {"code": error.code, "message": f"{error.field}: {error.reason}"}
    first = error.errors()[0]
    where = ".".join(str(part) for part in first["loc"])
    return {"code": first["type"], "message": f"{where}: {first['msg']}" if where else first["msg"]}


# ---- the family -------------------------------------------------------------------------------------------

@dataclass
class _Check:
    """An interval's midpoint, computed exactly, and how far the interpolation is from it."""

    value: float
    answer: dict | None
    error: dict | None
    partial: bool
    differences: dict | None = None     # per checked leaf, against the interpolation (the ends do not change)
    deviation: float = 0.0
    where: tuple = ()


@dataclass
class Family:
    """The members computed so far, ascending, and the checked midpoints of the intervals between them."""

    log: bool
    values: list[float] = field(default_factory=list)
    answers: list = field(default_factory=list)
    errors: list = field(default_factory=list)
    partial: list[bool] = field(default_factory=list)
    checks: dict[tuple[float, float], _Check] = field(default_factory=dict)
    checked: int = 0                    # midpoints computed, those that became members included
    extent: dict[tuple, list[float]] = field(default_factory=dict)     # ranges of the members' leaves

    def add(self, value: float, answer, error, partial: bool) -> None:
        if answer is not None:
            ranges(answer, self.extent)
        k = bisect_right(self.values, value)
        for column, item in ((self.values, value), (self.answers, answer), (self.errors, error),
                             (self.partial, partial)):
            column.insert(k, item)

    def intervals(self) -> list[tuple[float, float]]:
        return list(zip(self.values[:-1], self.values[1:]))

    def width(self, interval: tuple[float, float]) -> float:
        return coordinate(interval[1], self.log) - coordinate(interval[0], self.log)

    def score(self, interval: tuple[float, float], span: dict) -> float:
        """How much an interval asks to be halved: its relative interpolation error; 1 (100 %) for an
        answered–refused interval (the limit between them is to be found); infinite for a refused midpoint."""
        check = self.checks[interval]
        k = self.values.index(interval[0])
        ends = (self.answers[k], self.answers[k + 1])
        if ends[0] is None and ends[1] is None:
            return 0.0
        if ends[0] is None or ends[1] is None:
            return 1.0
        if check.answer is None:
            return math.inf
        if check.differences is None:
            approx = interpolate_family(self.values, self.answers, check.value, self.log)
            check.differences = differences(approx, check.answer, ends)
        check.deviation, check.where = deviation(check.differences, span)
        return check.deviation


def build(member: Callable[[float], Answer], low: float, high: float, log: bool, lang: str = "en") -> tuple[dict, bool]:
    """The family's answer (see the module) and whether it is partial: member(value) is the endpoint's
    answer at value; it raises pydantic's ValidationError or GeometryError where the endpoint refuses it."""
    started = time.perf_counter()
    deadline = started + TIME_BUDGET_S
    family = Family(log)
    finest = (coordinate(high, log) - coordinate(low, log)) * FINEST_FRACTION
    cut = False

    def computed(value: float) -> tuple:
        try:
            answer = member(value)
        except (ValidationError, GeometryError) as error:
            return None, refusal(error), False
        return as_tree(answer.payload), None, answer.partial

    first = spaced(low, high, START_MEMBERS, log)
    for index in COARSE_TO_FINE:
        if len(family.values) >= 2 and time.perf_counter() > deadline:       # min and max always
            cut = True
            break
        family.add(first[index], *computed(first[index]))
    while not cut:
        for interval in family.intervals():
            if interval in family.checks:
                continue
            if time.perf_counter() > deadline:
                cut = True
                break
            value = midpoint(*interval, log)
            family.checks[interval] = _Check(value, *computed(value))
            family.checked += 1
        span = widths(family.extent)
        scores = sorted(((family.score(i, span), i) for i in family.intervals()
                         if i in family.checks and family.width(i) > finest * (1 + 1e-9)),
                        key=lambda item: item[0], reverse=True)
        halve = [i for score, i in scores if score > TOLERANCE][:MAX_MEMBERS - len(family.values)]
        if not halve:
            break
        for interval in halve:
            check = family.checks.pop(interval)
            family.add(check.value, check.answer, check.error, check.partial)
    return _answer(family, lang, cut, started, finest)


def _answer(family: Family, lang: str, cut: bool, started: float, finest: float) -> tuple[dict, bool]:
    """The answer of the contract, and whether it is partial (cut at the time budget, or a member is)."""
    span = widths(family.extent)
    scores = {i: family.score(i, span) for i in family.intervals() if i in family.checks}
    answered = {i: score for i, score in scores.items() if family.answers[family.values.index(i[0])] is not None
                and family.answers[family.values.index(i[1])] is not None}       # both ends answered
    error = max((score for i, score in answered.items() if family.checks[i].answer is not None), default=None)
    texts = interface_texts(lang)
    number = CommaFloat if lang in DECIMAL_COMMA else ReadableFloat
    sentences = []
    if cut:
        sentences.append(texts["family_time_budget"].format(seconds=number(TIME_BUDGET_S), points=len(family.values)))
    worst: dict[str, tuple[float, tuple]] = {}          # the worst interval left above the tolerance, by why
    for interval, score in answered.items():
        if score > TOLERANCE:
            why = ("family_refused_inside" if family.checks[interval].answer is None else
                   "family_unresolved" if family.width(interval) <= finest * (1 + 1e-9) else
                   None if cut else "family_cap_unmet")    # cut short: the budget, said above
            if why and score > worst.get(why, (0.0,))[0]:
                worst[why] = (score, interval)
    for why, (score, (a, b)) in worst.items():
        where = family.checks[(a, b)].where
        sentences.append(texts[why].format(
            low=number(rounded(a)), high=number(rounded(b)), cap=MAX_MEMBERS, tolerance=number(100 * TOLERANCE),
            error=number(rounded(100 * score)) if math.isfinite(score) else score,
            quantity=".".join(str(part) for part in where)))
    partial = [v for v, p in zip(family.values, family.partial) if p]
    if partial:
        shown = ", ".join(f"{number(rounded(v)):g}" for v in partial[:8]) + (", …" if len(partial) > 8 else "")
        sentences.append(texts["family_partial_members"].format(count=len(partial), values=shown))
    method = texts["family_method_log" if family.log else "family_method_linear"].format(
        start=START_MEMBERS, tolerance=number(100 * TOLERANCE), cap=MAX_MEMBERS)
    return {
        "values": [rounded(v) for v in family.values],
        "answers": family.answers,
        "errors": family.errors,
        "interpolation_error": rounded(error) if error is not None else None,
        "tolerance": TOLERANCE,
        "numerics": {"method": method, "points": len(family.values), "checked": family.checked,
                     "runtime_ms": rounded(1e3 * (time.perf_counter() - started)), "message": " ".join(sentences)},
    }, cut or bool(partial) or any(check.partial for check in family.checks.values())
