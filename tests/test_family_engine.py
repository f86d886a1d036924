"""The family engine (server/families/family.py, server/api/family_batch.py): the error estimate h²·|f''|/8 from
neighbouring members against functions whose interpolation error is known in closed form, the bound against
the endpoints' own exact answers at random values on several scenes (a dynamics one among them), the coarse
stage, the memo of members, and the response cache keeping the stages apart.

Families here run in this process with the time budgets lifted, so that nothing depends on the machine's speed.
"""
from __future__ import annotations

import math
from contextlib import contextmanager
import random

import numpy as np
import pytest
from fastapi.testclient import TestClient

from server.api import family_batch
from server.runtime import heavy
from server.families import family
from server.api.app import app
from server.api.endpoints import compute_answer
from server.api.serialise import Answer
from server.core.dynamics import report

from test_family import API, SENT, TOLERANCE, family_body, post_family

FINEST = family.FINEST_FRACTION


@contextmanager
def unbudgeted_client():
    """The app in this process (no heavy processes) with the families' and reports' time budgets lifted."""
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(heavy, "HEAVY_PROCESSES", 0)
        patch.setattr(family, "TIME_BUDGET_S", 1e9)
        patch.setattr(report, "TIME_BUDGET_S", 1e9)
        yield TestClient(app)


@pytest.fixture(scope="module")
def client():
    with unbudgeted_client() as made:
        yield made


def synthetic(f, calls: list | None = None):
    """members(values, deadline) of a made-up endpoint answering {"y": f(value)} (a float array)."""
    def members(values, deadline):
        if calls is not None:
            calls.extend(values)
        return [family.Member.of(v, Answer({"y": np.atleast_1d(np.asarray(f(v), float))})) for v in values]
    return members


def test_the_linear_estimate_of_a_parabola_is_its_exact_interpolation_error():
    """For f = x² the second divided difference is exactly 2 on any spacing, and linear interpolation over
    [a, b] is off by (b − a)²/4 at the midpoint, i.e. h²·|f''|/8: the linear estimate is exact (to round-off
    and the 5 digits sent, hence rel=1e-4), on the even start members and on a refined, uneven spacing."""
    members = synthetic(lambda x: x * x)([0.0, 0.1, 0.2, 0.3, 0.4, 0.6, 0.8, 1.0], None)     # exact in 5 digits
    stack = family.Stack.of(members, False)
    assessed = family.assess(stack, {("y",): 1.0}, {})
    widths = np.diff([m.value for m in members])
    for k, (score, _) in enumerate(assessed.linear):
        assert score == pytest.approx(widths[k] ** 2 / 4, rel=1e-4)


def test_a_parabola_is_drawn_exactly_by_the_cubic_from_the_start_members():
    """The cubic through 4 members reproduces x² (its fourth divided differences are 0): the family keeps its
    9 start members, every interval cubic, the estimate 0 but for the 5 digits sent, and the interpolation
    exact at random values to those digits."""
    answer, partial = family.build(synthetic(lambda x: x * x), 0.0, 1.0, False)
    assert not partial and answer["values"] == family.spaced(0.0, 1.0, family.START_MEMBERS, False)
    assert answer["orders"] == [3] * 8 and answer["interpolation_error"] <= 1e-4
    members = [family.as_tree(a, sent=False) for a in answer["answers"]]
    for x in np.random.default_rng(2).uniform(0, 1, 50):
        assert family.interpolate_family(answer["values"], members, x, False, answer["orders"])["y"][0] == \
            pytest.approx(x * x, abs=SENT)


def test_a_curve_whose_grid_changes_with_the_value_claims_no_less_than_the_nearer_member_is_off():
    """y = v·x² on x = 11 + round(10 v) evenly spaced nodes of [0, 1]: where two neighbours hold the curve on
    different grids the page draws the nearer member's (x, y) as it is, off at its own x by |v − v_near|·x²
    from the exact curve (known in closed form). The interpolation error the family claims bounds that, at
    random values and near every change of grid, to the 5 digits sent (SENT of y's span, 1)."""
    def curve(v):
        x = np.linspace(0.0, 1.0, 11 + round(10 * v))
        return {"x": x, "y": v * x * x}

    members = lambda values, deadline: [family.Member.of(v, Answer(curve(v))) for v in values]  # noqa: E731
    answer, _ = family.build(members, 0.0, 1.0, False)
    values, orders = answer["values"], answer["orders"]
    trees = [family.as_tree(a, sent=False) for a in answer["answers"]]
    points = np.concatenate([np.random.default_rng(5).uniform(0, 1, 200), (np.arange(10) + 0.5) / 10 + 1e-3])
    worst = 0.0
    for v in points:
        drawn = family.interpolate_family(values, trees, v, False, orders)
        x, y = np.asarray(drawn["x"]), np.asarray(drawn["y"])
        worst = max(worst, float(np.max(np.abs(y - v * x * x))))
    assert worst > 0                                    # the grids do change: the nearer member is drawn
    assert worst <= answer["interpolation_error"] + SENT


