"""The compiled irregularities of a sampled family (server/core/interpolation_error.py) against the numpy
reference they replaced, operation for operation (agreement to rounding: rtol 1e-12, NaN where and only where
the reference has NaN), and against what the measures mean on curves whose answer is known."""
from __future__ import annotations

import math

import numpy as np
import pytest
from test_family import family_body

from server.families import family
from server.api.family_batch import member_batch
from server.core.interpolation_error import CONCENTRATED, PREDICTORS, divided_differences, irregularities


def largest(values: np.ndarray, starts: np.ndarray) -> np.ndarray:
    return np.fmax.reduceat(values, starts, axis=1)


def reference(x: np.ndarray, rows: np.ndarray, starts: np.ndarray, safety: float = family.SAFETY):
    """The numpy ``family.irregular`` as it was before it was compiled (commit 39f7008), each temporary over the
    whole stack."""
    count = len(x)
    h = np.diff(x)
    middle = (x[:-1] + x[1:]) / 2
    intervals = np.arange(count - 1)
    with np.errstate(invalid="ignore", over="ignore", divide="ignore"):
        slope = np.diff(rows, axis=0) / h[:, None]
        least = np.full(slope.shape, np.nan)
        for a, b in PREDICTORS:
            k = intervals[(intervals + min(a, b) >= 0) & (intervals + max(a, b) <= count - 2)]
            i, j = k + a, k + b
            t = ((middle[k] - middle[i]) / (middle[j] - middle[i]))[:, None]
            off = np.abs(slope[k] - (slope[i] + (slope[j] - slope[i]) * t)) * h[k, None]
            least[k] = np.fmin(least[k], off)
        turn = np.diff(slope, axis=0)
        a, b = turn[:-1], turn[1:]
        corners = np.full(slope.shape, np.nan)
        corners[1:-1] = np.where(a * b > 0, h[1:-1, None] * a * b / (a + b), 0.0)
        bend = np.full((count, slope.shape[1]), np.nan)
        bend[1:-1] = np.abs(2 * turn / (h[:-1] + h[1:])[:, None])
        inner = np.fmax(bend[:-1], bend[1:])
        beyond = np.full(slope.shape, np.nan)
        beyond[1:-1] = np.fmax(bend[:-3], bend[3:])
        alone = inner > CONCENTRATED * np.nan_to_num(beyond, nan=np.inf)
        kinked = np.where(alone, safety * inner * (h ** 2 / 8)[:, None], np.nan)
        changes = largest(np.abs(np.diff(rows, axis=0)), starts)
        return changes, largest(least, starts), largest(corners, starts), largest(kinked, starts)


def compiled(x, rows, starts):
    return irregularities(np.ascontiguousarray(x, float), np.ascontiguousarray(rows, float),
                          np.asarray(starts, np.int64), PREDICTORS, CONCENTRATED, float(family.SAFETY))


def random_stack(rng: np.random.Generator):
    """Members unevenly spaced; leaves of smooth curves, steps, corners and noise; NaN in refused rows, in
    elements some members lack, and whole leaves missing from some members."""
    count = int(rng.integers(2, 40))                  # fewer than 4: only the changes are numbers
    x = np.sort(rng.uniform(-3, 5, count))
    x = x[np.concatenate([[True], np.diff(x) > 1e-6])]
    count = len(x)
    sizes = rng.integers(1, 40, int(rng.integers(1, 9)))
    columns = []
    for size in sizes:
        kind = rng.integers(4)
        phase = rng.uniform(0, 6, size)
        if kind == 0:
            leaf = np.sin(x[:, None] * rng.uniform(0.2, 3) + phase)
        elif kind == 1:
            leaf = np.where(x[:, None] > rng.uniform(-3, 5), 1.0, 0.0) + 0.1 * x[:, None] + phase
        elif kind == 2:
            leaf = np.abs(x[:, None] - rng.uniform(-3, 5)) * rng.uniform(0.5, 2) + phase
        else:
            leaf = rng.normal(size=(count, size)) * 10.0 ** rng.uniform(-6, 6)
        columns.append(leaf)
    rows = np.concatenate(columns, axis=1)
    rows[rng.random(rows.shape) < rng.uniform(0, 0.2)] = np.nan
    rows[rng.random(count) < 0.1] = np.nan
    starts = np.cumsum([0, *sizes[:-1]])
    return x, rows, starts


