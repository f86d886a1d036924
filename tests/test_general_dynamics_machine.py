"""The general mechanism through the equation of motion, the flywheel and the API.

- The crank-slider and the four-bar as general linkages (their presets) with the dedicated modules' masses and
  loads reproduce today's dedicated machine: tables J, dJ/dφ, M_c, S(φ), the steady cycle, the start-up and the
  flywheel to 1e-10 (relative; both are closed forms integrated by the same integrator: only round-off differs).
- Every six-bar preset opens with its own masses and loads: a steady cycle whose energy balance over the cycle
  is ≤ 1e-8 of the driving work (recomputed here from the returned works), and a flywheel whose exact inertia
  achieves [δ].
- Bad input answers 422 naming the field.
"""
from __future__ import annotations

import numpy as np
import pytest
from fastapi.testclient import TestClient

from server.api.app import app
from server.api.endpoints import compute

from server.core.structure.presets import presets

SIX_BARS = sorted(name for name, preset in presets().items() if "dynamics" in preset)

DEDICATED = {
    "slider_crank": ({"J1": 0.05, "m2": 2.0, "J_S2": 0.02, "m3": 3.0}, {"force": 500.0, "return_factor": 0.2},
                     {"links": [{"link": 2, "mass": 2.0, "centre": [0.096, 0.0], "inertia": 0.02},
                                {"link": 3, "mass": 3.0}], "gravity": 0.0,
                      "forces": [{"joint": "B", "working": 500.0, "k": 0.2}]}),
    "four_bar": ({"J1": 0.05, "m2": 1.5, "J_S2": 0.03, "J3": 0.04}, {"force": 40.0, "return_factor": 0.3},
                 {"links": [{"link": 2, "mass": 1.5, "centre": [0.175, 0.0], "inertia": 0.03},
                            {"link": 3, "mass": 0.0, "inertia": 0.04}], "gravity": 0.0,
                  "moments": [{"link": 3, "working": 40.0, "k": 0.3}]}),
}
ROTOR = {"J_rotor": 0.01, "gear_ratio": 3.0}


def pair(name: str, beta: float, **extra):
    inertias, load, masses = DEDICATED[name]
    dedicated = {"mechanism": name, "inertias": inertias | ROTOR, "load": load | {"beta": beta}, **extra}
    general = {"mechanism": "general", "linkage": presets()[name]["linkage"], "masses": masses,
               "inertias": {"J1": inertias["J1"]} | ROTOR, "load": {"beta": beta}, **extra}
    return dedicated, general


def agree(a, b, path="", scale=0.0):
    """Every number of two answers equal to 1e-10 of the largest magnitude of its array, or of the numbers beside
    it (a difference such as works.net is measured against the works it is the difference of)."""
    if isinstance(a, dict):
        assert set(a) == set(b), path
        beside = max([abs(v) for v in a.values() if isinstance(v, float)] + [0.0])
        for key in a:
            if key not in ("numerics", "warnings"):
                agree(a[key], b[key], f"{path}.{key}", beside)
    elif isinstance(a, list) and a and isinstance(a[0], dict):
        assert len(a) == len(b), path
        for k, (x, y) in enumerate(zip(a, b)):
            agree(x, y, f"{path}.{k}")
    elif isinstance(a, list) and a and not isinstance(a[0], str):
        x, y = np.asarray(a, float), np.asarray(b, float)
        assert x.shape == y.shape, path
        same_numbers(x, y, path)
    elif isinstance(a, float):
        assert abs(a - b) <= 1e-10 * max(abs(a), scale, 1e-300), (path, a, b)
    else:
        assert a == b, path


def same_numbers(x: np.ndarray, y: np.ndarray, path: str) -> None:
    """Two arrays of an answer: null (no value, sent for what does not exist, e.g. ω before the flywheel where the
    machine stalls without it) in exactly the same places, and every number equal to 1e-10 of the largest
    magnitude among the numbers (a finite tolerance: no NaN reaches the comparison)."""
    missing = np.isnan(x)
    assert np.array_equal(missing, np.isnan(y)), (path, "null in different places")
    if missing.all():
        return
    tolerance = 1e-10 * max(float(np.max(np.abs(x[~missing]))), 1e-300)
    assert np.isfinite(tolerance), path
    assert np.max(np.abs(x[~missing] - y[~missing])) <= tolerance, path


def stall_curve_as_stated(answer: dict) -> None:
    """ω before the flywheel is null exactly where the answer says the machine stalls without it, and numbers
    everywhere else; ω after the flywheel is numbers throughout."""
    stalls = any("the machine cannot run" in warning for warning in answer["warnings"])     # notice stall_in_cycle
    before, after = answer["curves"]["omega_before"], answer["curves"]["omega_after"]
    assert set(before) == {None} if stalls else None not in before, (stalls, before[:3])
    assert None not in after


@pytest.mark.parametrize("name", sorted(DEDICATED))
def test_motion_through_the_general_path(name):
    dedicated, general = pair(name, beta=2.0, motor={"kind": "linear", "M0": 60.0, "b": 1.0},
                              outputs=["steady", "startup"], omega0=1.0)
    agree(compute("motion", dedicated), compute("motion", general))


