"""The course project (POST /api/v1/course-project, server/core/course_project/) on the shaping machine preset:

- Zhukovsky's lever gives the balancing moment the groups' equilibrium gives, at every position, without friction
  and with friction (its friction loads on the lever), to round-off; its rows are the drawing's geometry;
- the frictionless balancing moment at the real motion equals the reduced equation's J_II ε₁ + ½J′ω₁² − M_loads
  (Eremyants (1.1)–(1.5)), and with group I's inertia moment the constant driving moment (Eremyants (1.13));
- the real motion ω₁(φ) keeps [δ] to the flywheel's own error estimate and its mean ω₁ₘ, and ε₁ is ω₁ dω₁/dφ;
- the endpoint answers every section of the contract with no NaN, the same flywheel as /flywheel and the same
  balancing moment as /forces, and 422 naming the field of each bad request.
"""
from __future__ import annotations

import copy
import json
import math
from dataclasses import replace

import numpy as np
import pytest
from fastapi.testclient import TestClient

from server.runtime import heavy
from server.api.app import app
from server.api.schemas_dynamics import MassInput
from server.core.course_project.real_motion import real_motion, resistance
from server.core.course_project.report import course_project
from server.core.dynamics.general_machine import general_machine
from server.core.dynamics.motors import Motor
from server.core.dynamics.reduction import Inertias
from server.core.dynamics.resistance import Load
from server.core.structure.presets import presets

PRESET = presets()["shaping_machine"]
DYNAMICS = PRESET["dynamics"]
BODY = {"linkage": PRESET["linkage"], "masses": DYNAMICS["masses"], "inertias": DYNAMICS["inertias"],
        "omega_mean": DYNAMICS["flywheel"]["omega_mean"], "delta": DYNAMICS["flywheel"]["delta"], "positions": 12}
ROUND_OFF = 1e-9     # relative to the largest balancing moment over the positions: sums of ~20 products of
                     # forces of ~10⁴ N and analogs, each exact to ~1e-16 relative, agree far below this
ROUGH = {"friction": 0.1, "pair_radius": 0.01}
SECTIONS = ("structure", "positions", "scales", "plan_of_positions", "kinematics", "output_diagrams", "dynamics",
            "kinetostatics", "table", "title", "warnings")


def masses(**changes):
    return replace(MassInput(**DYNAMICS["masses"]).model(), **changes)


def project(count=12, **changes):
    return course_project(PRESET["linkage"], masses(**changes), Inertias(**DYNAMICS["inertias"]), {},
                          BODY["omega_mean"], BODY["delta"], count)[0]


@pytest.fixture(scope="module")
def plain():
    return project()


@pytest.fixture(scope="module")
def rough():
    return project(**ROUGH)


@pytest.fixture(scope="module")
def client():
    """The app, its heavy work in this process (no process pool left behind)."""
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(heavy, "HEAVY_PROCESSES", 0)
        yield TestClient(app)


def column(answer, name):
    return np.array([row[name] for row in answer["table"]], float)


@pytest.mark.parametrize("case", ["plain", "rough"])
def test_zhukovskys_lever_gives_the_groups_balancing_moment_at_every_position(case, request):
    answer = request.getfixturevalue(case)
    groups, levered = column(answer, "M_b_groups"), column(answer, "M_b_lever")
    scale = np.abs(groups).max()
    assert np.abs(levered - groups).max() <= ROUND_OFF * scale
    if case == "rough":
        with_friction, lever_friction = column(answer, "M_b_friction"), column(answer, "M_b_lever_friction")
        assert np.abs(lever_friction - with_friction).max() <= ROUND_OFF * np.abs(with_friction).max()
        assert np.abs(with_friction - groups).max() > 1e-3 * scale          # friction changes it: a real check
        rows = answer["kinetostatics"]["friction"]["zhukovsky"]["lever"]
        assert {row["kind"] for row in rows} >= {"friction", "inertia", "gravity", "useful"}
    else:
        assert all(row["M_b_friction"] is None for row in answer["table"])


