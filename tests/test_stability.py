"""Stiff and extreme cases over every computing endpoint: no NaN or infinity, an answer within the server's
own work bound, and either a result whose error estimate meets its tolerance or a sentence saying why not."""
import json
import math

import pytest
from fastapi.testclient import TestClient

from server.api.app import app

client = TestClient(app)
RIG = {"mechanism": "slider_crank", "params": {"l1": 0.1, "l2": 0.3},
       "inertias": {"J1": 0.5, "m2": 5, "J_S2": 0.05, "m3": 10, "J_rotor": 0.01, "gear_ratio": 5},
       "load": {"force": 2000, "return_factor": 0.2, "f": 0.1}, "motor": {"kind": "linear", "M0": 60, "b": 0.3}}
ENGINE = {"mechanism": "slider_crank", "params": {"l1": 0.12, "l2": 0.528, "a2": 0.32},
          "inertias": {"J1": 2.72, "m2": 24.2, "J_S2": 1.21, "m3": 36.2},
          "motor": {"kind": "indicator", "p_max": 4.4e6, "piston_diameter": 0.1}, "omega_mean": 47.124}


def strict(response):
    assert response.status_code in (200, 422), response.text
    return json.loads(response.text, parse_constant=lambda name: pytest.fail(f"{name} in the response"))


def no_non_finite(value):
    if isinstance(value, dict):
        return all(no_non_finite(v) for v in value.values())
    if isinstance(value, list):
        return all(no_non_finite(v) for v in value)
    return not isinstance(value, float) or math.isfinite(value)


KINEMATICS = [
    ("slider_crank", {"l1": 0.1, "l2": 0.1001}), ("slider_crank", {"l1": 0.1, "l2": 0.1 + 1e-3 * 0.1}),
    ("slider_crank", {"l1": 0.1, "l2": 10.0}), ("slider_crank", {"l1": 0.1, "l2": 0.2, "e": 0.0999}),
    ("slotted_link", {"l0": 0.1, "l1": 0.1}), ("slotted_link", {"l0": 0.0999, "l1": 0.1}),
    ("slotted_link", {"l0": 0.1001, "l1": 0.1}), ("slotted_link", {"l0": 0.001, "l1": 1.0}),
    ("four_bar", {"l0": 0.2, "l1": 0.1, "l2": 0.4, "l3": 0.3}), ("four_bar", {"l0": 0.2, "l1": 0.1, "l2": 0.4, "l3": 0.3, "limiter": 1}),
    ("four_bar", {"l0": 0.2, "l1": 0.1, "l2": 0.4, "l3": 0.3001}), ("four_bar", {"l0": 0.4, "l1": 0.1, "l2": 0.3, "l3": 0.2}),
    ("sine", {"l1": 1.0}),
]


@pytest.mark.parametrize("mechanism, params", KINEMATICS)
def test_kinematics_at_and_near_the_limits(mechanism, params):
    body = {"mechanism": mechanism, "params": params, "n": 3601,
            "outputs": ["s", "u31", "du31", "u21", "du21", "joints", "special", "harmonics"]}
    data = strict(client.post("/api/v1/kinematics", json=body))
    assert no_non_finite(data)
    if "detail" not in data and None in data["outputs"]["u31"]:
        assert data["warnings"]                      # a null always comes with its reason


@pytest.mark.parametrize("f", [0.0, 0.2, 0.99, 1.0, 1.5])
@pytest.mark.parametrize("mechanism, params", [("sine", {"l1": 1}), ("slider_crank", {"l1": 1, "l2": 1.02}),
                                               ("slider_crank", {"l1": 1, "l2": 3}), ("slotted_link", {"l0": 1, "l1": 1})])
