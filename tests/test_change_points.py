"""Change points of a general mechanism (server/core/structure/change_points.py) through every endpoint, against
closed forms that do not come from the code under test.

A parallelogram four-bar (frame 0.3 = coupler, crank 0.1 = rocker) has change points at φ = 0 and 180°: all
four joints in line, the two assemblies (parallelogram, antiparallelogram) meet.  Drawn as a parallelogram it
moves as one through both: θ₃ = φ, θ₂ = 0, so θ₃′ = 1, θ₂′ = 0 and every θ″ = 0.  With the estimate's masses
(server/core/structure/estimate.py: bars m₂ = 3 kg, S₂ at the coupler's middle, m₃ = 1 kg, S₃ at 0.05 m,
J_S3 = 1/1200 kg·m², a moment of 50 N·m on the rocker) the coupler translates with the crank pin:

    J(φ) = J_rotor·i² + J₁ + m₂l₁² + J_S3 + m₃c₃²  (constant),   dJ/dφ = 0,
    M_c(φ) = 50·θ₃′ + g(m₂ dy_S2/dφ + m₃ dy_S3/dφ) = 50 + g(m₂l₁ + m₃c₃) cos φ,   M_c0 = 50 N·m.

A Grashof-limit crank-rocker (l₀ + l₁ = l₂ + l₃: 4, 1, 3, 2) has one change point, at 180°; through it the
general mechanism must move as the four-bar module's closed form of the special four-bar (Eremyants (2.53),
half-angle form, the rocker passing through: FourBar with limiter 0) does.

Before the fix: θ₃′ = 1.07·10¹⁶ and θ″ ≈ 10⁶⁴ at 180° as numbers, a dead position at 359.5°, the antiparallelogram
past 180°, J(180°) ≈ 10³⁰ and θ₃′(π) ≈ −6·10¹⁵ on the crank-rocker.
"""
from __future__ import annotations

import math

import numpy as np
import pytest
from fastapi.testclient import TestClient

from server.api.app import app
from server.core.mechanisms import MECHANISMS
from server.core.structure.estimate import estimated_dynamics

G = 9.81
N = 721                                    # the grid: 0.5°, so 0°, 180° and 360° are grid points
PARALLELOGRAM = {"frame": {"joints": {"O": [0, 0], "C": [0.3, 0]}},
                 "input": {"link": 1, "pivot": "O", "joint": "A", "length": 0.1},
                 "groups": [{"kind": "RRR", "links": [2, 3], "outer": ["A", "C"], "inner": "B",
                             "lengths": [0.3, 0.1], "branch": 1}]}
CRANK_ROCKER = {"frame": {"joints": {"O": [0, 0], "C": [4, 0]}},
                "input": {"link": 1, "pivot": "O", "joint": "A", "length": 1},
                "groups": [{"kind": "RRR", "links": [2, 3], "outer": ["A", "C"], "inner": "B",
                            "lengths": [3, 2], "branch": 1}]}
CHANGE = [0, 360, 720]                     # grid indices of 0°, 180°, 360°


@pytest.fixture(scope="module")
def client():
    with TestClient(app) as c:
        yield c


def array(values) -> np.ndarray:
    return np.array([np.nan if v is None else v for v in values], float)


def ok(answer) -> dict:
    assert answer.status_code == 200, answer.text[:400]
    assert "NaN" not in answer.text and "Infinity" not in answer.text
    return answer.json()


def change_point_warnings(warnings: list[str]) -> list[str]:
    return [w for w in warnings if "change point at" in w]


def kinematics(client, linkage):
    return ok(client.post("/api/v1/kinematics?precision=full", json={"mechanism": "general", "linkage": linkage, "n": N, "outputs": [
        "angles", "angles_d1", "angles_d2", "joints_d1", "special"]}))


