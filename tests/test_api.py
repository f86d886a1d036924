"""The JSON API: what it lists, what it returns, and how it refuses.

GET /api/v1/mechanisms describes the four mechanisms; POST /api/v1/kinematics returns
exactly the requested outputs over the requested angles, never NaN or Infinity (a value
undefined at a singular position is null, with a warning saying why), and answers invalid
input with HTTP 422 naming the field and the reason, changing nothing.
"""
from __future__ import annotations

import json
import re

import numpy as np
import pytest
from fastapi.testclient import TestClient

from server.api.app import app
from server.core.kinematics import MAX_POINTS, compute_kinematics
from server.core.mechanisms import MECHANISMS

API = "/api/v1"
MECHANISM_NAMES = {"sine", "slider_crank", "slotted_link", "four_bar"}
SCENE_OUTPUTS = ["s", "u31", "du31", "s2", "u21", "du21", "joints", "special"]


@pytest.fixture(scope="module")
def client() -> TestClient:
    return TestClient(app)


def strict_json(text: str):
    """Parse JSON as the browser's JSON.parse would: NaN, Infinity and -Infinity are errors."""
    def reject(constant):
        raise ValueError(f"non-standard JSON constant {constant} in the response")
    return json.loads(text, parse_constant=reject)


def post(client: TestClient, body: dict, **query):
    response = client.post(f"{API}/kinematics", json=body, params=query)
    return response, strict_json(response.text)


def post_raw(client: TestClient, text: str):
    response = client.post(f"{API}/kinematics", content=text, headers={"content-type": "application/json"})
    return response, strict_json(response.text)


def assert_refused(client: TestClient, body, loc: list, *words: str) -> dict:
    """HTTP 422, the first error at ``loc`` (FastAPI's own format), its message containing ``words``."""
    response, data = post_raw(client, body) if isinstance(body, str) else post(client, body)
    assert response.status_code == 422, response.text
    error = data["detail"][0]
    assert error["loc"] == loc, error
    for word in words:
        assert word.lower() in error["msg"].lower(), error["msg"]
    return error


# --- GET /api/v1/mechanisms -----------------------------------------------------------------------

def test_mechanism_list_names_the_four_mechanisms_with_their_conventions(client):
    response = client.get(f"{API}/mechanisms")
    assert response.status_code == 200
    listed = strict_json(response.text)
    assert {m["name"] for m in listed} == MECHANISM_NAMES and len(listed) == 4
    for mech in listed:
        assert mech["title"]
        assert "φ" in mech["conventions"] and len(mech["conventions"]) > 80   # origin and sense of φ in words


def test_every_parameter_comes_with_unit_range_and_a_default_inside_it(client):
    for mech in strict_json(client.get(f"{API}/mechanisms").text):
        assert mech["params"], mech["name"]
        for param in mech["params"]:
            assert set(param) >= {"name", "unit", "description", "default", "minimum", "maximum", "integer"}
            assert param["unit"] in ("m", "1") and param["description"]
            assert param["minimum"] <= param["default"] <= param["maximum"], (mech["name"], param)
        lengths = [p for p in mech["params"] if p["name"][0] == "l" and p["name"][1:].isdigit()]
        assert lengths and all(p["unit"] == "m" and p["minimum"] > 0 for p in lengths)


def test_mechanism_list_names_every_output_with_its_unit(client):
    for mech in strict_json(client.get(f"{API}/mechanisms").text):
        names = {o["name"] for o in mech["outputs"]}
        assert names >= {"s", "u31", "du31", "s2", "u21", "du21", "joints", "special"}
        assert all(o["unit"] and o["description"] for o in mech["outputs"])


def test_default_parameters_of_every_mechanism_can_be_assembled_and_run(client):
    for name in MECHANISM_NAMES:
        response, data = post(client, {"mechanism": name, "n": 37, "outputs": SCENE_OUTPUTS})
        assert response.status_code == 200, (name, response.text)
        assert data["params"] == MECHANISMS[name].defaults()


# --- POST /api/v1/kinematics: what comes back ------------------------------------------------------

@pytest.mark.parametrize("outputs", [["u31"], ["s", "du21"], SCENE_OUTPUTS, ["joints"], ["special", "info"]],
                         ids=lambda o: "+".join(o))
