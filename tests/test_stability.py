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
    ours = [r for r in study["rows"] if r["ours"]]                    # the app's own method, as the page bolds it
    theirs = [r for r in study["rows"] if not r["ours"]]
    assert ours and theirs and all(r["error"] < 1e-6 for r in ours)
    tightest = {r["method"]: r for r in theirs if r["rtol"] == 1e-5}
    assert all(r["error"] < 1e-4 for r in tightest.values())        # the others converge too, only slower


def test_live_work_precision_study_of_an_elastic_machine(monkeypatch):
    """Through HTTP the study answers within its 6-s budget, saying so where the budget skipped runs (a loaded
    machine); the same study without a deadline (in this process) has every run, and the error falls with the
    tolerance for both solvers, ours compiled and scipy's."""
    from server.api.endpoints import elastic_machine, elastic_work_precision
    from server.api.schemas_elastic import ElasticRequest
    from server.core import work_precision
    body = ELASTIC | {"c": 1e5, "b": 5.0, "outputs": ["histories"]}
    answer = strict(client.post("/api/v1/work-precision/elastic", json=body))
    assert answer["study"]["rows"] and (not answer["study"]["skipped"]
                                        or any("time budget" in w for w in answer["warnings"]))
    with monkeypatch.context() as patch:                 # a budget that must skip runs: said in words
        patch.setattr(work_precision, "BUDGET_S", 0.05)
        cut = elastic_work_precision(ElasticRequest(**body), "en").payload
    assert cut["study"]["skipped"] and any("time budget" in w for w in cut["warnings"])
    machine = elastic_machine(ElasticRequest(**body))
    study = work_precision.elastic_study(machine, min(body["t_end"], 0.5), deadline=math.inf)
    assert not study["skipped"] and any(r["method"].startswith("ours") for r in study["rows"])
    for method in ("DOP853", "Radau"):                                # scipy's, or ours compiled: one row each
        errors = [r["error"] for r in study["rows"] if method in r["method"]]
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
    from server.core.dynamics.motion import node_tables
    from server.core.numerics import cumulative_simpson
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
    exact = 2 * (1 + 0.15**2) * 1.15 / math.pi           # M_c ≥ 0 here: the cycle mean of |M_c| is M_c0 itself
    true = abs(answer["resisting"]["mean"] / exact - 1)
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


# --- no diagnostic beyond its physical meaning, across the grid ----------------------------
# Every answer's numerics (the answer's own, the start-up's, any nested one) and every efficiency η:
#   error_estimate: a finite number ≥ 0, or null with the reason in words (numerics.message or a warning);
#   energy_residual: |net work| / driving work, within [0, 1] (a residual above 1 says nothing about energy);
#   η within [0, 1] (0 ≤ useful work ≤ driving work), or null with the reason in words;
#   and nothing non-finite anywhere (strict parse: text in words instead).

FRICTIONLESS = RIG | {"load": {"force": 2000, "return_factor": 0.2}}
FOUR_BAR = {"mechanism": "four_bar", "params": {"l0": 0.42, "l1": 0.095, "l2": 0.33, "l3": 0.27, "a2": 0.44, "assembly": 1},
            "inertias": {"J1": 0.21, "m2": 2.6, "J_S2": 0.024, "J3": 0.085, "J_rotor": 0.0047, "gear_ratio": 4.3},
            "load": {"force": 150.0, "return_factor": 0.27, "crank_moment": 3.3},
            "motor": {"kind": "induction", "M_nominal": 12.5, "omega_nominal": 141.0, "omega_sync": 152.0}, "rtol": 1e-09}
STILL_TWO_MASS = {"model": "two_mass", "mechanism": "slider_crank", "params": {"l1": 0.1, "l2": 0.3},
                  "inertias": {"J1": 0.5}, "motor": {"kind": "constant", "M0": 0}, "J_motor": 0.25, "c": 10000,
                  "twist0": 0.01, "t_end": 0.2, "outputs": ["histories"]}
FORCES = {"params": {"l1": 0.1, "l2": 0.13}, "loads": {"force": 1000, "gravity": False, "omega": 10}, "n": 73}