@pytest.mark.parametrize("case", ["plain", "rough"])
def test_the_levers_rows_are_the_turned_plans_geometry(case, request):
    """Each force's lever moment is its image × force on the plan turned by 90° (N·mm), its arm that moment over
    |F|, and the rows' moments times μ_v/ω₁ sum to the balancing moment (virtual power)."""
    sheet = request.getfixturevalue(case)["kinetostatics"]
    sheet = sheet["friction"] if case == "rough" else sheet
    zhukovsky, omega = sheet["zhukovsky"], request.getfixturevalue(case)["kinetostatics"]["omega1"]
    total = 0.0
    for row in zhukovsky["lever"]:
        if "force" in row:
            (x, y), (fx, fy) = row["image"], row["force"]
            assert row["moment"] == pytest.approx(x * fy - y * fx, rel=1e-12, abs=1e-9)
            size = math.hypot(fx, fy)
            assert row["arm"] * size == pytest.approx(row["moment"], rel=1e-12, abs=1e-9)
        total += row["moment"]
    assert total * zhukovsky["mu_v"] / omega == pytest.approx(sheet["balancing_moment"], rel=1e-12)
    force = zhukovsky["balancing_force"]               # F_b ⊥ OA at A: its moment about O is M_b (σ = +1 here)
    (ax, ay), (fx, fy) = force["at"], force["force"]
    assert ax * fy - ay * fx == pytest.approx(sheet["balancing_moment"], rel=1e-12)
    assert force["moment"] + total == pytest.approx(0.0, abs=1e-9 * abs(total))        # the lever in equilibrium
    assert zhukovsky["difference_percent"] <= 1e-7


def test_a_velocity_image_is_the_analytic_velocity_turned():
    """On the turned plan the image of a joint is i·v/μ_v: |image|·μ_v is the joint's speed of the kinematics
    sheet at the chosen position (two answers of two modules)."""
    answer = project()
    k = answer["kinetostatics"]["number"] - 1
    mu_v = answer["kinetostatics"]["zhukovsky"]["mu_v"]
    points = answer["kinematics"][k]["points"]
    for name, (x, y) in answer["kinetostatics"]["zhukovsky"]["images"].items():
        v = points[name]["v"]
        assert (x * mu_v, y * mu_v) == pytest.approx((-v["y"], v["x"]), rel=1e-12, abs=1e-12)


@pytest.mark.parametrize("case", ["plain", "rough"])
def test_the_frictionless_balancing_moment_is_the_reduced_equation_of_motion(case, request):
    """M_b = J_II ε₁ + ½ J′ ω₁² − M_loads at the real ω₁, ε₁ (Eremyants (1.1)–(1.5)), and M_b + I_I ε₁ = M_д without
    friction in the motion (Eremyants (1.13) with the constant driving moment)."""
    answer = request.getfixturevalue(case)
    groups = column(answer, "M_b_groups")
    assert np.abs(column(answer, "M_b_reduced") - groups).max() <= ROUND_OFF * np.abs(groups).max()
    if case == "plain":
        dynamics = answer["dynamics"]
        group_one = dynamics["flywheel"]["group_i_existing"] + dynamics["flywheel"]["flywheel_inertia"]
        driving = groups + group_one * column(answer, "epsilon1")
        # M_д from the quadrature of M_c, ε₁ from the machine's tables of J, J′, M_c (to ~1e-13 of their scale)
        assert np.abs(driving - dynamics["driving_moment"]).max() <= 1e-9 * dynamics["driving_moment"]


MACHINES = [name for name, preset in presets().items() if "flywheel" in preset.get("dynamics", {})]


@pytest.mark.parametrize("rough_pairs", [False, True])
@pytest.mark.parametrize("name", MACHINES)
def test_every_machine_preset_balances_three_ways(name, rough_pairs):
    """Slider forces, a link's load moment (a couple on the lever), two loaded sliders: the lever and the reduced
    equation give the groups' balancing moment at every position, the force plans close."""
    dynamics = presets()[name]["dynamics"]
    model = MassInput(**dynamics["masses"]).model()
    model = replace(model, **ROUGH) if rough_pairs else model
    answer, _ = course_project(presets()[name]["linkage"], model, Inertias(**dynamics["inertias"]), {},
                               dynamics["flywheel"]["omega_mean"], dynamics["flywheel"]["delta"], 8)
    groups = column(answer, "M_b_groups")
    scale = np.abs(groups).max()
    assert np.abs(column(answer, "M_b_lever") - groups).max() <= ROUND_OFF * scale
    assert np.abs(column(answer, "M_b_reduced") - groups).max() <= ROUND_OFF * scale
    sheet = answer["kinetostatics"]
    if rough_pairs:
        with_friction = column(answer, "M_b_friction")
        assert np.abs(column(answer, "M_b_lever_friction") - with_friction).max() <= \
            ROUND_OFF * np.abs(with_friction).max()
        sheet = sheet["friction"]
    assert max(plan["closure"] for plan in sheet["force_plans"]) <= 1e-12