def test_parallelogram_kinematics_null_at_the_change_points_and_a_parallelogram_throughout(client):
    answer = kinematics(client, PARALLELOGRAM)
    phi = np.array(answer["phi"])
    out = answer["outputs"]
    undefined = np.zeros(N, bool)
    undefined[CHANGE] = True
    for name in ("angles_d1", "angles_d2"):
        for link in ("2", "3"):
            values = array(out[name][link])
            assert np.array_equal(np.isnan(values), undefined), (name, link, np.flatnonzero(np.isnan(values)))
    # the closed form of the parallelogram: θ₃ = φ, θ₂ = 0 over the whole turn (not the antiparallelogram past 180°)
    np.testing.assert_allclose(array(out["angles"]["3"]), phi, rtol=0, atol=1e-12)
    np.testing.assert_allclose(np.mod(array(out["angles"]["2"]) + 1, 2 * np.pi) - 1, 0, rtol=0, atol=1e-12)
    fine = ~undefined
    np.testing.assert_allclose(array(out["angles_d1"]["3"])[fine], 1.0, rtol=0, atol=1e-9)
    np.testing.assert_allclose(array(out["angles_d1"]["2"])[fine], 0.0, rtol=0, atol=1e-9)
    for link in ("2", "3"):                # every θ″ = 0; the round-off is bounded by the neighbourhood's 1e-6
        assert np.nanmax(np.abs(array(out["angles_d2"][link]))) <= 1e-6
    # every number within its physical bound (|θ′| ≤ 1, the points' analogs ≤ the crank's length)
    for joint, values in out["joints_d1"].items():
        assert np.nanmax(np.abs(np.array(values, dtype=float)[fine])) <= 0.1 + 1e-9, joint
    # the warnings name both change points (and the branch kept), the special positions have no dead position
    said = change_point_warnings(answer["warnings"])
    assert len(said) == 2 and "φ = 0.0°" in said[0] and "φ = 180.0°" in said[1], answer["warnings"]
    assert "σ = −1" in said[1] and "parallelogram stays a parallelogram" in said[1]
    kinds = [(s["kind"], round(math.degrees(s["phi"]), 6)) for s in out["special"]]
    assert ("change_point", 0.0) in kinds and ("change_point", 180.0) in kinds, kinds
    assert not [k for k in kinds if k[0] == "dead_position"], kinds


def test_parallelogram_warnings_in_russian_name_the_change_points(client):
    answer = ok(client.post("/api/v1/kinematics?lang=ru&precision=full", json={"mechanism": "general", "linkage": PARALLELOGRAM,
                                                                "n": N, "outputs": ["angles_d1"]}))
    said = [w for w in answer["warnings"] if "смены сборки" in w]
    assert len(said) == 2 and "φ = 0,0°" in said[0] and "φ = 180,0°" in said[1], answer["warnings"]


def test_grashof_limit_crank_rocker_moves_as_the_four_bars_closed_form(client):
    answer = kinematics(client, CRANK_ROCKER)
    phi = np.array(answer["phi"])
    theta3, d1 = array(answer["outputs"]["angles"]["3"]), array(answer["outputs"]["angles_d1"]["3"])
    assert np.flatnonzero(np.isnan(d1)).tolist() == [360]               # null at 180° only
    four_bar = MECHANISMS["four_bar"]
    closed = None
    for assembly in (1, -1):
        params = four_bar.check({"l0": 4, "l1": 1, "l2": 3, "l3": 2, "assembly": assembly, "limiter": 0})
        ev = four_bar.evaluate(params, phi, set())
        if abs(ev.values["u31"][180] - d1[180]) < 1e-9:
            closed = ev
    assert closed is not None
    fine = ~np.isnan(d1)
    np.testing.assert_allclose(d1[fine], closed.values["u31"][fine], rtol=0, atol=1e-9)
    np.testing.assert_allclose(np.unwrap(theta3), closed.values["s"] - closed.values["s"][0] + theta3[0], atol=1e-9)
    assert np.nanmax(np.abs(d1)) < 0.7                              # Eremyants: |u₃₁| ≤ 0.6899
    said = change_point_warnings(answer["warnings"])
    assert len(said) == 1 and "φ = 180.0°" in said[0]
    assert any("odd number of change points" in w for w in answer["warnings"])