def test_friction_from_zero_to_past_self_locking(f, mechanism, params):
    body = {"mechanism": mechanism, "params": params, "load": {"force": 1, "f": f}, "inertias": {"J1": 1, "m3": 1, "J3": 1},
            "outputs": ["resisting", "inertia"]}
    data = strict(client.post("/api/v1/reduction", json=body))
    assert no_non_finite(data)
    if None in data["resisting"]["total"]:
        assert data["warnings"]


@pytest.mark.parametrize("masses", [1e-6, 1.0, 1e3])
@pytest.mark.parametrize("speed", [0.05, 300.0])
def test_masses_over_nine_decades_and_slow_and_fast_cranks(masses, speed):
    body = RIG | {"inertias": {"J1": 0.5 * masses, "m2": 5 * masses, "J_S2": 0.05 * masses, "m3": 10 * masses,
                               "J_rotor": 0.01, "gear_ratio": 5},
                  "motor": {"kind": "linear", "M0": 60 * speed / 40, "b": 0.3}, "outputs": ["steady"]}
    data = strict(client.post("/api/v1/motion", json=body))
    assert no_non_finite(data)
    numerics = data["numerics"]
    if "omega" in data:
        assert numerics["error_estimate"] is not None and numerics["error_estimate"] <= numerics["rtol"] or numerics["message"]
    else:
        assert data["warnings"]


@pytest.mark.parametrize("delta", [0.001, 0.01, 0.2])
def test_flywheel_from_precision_tools_to_crushers(delta):
    data = strict(client.post("/api/v1/flywheel", json=ENGINE | {"delta": delta}))
    assert no_non_finite(data)
    exact = next(m for m in data["methods"] if m["method"] == "exact")
    assert abs(exact["delta_achieved"] / delta - 1) <= 1e-6


ELASTIC = {"model": "two_mass", "J_motor": 0.25, "t_end": 0.2, "n": 201} | RIG | {      # J_motor is the rotor's side
    "inertias": {k: v for k, v in RIG["inertias"].items() if k != "J_rotor"}}


@pytest.mark.parametrize("c, b", [(1e2, 0.0), (1e5, 0.0), (1e8, 1e5), (1e9, 3e7)])
def test_elastic_stiffness_ratios_up_to_1e8_and_zero_damping(c, b):
    data = strict(client.post("/api/v1/elastic", json=ELASTIC | {"c": c, "b": b, "outputs": ["histories"]}))
    assert no_non_finite(data)
    numerics = data["numerics"]
    assert numerics["error_estimate"] <= 100 * numerics["rtol"] or data["warnings"]


def test_elastic_linkage_through_its_dead_positions():
    body = ELASTIC | {"model": "elastic_linkage", "compliances": {"e1": 1e-6, "e2": 1e-9}, "b": 100.0,
                      "outputs": ["histories", "modal"]}
    data = strict(client.post("/api/v1/elastic", json=body))
    assert no_non_finite(data) and None in data["modal"]["compliance"]      # e = ∞ at the dead positions


@pytest.mark.parametrize("f", [0.0, 0.3, 0.9])
def test_forces_up_to_self_locking(f):
    body = {"params": {"l1": 0.1, "l2": 0.105}, "loads": {"force": 1000, "omega": 10},
            "pairs": {"f12": f, "f23": f, "f34": f, "f14": f}, "n": 181}
    data = strict(client.post("/api/v1/forces", json=body))
    assert no_non_finite(data)
    if None in data["balancing_moment"]:
        assert data["warnings"]


def test_live_work_precision_study_of_the_steady_cycle():
    body = RIG | {"outputs": ["steady"]}
    study = strict(client.post("/api/v1/work-precision/motion", json=body))["study"]
    ours = [r for r in study["rows"] if r["method"].startswith("ours")]
    theirs = [r for r in study["rows"] if r["method"].startswith("solve_ivp")]
    assert ours and theirs and all(r["error"] < 1e-6 for r in ours)
    tightest = {r["method"]: r for r in theirs if r["rtol"] == 1e-5}
    assert all(r["error"] < 1e-4 for r in tightest.values())        # the others converge too, only slower