@pytest.mark.parametrize("seed", range(60))
def test_the_compiled_irregularities_agree_with_the_numpy_reference(seed):
    x, rows, starts = random_stack(np.random.default_rng(seed))
    for mine, theirs, name in zip(compiled(x, rows, starts), reference(x, rows, starts),
                                  ("changes", "steps", "corners", "kinked")):
        assert mine.shape == theirs.shape, name
        assert np.array_equal(np.isnan(mine), np.isnan(theirs)), name
        np.testing.assert_allclose(mine, theirs, rtol=1e-12, atol=0, err_msg=name)


def test_a_stack_without_leaves_has_an_interval_by_nothing():
    for got in compiled(np.arange(5.0), np.zeros((5, 0)), np.zeros(0, np.int64)):
        assert got.shape == (4, 0)


def test_a_stack_of_a_real_family_agrees_with_the_reference():
    """An equation-of-motion family's stack over the load (start-up curves whose length moves with the load:
    leaves that only some members hold) through family.irregular as the engine calls it."""
    body = family_body("equation-of-motion", "linear", "load")
    vary = [family.Vary(item["path"], item["factor"]) for item in body["vary"]]
    members = member_batch(body["endpoint"], body["request"], vary, "en")(
        family.spaced(body["min"], body["max"], 17, body["log"]), math.inf)
    stack = family.Stack.of(members, body["log"])
    assert stack.held is not None and stack.rows.shape[1] > 1000      # leaves in several shapes, as in the class
    mine = family.irregular(stack)
    for got, expected in zip((mine.changes, mine.steps, mine.corners, mine.kinked),
                             reference(stack.x, stack.rows, stack.starts)):
        assert np.array_equal(np.isnan(got), np.isnan(expected))
        np.testing.assert_allclose(got, expected, rtol=1e-12, atol=0)


def test_a_parabola_has_no_step_and_its_corner_measure_is_its_curvature_times_h_squared_over_2():
    """f = c x²: every predicted slope is exact (a chord's slope is f′ at its midpoint), so the steps are 0 to
    rounding; on an even spacing a = b = 2c·h, so the corners read h·a·b/(a + b) = c·h² = f″h²/2."""
    x = np.linspace(0.0, 2.0, 17)
    c, h = 3.0, x[1] - x[0]
    changes, steps, corners, kinked = compiled(x, (c * x**2)[:, None], np.array([0]))
    assert np.nanmax(steps) < 1e-12 * c * 4
    np.testing.assert_allclose(corners[1:-1, 0], c * h**2, rtol=1e-9)
    assert np.isnan(corners[[0, -1], 0]).all()
    assert np.isnan(kinked).all()               # an even curvature is nowhere concentrated


def test_a_jump_between_two_members_is_read_as_its_height_whatever_the_spacing():
    """f = x + J·[x > c]: the interval holding c gets u_k = J (its slope J/h + 1 beside neighbours of slope 1,
    times h); the others 0."""
    for members in (9, 17, 33):
        x = np.linspace(0.0, 1.0, members)
        jump = 0.25
        rows = (x + jump * (x > 0.52))[:, None]
        changes, steps, _, _ = compiled(x, rows, np.array([0]))
        k = int(np.searchsorted(x, 0.52)) - 1
        assert steps[k, 0] == pytest.approx(jump, rel=1e-12)
        h = 1 / (members - 1)
        assert changes[k, 0] == pytest.approx(jump + h, rel=1e-12)             # the jump and the line's rise
        np.testing.assert_allclose(np.delete(changes[:, 0], k), h, rtol=1e-9)
        assert np.delete(steps[:, 0], k).max() < 1e-12