def test_grashof_limit_crank_rocker_is_no_machine(client):
    """Continued through its one change point a turn it comes back to its start after two turns: the dynamics
    refuse it as they refuse a crank that cannot turn fully, naming the group."""
    masses = estimated_dynamics(PARALLELOGRAM)
    body = {"mechanism": "general", "linkage": CRANK_ROCKER, "masses": masses["masses"],
            "inertias": masses["inertias"], "outputs": ["inertia"]}
    answer = client.post("/api/v1/reduction?precision=full", json=body)
    assert answer.status_code == 422
    detail = answer.json()["detail"][0]
    assert detail["loc"] == ["body", "linkage", "groups", "0"] and detail["ctx"]["code"] == "change_point_odd"


def closed_form(phi: np.ndarray, estimate: dict) -> tuple[float, np.ndarray]:
    """J and M_c(φ) of the parallelogram with the estimate's masses (module docstring)."""
    links = {row["link"]: row for row in estimate["masses"]["links"]}
    inertias = estimate["inertias"]
    l1, c3 = 0.1, links[3]["centre"][0]
    m2, m3 = links[2]["mass"], links[3]["mass"]
    inertia = (inertias["J_rotor"] * inertias["gear_ratio"] ** 2 + inertias["J1"] + m2 * l1**2
               + links[3]["inertia"] + m3 * c3**2)
    working = estimate["masses"]["moments"][0]["working"]
    return inertia, working + G * (m2 * l1 + m3 * c3) * np.cos(phi)


@pytest.fixture(scope="module")
def estimate():
    found = estimated_dynamics(PARALLELOGRAM)
    assert found["masses"]["moments"][0]["link"] == 3 and found["masses"]["moments"][0]["sense"] == 1
    return found


def machine_body(estimate: dict) -> dict:
    return {"mechanism": "general", "linkage": PARALLELOGRAM, "masses": estimate["masses"],
            "inertias": estimate["inertias"]}


def test_parallelogram_reduction_nulls_at_change_points_and_the_closed_form_elsewhere(client, estimate):
    answer = ok(client.post("/api/v1/reduction?precision=full", json={**machine_body(estimate), "n": N,
                                                       "outputs": ["inertia", "resisting"]}))
    phi = np.array(answer["phi"])
    inertia, moment = closed_form(phi, estimate)
    J, dJ = array(answer["inertia"]["J"]), array(answer["inertia"]["dJ"])
    total = array(answer["resisting"]["total"])
    for values in (J, dJ, total):
        assert np.flatnonzero(np.isnan(values)).tolist() == CHANGE
    fine = ~np.isnan(J)
    np.testing.assert_allclose(J[fine], inertia, rtol=1e-9)
    np.testing.assert_allclose(dJ[fine], 0.0, rtol=0, atol=1e-9 * inertia)
    np.testing.assert_allclose(total[fine], moment[fine], rtol=1e-9)
    # the means integrate the continuing motion's limit: M_c0 = 50 N·m, J's mean the constant
    assert answer["resisting"]["mean"] == pytest.approx(50.0, rel=1e-9)
    assert answer["inertia"]["mean"] == pytest.approx(inertia, rel=1e-9)
    assert len(change_point_warnings(answer["warnings"])) == 2
    assert any("limit" in w for w in answer["warnings"])


def test_parallelogram_motion_flywheel_and_forces_agree(client, estimate):
    body = machine_body(estimate)
    inertia, _ = closed_form(np.zeros(1), estimate)
    steady = ok(client.post("/api/v1/motion?precision=full", json={**body, "motor": estimate["motor"], "outputs": ["steady"],
                                                   "rtol": 1e-10}))
    works = steady["works"]
    assert works["useful"] == pytest.approx(2 * np.pi * 50.0, rel=1e-8)        # M_c0 over a turn
    assert works["driving"] == pytest.approx(works["useful"], rel=1e-8)
    assert np.isfinite(steady["omega"]).all() and steady["omega_mean"] > 0
    fly = ok(client.post("/api/v1/flywheel?precision=full", json={**body, **estimate["flywheel"]}))
    for said in (steady["warnings"], fly["warnings"]):               # the change points and the limit, said
        assert len(change_point_warnings(said)) == 2 and any("limit" in w for w in said), said
    assert fly["group_i_existing"] == pytest.approx(inertia - 0.03 - links_variable(estimate), rel=1e-6)
    forces = ok(client.post("/api/v1/forces?precision=full", json={"mechanism": "general", "linkage": PARALLELOGRAM,
                                                    "masses": estimate["masses"], "loads": {"omega": 10.0},
                                                    "n": N}))
    phi = np.array(forces["phi"])
    _, moment = closed_form(phi, estimate)
    reduced, balancing = array(forces["reduced_moment"]), array(forces["balancing_moment"])
    assert np.flatnonzero(np.isnan(reduced)).tolist() == CHANGE
    assert np.flatnonzero(np.isnan(balancing)).tolist() == CHANGE
    fine = ~np.isnan(reduced)
    np.testing.assert_allclose(reduced[fine], moment[fine], rtol=1e-9)
    assert len(change_point_warnings(forces["warnings"])) == 2