def test_live_work_precision_study_of_an_elastic_machine():
    body = ELASTIC | {"c": 1e5, "b": 5.0, "outputs": ["histories"]}
    study = strict(client.post("/api/v1/work-precision/elastic", json=body))["study"]
    assert any(r["method"].startswith("ours: ") for r in study["rows"])
    for method in ("DOP853", "Radau"):
        errors = [r["error"] for r in study["rows"] if r["method"].endswith(method)]
        assert errors == sorted(errors, reverse=True) and errors[-1] < 1e-5   # error falls with the tolerance


def test_motion_error_estimate_does_not_underestimate_the_true_error():
    for force, b in ((2000, 0.3), (500, 0.1), (1000, 0.6)):
        body = RIG | {"load": {"force": force, "return_factor": 0.2, "f": 0.1}, "motor": {"kind": "linear", "M0": 60, "b": b}}
        for rtol in (1e-4, 1e-7):
            answer = strict(client.post("/api/v1/motion", json=body | {"outputs": ["steady"], "rtol": rtol}))
            reference = strict(client.post("/api/v1/motion", json=body | {"outputs": ["steady"], "rtol": 1e-11}))
            true = abs(answer["omega"][0] / reference["omega"][0] - 1)
            assert true <= 10 * answer["numerics"]["error_estimate"] + 1e-12


def test_flywheel_error_estimate_does_not_underestimate_the_true_error():
    from server.core.dynamics import flywheel as fw
    from server.core.dynamics.machine import Machine
    from server.core.dynamics.motion import cumulative_simpson, node_tables
    from server.core.dynamics.motors import Motor
    from server.core.dynamics.reduction import Inertias
    from server.core.dynamics.resistance import Load
    from server.core.mechanisms import MECHANISMS
    answer = strict(client.post("/api/v1/flywheel", json=ENGINE | {"delta": 0.0125}))
    inertia = next(m["inertia"] for m in answer["methods"] if m["method"] == "exact")
    machine = Machine("slider_crank", MECHANISMS["slider_crank"].check(ENGINE["params"]),
                      Inertias(**ENGINE["inertias"]), Load(), Motor("indicator", p_max=4.4e6, piston_diameter=0.1))
    tables = node_tables(machine, 1 << 15, balance=True)
    work = cumulative_simpson(tables.net_phi, float(tables.phi[2] - tables.phi[0]))
    reference = fw.exact(fw.Cycle(tables.phi[::2], work, tables.J[::2] - 2.72), 47.124, 0.0125, inertia).inertia
    assert abs(inertia / reference - 1) <= 10 * answer["numerics"]["error_estimate"] + 1e-13


def test_reduction_error_estimate_against_the_closed_form_mean():
    body = {"mechanism": "sine", "params": {"l1": 1}, "load": {"force": 1, "f": 0.15, "convention": "textbook"},
            "outputs": ["resisting"]}
    answer = strict(client.post("/api/v1/reduction", json=body))
    true = abs(answer["resisting"]["mean"] - 2 * (1 + 0.15**2) * 1.15 / math.pi)
    assert true <= 10 * answer["numerics"]["error_estimate"]


@pytest.mark.parametrize("lam", [0.001, 0.5, 0.999])
def test_angular_acceleration_near_the_locking_ratio(lam):
    data = strict(client.post("/api/v1/angular-acceleration", json={"lam": lam, "law": "harmonic", "amplitude": 0.9,
                                                                    "n": 2001}))
    assert no_non_finite(data)


def test_wear_at_extreme_speed_and_life():
    body = {"params": {"l1": 0.045, "l2": 0.18, "a2": 0.38}, "rpm": 20000, "hours": 1e5,
            "loads": {"m2": 1.8, "m3": 1.33, "gas": {"kind": "indicator", "p_max": 3e6, "piston_diameter": 0.075}}}
    assert no_non_finite(strict(client.post("/api/v1/wear", json=body)))