def test_a_quantity_null_at_every_member_has_a_span_of_zero_and_is_drawn_as_null():
    """A curve that is null wherever it is held (the flywheel's ω without the flywheel, at a mean speed where
    the machine alone would stall, for every value of the slider) is a leaf of every member all the same: the
    family, sent packed and rebuilt as the page rebuilds it, gives it a span (0: nothing of it is drawn), so
    that the bound is checked on every leaf the preview holds (tests/test_family_bound.py looks each one's
    span up), and the preview draws it null. The other leaf, y = v², meets the bound as usual."""
    from test_family_fields import whole_members

    def members(values, deadline):
        return [family.Member.of(v, Answer({"curves": {"y": np.array([v * v, v]), "stalled": np.full(3, np.nan)}}))
                for v in values]
    answer, _ = family.build(members, 0.0, 1.0, False, pack=True)
    rebuilt = whole_members(answer)
    width = family.spans(rebuilt)
    assert width[("curves", "stalled")] == 0.0 and width[("curves", "y")] == pytest.approx(1.0)
    for v in np.random.default_rng(9).uniform(0, 1, 20):
        drawn = family.interpolate_family(answer["values"], rebuilt, v, False, answer["orders"])
        exact = {"curves": {"y": np.array([v * v, v]), "stalled": np.full(3, np.nan)}}
        for path, leaf in family.checked_leaves(exact):
            bound = (TOLERANCE + family.PACK_QUANTUM / 2) * width[path] + SENT * np.abs(leaf)
            assert not np.any(np.abs(family._leaf(drawn, path) - leaf) > bound), (v, path)
        assert np.isnan(drawn["curves"]["stalled"]).all()


def test_the_cubic_estimate_of_a_quartic_is_its_exact_interpolation_error():
    """For f = x⁴ the fourth divided difference is exactly 1 on any 5 members, and the cubic through 4 of
    them is off by exactly Π (x − xᵢ) at x (f − p = ω(x)·f[x₀ … x₃, x], and that is 1): the estimate, max|ω|
    over the interval times f[5 members], bounds the largest true error closely (the fourth differences of the
    members' 5 significant digits, and the sampling of ω at 65 points, see below).
    The family halves until every interval's estimate is below TOLERANCE / CUBIC_SAFETY of the span (15/16 on
    [1/2, 1], where f″ ≥ 3 keeps every interval's cubic bound below its linear one)."""
    answer, _ = family.build(synthetic(lambda x: x ** 4), 0.5, 1.0, False)
    values = answer["values"]
    members = [family.as_tree(a, sent=False) for a in answer["answers"]]
    assert set(answer["orders"]) == {3} and answer["interpolation_error"] <= TOLERANCE / family.CUBIC_SAFETY
    worst = 0.0
    for k in range(len(values) - 1):
        first = int(family.stencils(len(values))[k])
        nodes = values[first:first + 4]
        t = np.linspace(values[k], values[k + 1], 401)[1:-1]
        true = np.array([abs(family.interpolate_family(values, members, x, False, answer["orders"])["y"][0] - x ** 4)
                         for x in t])
        omega = np.abs(np.prod([t - node for node in nodes], axis=0))
        assert np.allclose(true, omega, atol=SENT)               # the error is ω itself, to the digits sent
        worst = max(worst, omega.max())
    # the estimate holds (never below the true worst) and is close: the fourth differences of members sent with 5
    # digits carry their rounding (≈ 5e-6 / h⁴ at the finest members), so it is within 1.5×, not exact
    assert worst / (15 / 16) <= answer["interpolation_error"] <= 1.5 * worst / (15 / 16)


def test_a_corner_in_the_middle_of_an_interval_is_within_the_bound():
    """f = |x − x0| with x0 in the middle of a start interval, the worst case of the estimate (4× too small):
    at 200 random x the interpolation is within TOLERANCE × span of the closed form, or the corner is left
    in an interval narrower than a slider resolves."""
    x0 = 1 / 16
    answer, _ = family.build(synthetic(lambda x: abs(x - x0)), 0.0, 1.0, False)
    values = answer["values"]
    members = [family.as_tree(a, sent=False) for a in answer["answers"]]
    span = 1 - x0
    rng = np.random.default_rng(4)
    for x in rng.uniform(0, 1, 200):
        k = np.searchsorted(values, x) - 1
        if values[k + 1] - values[k] <= FINEST * 1.01:
            continue
        preview = family.interpolate_family(values, members, x, False, answer["orders"])["y"]
        assert abs(preview[0] - abs(x - x0)) <= TOLERANCE * span + SENT


