"""A family pruned to what a preview draws ("fields") and packed ("packed": shared arrays once, arrays as integer
steps in a quantum of at most 1e-4 of their span): server/families/family.py, sections Fields and Packed.

The accuracy contract is checked against the endpoint itself (a separate POST at the midpoint of intervals,
at full precision), not against the family's own estimate: at each midpoint every drawn quantity of the
interpolated, unpacked family is within 0.5 % of its span of the exact answer, plus the contract's rounding
to 5 significant digits (SENT) and what packing may move a value (PACK_QUANTUM / 2 of the span). Families run
in this process with the time budgets lifted, so no answer depends on how fast the machine is.
"""
from __future__ import annotations

import numpy as np
import orjson
import pytest

from server.families import family
from server.api.serialise import Answer
from test_family import API, SENT, TOLERANCE, exact, family_body, post_family, strict_json
from test_family_engine import client  # noqa: F401,F811  the fixture: in-process, no time budgets

# What the page's panels draw for these variants (web/static/js/common/model/family_fields.js gives the same; the browser
# test checks the page sends those): a light kinematics scene, the forces' drawing and plots, an elastic scene.
FIELDS = {
    ("transfer-functions", "slider_crank"): ["cycle", "mechanism", "outputs.approx_error", "outputs.du21",
                                             "outputs.du31", "outputs.du31_approx", "outputs.harmonics",
                                             "outputs.joints", "outputs.s", "outputs.s2", "outputs.special",
                                             "outputs.u21", "outputs.u31", "outputs.u31_approx", "params", "phi"],
    ("forces-friction", "central"): ["applied", "balancing_moment", "friction", "friction_circles",
                                     "magnitudes.R12", "magnitudes.R23", "magnitudes.R34", "magnitudes.R41",
                                     "phi", "points", "reactions"],
    ("elastic-linkage", "slider_crank"): ["modal.compliance", "modal.damping_ratio", "modal.natural_frequency",
                                          "modal.phi", "modal.stiffness", "omega", "omega_motor", "rigid.omega",
                                          "t", "twist"],
}
CASES = {
    "crank-slider λ (kinematics)": ("transfer-functions", "slider_crank", "lambda"),
    "forces, λ (drawing and plots)": ("forces-friction", "central", "lambda"),
    "elastic linkage, e₁": ("elastic-linkage", "slider_crank", "e1"),
}


def lean_body(scene: str, variant: str, slider: str, **change) -> dict:
    return family_body(scene, variant, slider) | {"fields": FIELDS[scene, variant], "packed": True} | change


def whole_members(answer: dict) -> list:
    """The members as the page rebuilds them: unpacked, the shared arrays merged in, as trees of arrays."""
    shared = family.unpacked(answer.get("shared") or {})
    return [None if a is None else family.as_tree(family.merged(shared, family.unpacked(a)), sent=False)
            for a in answer["answers"]]


@pytest.fixture(scope="module")
def lean_families(client):
    return {name: (body := lean_body(*spec), post_family(client, body)[1]) for name, spec in CASES.items()}


