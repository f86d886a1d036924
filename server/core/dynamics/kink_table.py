"""Functions of the crank angle between the kinks as piecewise Chebyshev interpolants: a general mechanism's
J(φ), J′(φ), M_useful(φ), S(φ) (general_machine.GeneralMachine.smooth_table) and its dry-friction moment M_T(φ)
(GeneralMachine.dry_table).

Evaluating a general mechanism costs a composition of its groups (and for M_T a friction solve) per call, and the
equation of motion asks for them on thousands of nodes in twenty-odd calls per answer (the steady cycle's nested
levels, the start-up, the flywheel's cycle).  Between two consecutive kinks (Machine.find_kinks: the loads'
reversals and diagram points, the rough pairs' reversals, the normal forces' zeros) each function is analytic, so
its interpolant in the Chebyshev points of the second kind x_j = cos(jπ/n) converges geometrically (Trefethen,
Approximation Theory and Approximation Practice, Thm 8.2); it is evaluated from its Chebyshev coefficients (the
DCT-I of the values) by Clenshaw's recurrence in compiled code, while building in the barycentric form with
weights (−1)^j, halved at the ends (Berrut & Trefethen 2004, (5.4)).

Each segment's interval is pulled KINK_SIDE inside at a kink, where the integrator evaluates its sided nodes.
The degree doubles from orders[0] (the points are nested: each doubling evaluates the n new points only) until,
for every function, the interpolant of half the degree (through every other point) reproduces it at the other
points to ``tolerance`` of its largest magnitude over the turn; that measured error of the coarser interpolant
(at the midpoints of its nodes in θ = arccos x, where its error peaks) is the segment's error estimate,
conservative for the finer one kept (geometric convergence: its error is smaller by the factor of convergence
again).  A segment with a value that is not finite (self-locking, the solve's work bound) or not accepted at the
last degree (a corner the kinks did not name, a steep stretch near a dead position or self-locking) is not
interpolated: its angles are evaluated directly, as are angles within KINK_SIDE of a kink; the kinks themselves
are evaluated once when the table is built and kept.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Callable

import numpy as np
from numba import njit

from .integrator import KINK_SIDE
from .machine import KINK_MERGE

TURN = 2 * np.pi


@dataclass(frozen=True)
class KinkTable:
    """m functions on [0, 2π): ``edges`` of the segments (kinks, 0 and 2π), which edges are kinks (``sided``),
    per segment the interval [low, high] of its nodes and the Chebyshev coefficients of each function's
    interpolant in t = (2φ − low − high)/(high − low) (None: the segment is evaluated directly), and the values at
    the kinks given (``kinks``, ``kink_values``: (m, K))."""

    edges: np.ndarray
    sided: np.ndarray
    low: np.ndarray
    high: np.ndarray
    coefficients: tuple[tuple[np.ndarray, ...] | None, ...]
    kinks: np.ndarray
    kink_values: np.ndarray
    error: np.ndarray            # per function: the largest error estimate of an interpolated segment
    scale: np.ndarray            # per function: its largest magnitude over the nodes
    evaluated: int               # angles evaluated to build it
    flat: np.ndarray = field(init=False, repr=False)     # the coefficients one after another, for ``evaluate``:
    start: np.ndarray = field(init=False, repr=False)    # (segments, m) where each interpolant's begin, and
    degree: np.ndarray = field(init=False, repr=False)   # its degree (−1: evaluated directly)

    def __post_init__(self):
        count = self.kink_values.shape[0]
        degree = np.array([[-1] * count if c is None else [len(f) - 1 for f in c] for c in self.coefficients],
                          np.int64).reshape(len(self.coefficients), count)
        start = np.concatenate([[0], np.cumsum(np.maximum(degree, -1).ravel() + 1)[:-1]]).reshape(degree.shape)
        flat = np.concatenate([f for c in self.coefficients if c is not None for f in c] or [np.zeros(0)])
        object.__setattr__(self, "degree", degree)
        object.__setattr__(self, "start", start.astype(np.int64))
        object.__setattr__(self, "flat", flat)

    def at(self, phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The functions at ``phi`` ((m, N): from the interpolants by Clenshaw's recurrence, compiled:
        ``evaluate``; at a kink given, its kept values), and where they are to be evaluated directly (those
        values NaN): on a segment not interpolated, and within KINK_SIDE / 2 of a kink but not on it (the
        integrator's sided nodes, KINK_SIDE inside, are interpolated: they are the segments' ends)."""
        phi = np.asarray(phi, float)
        out = evaluate(phi.ravel(), self.edges, self.edges[self.sided], self.kinks, self.kink_values, self.low,
                       self.high, self.flat, self.start, self.degree, 0.5 * KINK_SIDE)
        out = out.reshape((out.shape[0],) + phi.shape)
        return out, np.isnan(out).any(axis=0)