@pytest.fixture(scope="module")
def motion():
    machine = general_machine(PRESET["linkage"], masses(), Inertias(**DYNAMICS["inertias"]), Load(),
                              Motor("constant", 0.0))
    answer = project()
    return real_motion(resistance(machine), answer["dynamics"]["flywheel"]["flywheel_inertia"],
                       BODY["omega_mean"]), answer


def test_the_real_motion_keeps_the_permissible_delta_at_the_mean_speed(motion):
    """δ achieved is [δ] to the flywheel study's own error estimate (its inertia on a grid of half the steps), and
    (ω_max + ω_min)/2 is ω₁ₘ on a dense grid to its parabola's error."""
    real, answer = motion
    dynamics = answer["dynamics"]
    assert abs(dynamics["delta_achieved"] / BODY["delta"] - 1) <= dynamics["flywheel"]["numerics"]["error_estimate"]
    omega = real.state(np.linspace(0.0, 2 * np.pi, 20001))["omega"]
    assert 0.5 * (omega.max() + omega.min()) == pytest.approx(BODY["omega_mean"], rel=1e-8)
    assert (omega.max() - omega.min()) / BODY["omega_mean"] == pytest.approx(dynamics["delta_achieved"], rel=1e-6)
    rows = answer["kinematics"]
    assert [row["omega1"] for row in rows] == pytest.approx(real.state(np.array([r["phi"] for r in rows]))["omega"],
                                                            rel=1e-14)


def test_epsilon_is_omega_times_its_slope(motion):
    """ε₁ = ω₁ dω₁/dφ against central differences of the exact ω₁(φ) (step 1e-4: truncation ~1e-8, rounding
    ~1e-11 of ε's scale), away from the kinks of M_c where ε₁ has a corner."""
    real, _ = motion
    kinks = np.asarray(real.resistance.machine.kinks())
    phi = np.linspace(0.01, 2 * np.pi - 0.01, 97)
    phi = phi[np.min(np.abs(phi[:, None] - kinks[None, :]), axis=1, initial=np.inf) > 1e-2]
    h = 1e-4
    state = real.state(phi)
    slope = (real.state(phi + h)["omega"] - real.state(phi - h)["omega"]) / (2 * h)
    assert np.abs(state["omega"] * slope - state["epsilon"]).max() <= 1e-6 * np.abs(state["epsilon"]).max()


def strict(text: str):
    def refuse(constant):
        raise ValueError(f"{constant} in the answer")
    return json.loads(text, parse_constant=refuse)


def test_the_endpoint_answers_the_contract_as_flywheel_and_forces_do(client):
    answer = client.post("/api/v1/course-project?precision=full", json=BODY | {"start": 0.0, "chosen": 4})
    assert answer.status_code == 200, answer.text[:300]
    body = strict(answer.text)
    assert tuple(body) == SECTIONS and body["warnings"] == []
    assert body["positions"]["start"] == "typed" and body["kinetostatics"]["number"] == 4
    assert set(body["scales"]) == {"mu_l", "mu_v", "mu_a", "mu_F"} and all(body["scales"].values())
    dynamics = body["dynamics"]
    flywheel = client.post("/api/v1/flywheel?precision=full", json={
        "mechanism": "general", "linkage": BODY["linkage"], "masses": BODY["masses"], "inertias": BODY["inertias"],
        "motor": {"kind": "constant", "M0": dynamics["driving_moment"] / BODY["inertias"]["gear_ratio"]},
        "omega_mean": BODY["omega_mean"], "delta": BODY["delta"], "balance": True}).json()
    assert dynamics["flywheel"]["flywheel_inertia"] == pytest.approx(flywheel["flywheel_inertia"], rel=1e-9)
    for k in (0, 3, 7):                     # positions at 0°, 90°, 210°: nodes of /forces' 1° grid
        row = body["table"][k]
        forces = client.post("/api/v1/forces?precision=full", json={
            "mechanism": "general", "linkage": BODY["linkage"], "masses": BODY["masses"], "n": 361,
            "loads": {"omega": row["omega1"], "epsilon": row["epsilon1"]}}).json()
        assert forces["phi"][30 * k] == pytest.approx(row["phi"], abs=1e-12)
        assert forces["balancing_moment"][30 * k] == pytest.approx(row["M_b_groups"], rel=1e-9)


def test_the_chosen_position_by_default_has_the_largest_useful_load(plain):
    useful = np.abs(column(plain, "useful_load"))
    assert plain["kinetostatics"]["number"] == int(np.argmax(useful)) + 1 == plain["positions"]["chosen"]
    assert plain["positions"]["drawn"] == [plain["positions"]["chosen"]]


