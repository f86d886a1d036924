"""POST /api/v1/family: a slider's family of answers, interpolated by the page while the slider moves.

The bound "dragging is a lookup" asks for: between members, the interpolated answer is
within 0.5 % of each plotted quantity's span of the exact answer at that value, a plot's resolution. It is
checked against the endpoint itself (a separate POST at random slider values between the members), not
against the family's own midpoint checks. The families here run in this process (no heavy process) with the
time budgets lifted, so that no answer depends on how fast the machine is.
"""
from __future__ import annotations

import copy
import json
import math
import random
import re

import numpy as np
import pytest
from fastapi.testclient import TestClient

from server.runtime import heavy
from server.families import family
from server.api.app import app
from server.api.endpoints import ENDPOINTS
from server.api.routers.family import WITHOUT_FAMILY
from server.lessons.scenes import scenes
from server.lessons.requests import path_value, scene_request
from server.core.dynamics import report

API = "/api/v1"
TOLERANCE = 0.005            # the bound: 0.5 % of each quantity's span over the family
SENT = 5e-5                  # half a unit of the 5th significant digit the contract sends (a constant's 2π: 6.2832)


@pytest.fixture(scope="module")
def client():
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(heavy, "HEAVY_PROCESSES", 0)          # in this process, where the budgets are patched
        patch.setattr(family, "TIME_BUDGET_S", 1e9)         # complete families on any machine
        patch.setattr(report, "TIME_BUDGET_S", 1e9)         # complete steady cycles on any machine
        yield TestClient(app)


def strict_json(text: str):
    """Parse as the browser's JSON.parse: NaN and Infinity are errors."""
    def reject(constant):
        raise ValueError(f"non-standard JSON constant {constant}")
    return json.loads(text, parse_constant=reject)


def family_body(scene_id: str, variant_id: str, slider_id: str, **change) -> dict:
    """The family request the page sends when a slider is grabbed (scene_requests: value × factor at each
    path; the factor is the slider's unit conversion times the value at its scale path)."""
    scene = scenes()[scene_id]
    variant = next(v for v in scene.variants if v.id == variant_id)
    slider = next(s for s in variant.sliders if s.id == slider_id)
    body = scene_request(scene, variant)
    if scene.kind == "kinematics":
        vary = [{"path": f"params.{slider.param}", "factor": body["params"][slider.scale] if slider.scale else 1.0}]
    else:
        scale = path_value(body, slider.scale) if slider.scale else 1.0
        vary = [{"path": path, "factor": slider.to_si * scale} for path in (slider.param, *slider.also)]
    return {"endpoint": scene.endpoint, "request": body, "vary": vary, "min": slider.min, "max": slider.max,
            "log": slider.log} | change


def post_family(client, body: dict):
    response = client.post(f"{API}/family", json=body)
    assert response.status_code == 200, response.text[:2000]
    return response, strict_json(response.text)


FAMILIES = {
    "crank-slider λ (kinematics)": ("transfer-functions", "slider_crank", "lambda"),
    "equation of motion, λ": ("equation-of-motion", "linear", "lambda"),
    "flywheel δ (log slider)": ("flywheel", "rig", "delta"),
}


@pytest.fixture(scope="module")
def families(client):
    """Each family of FAMILIES, computed once: (request, response, answer)."""
    computed = {}
    for name, spec in FAMILIES.items():
        body = family_body(*spec)
        computed[name] = (body, *post_family(client, body))
    return computed


def exact(client, body: dict, value: float) -> dict:
    """The endpoint's own answer at value (full precision), as a tree of arrays."""
    member = family.member_body(body["request"], [family.Vary(v["path"], v["factor"]) for v in body["vary"]], value)
    response = client.post(f"{API}/{body['endpoint']}", json=member, params={"precision": "full"})  # 7 digits by default soon
    assert response.status_code == 200, response.text[:2000]
    return family.as_tree(strict_json(response.text), sent=False)