def test_a_refined_family_of_a_smooth_curve_is_within_the_bound_at_random_values():
    """f(x, φ) = sin(3x + φ) on 50 angles, x in [0, 4]: at 400 random x the interpolated family differs from
    the closed form by at most TOLERANCE × span (span 2) plus the 5 digits sent (SENT). The estimate uses
    the smaller |f''| of an interval's two ends; the safety factor covers that |f''| changes within it."""
    phi = np.linspace(0, 2 * np.pi, 50)
    answer, _ = family.build(synthetic(lambda x: np.sin(3 * x + phi)), 0.0, 4.0, False)
    members = [family.as_tree(a, sent=False) for a in answer["answers"]]
    rng = np.random.default_rng(13)
    for x in rng.uniform(0, 4, 400):
        preview = family.interpolate_family(answer["values"], members, x, False, answer["orders"])["y"]
        assert np.max(np.abs(preview - np.sin(3 * x + phi))) <= TOLERANCE * 2 + SENT


def test_every_computed_value_is_a_member_and_a_jump_costs_one_member_per_halving():
    """A step at x = 0.3 on [0, 1] beside a straight line: the start members and then one midpoint per
    halving of the interval holding the step, down to FINEST_FRACTION (10 halvings of 1/8); the intervals
    beside it are not halved for their neighbour's jump. The message names the jump and its size."""
    calls = []
    answer, _ = family.build(synthetic(lambda x: (x > 0.3) + 0.1 * x, calls), 0.0, 1.0, False)
    assert answer["values"] == sorted(set(calls)) and answer["numerics"]["checked"] == len(calls)
    assert len(calls) <= family.START_MEMBERS + 7 + 2
    values = np.asarray(answer["values"])
    k = np.searchsorted(values, 0.3)
    assert values[k] - values[k - 1] <= FINEST * 1.01
    assert "faster than a slider can resolve" in answer["numerics"]["message"]
    # the error given there is the change across that interval, the step 1 over the span 1.1 (not the J/8
    # that second differences read for a step)
    assert answer["interpolation_error"] == pytest.approx(1 / 1.1, rel=1e-3)


def test_the_coarse_stage_is_the_nine_start_members_with_an_estimate():
    calls = []
    answer, partial = family.build(synthetic(lambda x: x ** 3, calls), 1.0, 3.0, False, stage="coarse")
    assert not partial and len(calls) == family.START_MEMBERS
    assert answer["values"] == family.spaced(1.0, 3.0, family.START_MEMBERS, False)
    assert answer["numerics"]["stage"] == "coarse" and answer["numerics"]["message"] == ""
    assert "coarse" in answer["numerics"]["method"]
    # x³ is a cubic: drawn exactly by the cubic through 4 members, its estimate 0 but for the 5 digits sent
    assert answer["orders"] == [3] * 8 and answer["interpolation_error"] <= 1e-5


def test_objects_in_an_array_are_one_quantity_only_while_their_texts_agree():
    a = {"special": [{"kind": "dead_centre", "phi": 0.0}, {"kind": "extreme", "phi": 1.0}]}
    b = {"special": [{"kind": "extreme", "phi": 0.5}, {"kind": "extreme", "phi": 3.0}]}
    mixed = family.interpolate(a, b, 0.25)
    assert mixed["special"][0] == {"kind": "dead_centre", "phi": 0.0}         # another kind: the nearer one
    assert mixed["special"][1]["phi"] == pytest.approx(1.5)                   # the same kind: interpolated
    paths_a, paths_b = set(family.flatten(a)), set(family.flatten(b))
    assert len(paths_a & paths_b) == 1                                        # only the second is compared
    assert family.quantity(next(iter(paths_a & paths_b))) == "special.1.phi"


def test_the_memo_is_bounded_in_members_and_in_bytes():
    member = family.Member.of(1.0, Answer({"y": np.zeros(1000)}))
    memo = family_batch.MemberMemo(entries=3, size=10 * member.size())
    for k in range(5):
        memo.put(("e", str(k)), member)
    assert list(memo.store) == [("e", "2"), ("e", "3"), ("e", "4")]
    assert memo.get(("e", "2")) is member and list(memo.store)[-1] == ("e", "2")
    small = family_batch.MemberMemo(entries=100, size=int(2.5 * member.size()))
    for k in range(5):
        small.put(("e", str(k)), member)
    assert len(small.store) == 2 and small.held <= small.size
    partial = family.Member.of(1.0, Answer({"y": np.zeros(3)}, partial=True))
    small.put(("p",), partial)
    assert ("p",) not in small.store                          # cut short by a bound: computed again next time