def test_a_corner_inside_one_interval_is_flagged_kinked_and_a_leaf_takes_its_largest_element():
    """|x − c| with c inside an interval: slopes −1, 0, 1 over intervals 4, 5, 6 (h = 0.1), so |f″| = 2·1/(2h)
    = 10 at members 5 and 6 and 0 at 4 and 7: interval 5 alone is kinked, SAFETY·h²/8·10 = 0.05; its neighbours
    see member 6 or 5 beyond them (elsewhere only round-off reads as a kink). A second leaf of a smooth line reads no kink, and the leaves stay apart."""
    x = np.linspace(0.0, 1.0, 11)
    rows = np.stack([np.abs(x - 0.55), 2 * x, 0 * x + 1], axis=1)
    changes, steps, corners, kinked = compiled(x, rows, np.array([0, 1]))
    assert kinked[5, 0] == pytest.approx(family.SAFETY * 0.1**2 / 8 * 10, rel=1e-12)
    assert np.nan_to_num(np.delete(kinked[:, 0], 5)).max() < 1e-12     # (round-off "curvature" on a line)
    assert np.isnan(kinked[:, 1]).all()
    assert np.nanmax(steps[:, 1]) < 1e-12 and np.nanmax(corners[:, 1]) == 0.0


def divided_reference(x, rows, starts, order: int, leaves: list[int]):
    """family.divided's numpy arithmetic before it was compiled: every window of order + 1 members, the columns
    of ``leaves`` gathered, the weighted rows summed, |·| reduced per leaf."""
    width = order + 1
    first = np.arange(len(x) - order)
    nodes = x[first[:, None] + np.arange(width)]
    gaps = nodes[:, :, None] - nodes[:, None, :]
    gaps[:, np.arange(width), np.arange(width)] = 1.0
    weights = 1.0 / np.prod(gaps, axis=2)
    ends = np.append(starts[1:], rows.shape[1])
    columns = np.concatenate([np.arange(starts[leaf], ends[leaf]) for leaf in leaves])
    local = np.cumsum([0, *[ends[leaf] - starts[leaf] for leaf in leaves][:-1]])
    with np.errstate(invalid="ignore", over="ignore"):
        total = weights[:, 0, None] * rows[first[:, None], columns]
        for i in range(1, width):
            total += weights[:, i, None] * rows[(first + i)[:, None], columns]
        return weights, np.fmax.reduceat(np.abs(total), local, axis=1)


@pytest.mark.parametrize("seed", range(30))
def test_the_compiled_divided_differences_agree_with_the_numpy_reference(seed):
    rng = np.random.default_rng(100 + seed)
    x, rows, starts = random_stack(rng)
    for order in (2, 4):
        if len(x) <= order:
            continue
        leaves = sorted(rng.choice(len(starts), int(rng.integers(1, len(starts) + 1)), replace=False).tolist())
        weights, expected = divided_reference(x, rows, starts, order, leaves)
        ends = np.append(starts[1:], rows.shape[1])
        got = divided_differences(rows, np.arange(len(x) - order, dtype=np.int64), weights,
                                  np.asarray(starts, np.int64)[leaves], np.asarray(ends, np.int64)[leaves])
        assert np.array_equal(np.isnan(got), np.isnan(expected))
        np.testing.assert_allclose(got, expected, rtol=1e-12, atol=0)


def test_the_divided_differences_of_polynomials_are_their_leading_coefficients():
    """f[x_0 … x_n] of a polynomial of degree n is its leading coefficient on any spacing: 3x² − x + 2 → 3 for
    order 2, −2x⁴ + x³ → −2 (|·| = 2) for order 4."""
    x = np.sort(np.random.default_rng(7).uniform(0.0, 2.0, 12))
    rows = np.stack([3 * x**2 - x + 2, -2 * x**4 + x**3], axis=1)
    for order, column, coefficient in ((2, 0, 3.0), (4, 1, 2.0)):
        weights, _ = divided_reference(x, rows, np.array([0, 1]), order, [column])
        got = divided_differences(rows, np.arange(len(x) - order, dtype=np.int64), weights,
                                  np.array([column], np.int64), np.array([column + 1], np.int64))
        np.testing.assert_allclose(got[:, 0], coefficient, rtol=1e-7)