@pytest.mark.parametrize("name", list(CASES))
def test_a_pruned_packed_family_interpolates_within_half_a_percent_of_the_exact_answer_at_midpoints(
        client, lean_families, name):
    body, answer = lean_families[name]
    values, log = answer["values"], body["log"]
    members = whole_members(answer)
    assert answer["interpolation_error"] <= TOLERANCE and not answer["numerics"]["message"]
    width = family.spans(members)
    trie = family.field_trie(body["fields"])
    finest = (family.coordinate(values[-1], log) - family.coordinate(values[0], log)) * family.FINEST_FRACTION
    checked = 0
    for k in range(0, len(values) - 1, max(1, (len(values) - 1) // 12)):
        a, b = family.coordinate(values[k], log), family.coordinate(values[k + 1], log)
        if b - a <= finest * 1.01:
            continue
        value = family.from_coordinate((a + b) / 2, log)
        truth = family.pruned(exact(client, body, value), trie)
        preview = family.interpolate_family(values, members, value, log, answer["orders"])
        assert set(preview) == set(truth), value                # the same drawn leaves, nothing else
        for path, leaf in family.checked_leaves(truth):
            guess = family._leaf(preview, path)
            shapes = {np.shape(x) for x in (guess, leaf, family._leaf(members[k], path),
                                            family._leaf(members[k + 1], path))}
            if guess is None or len(shapes) > 1:
                continue                # the nearer member's curve on its own grid (the contract), or a null
            guess, leaf = np.asarray(guess, float), np.asarray(leaf, float)
            missing = np.isnan(leaf)        # null in the exact answer: null in the preview too, numbers elsewhere
            assert np.array_equal(np.isnan(guess), missing), (name, value, path, "nulls differ")
            bound = (TOLERANCE + family.PACK_QUANTUM / 2) * width[path] + SENT * np.abs(leaf[~missing])
            assert np.all(np.abs(guess[~missing] - leaf[~missing]) <= bound), (name, value, path)
            checked += 1
    assert checked >= 12


def test_packing_moves_no_value_by_more_than_half_its_quantum(client):
    """The packed family unpacked (as the page does) against the same family sent plain: the same members,
    the same leaves, each value within PACK_QUANTUM/2 of its span (quanta are powers of ten ≤ 1e-4 of it)."""
    body = lean_body("forces-friction", "central", "f", stage="coarse")
    _, plain = post_family(client, body | {"packed": False})
    _, packed = post_family(client, body)
    assert "shared" not in plain and set(packed["shared"]) >= {"phi", "points"}   # f moves no joint
    assert plain["values"] == packed["values"]
    exact_members = [family.as_tree(a, sent=False) for a in plain["answers"]]
    width = family.spans(exact_members)
    for ours, theirs in zip(whole_members(packed), exact_members):
        mine, reference = family.flatten(ours), family.flatten(theirs)
        assert mine.keys() == reference.keys()
        for path, leaf in reference.items():
            assert np.array_equal(np.isnan(mine[path]), np.isnan(leaf)), path
            assert np.nanmax(np.abs(mine[path] - leaf), initial=0.0) <= family.PACK_QUANTUM / 2 * width[path] * 1.001


def test_members_hold_only_the_fields_and_unknown_paths_are_left_out(client):
    body = lean_body("transfer-functions", "slider_crank", "lambda", stage="coarse", packed=False,
                     fields=["phi", "outputs.u31", "outputs.nothing_here", "no_such_key.below"])
    _, answer = post_family(client, body)
    for member in answer["answers"]:
        assert set(member) == {"phi", "outputs"} and set(member["outputs"]) == {"u31"}
    whole = post_family(client, family_body("transfer-functions", "slider_crank", "lambda", stage="coarse"))[1]
    assert "shared" not in whole and {"warnings", "units", "outputs"} <= set(whole["answers"][0])   # as before
    assert whole["answers"][0]["outputs"]["u31"] == answer["answers"][0]["outputs"]["u31"]


def test_a_path_under_a_whole_object_adds_nothing_and_copies_nothing():
    answer = {"modal": {"phi": np.arange(3.0), "c": np.ones(3)}, "t": np.zeros(2), "n": 1}
    kept = family.pruned(answer, family.field_trie(["modal.phi", "modal", "t.x", "n"]))
    assert kept.keys() == {"modal", "n"} and kept["modal"] is answer["modal"]


@pytest.mark.parametrize("fields, where, words", [
    (["phi", "outputs..u31"], 1, ["dotted path"]),
    (["phi[0]"], 0, ["dotted path"]),
    ([""], 0, ["dotted path"]),
    (["a." * 9 + "b"], 0, ["8 deep"]),
])
def test_malformed_fields_are_refused_naming_the_field(client, fields, where, words):
    response = client.post(f"{API}/family", json=lean_body("transfer-functions", "slider_crank", "lambda",
                                                           fields=fields))
    assert response.status_code == 422, response.text
    error = strict_json(response.text)["detail"][0]
    assert error["loc"][:2] == ["body", "fields"] and f"fields[{where}]" in error["msg"], error
    assert all(word in error["msg"] for word in words), error


@pytest.mark.parametrize("fields, words", [([], ["at least 1"]), (["phi"] * (family.MAX_FIELDS + 1), ["at most"])])
def test_too_few_or_too_many_fields_are_refused(client, fields, words):
    response = client.post(f"{API}/family", json=lean_body("transfer-functions", "slider_crank", "lambda",
                                                           fields=fields))
    assert response.status_code == 422
    error = strict_json(response.text)["detail"][0]
    assert error["loc"][:2] == ["body", "fields"] and all(w in error["msg"] for w in words), error


def test_the_memo_keeps_members_of_other_fields_apart(client):
    """The same bodies asked with other fields are other members (the memo keys them by the fields)."""
    narrow = post_family(client, lean_body("forces-friction", "central", "f", stage="coarse",
                                           fields=["phi", "balancing_moment"], packed=False))[1]
    wide = post_family(client, lean_body("forces-friction", "central", "f", stage="coarse", packed=False))[1]
    assert set(narrow["answers"][0]) == {"phi", "balancing_moment"}
    assert {"points", "reactions", "applied"} <= set(wide["answers"][0])


def test_the_stacked_members_give_the_same_family_whether_their_leaves_agree_or_not(monkeypatch):
    """The members stacked as rows of one layout (every member holding the same leaves: its flat vector is its
    row) give the same family, byte for byte, as the union of layouts (each leaf placed in its columns, NaN
    where a member lacks it; family._one_layout forced false), on a made-up answer with several leaves and
    shapes, a null inside, a jump, a steep corner and a flat leaf."""
    def answer(v):
        x = np.linspace(0.0, 1.0, 50)
        bend = np.sin(3 * v * x) + (v > 0.61) * 0.3
        bend[7] = np.nan
        return {"curve": bend, "pair": np.column_stack([np.cos(v * x), x * abs(v - 0.3) ** 0.5]),
                "level": np.float64(v ** 3), "flat": np.ones(4), "nested": {"z": np.exp(-v * x[:5])}}

    def members(values, deadline):
        return [family.Member.of(v, Answer(answer(v))) for v in values]

    def built():
        result, _ = family.build(members, 0.1, 2.0, False, pack=True)
        result["numerics"].pop("runtime_ms")
        return orjson.dumps(result, option=orjson.OPT_SERIALIZE_NUMPY)

    stacked = built()
    monkeypatch.setattr(family, "_one_layout", lambda flats, answered: False)
    assert built() == stacked


@pytest.mark.parametrize("scene, variant, fields", [
    ("elastic-linkage", "slider_crank", FIELDS["elastic-linkage", "slider_crank"]),
    ("elastic-linkage", "bearings", ["modal.phi", "modal.stiffness"]),
    ("forces-friction", "central", FIELDS["forces-friction", "central"])])
def test_an_endpoint_told_what_is_read_gives_the_read_leaves_of_the_whole_answer(scene, variant, fields):
    """compute_answer(…, reads): the elastic machine without its check run at rtol/10 (and without the
    bearing iteration where only the modal curves are read), the forces without the crank check: every leaf
    read is the whole answer's, bit for bit, and the work skipped is really left out."""
    from server.api.endpoints import compute_answer
    from server.lessons.requests import scene_request
    from server.lessons.scenes import scenes
    spec = scenes()[scene]
    body = scene_request(spec, next(v for v in spec.variants if v.id == variant))
    trie = family.field_trie(fields)
    whole = compute_answer(spec.endpoint, body, "en").payload
    lean = compute_answer(spec.endpoint, body, "en", frozenset(trie)).payload
    ours, reference = family.flatten(family.pruned(lean, trie)), family.flatten(family.pruned(whole, trie))
    assert ours.keys() == reference.keys() and ours
    for path, leaf in reference.items():
        assert np.array_equal(ours[path], leaf, equal_nan=True), path
    if spec.endpoint == "forces":
        assert "crank_check" in whole and "crank_check" not in lean
    elif variant == "bearings":
        assert "bearings" in whole and "bearings" not in lean and "t" not in lean
    else:
        assert whole["numerics"]["error_estimate"] is not None and lean["numerics"]["error_estimate"] is None
