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
Nearest intervals (``orders``[k] = 0, a coarse family's interval whose bound exceeds the tolerance): the
nearer member's answer whole (a when w < 1/2, else b), a true answer of a nearby value; the error given for
such an interval is the change across it, |f(b) − f(a)| / span (what the nearer member may be off by wherever
f is monotone inside).
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

Stages. ``coarse`` answers the 9 start members at once, unrefined: an interval whose bound is within the
tolerance is interpolated (its estimate the error given), every other one drawn from its nearer member (``lean``, while previews queue on a busy server: the first LEAN_MEMBERS of them in the
order above, every other one of the 9); ``full`` (the default) refines. The members are the same values in both, so a full
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
import time
from bisect import bisect_right
from dataclasses import dataclass, field

import numpy as np

from ..lessons.numbers import DECIMAL_COMMA, CommaFloat, ReadableFloat
from ..lessons.scenes import interface_texts
# the engine's parts, and the names its users read here (family.coordinate, family.PACK_QUANTUM, ...)
from .accuracy import (COARSE_TO_FINE, CUBIC_SAFETY, FIELD, FINEST_FRACTION, LEAN_MEMBERS, MAX_FIELDS, MAX_MEMBERS,
                       PACK_QUANTUM, PREVIEW, PREVIEW_FRACTION, SAFETY, SIGNIFICANT, STAGES, START_MEMBERS, TOLERANCE)
from .bodies import Vary, field_trie, member_body, path_exists, pruned, shared
from .packing import merged, packed, quanta, shared_arrays, unpacked
from .interpolation import (as_tree, coordinate, from_coordinate, interpolate, interpolate_family, midpoint, rounded,
                            rounded_array, spaced, stencils)
from .bounds import (Assessment, Member, MemberBatch, Stack, _leaf, _one_layout, assess, checked_leaves, divided,
                     extend_member, flatten, irregular, quantity, relative, spans, widths)

TIME_BUDGET_S = float(os.environ.get("MDL_FAMILY_BUDGET_S", "5"))   # wall-clock bound of one family (each
                                # member keeps its endpoint's own budget); a slow or shared host may give more


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
          stage: str = "full", pack: bool = False, lean: bool = False) -> tuple[dict, bool]:
    """The family's answer (see the module) and whether it is partial. members(values, deadline) gives the
    members at values, in order, stopping early (a shorter list) once the deadline has passed. ``pack``:
    sent packed (see the module: shared arrays once, arrays as integer steps). ``lean`` (the coarse stage
    only): LEAN_MEMBERS start members instead of START_MEMBERS, every other one of them (see Stages)."""
    started = time.perf_counter()
    deadline = started + TIME_BUDGET_S
    family = Family(log, (coordinate(high, log) - coordinate(low, log)) * FINEST_FRACTION)
    first = spaced(low, high, START_MEMBERS, log)
    start = LEAN_MEMBERS if lean and stage == "coarse" else START_MEMBERS
    order = [first[index] for index in COARSE_TO_FINE[:start]]
    for member in members(order[:2], math.inf) + members(order[2:], deadline):   # min and max always
        family.add(member)
    cut = len(family.members) < start
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
    return _answer(family, assessed, lang, cut, started, stage, pack, start)


def _answer(family: Family, assessed: tuple, lang: str, cut: bool, started: float, stage: str,
            pack: bool = False, start: int = START_MEMBERS) -> tuple[dict, bool]:
    """The answer of the contract, and whether it is partial (cut at the time budget, or a member is)."""
    stack, span, assessment = assessed
    members = family.members
    orders, scores, where = list(assessment.orders), list(assessment.scores), list(assessment.where)
    if stage == "coarse":           # an interval not shown within the tolerance: the nearer member, a true answer
        for k in range(len(members) - 1):
            if members[k].answer is not None and members[k + 1].answer is not None and not (
                    assessment.bounds[k] <= TOLERANCE):
                orders[k] = 0
                scores[k], where[k] = change(stack, span, k)
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
        start=start, tolerance=number(100 * TOLERANCE), safety=SAFETY, cap=MAX_MEMBERS)
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