@pytest.mark.parametrize("mechanism", sorted(MECHANISM_NAMES))
def test_kinematics_returns_phi_and_exactly_the_requested_outputs(client, mechanism, outputs):
    response, data = post(client, {"mechanism": mechanism, "n": 19, "outputs": outputs}, precision="full")
    assert response.status_code == 200, response.text
    assert set(data["outputs"]) == set(outputs)
    assert set(data["units"]) == set(outputs)
    assert len(data["phi"]) == 19
    assert data["phi"][0] == 0.0 and data["phi"][-1] == pytest.approx(data["cycle"], abs=1e-15)
    for name in set(outputs) - {"joints", "special", "info", "harmonics"}:
        assert len(data["outputs"][name]) == 19


FOUR_BAR_AT_ANGLES = {"mechanism": "four_bar", "params": {"l0": 0.4, "l1": 0.1, "l2": 0.35, "l3": 0.3, "assembly": -1},
                      "phi": [0.0, 0.3, 1.7, 4.0, 6.2], "outputs": ["s", "u31", "du31", "u21", "joints"]}


def test_kinematics_values_at_full_precision_are_the_numeric_core_values_unchanged(client):
    body = FOUR_BAR_AT_ANGLES
    _, data = post(client, body, precision="full")
    core = compute_kinematics("four_bar", body["params"], body["outputs"], phi=np.array(body["phi"]))
    assert data["phi"] == body["phi"]
    for name in ("s", "u31", "du31", "u21"):
        assert data["outputs"][name] == core.outputs[name].tolist()   # JSON floats round-trip exactly
    for joint, xy in core.outputs["joints"].items():
        assert data["outputs"]["joints"][joint] == xy.tolist()


def test_kinematics_values_at_plot_precision_are_the_core_values_to_seven_significant_digits(client):
    """The default: each float is the core's rounded to 7 significant digits, so within half a unit of the 7th
    digit, |sent − exact| ≤ 5·10⁻⁷ |exact| (and a little more for the double nearest the decimal: 1e-15)."""
    body = FOUR_BAR_AT_ANGLES
    response, data = post(client, body)
    core = compute_kinematics("four_bar", body["params"], body["outputs"], phi=np.array(body["phi"]))
    for name in ("s", "u31", "du31", "u21"):
        sent, exact = np.array(data["outputs"][name]), core.outputs[name]
        assert np.all(np.abs(sent - exact) <= (5e-7 + 1e-15) * np.abs(exact))
    mantissas = re.findall(rb"(\d+(?:\.\d+)?)(?:e[-+]?\d+)?", response.content.split(b'"outputs"')[1])
    assert mantissas and max(len(m.replace(b".", b"").strip(b"0")) for m in mantissas) <= 7
    assert len(response.content) < len(post(client, body, precision="full")[0].content)


def test_joints_are_lists_of_points_one_per_angle(client):
    _, data = post(client, {"mechanism": "slider_crank", "n": 7, "outputs": ["joints"]})
    joints = data["outputs"]["joints"]
    assert set(joints) >= {"O", "A", "B"}
    assert all(len(points) == 7 and all(len(xy) == 2 for xy in points) for points in joints.values())


def test_largest_grid_of_10001_points_is_accepted(client):
    response, data = post(client, {"mechanism": "four_bar", "n": MAX_POINTS, "outputs": ["u31"]})
    assert response.status_code == 200 and len(data["outputs"]["u31"]) == MAX_POINTS == 10001


def test_a_long_table_answered_in_a_thread_agrees_with_a_short_one_answered_inline(client):
    """Up to INLINE_POINTS angles the route answers on the event loop, beyond in a thread: one answer either
    way. With n = 10001 and n = 11 over one turn, every 1000th angle of the long table is an angle of the
    short one: the same closed form at the same angle, to round-off of the angle grid (1e-12)."""
    from server.api.routers.kinematics import INLINE_POINTS
    long_body = {"mechanism": "four_bar", "n": MAX_POINTS, "outputs": ["u31", "s"]}
    assert MAX_POINTS > INLINE_POINTS >= 11
    _, long = post(client, long_body, precision="full")
    _, short = post(client, {**long_body, "n": 11}, precision="full")
    for name in ("u31", "s"):
        assert np.allclose(np.array(long["outputs"][name])[::1000], short["outputs"][name], rtol=1e-12, atol=1e-12)