@njit(cache=True)
def evaluate(phi, edges, inner, kinks, kink_values, low, high, flat, start, degree, near):
    """KinkTable.at, compiled: (functions, N) from each angle's segment by Clenshaw's recurrence; NaN within
    ``near`` of an inner kink (either side, around the turn) off the kink itself and on a segment without
    interpolants; a given kink's kept values on the kink."""
    count = degree.shape[1]
    last = low.size - 1
    out = np.empty((count, phi.size))
    for i in range(phi.size):
        psi = phi[i] % TURN
        segment = min(max(np.searchsorted(edges, psi, side="right") - 1, 0), last)
        if inner.size:
            index = np.searchsorted(inner, psi)
            for side in (index - 1 if index > 0 else inner.size - 1, index % inner.size):
                gap = abs(psi - inner[side])
                if min(gap, TURN - gap) < near:
                    segment = -1
        if segment < 0 or degree[segment, 0] < 0:
            out[:, i] = np.nan
        else:
            t = (2.0 * psi - (low[segment] + high[segment])) / (high[segment] - low[segment])
            for f in range(count):
                out[f, i] = clenshaw(t, flat, start[segment, f], degree[segment, f])
        if kinks.size:
            place = min(np.searchsorted(kinks, phi[i]), kinks.size - 1)
            if kinks[place] == phi[i]:
                out[:, i] = kink_values[:, place]
    return out


@njit(cache=True)
def clenshaw(t, flat, first, degree):
    """Σ_k c_k T_k(t), c = flat[first:first + degree + 1], by Clenshaw's recurrence (Trefethen, ATAP, ch. 3)."""
    b1 = 0.0
    b2 = 0.0
    for j in range(degree, 0, -1):
        b1, b2 = 2.0 * t * b1 - b2 + flat[first + j], b1
    return t * b1 - b2 + flat[first]


def chebyshev_coefficients(values: np.ndarray) -> np.ndarray:
    """c_k of the interpolants through each row of ``values`` at x_j = cos(jπ/n): the DCT-I of the values (by
    the FFT of their even extension; Trefethen, ATAP, ch. 3)."""
    n = values.shape[-1] - 1
    c = np.fft.rfft(np.concatenate([values, values[..., -2:0:-1]], axis=-1), axis=-1).real[..., :n + 1] / n
    c[..., 0] *= 0.5
    c[..., n] *= 0.5
    return c


def chop(c: np.ndarray, allowed: float) -> tuple[np.ndarray, float]:
    """The coefficients without the longest tail whose sum of magnitudes is at most ``allowed`` (what dropping
    it can change at any t in [−1, 1], as |T_k| ≤ 1), and that sum: a function that converges fast keeps few
    terms (Clenshaw's recurrence costs one step a term)."""
    tail = np.cumsum(np.abs(c[::-1]))[::-1]              # tail[k] = Σ_{j≥k} |c_j|
    keep = max(int(np.argmax(np.append(tail, 0.0) <= allowed)), 1)   # the first k whose tail may go (c₀ stays)
    return c[:keep], float(tail[keep]) if keep < c.size else 0.0


def warm_up() -> float:
    """Compile (or load from the disk cache) ``evaluate`` and its ``clenshaw``; seconds."""
    started = time.perf_counter()
    evaluate(np.zeros(1), np.array([0.0, 1.0, TURN]), np.array([1.0]), np.array([1.0]), np.zeros((1, 1)),
             np.zeros(2), np.ones(2), np.ones(4), np.array([[0], [2]], np.int64), np.ones((2, 1), np.int64), 0.1)
    return time.perf_counter() - started


def nodes(n: int) -> np.ndarray:
    """x_j = cos(jπ/n), j = 0…n."""
    return np.cos(np.pi * np.arange(n + 1) / n)


def barycentric(values: np.ndarray, low: float, high: float, phi: np.ndarray) -> np.ndarray:
    """The interpolants through the rows of ``values`` ((m, n + 1)) at the Chebyshev points of [low, high], at
    ``phi``: (m, N)."""
    n = values.shape[1] - 1
    x = nodes(n)
    weights = (-1.0) ** np.arange(n + 1)
    weights[0] *= 0.5
    weights[-1] *= 0.5
    t = (2 * phi - (low + high)) / (high - low) if high > low else np.zeros(phi.shape)
    difference = t[:, None] - x[None, :]
    exact = difference == 0
    terms = weights / np.where(exact, 1.0, difference)
    out = (values @ terms.T) / terms.sum(axis=1)
    hit = exact.any(axis=1)
    if hit.any():
        out[:, hit] = values[:, np.argmax(exact[hit], axis=1)]
    return out


