"""The dynamics API: validation, words instead of numbers where there is no motion, never NaN."""
import json

import pytest
from fastapi.testclient import TestClient

from server.api.app import app

client = TestClient(app)

MACHINE = {"mechanism": "slider_crank", "params": {"l1": 0.1, "l2": 0.3},
           "inertias": {"J1": 0.5, "m2": 5, "J_S2": 0.05, "m3": 10, "J_rotor": 0.01, "gear_ratio": 5},
           "load": {"force": 2000, "return_factor": 0.2, "f": 0.1}, "motor": {"kind": "linear", "M0": 60, "b": 0.3}}


def strict(response):
    return json.loads(response.text, parse_constant=lambda name: pytest.fail(f"{name} in the response"))


def post(path, body, lang="en"):
    return client.post(f"/api/v1/{path}?lang={lang}", json=body)


def test_motion_returns_the_steady_cycle_with_its_numerics():
    data = strict(post("motion", MACHINE | {"outputs": ["steady"]}))
    assert set(data["numerics"]) >= {"method", "rtol", "steps", "runtime_ms", "error_estimate"}
    assert len(data["phi"]) == len(data["omega"]) == len(data["epsilon"])
    assert 0 < data["efficiency"] < 1 and 0 < data["delta"] < 1
    assert "startup" not in data                       # only what was asked for


def test_motion_startup_only_does_not_compute_the_steady_cycle():
    data = strict(post("motion", MACHINE | {"outputs": ["startup"]}))
    assert "omega_mean" not in data and data["startup"]["omega"][0] == 0.0


@pytest.mark.parametrize("lang, word", [("en", "Stall"), ("ru", "Останов"), ("uk", "Зупинка")])
def test_stall_is_reported_in_words_in_every_language(lang, word):
    body = MACHINE | {"motor": {"kind": "linear", "M0": 10, "b": 0.3}, "outputs": ["steady", "startup"]}
    data = strict(post("motion", body, lang))
    assert "omega" not in data and any(word in w for w in data["warnings"])


def test_self_locking_is_reported_and_no_number_is_sent():
    body = MACHINE | {"params": {"l1": 0.1, "l2": 0.101}, "load": {"force": 2000, "f": 0.3}, "outputs": ["steady"]}
    data = strict(post("motion", body))
    assert "omega" not in data and any("Self-locking" in w for w in data["warnings"])
    reduction = strict(post("reduction", {"mechanism": "slider_crank", "params": {"l1": 1, "l2": 1.01},
                                          "load": {"force": 1, "f": 0.2}, "outputs": ["resisting"]}))
    assert None in reduction["resisting"]["total"] and reduction["resisting"]["self_locking"]


@pytest.mark.parametrize("change, field", [
    ({"motor": {"kind": "induction", "M_nominal": 10, "omega_nominal": 160, "omega_sync": 157}}, "motor"),
    ({"motor": {"kind": "linear", "M0": 10, "b": 0}}, "motor"),
    ({"motor": {"kind": "warp"}}, "motor"),
    ({"load": {"f": -0.1}}, "load"),
    ({"inertias": {"m2": -1}}, "inertias"),
    ({"params": {"l1": 0.1, "l2": 0.1}}, "params"),
    ({"rtol": 0.0}, "rtol"),
    ({"max_cycles": 10000}, "max_cycles"),
    ({"mechanism": "sine", "params": {"l1": 0.1}, "motor": {"kind": "indicator", "p_max": 1e6, "piston_diameter": 0.1}},
     "motor"),
])
def test_bad_machine_input_is_a_422_naming_the_field(change, field):
    response = post("motion", MACHINE | change | {"outputs": ["steady"]})
    assert response.status_code == 422
    assert field in json.dumps([e["loc"] for e in response.json()["detail"]])


def test_machine_without_inertia_is_refused():
    body = MACHINE | {"inertias": {}, "outputs": ["steady"]}
    response = post("motion", body)
    assert response.status_code == 422 and "inertia" in response.text


def test_reduction_gives_both_conventions_of_the_mean():
    data = strict(post("reduction", {"mechanism": "slider_crank", "params": {"l1": 1, "l2": 3}, "n": 2001,
                                     "load": {"force": 1, "f": 0.2, "return_factor": 0.2, "convention": "textbook"},
                                     "outputs": ["resisting"]}))
    assert data["resisting"]["means"]["textbook"] == pytest.approx(0.3953, abs=1e-4)
    assert data["resisting"]["means"]["consistent"] == pytest.approx(0.4042, abs=1e-4)
    assert "inertia" not in data


def test_friction_iteration_exists_only_where_the_textbook_iterates():
    response = post("reduction", {"mechanism": "slotted_link", "load": {"force": 1, "f": 0.2},
                                  "outputs": ["friction_iteration"]})
    assert response.status_code == 422


def test_piston_engine_runs_at_the_given_mean_speed():
    body = {"mechanism": "slider_crank", "params": {"l1": 0.12, "l2": 0.528, "a2": 0.32008},
            "inertias": {"J1": 2.72, "m2": 24.2, "J_S2": 1.21, "m3": 36.2},
            "motor": {"kind": "indicator", "p_max": 4.4e6, "piston_diameter": 0.1}, "balance": True,
            "omega_mean": 47.124, "outputs": ["steady"]}
    data = strict(post("motion", body))
    assert data["omega_mean"] == pytest.approx(47.124, rel=1e-8)
    assert data["works"]["balancing_moment"] > 0


def test_openapi_documents_the_dynamics_inputs_with_units():
    schema = client.get("/api/v1/openapi.json").json()
    assert "/api/v1/motion" in schema["paths"] and "/api/v1/reduction" in schema["paths"]
    inertia = schema["components"]["schemas"]["InertiaInput"]["properties"]
    assert "kg" in inertia["m2"]["description"] and "kg·m²" in inertia["J1"]["description"]


def test_block_on_the_lever_pivot_is_reported_once_in_words():
    body = {"mechanism": "slotted_link", "params": {"l0": 0.1, "l1": 0.1}, "inertias": {"J1": 0.5, "J3": 0.1},
            "load": {"force": 20, "f": 0.2}, "motor": {"kind": "linear", "M0": 60, "b": 0.3},
            "outputs": ["steady", "startup"]}
    data = strict(post("motion", body))
    assert "omega" not in data and len(data["warnings"]) == len(set(data["warnings"])) >= 1
    assert any("jam" in w for w in data["warnings"])


def test_start_from_rest_that_stalls_at_once_ends_with_words():
    body = MACHINE | {"load": {"force": 6000, "return_factor": 0.2, "f": 0.1},
                      "motor": {"kind": "kloss", "M_max": 10, "s_critical": 0.2, "omega_sync": 157},
                      "outputs": ["startup"]}
    data = strict(post("motion", body))
    assert any("Stall at" in w for w in data["warnings"]) and data["startup"]["omega"][-1] >= 0