def test_special_positions_are_returned_with_kind_angle_and_value(client):
    _, data = post(client, {"mechanism": "slider_crank", "params": {"l1": 0.1, "l2": 0.3}, "n": 2,
                            "outputs": ["special"]})
    dead = [sp for sp in data["outputs"]["special"] if sp["kind"] == "dead_centre"]
    assert [sp["phi"] for sp in dead] == [0.0, pytest.approx(np.pi)]
    assert dead[1]["value"] == pytest.approx(0.2)   # the stroke 2l₁
    assert all(sp["description"] for sp in data["outputs"]["special"])
    _, data = post(client, {"mechanism": "four_bar", "n": 2, "outputs": ["special"]})
    kinds = [sp["kind"] for sp in data["outputs"]["special"]]
    assert kinds.count("rocker_extreme") == 2 and "min_transmission_angle" in kinds
    _, data = post(client, {"mechanism": "four_bar", "params": {"l0": 2, "l1": 1, "l2": 4, "l3": 3, "limiter": 0},
                            "n": 2, "outputs": ["special"]})
    assert data["cycle"] == pytest.approx(4 * np.pi)
    assert [sp["phi"] for sp in data["outputs"]["special"] if sp["kind"] == "change_point"] == \
        [0.0, pytest.approx(2 * np.pi)]


# --- never NaN or Infinity ----------------------------------------------------------------------------

def test_singular_position_is_sent_as_null_with_a_warning_saying_why(client):
    """Slotted link with λ = l₀/l₁ = 1 at φ = 180°: the block sits on the lever pivot."""
    body = {"mechanism": "slotted_link", "params": {"l0": 0.1, "l1": 0.1}, "phi": [0.0, np.pi / 2, np.pi, 4.0],
            "outputs": SCENE_OUTPUTS}
    response, data = post(client, body)   # strict_json: no NaN/Infinity anywhere in the text
    assert response.status_code == 200
    out = data["outputs"]
    for name in ("s", "u31", "du31", "u21", "du21"):
        assert out[name][2] is None, name
        assert all(isinstance(v, float) for i, v in enumerate(out[name]) if i != 2), name
    assert out["u31"][1] == pytest.approx(0.5)   # λ = 1: the lever turns at half the crank speed elsewhere
    assert all(None not in xy for points in out["joints"].values() for xy in points)   # still drawable
    text = " ".join(data["warnings"])
    assert "λ = 1" in text and "pivot" in text
    assert "u31: undefined at 1 point(s)" in text


@pytest.mark.parametrize("lang", ["ru", "uk", "en"])
def test_singular_position_warning_exists_in_every_language(client, lang):
    body = {"mechanism": "slotted_link", "params": {"l0": 0.1, "l1": 0.1}, "phi": [np.pi], "outputs": ["u31"]}
    response, data = post(client, body, lang=lang)
    assert response.status_code == 200 and len(data["warnings"]) == 2
    assert all(w.strip() for w in data["warnings"])


@pytest.mark.parametrize("mechanism, params", [
    ("slider_crank", {"l1": 0.1, "l2": 0.1001}),
    ("slotted_link", {"l0": 0.0999, "l1": 0.1}),
    ("four_bar", {"l0": 0.4, "l1": 0.1, "l2": 0.35, "l3": 0.15001}),
    ("four_bar", {"l0": 2, "l1": 1, "l2": 4, "l3": 3, "limiter": 1}),
])
def test_near_singular_linkages_give_finite_json_and_a_warning(client, mechanism, params):
    response, data = post(client, {"mechanism": mechanism, "params": params, "n": 721,
                                   "outputs": SCENE_OUTPUTS + ["chi21", "v_s2", "a_s2", "harmonics", "info"]})
    assert response.status_code == 200
    assert all(v is not None for name in ("u31", "du31", "u21", "du21") for v in data["outputs"][name])
    if mechanism != "four_bar" or "limiter" not in params:
        assert data["warnings"]


# --- HTTP 422: the field and the reason --------------------------------------------------------------