GRID = [
    ("motion", RIG | {"outputs": ["steady", "startup"]}, "rig"),
    ("motion", FRICTIONLESS | {"outputs": ["steady", "startup"]}, "rig-frictionless"),
    ("motion", RIG | {"motor": {"kind": "constant", "M0": 25.0}, "outputs": ["steady", "startup"]}, "constant-torque"),
    ("motion", RIG | {"inertias": {"J1": 5e-7, "m2": 5e-6, "m3": 1e-5, "J_rotor": 0.01, "gear_ratio": 5},
                      "outputs": ["steady"]}, "rig-light"),
    ("motion", RIG | {"inertias": {"J1": 500, "m2": 5e3, "m3": 1e4, "J_rotor": 0.01, "gear_ratio": 5},
                      "outputs": ["steady"]}, "rig-heavy"),
    ("motion", FOUR_BAR | {"outputs": ["steady", "startup"]}, "four-bar-reversal"),
    ("motion", ENGINE | {"load": {}, "balance": True, "outputs": ["steady"]}, "engine"),
    ("flywheel", ENGINE | {"delta": 0.001}, "flywheel-0.001"),
    ("flywheel", ENGINE | {"delta": 0.2}, "flywheel-0.2"),
    *[("reduction", {"mechanism": m, "params": p, "load": {"force": 1, "f": f, "beta": 0.5}, "omega": 3.0,
                     "inertias": {"J1": 1, "m3": 1, "J3": 1}, "outputs": ["resisting", "inertia"]}, f"reduction-{m}-{p}-f{f}")
      for m, p in (("sine", {"l1": 1}), ("slider_crank", {"l1": 1, "l2": 1.02}), ("slotted_link", {"l0": 1, "l1": 1}))
      for f in (0.0, 0.99, 1.5)],
    *[("elastic", ELASTIC | {"c": c, "b": b, "outputs": ["histories"]}, f"elastic-c{c:g}-b{b:g}")
      for c, b in ((1e2, 0.0), (1e5, 0.0), (1e8, 1e5))],
    ("elastic", ELASTIC | {"c": 1e5, "b": 5.0, "load": {"force": 2000, "return_factor": 0.2}, "outputs": ["histories"]},
     "elastic-frictionless"),
    ("elastic", STILL_TWO_MASS, "elastic-no-input-work"),
    ("elastic", ELASTIC | {"model": "elastic_linkage", "compliances": {"e1": 1e-6, "e2": 1e-9}, "b": 100.0,
                           "outputs": ["histories", "modal"]}, "elastic-linkage"),
    *[("forces", FORCES | {"pairs": {"f12": f, "f23": f, "f34": f, "f14": f}}, f"forces-f{f}") for f in (0.0, 0.3, 0.9)],
    ("forces", FORCES | {"pairs": {"f34": 0.8}}, "forces-slow-iteration"),
    ("angular-acceleration", {"lam": 0.999, "law": "harmonic", "amplitude": 0.9, "n": 2001}, "angular-near-locking"),
    ("angular-acceleration", {"mechanism": "trammel", "law": "accelerating", "epsilon0": 3.0}, "trammel"),
]


def numerics_and_efficiencies(value, path="answer"):
    """(path, kind, item) for every numerics dict and every efficiency anywhere in an answer."""
    if isinstance(value, dict):
        for key, item in value.items():
            where = f"{path}.{key}"
            if key == "numerics" and isinstance(item, dict):
                yield where, "numerics", item
            elif key == "efficiency":
                yield where, "efficiency", item
            else:
                yield from numerics_and_efficiencies(item, where)
    elif isinstance(value, list):
        for i, item in enumerate(value):
            if isinstance(item, (dict, list)):
                yield from numerics_and_efficiencies(item, f"{path}[{i}]")


def beyond_meaning(data: dict) -> list[str]:
    """The diagnostics of an answer that exceed their physical meaning, each in words."""
    problems, words = [], bool(data.get("warnings"))
    for where, kind, item in numerics_and_efficiencies(data):
        if kind == "efficiency":
            for eta in item if isinstance(item, list) else [item]:
                if eta is None and not words:
                    problems.append(f"{where}: η null without a warning saying why")
                elif eta is not None and not 0.0 <= eta <= 1.0:
                    problems.append(f"{where}: η = {eta!r} outside [0, 1]")
            continue
        estimate, residual = item.get("error_estimate"), item.get("energy_residual")
        said = words or bool(item.get("message"))
        if estimate is None and not said:
            problems.append(f"{where}.error_estimate: null without words")
        elif estimate is not None and not (isinstance(estimate, (int, float)) and estimate >= 0):
            problems.append(f"{where}.error_estimate = {estimate!r}, not a number ≥ 0")
        if residual is not None and not 0.0 <= residual <= 1.0:
            problems.append(f"{where}.energy_residual = {residual!r} outside [0, 1]")
        if item.get("runtime_ms") is not None and item["runtime_ms"] < 0:
            problems.append(f"{where}.runtime_ms = {item['runtime_ms']!r} < 0")
    return problems


@pytest.mark.parametrize("endpoint, body", [(e, b) for e, b, _ in GRID], ids=[name for _, _, name in GRID])
def test_no_diagnostic_exceeds_its_physical_meaning(endpoint, body):
    data = strict(client.post(f"/api/v1/{endpoint}", json=body))
    assert "detail" not in data, data["detail"]                      # every grid point is a valid request
    assert no_non_finite(data)
    assert beyond_meaning(data) == []


def test_the_grid_check_itself_flags_what_it_should():
    """The checker against hand-made answers (so that a pass above means something)."""
    assert beyond_meaning({"numerics": {"error_estimate": 1e-9, "energy_residual": 0.5}, "efficiency": 1.0}) == []
    assert len(beyond_meaning({"numerics": {"error_estimate": None, "energy_residual": 3.5e294, "message": ""},
                               "startup": {"numerics": {"error_estimate": -1.0}}, "efficiency": 1.0000005})) == 4
    assert beyond_meaning({"numerics": {"error_estimate": None, "message": "one level only"}}) == []
