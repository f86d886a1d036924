"""The first estimate of a student's own mechanism's masses, loads and motor (server/core/structure/estimate.py,
POST /api/v1/dynamics-estimate): uniform bars against the linkage's own lengths and joints, every moving link
present, and the default machine of every crank-driven preset and of a hand-built six-bar starting from rest
and reaching a steady cycle whose energy balance closes to 1e-8 of the driving work."""
from __future__ import annotations

import copy
import math

import numpy as np
import pytest
from fastapi.testclient import TestClient

from server.api.app import app
from server.api.endpoints import compute
from server.api.schemas_dynamics import MotionRequest
from server.core.structure.compose import compose
from server.core.structure.masses import check_model
from server.core.structure.estimate import BAR_DENSITY, BLOCK_MASS, OMEGA_TARGET, estimated_dynamics
from server.core.structure.presets import presets
from server.core.structure.spec import parse

CRANK_DRIVEN = sorted(name for name, p in presets().items() if p["linkage"]["input"].get("kind") != "slider")

# A six-bar built by hand (not a preset): crank O–A, an RRR dyad A–B–C on the frame joint C, then an RRP dyad
# from B's link to a slider on a horizontal frame guide.
HAND_BUILT = {
    "frame": {"joints": {"O": [0.0, 0.0], "C": [0.28, -0.05]}, "guides": {"g": {"through": [0.0, 0.32], "angle": 0}}},
    "input": {"link": 1, "pivot": "O", "joint": "A", "length": 0.08},
    "groups": [
        {"kind": "RRR", "links": [2, 3], "outer": ["A", "C"], "inner": "B", "lengths": [0.3, 0.25], "branch": 1,
         "points": {"D": {"link": 3, "along": 0.4}}},
        {"kind": "RRP", "links": [4, 5], "outer": ["D"], "guide": "g", "inner": "E", "length": 0.2, "branch": 1},
    ],
}


def by_link(estimate: dict) -> dict[int, dict]:
    return {row["link"]: row for row in estimate["masses"]["links"]}


def test_uniform_bars_against_the_linkages_lengths():
    """Four-bar: the coupler (0.35 m… as the preset writes it) and the rocker are bars of q·l, S at mid-length,
    J_S = ml²/12; the crank J₁ = q l³/3."""
    linkage = presets()["four_bar"]["linkage"]
    rows = by_link(estimated_dynamics(linkage))
    coupler, rocker = linkage["groups"][0]["lengths"]
    for link, length in ((2, coupler), (3, rocker)):
        mass = BAR_DENSITY * length
        assert rows[link]["mass"] == pytest.approx(mass, rel=1e-5)
        assert rows[link]["centre"] == pytest.approx([length / 2, 0.0], abs=1e-6)
        assert rows[link]["inertia"] == pytest.approx(mass * length ** 2 / 12, rel=1e-5)
    l1 = linkage["input"]["length"]
    assert estimated_dynamics(linkage)["inertias"]["J1"] == pytest.approx(BAR_DENSITY * l1 ** 3 / 3, rel=1e-5)


@pytest.mark.parametrize("name", ["shaping_machine", "four_bar"])
def test_centre_is_the_middle_between_the_links_joints(name):
    """S of each bar, placed by the link's frame, lies in the middle between two joints of the composition (the
    link's origin and its farthest joint), at every crank angle; a block (one joint) has S on its joint."""
    linkage = presets()[name]["linkage"]
    comp = compose(parse(linkage), np.linspace(0.3, 6.0, 7))
    points = [p.z for p in comp.joints.values()]
    for link, row in by_link(estimated_dynamics(linkage)).items():
        origin, angle = comp.links[link]
        s = origin.z + complex(*row["centre"]) * np.exp(1j * angle.th)
        if row["mass"] == BLOCK_MASS and row["inertia"] == 0:
            assert any(np.allclose(s, z, atol=1e-9) for z in points)
            continue
        assert any(np.allclose(s, (a + b) / 2, atol=1e-9) for a in points for b in points), link


@pytest.mark.parametrize("name", CRANK_DRIVEN)
def test_every_moving_link_has_a_mass(name):
    linkage = parse(presets()[name]["linkage"])
    moving = set(compose(linkage, np.zeros(1)).links) - {linkage.crank.link}
    assert set(by_link(estimated_dynamics(presets()[name]["linkage"]))) == moving


def machine(linkage: dict, estimate: dict, **extra) -> dict:
    body = {"mechanism": "general", "linkage": linkage, "masses": estimate["masses"],
            "inertias": estimate["inertias"], "motor": estimate["motor"], "rtol": 1e-10, **extra}
    MotionRequest.model_validate(body | {"outputs": ["steady"]})    # what the API accepts
    return body