def links_variable(estimate: dict) -> float:
    """The links' part of J that the flywheel's constant group I_I leaves out: the rocker's J_S3 + m₃c₃² (its
    θ₃′ = 1 is constant too, but the lecture's group I holds the crank and rotor only)."""
    links = {row["link"]: row for row in estimate["masses"]["links"]}
    return links[3]["inertia"] + links[3]["mass"] * links[3]["centre"][0] ** 2


def test_four_bar_module_parallelogram_names_both_change_points_and_turns_once():
    """The four-bar module's parallelogram (P₀ = Q₀ = 0): its half-angle branch passes both change points, 0 and
    180°, and is periodic over one turn; drawn as a parallelogram (assembly −1) u₃₁ = 1, u′₃₁ = 0 throughout."""
    four_bar = MECHANISMS["four_bar"]
    params = four_bar.check({"l0": 0.3, "l1": 0.1, "l2": 0.3, "l3": 0.1, "assembly": -1, "limiter": 0})
    assert four_bar.cycle(params) == pytest.approx(2 * np.pi)
    points = [round(math.degrees(sp.phi), 9) for sp in four_bar.special_positions(params) if sp.kind == "change_point"]
    assert points == [0.0, 180.0]
    ev = four_bar.evaluate(params, np.linspace(0.0, 2 * np.pi, N), set())
    np.testing.assert_allclose(ev.values["u31"], 1.0, rtol=0, atol=1e-12)
    np.testing.assert_allclose(ev.values["du31"], 0.0, rtol=0, atol=1e-12)


def test_isosceles_crank_slider_moves_on_through_its_change_points(client):
    """An RRP group: crank = rod = 0.1 m, the guide through the crank's pivot. At φ = 90° and 270° the rod stands
    across the guide with the slider on the pivot, where the slider could also stay (the other assembly); kept on
    its motion the slider runs s = 2l₁cos φ (closed form), its analogs null at those two angles only."""
    linkage = {"frame": {"joints": {"O": [0, 0]}, "guides": {"g": {"through": [0, 0], "angle": 0}}},
               "input": {"link": 1, "pivot": "O", "joint": "A", "length": 0.1},
               "groups": [{"kind": "RRP", "links": [2, 3], "outer": ["A"], "guide": "g", "inner": "B",
                           "length": 0.1, "branch": 1}]}
    answer = ok(client.post("/api/v1/kinematics?precision=full", json={
        "mechanism": "general", "linkage": linkage, "n": N, "outputs": ["slides", "slides_d1", "slides_d2"]}))
    phi = np.array(answer["phi"])
    s, s1, s2 = (array(answer["outputs"][name]["B/g"]) for name in ("slides", "slides_d1", "slides_d2"))
    assert np.flatnonzero(np.isnan(s1)).tolist() == [180, 540] == np.flatnonzero(np.isnan(s2)).tolist()
    np.testing.assert_allclose(s, 0.2 * np.cos(phi), rtol=0, atol=1e-12)
    fine = ~np.isnan(s1)
    np.testing.assert_allclose(s1[fine], -0.2 * np.sin(phi[fine]), rtol=0, atol=1e-9)
    np.testing.assert_allclose(s2[fine], -0.2 * np.cos(phi[fine]), rtol=0, atol=1e-9)
    said = change_point_warnings(answer["warnings"])
    assert len(said) == 2 and "φ = 90.0°" in said[0] and "φ = 270.0°" in said[1]