def build(values: Callable[[np.ndarray], np.ndarray], kinks: np.ndarray, tolerance: float,
          orders: tuple[int, ...]) -> KinkTable:
    """The table of the functions ``values(phi)`` ((m, N), NaN where one does not exist) between ``kinks`` (rad,
    any turn: taken modulo 2π for the segments), each segment's degree doubled through ``orders`` until every
    function's estimate is below ``tolerance`` of its scale."""
    kinks = np.asarray(kinks, float)
    inner = np.sort(np.mod(kinks, TURN))
    inner = np.where(inner >= TURN - KINK_MERGE, 0.0, inner)          # a kink of another turn, the same angle
    inner = np.unique(inner)
    inner = inner[np.append(True, np.diff(inner) > KINK_MERGE)] if inner.size else inner
    sided_zero = bool(inner.size and inner[0] <= KINK_MERGE)
    inner = inner[inner > KINK_MERGE]
    edges = np.concatenate([[0.0], inner, [TURN]])
    sided = np.concatenate([[sided_zero], np.ones(inner.size, bool), [sided_zero]])
    low = edges[:-1] + np.where(sided[:-1], KINK_SIDE, 0.0)
    high = edges[1:] - np.where(sided[1:], KINK_SIDE, 0.0)
    count = low.size
    n = orders[0]
    angles = (0.5 * (low + high)[:, None] + 0.5 * (high - low)[:, None] * nodes(n)[None, :]).ravel()
    given = np.unique(kinks)
    both = values(np.concatenate([angles, given]))       # the kinks too: the integrator asks for them
    first, kink_values = both[:, :angles.size], both[:, angles.size:]
    functions = both.shape[0]
    rows: list[np.ndarray | None] = [first[:, k * (n + 1):(k + 1) * (n + 1)] for k in range(count)]
    evaluated = both.shape[1]
    scale = np.nanmax(np.abs(np.where(np.isfinite(first), first, np.nan)), axis=1, initial=0.0)
    open_ = [k for k in range(count) if np.isfinite(rows[k]).all()]
    done: dict[int, np.ndarray] = {}
    for level, n in enumerate(orders):
        if level and open_:                               # the points of degree n not among those of n / 2
            new = nodes(n)[1::2]
            low_o, high_o = low[open_], high[open_]
            found = values((0.5 * (low_o + high_o)[:, None] + 0.5 * (high_o - low_o)[:, None] * new[None, :]).ravel())
            found = found.reshape(functions, len(open_), new.size)
            evaluated += found.shape[1] * found.shape[2]
            scale = np.maximum(scale, np.nanmax(np.abs(np.where(np.isfinite(found), found, np.nan)), axis=(1, 2),
                                                initial=0.0))
        still = []
        for row, k in enumerate(open_):
            if level:
                if not np.isfinite(found[:, row]).all():    # a value that does not exist inside: evaluated directly
                    continue
                merged = np.empty((functions, n + 1))
                merged[:, 0::2], merged[:, 1::2] = rows[k], found[:, row]
                rows[k] = merged
            coarse, odd = rows[k][:, 0::2], rows[k][:, 1::2]   # degree n / 2, and the points it does not have
            x = 0.5 * (low[k] + high[k]) + 0.5 * (high[k] - low[k]) * nodes(n)[1::2]
            estimate = np.max(np.abs(barycentric(coarse, low[k], high[k], x) - odd), axis=1)
            if (estimate <= tolerance * scale).all():
                done[k] = estimate
            else:
                still.append(k)
        open_ = still
        if not open_:
            break
    coefficients, chopped = [], {}
    for k in range(count):                                 # else not finite, or not accepted at the last degree
        if k in done:
            allowed = np.minimum(0.1 * tolerance * scale, tolerance * scale - done[k])   # the estimate stays in
            kept, dropped = zip(*(chop(c, a) for c, a in zip(chebyshev_coefficients(rows[k]), allowed)))
            coefficients.append(kept)
            chopped[k] = done[k] + np.array(dropped)
        else:
            coefficients.append(None)
    error = np.max(np.array(list(chopped.values())), axis=0) if chopped else np.zeros(functions)
    return KinkTable(edges, sided, low, high, tuple(coefficients), given, kink_values, error, scale, evaluated)