@pytest.mark.parametrize("name", [*CRANK_DRIVEN, "hand built"])
def test_the_estimated_machine_starts_and_reaches_a_steady_cycle(name):
    linkage = HAND_BUILT if name == "hand built" else presets()[name]["linkage"]
    estimate = estimated_dynamics(linkage)
    assert estimate["masses"]["forces"] or estimate["masses"]["moments"]       # a useful load to carry
    answer = compute("motion", machine(linkage, estimate, outputs=["steady", "startup"], omega0=0.0))
    assert answer["warnings"] == []
    assert answer["omega_mean"] == pytest.approx(OMEGA_TARGET, rel=0.1)      # the motor sized for ω_target
    assert 0 < answer["delta"] < 0.25
    works = answer["works"]
    assert works["useful"] > 0
    balance = works["driving"] - works["useful"] - works["dry_friction"] - works["viscous_friction"]
    assert abs(balance) <= 1e-8 * works["driving"], works
    startup = answer["startup"]                       # from rest onto the cycle: the motor carries the load
    assert startup["omega"][0] == 0 and min(startup["omega"][1:]) > 0
    assert startup["omega"][-1] == pytest.approx(np.interp(startup["phi"][-1] % (2 * math.pi), answer["phi"],
                                                           answer["omega"]), rel=1e-3)


def test_flywheel_of_the_estimate():
    linkage = presets()["shaping_machine"]["linkage"]
    estimate = estimated_dynamics(linkage)
    body = {"mechanism": "general", "linkage": linkage, "masses": estimate["masses"],
            "inertias": estimate["inertias"], **estimate["flywheel"]}
    answer = compute("flywheel", body)
    assert answer["warnings"] == [] and answer["flywheel_inertia"] >= 0


@pytest.mark.parametrize("name", [*CRANK_DRIVEN, "hand built"])
def test_a_load_may_stand_on_every_sliding_pair_and_every_moving_link(name):
    """The places the editor offers for a load are the kinematics' `slides` (as masses.forces.joint names them)
    and every moving link, the crank included; the estimate's own load is one of them, as offered."""
    linkage = HAND_BUILT if name == "hand built" else presets()[name]["linkage"]
    comp = compose(parse(linkage), np.zeros(1))
    estimate = estimated_dynamics(linkage)
    places = estimate["load_places"]
    assert [f["joint"] for f in places["forces"]] == list(comp.slides)
    assert [m["link"] for m in places["moments"]] == sorted(comp.links)
    for load in estimate["masses"]["forces"]:
        assert load in places["forces"]
    for load in estimate["masses"]["moments"]:
        assert load in places["moments"]
    body = machine(linkage, {**estimate, "masses": estimate["masses"] | places})
    check_model(comp, MotionRequest.model_validate(body | {"outputs": ["steady"]}).masses.model())   # the API's check


def test_a_moment_on_the_shaping_machines_rocker_does_its_work_over_the_swing():
    """The rocker (link 3) of the shaping machine swings through 2·asin(l₁/OC) each way (the crank 0.1 m, the
    rocker's pivot C 0.3 m below O, its slot through the crank pin): a load moment M on it, k·M on the return, does
    M·2·asin(1/3)·(1 + k) of useful work per cycle, whichever stroke is the working one."""
    linkage = presets()["shaping_machine"]["linkage"]
    estimate = estimated_dynamics(linkage)
    offered = next(m for m in estimate["load_places"]["moments"] if m["link"] == 3)
    for sense in (1, -1):
        load = offered | {"working": 400.0, "k": 0.25, "sense": sense}
        masses = estimate["masses"] | {"forces": [], "moments": [load]}
        answer = compute("motion", machine(linkage, {**estimate, "masses": masses}, outputs=["steady"]))
        assert answer["works"]["useful"] == pytest.approx(400.0 * 2 * math.asin(1 / 3) * 1.25, rel=1e-6)


def test_endpoint_answers_the_estimate_and_refuses_a_slider_input():
    client = TestClient(app)
    linkage = copy.deepcopy(HAND_BUILT)
    answer = client.post("/api/v1/dynamics-estimate", json={"linkage": linkage})
    assert answer.status_code == 200
    assert by_link(answer.json()) == by_link(estimated_dynamics(linkage))
    assert answer.json()["load_places"] == estimated_dynamics(linkage)["load_places"]
    refused = client.post("/api/v1/dynamics-estimate?lang=uk",
                          json={"linkage": presets()["slider_driven_crank"]["linkage"]})
    assert refused.status_code == 422
    assert refused.json()["detail"][0]["loc"][-1] == "kind"