@pytest.mark.parametrize("name", list(FAMILIES))
def test_interpolating_the_family_is_within_half_a_percent_of_each_span_of_the_exact_answer(client, families, name):
    """At random values inside the members' intervals (the page's preview), every plotted quantity of the
    interpolated family differs from the endpoint's exact answer there by at most 0.5 % of that quantity's
    span over the family, plus the rounding to 5 significant digits that the contract prescribes (spans as
    the contract defines them; family.spans also floors the span of a quantity that is zero but for the
    solver's residual, beside siblings 10⁴ times larger). A curve whose number of points differs between the
    neighbours is drawn from the nearer member, and is not compared; nor is an interval narrower than a
    slider resolves, which the family names as a jump or a corner in its message."""
    body, _, answer = families[name]
    values, log = answer["values"], body["log"]
    members = [None if a is None else family.as_tree(a, sent=False) for a in answer["answers"]]
    width = family.spans(members)
    finest = (family.coordinate(values[-1], log) - family.coordinate(values[0], log)) * family.FINEST_FRACTION
    rng = random.Random(13)
    for k in rng.sample(range(len(values) - 1), min(12, len(values) - 1)):
        a, b = family.coordinate(values[k], log), family.coordinate(values[k + 1], log)
        if b - a <= finest * 1.01:
            continue                # a jump, narrower than any slider resolves, named in numerics.message
        value = family.from_coordinate(a + rng.uniform(0.1, 0.9) * (b - a), log)
        truth = exact(client, body, value)
        preview = family.interpolate_family(values, members, value, log, answer["orders"])
        for path, leaf in family.checked_leaves(truth):
            guess = family._leaf(preview, path)
            shapes = {np.shape(x) for x in (guess, leaf, family._leaf(members[k], path),
                                            family._leaf(members[k + 1], path))}
            if guess is None or len(shapes) > 1:
                continue            # the nearer member's curve on its own grid (the contract), or a null
            guess, leaf = np.asarray(guess, float), np.asarray(leaf, float)
            missing = np.isnan(leaf)        # null in the exact answer: null in the preview too, numbers elsewhere
            assert np.array_equal(np.isnan(guess), missing), (name, value, path, "nulls differ")
            bound = TOLERANCE * width[path] + SENT * np.abs(leaf[~missing])
            assert np.all(np.abs(guess[~missing] - leaf[~missing]) <= bound), (name, value, path)


def test_the_family_reports_its_interpolation_error_and_names_what_it_cannot_resolve(families):
    """Within the tolerance everywhere for the crank-slider's λ and the equation of motion's λ. The flywheel
    needs none once δ passes the value where the crank and rotor alone keep it (δ ≈ 0.168 here): the disk's
    width falls to zero there with an infinite slope, which no spacing a slider resolves can interpolate
    to 0.5 %; the message says where, and the rest of the range is within the tolerance."""
    for name, (_, _, answer) in families.items():
        numerics = answer["numerics"]
        assert answer["tolerance"] == TOLERANCE
        assert numerics["points"] == len(answer["values"]) == len(answer["answers"]) == len(answer["errors"])
        assert 9 <= numerics["points"] <= family.MAX_MEMBERS and numerics["checked"] >= numerics["points"] - 1
        assert numerics["method"] and numerics["runtime_ms"] >= 0
        if name.startswith("flywheel"):
            assert answer["interpolation_error"] > TOLERANCE and "steep corner" in numerics["message"]
            low, high = (float(x) for x in re.findall(r"between ([\d.]+) and ([\d.]+)", numerics["message"], re.I)[0])
            assert math.log(high / low) <= math.log(0.2 / 0.001) / 1024 * 1.05    # narrower than a slider resolves
            widths = [(a or {}).get("disk", {}).get("width") for a in answer["answers"]]
            ceases = next(k for k, width in enumerate(widths) if not width)      # no flywheel from here on
            assert widths[ceases - 1] > 0 and math.log(answer["values"][ceases] / answer["values"][ceases - 1]) \
                <= math.log(0.2 / 0.001) / 1024 * 1.05                           # the corner found to that width
        else:
            assert 0 <= answer["interpolation_error"] <= TOLERANCE and not numerics["message"], name


def test_members_crowd_where_the_answer_bends_and_thin_out_where_it_is_flat(families):
    """The crank-slider's transfer functions change fastest near λ = 1 (the rod barely longer than the crank:
    u₂₁ ~ 1/√(λ² − sin²φ)) and slowly at λ = 8: the refinement adds members at the lower limit, none at the top."""
    body, _, answer = families["crank-slider λ (kinematics)"]
    values = np.asarray(answer["values"])
    assert values[0] == body["min"] and values[-1] == body["max"] and np.all(np.diff(values) > 0)
    start = np.linspace(body["min"], body["max"], 9)
    gaps = np.diff(values)
    inside_first = (values > start[0] + 1e-3) & (values < start[1] - 1e-3)
    inside_last = (values > start[-2] + 1e-3) & (values < start[-1] - 1e-3)
    assert inside_first.sum() >= 3                              # the first of the 9 intervals halved repeatedly
    assert inside_last.sum() == 0                               # the last one left as it was
    assert gaps[0] < gaps[-1] / 8


def test_a_log_slider_spaces_its_members_in_log_value(families):
    body, _, answer = families["flywheel δ (log slider)"]
    logs = np.log(answer["values"])
    coarse = np.linspace(math.log(body["min"]), math.log(body["max"]), 9)
    for x in coarse:                                            # the first 9 members are evenly spaced in log δ
        assert np.min(np.abs(logs - x)) < 1e-4