def test_unknown_mechanism_is_refused_at_the_mechanism_field(client):
    error = assert_refused(client, {"mechanism": "cam", "n": 5, "outputs": ["s"]}, ["body", "mechanism"])
    assert "slider_crank" in error["msg"]


def test_negative_length_is_refused_at_that_parameter(client):
    assert_refused(client, {"mechanism": "slider_crank", "params": {"l1": -0.1}, "n": 5, "outputs": ["s"]},
                   ["body", "params", "l1"], "negative")


def test_out_of_range_length_is_refused_with_the_range(client):
    assert_refused(client, {"mechanism": "sine", "params": {"l1": 5.0}, "n": 5, "outputs": ["s"]},
                   ["body", "params", "l1"], "between")


@pytest.mark.parametrize("l2, e", [(0.1, 0.0), (0.05, 0.0), (0.15, 0.05), (0.15, -0.06)])
def test_crank_slider_with_rod_not_longer_than_crank_plus_offset_is_refused(client, l2, e):
    """l₂ ≤ l₁ + |e|: the crank cannot make a full turn."""
    error = assert_refused(client, {"mechanism": "slider_crank", "params": {"l1": 0.1, "l2": l2, "e": e}, "n": 5,
                                    "outputs": ["s"]}, ["body", "params", "l2"], "cannot turn")
    assert error["ctx"]["code"] == "slider_crank_no_full_turn"


@pytest.mark.parametrize("params, code", [
    ({"l0": 0.4, "l1": 0.1, "l2": 0.2, "l3": 0.2}, "four_bar_no_full_turn_pi"),     # l₀ + l₁ > l₂ + l₃
    ({"l0": 0.4, "l1": 0.1, "l2": 0.6, "l3": 0.2}, "four_bar_no_full_turn_0"),      # |l₀ − l₁| < |l₂ − l₃|
    ({"l0": 0.3, "l1": 0.3, "l2": 0.35, "l3": 0.35}, "four_bar_through_pivot"),     # l₀ = l₁: B passes over D
])
def test_four_bar_that_cannot_turn_its_crank_is_refused(client, params, code):
    response, data = post(client, {"mechanism": "four_bar", "params": params, "n": 5, "outputs": ["s"]})
    assert response.status_code == 422
    error = data["detail"][0]
    assert error["loc"][:2] == ["body", "params"] and error["loc"][2] in params
    assert error["msg"] and error["ctx"]["code"] == code


@pytest.mark.parametrize("assembly", [0, 0.5, 2])
def test_assembly_mode_other_than_plus_or_minus_one_is_refused(client, assembly):
    response, data = post(client, {"mechanism": "four_bar", "params": {"assembly": assembly}, "n": 5, "outputs": ["s"]})
    assert response.status_code == 422 and data["detail"][0]["loc"] == ["body", "params", "assembly"]


def test_more_than_10001_points_are_refused(client):
    assert_refused(client, {"mechanism": "sine", "n": MAX_POINTS + 1, "outputs": ["s"]}, ["body", "n"], "10001")
    assert_refused(client, {"mechanism": "sine", "phi": [0.0] * (MAX_POINTS + 1), "outputs": ["s"]},
                   ["body", "phi"], "10001")


def test_fewer_than_two_grid_points_are_refused(client):
    assert_refused(client, {"mechanism": "sine", "n": 1, "outputs": ["s"]}, ["body", "n"])


def test_unknown_output_is_refused_at_its_position_in_the_list(client):
    error = assert_refused(client, {"mechanism": "sine", "n": 5, "outputs": ["s", "torque"]},
                           ["body", "outputs", "1"], "torque")
    assert "u31" in error["msg"]   # the message lists what is available


def test_giving_both_phi_and_n_or_neither_is_refused(client):
    assert_refused(client, {"mechanism": "sine", "n": 5, "phi": [0.1], "outputs": ["s"]}, ["body"], "exactly one")
    assert_refused(client, {"mechanism": "sine", "outputs": ["s"]}, ["body"], "exactly one")