@pytest.mark.parametrize("case", ["plain", "rough"])
def test_every_groups_force_plan_closes(case, request):
    sheet = request.getfixturevalue(case)["kinetostatics"]
    sheet = sheet["friction"] if case == "rough" else sheet
    assert [plan["group"] for plan in sheet["force_plans"]] == [1, 0, "crank"]
    for plan in sheet["force_plans"]:
        assert plan["closure"] <= 1e-12
        assert plan["vectors"][-1]["to"] == pytest.approx([0.0, 0.0], abs=1e-9)


def test_the_inertia_loads_resultant_has_the_couples_moment_about_the_centre(plain):
    for link in plain["kinetostatics"]["inertia"]:
        if link["point"] is None:
            continue
        (sx, sy), (kx, ky), (fx, fy) = link["centre"], link["point"], link["force"]
        assert (kx - sx) * fy - (ky - sy) * fx == pytest.approx(link["moment"], rel=1e-12, abs=1e-12)
        assert math.hypot(kx - sx, ky - sy) == pytest.approx(link["offset"], rel=1e-12, abs=1e-15)


def four_bar(length: float) -> dict:
    linkage = copy.deepcopy(presets()["four_bar"]["linkage"])
    linkage["input"]["length"] = length
    return linkage


BAD = [
    (BODY | {"linkage": four_bar(0.3)}, ["body", "linkage", "groups", "0"]),                # cannot turn fully
    (BODY | {"positions": 10}, ["body", "positions"]),
    (BODY | {"chosen": 13}, ["body", "chosen"]),
    (BODY | {"chosen": 9, "positions": 8}, ["body", "chosen"]),
    (BODY | {"drawn": [3, 25]}, ["body", "drawn"]),
    (BODY | {"drawn": [9], "positions": 8}, ["body", "drawn"]),
    ({k: v for k, v in BODY.items() if k != "masses"}, ["body", "masses"]),
    (BODY | {"masses": DYNAMICS["masses"] | {"links": []}}, ["body", "masses", "links"]),
    (BODY | {"masses": DYNAMICS["masses"] | {"forces": []}}, ["body", "masses", "forces"]),
    (BODY | {"linkage": presets()["slider_driven_crank"]["linkage"]}, ["body", "linkage", "input", "kind"]),
    (BODY | {"pair_friction": {"A": {"f": 0.1, "r": 0.01, "beta": 1.0}}}, ["body", "pair_friction", "A", "beta"]),
    (BODY | {"title": {"student": "x" * 81}}, ["body", "title", "student"]),
    (BODY | {"output": "nope"}, ["body", "output"]),
    (BODY | {"output": "link 1"}, ["body", "output"]),                   # the crank turns: it never reverses
]


@pytest.mark.parametrize("body,loc", BAD)
def test_bad_input_is_refused_naming_the_field(client, body, loc):
    answer = client.post("/api/v1/course-project", json=body)
    assert answer.status_code == 422, answer.text[:300]
    detail = answer.json()["detail"][0]
    assert detail["loc"][:len(loc)] == loc, detail


TOOL = {"link": 5, "point": [0.1, -0.05], "name": "K", "magnitude": 3000.0,
        "direction": {"kind": "fixed", "angle": 0.0}, "acts": "working",
        "diagram": {"over": "stroke", "points": [[0.05, 0.0], [0.1, 1.0], [0.9, 1.0], [0.95, 0.0]]}}


@pytest.mark.parametrize("friction", [{}, ROUGH])
def test_a_force_at_the_tool_point_with_a_stroke_diagram_carries_the_whole_project(client, friction):
    """The shaping machine's cutting force at its tool point K over 5…95 % of the stroke (no slider force): the
    endpoint answers every section, the load's reduced moment is its M_c part, and the lever and the reduced
    equation give the groups' balancing moment at every position (to ROUND_OFF of its largest value)."""
    body = BODY | {"masses": DYNAMICS["masses"] | friction | {"forces": [], "point_forces": [TOOL]}}
    answer = client.post("/api/v1/course-project", json=body)
    assert answer.status_code == 200, answer.text[:300]
    result = answer.json()
    assert set(SECTIONS) <= set(result) and "force K" in result["dynamics"]["M_c_parts"]
    groups = column(result, "M_b_friction" if friction else "M_b_groups")
    scale = np.abs(groups).max()
    lever = column(result, "M_b_lever_friction" if friction else "M_b_lever")
    assert np.abs(lever - groups).max() <= ROUND_OFF * scale
    if not friction:
        assert np.abs(column(result, "M_b_reduced") - groups).max() <= ROUND_OFF * scale