@pytest.mark.parametrize("name", sorted(DEDICATED))
def test_flywheel_through_the_general_path(name):
    dedicated, general = pair(name, beta=0.0, motor={"kind": "constant", "M0": 30.0}, omega_mean=12.0, delta=0.04)
    a, b = compute("flywheel", dedicated), compute("flywheel", general)
    assert a["methods"] and a["warnings"] == b["warnings"]
    stall_curve_as_stated(a)
    stall_curve_as_stated(b)
    agree(a, b)


@pytest.mark.parametrize("name", sorted(DEDICATED))
def test_reduction_through_the_general_path(name):
    dedicated, general = pair(name, beta=0.5, outputs=["inertia", "resisting"], n=181, omega=3.0)
    a, b = compute("reduction", dedicated), compute("reduction", general)
    for key in ("J", "dJ", "mean"):
        agree(a["inertia"][key], b["inertia"][key])
    for key in ("total", "useful", "viscous"):
        agree(a["resisting"][key], b["resisting"][key])
    means_agree(a, b)
    assert sum(np.asarray(p) for p in b["inertia"]["parts"].values()) == pytest.approx(np.asarray(b["inertia"]["J"]),
                                                                                       rel=1e-14)


def means_agree(a: dict, b: dict) -> None:
    """M_c0 of two reductions within their error estimates (relative to the cycle mean of |M_c|, here of the
    dedicated M_c on its closed grid): the dedicated machine's trapezoid rule and the general machine's
    Gauss–Legendre between the kinks are different rules (tests/test_general_cycle_mean.py: the latter against
    scipy.integrate.quad)."""
    scale = float(np.mean(np.abs(np.asarray(a["resisting"]["total"])[:-1])))
    allowed = (a["numerics"]["error_estimate"] + b["numerics"]["error_estimate"]) * scale * 1.01
    assert abs(a["resisting"]["mean"] - b["resisting"]["mean"]) <= allowed + 1e-13 * scale


def preset_body(name: str, **extra) -> dict:
    dynamics = presets()[name]["dynamics"]
    return {"mechanism": "general", "linkage": presets()[name]["linkage"], "masses": dynamics["masses"],
            "inertias": dynamics["inertias"], **extra}


@pytest.mark.parametrize("name", SIX_BARS)
def test_preset_steady_cycle_and_flywheel(name):
    dynamics = presets()[name]["dynamics"]
    steady = compute("motion", preset_body(name, motor=dynamics["motor"], outputs=["steady"], rtol=1e-10))
    assert steady["warnings"] == [] and steady["omega_mean"] > 0
    works = steady["works"]
    balance = works["driving"] - works["useful"] - works["dry_friction"] - works["viscous_friction"]
    assert abs(balance) <= 1e-8 * works["driving"], works
    fly = compute("flywheel", preset_body(name, **dynamics["flywheel"]))
    assert fly["warnings"] == [] and fly["flywheel_inertia"] > 0
    exact = fly["methods"][-1]
    assert exact["method"] == "exact" and exact["delta_achieved"] == pytest.approx(dynamics["flywheel"]["delta"],
                                                                                   rel=1e-8)


@pytest.fixture(scope="module")
def client():
    with TestClient(app) as c:
        yield c


def refused(client, endpoint, body, loc, words):
    answer = client.post(f"/api/v1/{endpoint}", json=body)
    assert answer.status_code == 422, answer.text[:300]
    detail = answer.json()["detail"][0]
    assert detail["loc"][:len(loc)] == loc and words in detail["msg"], detail


def test_bad_general_requests(client):
    name = "shaping_machine"
    motor = presets()[name]["dynamics"]["motor"]
    good = preset_body(name, motor=motor, outputs=["steady"])
    masses = good["masses"]
    refused(client, "motion", {**good, "masses": {**masses, "links": [{"link": 9, "mass": 1.0}]}},
            ["body", "masses", "links", "0", "link"], "no moving link 9")
    refused(client, "motion", {**good, "masses": {**masses, "forces": [{"joint": "Q", "working": 1.0}]}},
            ["body", "masses", "forces", "0", "joint"], "no sliding pair")
    refused(client, "motion", {**good, "load": {"force": 100.0}}, ["body", "load", "force"], "masses")
    refused(client, "motion", {k: v for k, v in good.items() if k != "linkage"}, ["body"], "linkage")
    refused(client, "motion", {**good, "mechanism": "slider_crank", "linkage": None}, ["body"], "masses")
    refused(client, "motion", {**good, "masses": {**masses, "links": [{"link": 3, "mass": -1.0}]}},
            ["body", "masses", "links", 0, "mass"], "greater than or equal")
    crossing = {**good["linkage"], "groups": [{**good["linkage"]["groups"][0]},
                                              {**good["linkage"]["groups"][1], "length": 0.01}]}
    refused(client, "flywheel", {**preset_body(name, **presets()[name]["dynamics"]["flywheel"]), "linkage": crossing},
            ["body", "linkage", "groups", "1"], "cannot be assembled")
