"""brackets.refine_zeros against zeros known exactly: a simple zero, zeros of odd multiplicity (a relative
velocity crossing zero with zero slope at a symmetric dead point), a jump through zero (a load switching with the
sense of motion), an exact zero at a point or an end, a bracket with no value inside (NaN: no equilibrium).
Each zero is found to a few doubles (4 ulps of the angle: what the kinks' merge, 1e-12 rad, relies on), in
at most log(width / ulp) / log(sections − 2) + 2 passes, whatever kind of zero it is: a bound on the work,
no clock."""
from __future__ import annotations

import math

import numpy as np
import pytest

from server.core.dynamics.brackets import SECTIONS, own_rows, refine_zeros, ulps

ROOT = 1.2345678
WIDTH = 2 * np.pi / 4096            # a scan's interval (machine.KINK_SCAN per turn)
SHAPES = {
    "simple": lambda x: 3 * np.sin(x - ROOT) + (x - ROOT) ** 2,
    "triple": lambda x: (x - ROOT) ** 3,
    "quintic": lambda x: -((x - ROOT) ** 5),
    "jump": lambda x: np.where(x < ROOT, -1.0, 2.0),
}


def counted(shape):
    """f as refine_zeros calls it (brackets' indices, angles (brackets, points)), counting its calls."""
    calls = []

    def f(index, at):
        assert at.shape[0] == index.size
        calls.append(at.shape)
        return SHAPES[shape](at)
    return f, calls


def passes_bound(width: float, sections: int) -> int:
    return math.ceil(math.log(width / (ulps(np.array(ROOT), np.array(ROOT)) / 4)) / math.log(sections - 2)) + 2


@pytest.mark.parametrize("sections", [8, SECTIONS])
@pytest.mark.parametrize("shape", SHAPES)
def test_every_kind_of_zero_to_a_few_doubles_within_the_bound_on_passes(shape, sections):
    f, calls = counted(shape)
    low, high = np.array([ROOT - 0.3 * WIDTH]), np.array([ROOT + 0.7 * WIDTH])
    found = refine_zeros(f, low, high, SHAPES[shape](low), SHAPES[shape](high), sections=sections)
    assert abs(found[0] - ROOT) <= ulps(np.array(ROOT), np.array(ROOT))
    assert len(calls) <= passes_bound(WIDTH, sections)
    assert all(points == sections for _, points in calls)
    if shape == "simple":
        assert len(calls) <= 4                  # the false-position point and its neighbours close in at once


def test_many_brackets_at_once_each_with_its_own_function():
    roots = np.array([0.3, 1.1, 2.5, 4.0])
    signs = np.array([1.0, -1.0, 1.0, -1.0])
    powers = np.array([1, 3, 5, 0])             # simple, triple, quintic, a jump

    def value(k, x):
        return signs[k] * (np.sign(x - roots[k]) if powers[k] == 0 else (x - roots[k]) ** powers[k])

    def f(index, at):
        return np.stack([value(k, row) for k, row in zip(index, at)])
    low, high = roots - 0.6 * WIDTH, roots + 0.4 * WIDTH
    ends = np.arange(roots.size)
    found = refine_zeros(f, low, high, np.array([value(k, low[k]) for k in ends]),
                         np.array([value(k, high[k]) for k in ends]))
    assert np.all(np.abs(found - roots) <= ulps(roots, roots))


def test_an_exact_zero_at_an_end_or_inside_is_that_point():
    f = lambda index, at: at - 1.0              # noqa: E731
    found = refine_zeros(f, np.array([1.0, 0.5]), np.array([1.5, 1.0]), np.array([0.0, -0.5]),
                         np.array([0.5, 0.0]))
    assert found.tolist() == [1.0, 1.0]
    inside = refine_zeros(f, np.array([0.0]), np.array([2.0]), np.array([-1.0]), np.array([1.0]), sections=4)
    assert inside.tolist() == [1.0]             # 1.0 is one of the sections' points: found exactly


def test_a_bracket_without_values_inside_stops_at_once():
    calls = []

    def f(index, at):
        calls.append(at.shape)
        return np.full(at.shape, np.nan)       # no equilibrium anywhere inside
    found = refine_zeros(f, np.array([1.0]), np.array([1.1]), np.array([-1.0]), np.array([1.0]))
    assert len(calls) == 1 and found.tolist() == [1.05]


def test_no_brackets_no_calls():
    found = refine_zeros(lambda index, at: pytest.fail("called"), np.zeros(0), np.zeros(0), np.zeros(0),
                         np.zeros(0))
    assert found.shape == (0,)


def test_each_bracket_reads_its_own_function_at_its_points():
    values = np.arange(2 * 6, dtype=float).reshape(2, 6)       # two functions at 3 brackets × 2 points
    assert own_rows(values, np.array([1, 0, 1]), (3, 2)).tolist() == [[6.0, 7.0], [2.0, 3.0], [10.0, 11.0]]