def test_a_range_that_crosses_the_geometric_limit_gives_null_members_with_the_reason(client):
    """λ from 0.5 to 3 on a crank-slider: below λ = 1 the crank cannot turn fully (the endpoint's 422).
    Those members are null with the code and message of that 422, the others answer, and the limit is
    found to within 1/1024 of the range."""
    body = family_body("transfer-functions", "slider_crank", "lambda", min=0.5, max=3.0)
    _, answer = post_family(client, body)
    values = np.asarray(answer["values"])
    refused = np.array([a is None for a in answer["answers"]])
    assert refused.any() and not refused.all()
    for value, member, error in zip(values, answer["answers"], answer["errors"]):
        assert (member is None) == (error is not None)
        assert (value <= 1.0) == (member is None), value     # e = 0: the crank turns fully for λ > 1
        if error is not None:
            assert error["code"] == "slider_crank_no_full_turn" and "l2" in error["message"]
    last_refused, first_answered = values[refused].max(), values[~refused].min()
    assert first_answered - last_refused <= (body["max"] - body["min"]) / 1024 * 1.001
    members = [None if a is None else family.as_tree(a) for a in answer["answers"]]
    assert family.interpolate_family(answer["values"], members, 0.7, False, answer["orders"]) is None
    assert family.interpolate_family(answer["values"], members, (last_refused + first_answered) / 2, False, answer["orders"]) is None


@pytest.mark.parametrize("change, loc, words", [
    ({"endpoint": "teleport"}, ["body", "endpoint"], ["kinematics"]),
    ({"vary": [{"path": "params.l9", "factor": 1.0}]}, ["body", "vary"], ["params.l9", "not a number"]),
    ({"vary": [{"path": "mechanism", "factor": 1.0}]}, ["body", "vary"], ["mechanism"]),
    ({"vary": []}, ["body", "vary"], ["at least 1"]),
    ({"vary": [{"path": "params.l2", "factor": 1.0}] * 9}, ["body", "vary"], ["at most 8"]),
    ({"min": 3.0, "max": 3.0}, ["body", "max"], ["greater than min"]),
    ({"min": 4.0, "max": 2.0}, ["body", "max"], ["greater than min"]),
    ({"log": True, "min": 0.0}, ["body", "min"], ["log", "min > 0"]),
    ({"log": True, "min": -1.0}, ["body", "min"], ["min > 0"]),
])
def test_invalid_family_requests_are_refused_naming_the_field(client, change, loc, words):
    body = family_body("transfer-functions", "slider_crank", "lambda") | change
    response = client.post(f"{API}/family", json=body)
    assert response.status_code == 422, response.text
    error = strict_json(response.text)["detail"][0]
    assert error["loc"][:len(loc)] == loc, error
    for word in words:
        assert word.lower() in error["msg"].lower(), error


@pytest.mark.parametrize("field, loc", [('"max": 8.0', ["body", "max"]), ('"min": 1.05', ["body", "min"]),
                                        ('"factor": 0.1', ["body", "vary", 0, "factor"])])
def test_non_finite_numbers_are_refused(client, field, loc):
    text = json.dumps(family_body("transfer-functions", "slider_crank", "lambda"))
    assert field in text
    text = text.replace(field, field.split(":")[0] + ": NaN")
    response = client.post(f"{API}/family", content=text, headers={"content-type": "application/json"})
    assert response.status_code == 422 and strict_json(response.text)["detail"][0]["loc"] == loc


def test_the_endpoint_choice_is_every_computing_endpoint_but_those_without_a_family(client):
    """Every computing endpoint but the course project (a family of whole course projects costs seconds to
    minutes of CPU), which the family endpoint refuses."""
    schema = client.get(f"{API}/openapi.json").json()["components"]["schemas"]["FamilyRequest"]
    assert WITHOUT_FAMILY == ("course-project",)
    assert set(schema["properties"]["endpoint"]["enum"]) == set(ENDPOINTS) - set(WITHOUT_FAMILY)


def test_the_answer_holds_no_nan_and_floats_of_at_most_five_significant_digits(families):
    def floats(tree):
        if isinstance(tree, dict):
            for value in tree.values():
                yield from floats(value)
        elif isinstance(tree, list):
            for value in tree:
                yield from floats(value)
        elif isinstance(tree, float):
            yield tree
    for name, (_, response, answer) in families.items():
        strict_json(response.text)                               # NaN/Infinity would raise
        numbers = list(floats(answer))
        assert numbers and all(math.isfinite(x) for x in numbers)
        too_long = [x for x in numbers if float(f"{x:.5g}") != x]
        assert not too_long, (name, too_long[:5])