@pytest.mark.parametrize("raw_angle", ["NaN", "Infinity", "-Infinity", "1e400", "1e300", "-2000.5"])
def test_non_finite_or_huge_angles_are_refused_at_phi(client, raw_angle):
    body = f'{{"mechanism": "sine", "phi": [0.5, {raw_angle}], "outputs": ["s"]}}'
    non_finite = raw_angle in ("NaN", "Infinity", "-Infinity", "1e400")     # 1e400 reads as inf
    assert_refused(client, body, ["body", "phi", 1] if non_finite else ["body", "phi"], "finite")


@pytest.mark.parametrize("raw_value", ["NaN", "Infinity"])
def test_non_finite_parameter_is_refused_at_that_parameter(client, raw_value):
    body = f'{{"mechanism": "slider_crank", "params": {{"l2": {raw_value}}}, "n": 5, "outputs": ["s"]}}'
    assert_refused(client, body, ["body", "params", "l2"], "finite")


def test_non_finite_number_of_points_is_refused_at_n(client):
    assert_refused(client, '{"mechanism": "sine", "n": NaN, "outputs": ["s"]}', ["body", "n"])


def test_unknown_parameter_is_refused_by_name(client):
    assert_refused(client, {"mechanism": "slider_crank", "params": {"lambda": 3}, "n": 5, "outputs": ["s"]},
                   ["body", "params", "lambda"], "not a parameter")


def test_unknown_request_field_is_refused(client):
    assert_refused(client, {"mechanism": "sine", "n": 5, "outputs": ["s"], "omega": 10}, ["body", "omega"])


def test_refused_request_changes_nothing(client):
    valid = {"mechanism": "four_bar", "params": {"l0": 0.4, "l1": 0.1, "l2": 0.35, "l3": 0.3, "assembly": -1},
             "n": 73, "outputs": SCENE_OUTPUTS}
    before = client.post(f"{API}/kinematics", json=valid).text
    defaults = {name: mech.defaults() for name, mech in MECHANISMS.items()}
    invalid = [
        {"mechanism": "four_bar", "params": {"l0": 0.4, "l1": 0.1, "l2": 0.2, "l3": 0.2}, "n": 73, "outputs": ["s"]},
        {"mechanism": "four_bar", "params": {"l0": 0.4, "assembly": 0}, "n": 73, "outputs": ["s"]},
        {"mechanism": "four_bar", "params": {"l0": -1.0}, "n": 73, "outputs": ["s"]},
        {"mechanism": "four_bar", "params": {"l9": 1.0}, "n": 73, "outputs": ["s"]},
        {"mechanism": "four_bar", "n": 73, "outputs": ["s", "nothing"]},
        {"mechanism": "four_bar", "n": 10 ** 6, "outputs": ["s"]},
    ]
    for body in invalid:
        assert client.post(f"{API}/kinematics", json=body).status_code == 422
    assert client.post(f"{API}/kinematics", json=valid).text == before
    assert {name: mech.defaults() for name, mech in MECHANISMS.items()} == defaults


# --- OpenAPI ----------------------------------------------------------------------------------------

def test_openapi_documents_the_kinematics_endpoint_and_its_fields(client):
    response = client.get(f"{API}/openapi.json")
    assert response.status_code == 200
    spec = strict_json(response.text)
    post_op = spec["paths"][f"{API}/kinematics"]["post"]
    assert post_op["summary"] and "422" in post_op["responses"]
    ref = post_op["requestBody"]["content"]["application/json"]["schema"]["$ref"]
    request_schema = spec["components"]["schemas"][ref.rsplit("/", 1)[1]]
    assert set(request_schema["properties"]) >= {"mechanism", "params", "phi", "n", "outputs"}
    assert all(field.get("description") for field in request_schema["properties"].values())
    assert f"{API}/mechanisms" in spec["paths"] and "get" in spec["paths"][f"{API}/mechanisms"]


def test_the_server_warms_the_compiled_code_before_its_first_request(monkeypatch):
    from server.api import app as app_module
    from server.api.app import create_app
    calls = []
    monkeypatch.setattr(app_module, "warm_up", lambda: calls.append("warmed") or {"equation of motion": 0.0})
    with TestClient(create_app()) as client:
        assert calls == ["warmed"]
        assert client.post(f"{API}/kinematics", json={"mechanism": "sine", "n": 5, "outputs": ["s"]}).status_code == 200