def test_the_full_family_after_the_coarse_one_reuses_its_members_and_answers_the_same(client):
    family_batch.MEMO.store.clear()
    family_batch.MEMO.held = 0
    body = family_body("reduced-inertia", "slider_crank", "lambda")
    _, coarse = post_family(client, body | {"stage": "coarse"})
    response, full = post_family(client, body | {"stage": "full"})
    assert coarse["numerics"]["stage"] == "coarse" and full["numerics"]["stage"] == "full"
    assert response.headers["x-cache"] == "miss"              # the response cache keeps the stages apart
    assert coarse["numerics"]["computed"] == 9
    assert full["numerics"]["computed"] == full["numerics"]["points"] - 9
    for value, member in zip(coarse["values"], coarse["answers"]):
        assert full["answers"][full["values"].index(value)] == member
    again, same = post_family(client, body)                   # no stage: "full", the same cached answer
    assert again.headers["x-cache"] == "hit" and same == full


@pytest.mark.parametrize("scene, variant, slider", [
    ("reduced-inertia", "slider_crank", "lambda"),
    ("forces-friction", "central", "load"),
    ("angular-acceleration", "crank_slider", "lam"),
    ("wear", "engine", "rpm"),
    ("equation-of-motion", "constant", "beta"),
])
def test_interpolation_is_within_the_bound_of_the_exact_endpoint_at_random_values(client, scene, variant, slider):
    """At 8 seeded random values in intervals wider than a slider resolves, every checked leaf of the
    interpolated family (linear or cubic by interval) is within TOLERANCE × its span of the endpoint's exact
    answer, plus SENT × |value| (the 5 digits the contract sends). No other slack: the engine halves at
    TOLERANCE / SAFETY (linear: its h²·|f''|/8 is 4× too small at worst for a corner) or TOLERANCE /
    CUBIC_SAFETY (cubic)."""
    body = family_body(scene, variant, slider)
    _, answer = post_family(client, body)
    values, log = answer["values"], body["log"]
    members = [None if a is None else family.as_tree(a, sent=False) for a in answer["answers"]]
    width = family.spans(members)
    finest = (family.coordinate(values[-1], log) - family.coordinate(values[0], log)) * FINEST
    vary = [family.Vary(v["path"], v["factor"]) for v in body["vary"]]
    rng = random.Random(14)
    for k in rng.sample(range(len(values) - 1), min(8, len(values) - 1)):
        a, b = family.coordinate(values[k], log), family.coordinate(values[k + 1], log)
        if b - a <= finest * 1.01 or members[k] is None or members[k + 1] is None:
            continue
        value = family.from_coordinate(a + rng.uniform(0.1, 0.9) * (b - a), log)
        exact = family.as_tree(compute_answer(body["endpoint"], family.member_body(body["request"], vary, value)).payload,
                               sent=False)
        preview = family.interpolate_family(values, members, value, log, answer["orders"])
        for path, leaf in family.checked_leaves(exact):
            guess = family._leaf(preview, path)
            ends = [family._leaf(members[k], path), family._leaf(members[k + 1], path)]
            shapes = {np.shape(x) for x in (guess, leaf, *ends)}
            if guess is None or any(end is None for end in ends) or len(shapes) > 1:
                continue    # the nearer member's leaf (the contract): another grid, or a quantity one end lacks
            guess, leaf = np.asarray(guess, float), np.asarray(leaf, float)
            missing = np.isnan(leaf)             # null in the exact answer: the preview draws nothing there either
            assert np.array_equal(np.isnan(guess), missing), (scene, slider, value, family.quantity(path))
            bound = TOLERANCE * width[path] + SENT * np.abs(leaf[~missing])
            off = np.abs(guess[~missing] - leaf[~missing])
            assert np.all(off <= bound), (scene, slider, value, family.quantity(path), float(np.max(off / width[path])))


def test_a_stage_that_is_not_coarse_or_full_is_refused(client):
    body = family_body("reduced-inertia", "slider_crank", "lambda") | {"stage": "medium"}
    response = client.post(f"{API}/family", json=body)
    assert response.status_code == 422 and response.json()["detail"][0]["loc"] == ["body", "stage"]


def test_the_shared_key_does_not_tell_a_missing_stage_from_full():
    body = family_body("reduced-inertia", "slider_crank", "lambda")
    assert family.shared(body) == family.shared(body | {"stage": "full"}) != family.shared(body | {"stage": "coarse"})
    assert math.isfinite(body["min"])


def test_the_course_project_has_no_family(client):
    """Its page drags no slider: a family of whole course projects is refused, naming the field."""
    refused = client.post("/api/v1/family", json={"endpoint": "course-project", "request": {},
                                                 "vary": [{"path": "omega_mean"}], "values": [1.0, 2.0]})
    assert refused.status_code == 422
    assert any(e["loc"][:2] == ["body", "endpoint"] for e in refused.json()["detail"])