def test_rounding_keeps_the_shortest_decimal_of_five_digits():
    rng = np.random.default_rng(5)
    x = rng.standard_normal(20000) * 10.0 ** rng.integers(-40, 40, 20000)
    x[:6] = [0.0, 1e-300, 5e-324, 123456789.0, 99999.5, 9.99995]
    rounded = family.rounded_array(x)
    for original, short in zip(x, rounded):
        assert repr(float(short)) == repr(float(f"{original:.5g}"))
    assert np.isnan(family.rounded_array(np.array([np.nan, np.inf, -np.inf]))).all()


def test_the_interpolation_rule_of_the_contract():
    a = {"x": 1.0, "y": [0.0, 2.0, None], "n": 3, "name": "a", "z": [1.0], "only_a": 5.0, "m": None}
    b = {"x": 3.0, "y": [2.0, 4.0, 1.0], "n": 5, "name": "b", "z": [1.0, 2.0], "m": 1.0}
    near_a = family.interpolate(family.as_tree(a, sent=False), family.as_tree(b, sent=False), 0.25)
    assert near_a["x"] == 1.5 and near_a["n"] == 3.5                  # numbers: (1 − w)a + w b
    assert np.allclose(near_a["y"][:2], [0.5, 2.5]) and np.isnan(near_a["y"][2])   # element-wise, null → null
    assert near_a["name"] == "a" and list(near_a["z"]) == [1.0]       # strings, other lengths: the nearer
    assert near_a["m"] is None and near_a["only_a"] == 5.0
    undefined = family.interpolate(family.as_tree([1.0, 2.0]), family.as_tree([None, None]), 0.1)
    assert np.isnan(undefined).all()                                  # a curve undefined in one: null
    near_b = family.interpolate(a, b, 0.75)
    assert near_b["name"] == "b" and "only_a" not in near_b and near_b["y"][2] is None
    assert family.interpolate(None, b, 0.9) is None


def test_same_family_twice_is_answered_from_the_cache(client):
    body = family_body("transfer-functions", "slider_crank", "offset", min=-0.2, max=0.2)
    first, answer = post_family(client, body)
    second, again = post_family(client, body)
    assert second.headers["x-cache"] == "hit" and again == answer
    assert "x-partial" not in first.headers


def test_students_whose_slider_stands_elsewhere_share_the_family(client):
    """The family does not depend on where the slider stands now (every member sets the varied paths): a
    second student with the same other values, the slider at another value, gets the first one's answer."""
    body = family_body("transfer-functions", "slider_crank", "offset", min=-0.2, max=0.2)
    first, answer = post_family(client, body)
    moved = family.member_body(body["request"], [family.Vary(v["path"], v["factor"]) for v in body["vary"]], 0.123)
    second, again = post_family(client, body | {"request": moved})
    assert second.headers["x-cache"] == "hit" and again == answer
    other = copy.deepcopy(body)
    other["request"]["params"]["l1"] *= 1.01                      # another value of a fixed parameter: its own
    assert post_family(client, other)[0].headers["x-cache"] == "miss"


def test_a_family_cut_by_its_time_budget_spans_the_range_and_says_it_is_partial(client, monkeypatch):
    monkeypatch.setattr(family, "TIME_BUDGET_S", 0.0)
    body = family_body("transfer-functions", "slider_crank", "lambda", max=7.5)
    response, answer = post_family(client, body)
    assert response.headers["x-partial"] == "1"
    assert answer["values"] == [body["min"], body["max"]]            # min and max first, always
    assert "time budget" in answer["numerics"]["message"]


def test_members_stopped_at_their_own_work_bound_are_named(client, monkeypatch):
    """A steady cycle with no time to converge returns its last refinement and says so; the family marks
    those members in its message and as partial (X-Partial: 1, so the cache does not keep it)."""
    monkeypatch.setattr(report, "TIME_BUDGET_S", 0.0)
    body = family_body("equation-of-motion", "linear", "load", min=1000.0, max=1100.0)
    body["request"]["outputs"] = ["steady"]
    response, answer = post_family(client, body)
    assert response.headers["x-partial"] == "1"
    assert "work bound" in answer["numerics"]["message"]


def test_messages_are_in_the_readers_language(client):
    body = family_body("transfer-functions", "slider_crank", "lambda", min=2.0, max=3.0)
    for lang, word in (("ru", "логарифм"), ("uk", "логарифм")):
        response = client.post(f"{API}/family", json=body | {"log": True}, params={"lang": lang})
        assert response.status_code == 200 and word in response.json()["numerics"]["method"]
