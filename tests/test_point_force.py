"""Forces at points of links and load diagrams of a general mechanism (masses.point_forces, moments' diagrams;
structure/load_kinematics.py), each against something that is not the code under test:

- virtual work (Chaika–Vasylenko (3.24), power equality): the reduced moment of a point force is M = −F·dz_P/dφ
  with dz_P/dφ from five-point central differences of the point's exact positions z_O + w e^{iθ} (the composed
  linkage at φ + mh, h = 1e-3): truncation (h⁴/30)|z⁽⁵⁾| ≈ 3e-14·|z⁽⁵⁾| (|z⁽⁵⁾| of order 1 m on six-bars whose
  groups keep |det| ≥ 0.7), round-off ~ε|z|/h ≈ 1e-13 m, so 1e-9 of the largest moment is far above both.  The
  force is built here: P e with e from the angle given (or the link's exact angle), on the working stroke
  where the differenced velocity along e is negative.  Two six-bars that are no presets (crank + RRR + RRP with
  the slider's group on the coupler's point, crank + RPR with an offset slot + RRR);
- a slider force on a moving guide (the shaping machine's block on its slotted link): the same virtual work
  with the block's own (absolute) velocity; with the slot offset from the lever's pivot by e that velocity
  along the slot is s′ − eθ′, not the sliding s′ (both from differences of the exact positions), while two
  opposite point forces along the slot, on the block and on the lever, reduce to −F s′;
- the kinetostatics by groups without friction: the balancing moment equals the loads' reduced moment by
  power equality (GroupForces.reduced_moment) and the dynamics' J ε + ½J′ω² + M_c, to round-off (1e-10);
- a stroke diagram and the working stroke's switch against a hand computation: the travel x from the exact
  positions and the extremes on a 200 001-point turn (their error (Δφ)²|x″|/8 ≈ 1e-10 m: 1e-9 of the stroke),
  p(x) by scipy's PchipInterpolator through the points, zero outside; the machine's kinks hold the angles where
  x passes each break and where the point reverses, found here by brentq on the exact positions (xtol 1e-14);
- the API: 422 naming the field for each bad input; load_factor scales a point force's moment linearly
  (the same arithmetic on one magnitude: 1e-12).
"""
from __future__ import annotations

import copy
import math

import numpy as np
import pytest
from fastapi.testclient import TestClient
from scipy.interpolate import PchipInterpolator
from scipy.optimize import brentq

from server.api.app import app
from server.api.endpoints import machine
from server.api.schemas_dynamics import MotionRequest
from server.core.kinetostatics.groups.analysis import analyse
from server.core.kinetostatics.groups.loads import link_loads
from server.core.mechanisms.base import GeometryError
from server.core.mechanisms.general import GeneralMechanism
from server.core.structure.compose import compose
from server.core.structure.masses import (LinkMass, LinkMoment, LoadDiagram, MassModel, PointForce, SliderForce,
                                          check_model, with_strokes)
from server.core.structure.presets import presets
from server.core.structure.reduction import reduced_loads

from group_force_checks import reduction_moment

FIVE = {-2: 1 / 12, -1: -8 / 12, 1: 8 / 12, 2: -1 / 12}
H = 1e-3
PHI = np.linspace(0, 2 * np.pi, 97)[:-1] + 0.0123

# crank + RRR + RRP: the slider's group hangs on the coupler's point C (a Stephenson six-bar), an inclined guide
STEPHENSON = {
    "frame": {"joints": {"O": [0, 0], "D": [0.22, 0.1]}, "guides": {"incline": {"through": [0.0, -0.02],
                                                                                  "angle": 0.35}}},
    "input": {"link": 1, "pivot": "O", "joint": "A", "length": 0.06},
    "groups": [{"kind": "RRR", "links": [2, 3], "outer": ["A", "D"], "inner": "B", "lengths": [0.25, 0.18],
                "branch": 1, "points": {"C": {"link": 2, "along": 0.12, "across": -0.08}}},
               {"kind": "RRP", "links": [4, 5], "outer": ["C"], "guide": "incline", "inner": "E", "length": 0.2,
                "branch": -1}]}
# crank + RPR (slot offset from the lever's pivot) + RRR on the lever's point D
SLOTTED = {
    "frame": {"joints": {"O": [0, 0], "C": [0.02, -0.25], "F": [0.32, 0.28]}},
    "input": {"link": 1, "pivot": "O", "joint": "A", "length": 0.08},
    "groups": [{"kind": "RPR", "links": [2, 3], "outer": ["A", "C"], "offset": 0.02, "branch": 1, "inner": "s23",
                "points": {"D": {"link": 3, "along": 0.42, "across": 0.03}}},
               {"kind": "RRR", "links": [4, 5], "outer": ["D", "F"], "inner": "G", "lengths": [0.3, 0.24],
                "branch": 1}]}
FORCES = {
    "stephenson": (STEPHENSON, (PointForce(2, (0.2, 0.05), 800.0, 0.6, "fixed", "working", name="T"),
                                PointForce(4, (0.1, -0.03), 500.0, 1.2, "link", "always"),
                                PointForce(5, (0.04, 0.02), 1200.0, math.pi + 0.35, "fixed", "working"),
                                PointForce(3, (0.09, 0.04), 300.0, -0.4, "link", "working"))),
    "slotted": (SLOTTED, (PointForce(3, (0.3, -0.05), 900.0, -2.0, "fixed", "working", name="K"),
                          PointForce(5, (0.2, 0.04), 600.0, math.pi / 2, "link", "working"),
                          PointForce(2, (0.0, 0.0), 400.0, 0.3, "link", "always"),
                          PointForce(4, (0.15, 0.0), 700.0, 2.5, "fixed", "always"))),
}
SHAPING = presets()["shaping_machine"]
K = {"link": 5, "point": [0.1, -0.05], "name": "K", "magnitude": 3000.0,
     "direction": {"kind": "fixed", "angle": 0.0}, "acts": "working"}


def exact(linkage, link: int, w: complex, phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """A point w of a link (its frame) and the link's angle, from the exact positions at phi."""
    origin, angle = compose(linkage, phi).links[link]
    return origin.z + w * np.exp(1j * angle.th), angle.th


def velocity(linkage, link: int, w: complex, phi: np.ndarray) -> np.ndarray:
    """dz_P/dφ by five-point central differences of the exact positions."""
    return sum(c * exact(linkage, link, w, phi + m * H)[0] for m, c in FIVE.items()) / H


def virtual_work(linkage, force: PointForce, phi: np.ndarray) -> np.ndarray:
    """M = −F·dz_P/dφ with F = P e built here, on the working stroke where the point moves against e."""
    v = velocity(linkage, force.link, complex(*force.point), phi)
    theta = exact(linkage, force.link, 0j, phi)[1]
    e = np.exp(1j * (force.angle + (theta if force.direction == "link" else 0.0)))
    along = (v * np.conj(e)).real
    F = force.magnitude * e * (along < 0 if force.acts == "working" else 1.0)
    return -(np.conj(F) * v).real, along


@pytest.mark.parametrize("name", sorted(FORCES))
def test_point_force_moment_is_its_virtual_work(name):
    raw, forces = FORCES[name]
    mech = GeneralMechanism(raw)
    comp = compose(mech.linkage, PHI)
    assert all(g.closes.all() and np.abs(g.determinant).min() >= 0.7 for g in comp.groups)
    model = MassModel(gravity=0.0, point_forces=forces)
    check_model(comp, model)
    parts = reduced_loads(mech, comp, model).parts
    for force in forces:
        expected, along = virtual_work(mech.linkage, force, PHI)
        moment = parts[f"force {force.label}"]
        assert np.abs(moment - expected).max() <= 1e-9 * np.abs(expected).max(), force
        assert (along > 0).any() and (along < 0).any()          # the point goes both ways along e
        if force.acts == "working":                              # it only resists, and rests on the return
            assert (moment >= 0).all() and (moment[along > 1e-9] == 0).all()
    assert set(parts) == {f"force {f.label}" for f in forces}       # "force T", "force 4:0.1,-0.03", …
    assert forces[0].label in ("T", "K") and forces[1].label == f"{forces[1].link}:{forces[1].point[0]:g}," \
                                                                 f"{forces[1].point[1]:g}"


def block_check(linkage: dict, P: float, k: float) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The code's moment of a force on the shaping machine's block s23 (at the crank pin A, sliding in the slot of
    link 3), its virtual work with the block's velocity along the slot, and the differenced s′, θ′₃."""
    mech = GeneralMechanism(linkage)
    comp = compose(mech.linkage, PHI)
    model = MassModel(gravity=0.0, forces=(SliderForce("s23", P, k),))
    moment = reduced_loads(mech, comp, model).parts["force s23"]
    shifted = {m: compose(mech.linkage, PHI + m * H) for m in FIVE}
    v_block = sum(c * shifted[m].joints["A"].z for m, c in FIVE.items()) / H
    slot = np.exp(1j * comp.links[3][1].th)
    w = (v_block * np.conj(slot)).real
    F = -np.where(w >= 0, 1.0, k) * P * np.sign(w) * slot       # on the block, against its motion along the slot
    s1 = sum(c * shifted[m].slides["s23"].s for m, c in FIVE.items()) / H
    th1 = sum(c * np.unwrap(shifted[m].links[3][1].th) for m, c in FIVE.items()) / H
    return moment, -(np.conj(F) * v_block).real, s1, th1


def test_slider_force_on_a_moving_guide_is_reduced_with_the_blocks_own_velocity():
    moment, work, s1, _ = block_check(SHAPING["linkage"], 1000.0, 0.3)
    assert np.abs(moment - work).max() <= 1e-9 * np.abs(work).max()
    # the preset's slot runs through the lever's fixed pivot C: the block's velocity along it is s′ itself
    assert np.abs(moment - 1000.0 * np.where(s1 >= 0, 1.0, 0.3) * np.abs(s1)).max() <= 1e-9 * np.abs(work).max()
    offset = copy.deepcopy(SHAPING["linkage"])
    offset["groups"][0]["offset"] = 0.03
    moment, work, s1, th1 = block_check(offset, 1000.0, 1.0)
    assert np.abs(moment - work).max() <= 1e-9 * np.abs(work).max()
    # offset by e: B = C + (s + ie)e^{iθ}, so Re(z′_B e^{−iθ}) = s′ − eθ′: the power of a force on the block
    assert np.abs(moment - 1000.0 * np.abs(s1 - 0.03 * th1)).max() <= 1e-9 * np.abs(work).max()
    assert np.abs(moment - 1000.0 * np.abs(s1)).max() >= 0.1 * np.abs(work).max()   # not the sliding's P|s′|
    # a force between the block and its slotted link (a spring in the slot): two opposite point forces along the
    # slot, on the block at B and on the lever at a point of the slot's line, whose power is F s′
    pair = (PointForce(2, (0.0, 0.0), 1000.0, 0.0, "link", "always", name="on 2"),
            PointForce(3, (0.3, 0.03), 1000.0, math.pi, "link", "always", name="on 3"))
    mech = GeneralMechanism(offset)
    spring = reduced_loads(mech, compose(mech.linkage, PHI), MassModel(gravity=0.0, point_forces=pair)).total
    assert np.abs(spring + 1000.0 * s1).max() <= 1e-9 * np.abs(work).max()


@pytest.mark.parametrize("name", ["shaping", "slotted"])
def test_balancing_moment_without_friction_is_the_reduced_moment(name):
    if name == "shaping":
        raw = SHAPING["linkage"]
        links = tuple(LinkMass(k, 3.0 + k, (0.05, 0.01), 0.01 * k) for k in range(1, 6))
        forces = (PointForce(5, (0.1, -0.05), 3000.0, 0.0, name="K"),
                  PointForce(3, (0.4, 0.02), 200.0, 0.5, "link", "always"))
        moments = (LinkMoment(4, 40.0, 0.2, -1, LoadDiagram("phi", ((0.5, 0.2), (2.0, 1.0), (4.0, 0.6)))),)
    else:
        raw, forces = FORCES["slotted"]
        links = tuple(LinkMass(k, 1.0 + k, (0.03, -0.02), 0.004 * k) for k in range(1, 6))
        moments = (LinkMoment(5, 25.0, 0.5, 1, LoadDiagram("stroke", ((0.0, 1.0), (0.5, 0.4), (1.0, 0.9)))),)
    mech = GeneralMechanism(raw)
    model = MassModel(links, point_forces=forces, moments=moments)
    result = analyse(mech, model, PHI, omega=8.0, epsilon=3.0)
    balancing = result.solution.balancing
    scale = np.abs(balancing).max()
    assert np.abs(balancing - result.reduced_moment).max() <= 1e-10 * scale
    resolved = with_strokes(mech, model)
    assert np.abs(balancing - reduction_moment(mech, resolved, result, 8.0, 3.0)).max() <= 1e-10 * scale
    useful = {load.name for load in result.loads if load.kind == "useful"}
    assert {f"F_{f.label}" for f in forces} <= useful


SHAPING_LINKAGE = GeneralMechanism(SHAPING["linkage"]).linkage
K_TURN = compose(SHAPING_LINKAGE, np.linspace(0, 2 * np.pi, 200_001)).joints["E"].z.real + 0.1


def shaping_k_travel(phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The tool point K's x (E's x + 0.1 m on the ram) and its travel from the working stroke's start (its
    largest x: the working stroke is against e = +x) as a fraction of the stroke, from the exact positions."""
    x = compose(SHAPING_LINKAGE, phi).joints["E"].z.real + 0.1
    return x, (K_TURN.max() - x) / (K_TURN.max() - K_TURN.min())


STROKE_POINTS = [[0.1, 0.3], [0.3, 1.0], [0.7, 0.8], [0.9, 0.2]]


def motion_body(point_forces: list, moments: list | None = None) -> dict:
    dynamics = SHAPING["dynamics"]
    masses = dynamics["masses"] | {"forces": [], "moments": moments or [], "point_forces": point_forces}
    return {"mechanism": "general", "linkage": SHAPING["linkage"], "masses": masses,
            "inertias": dynamics["inertias"], "motor": dynamics["motor"], "outputs": ["steady"]}


def test_stroke_diagram_and_working_stroke_against_a_hand_computation():
    mech = GeneralMechanism(SHAPING["linkage"])
    force = PointForce(5, (0.1, -0.05), 3000.0, 0.0, diagram=LoadDiagram("stroke", tuple(map(tuple, STROKE_POINTS))),
                       name="K")
    model = with_strokes(mech, MassModel(gravity=0.0, point_forces=(force,)))
    comp = compose(mech.linkage, PHI)
    _, x = shaping_k_travel(PHI)
    v = velocity(mech.linkage, 5, 0.1 - 0.05j, PHI).real
    xs, ps = np.array(STROKE_POINTS).T
    p = np.where((x >= xs[0]) & (x <= xs[-1]), PchipInterpolator(xs, ps)(np.clip(x, xs[0], xs[-1])), 0.0)
    expected = 3000.0 * p * np.where(v < 0, -v, 0.0)              # −F·v, F = P p(x) on the working stroke
    moment = reduced_loads(mech, comp, model).parts["force K"]
    assert np.abs(moment - expected).max() <= 1e-7 * np.abs(expected).max()
    on_working = v < 0
    assert (moment[~on_working] == 0).all() and (moment[on_working & ((x < 0.1) | (x > 0.9))] == 0).all()
    assert (moment[on_working & (x > 0.1) & (x < 0.9)] > 0).all()
    load = next(l for l in link_loads(mech, comp, model, 5.0, 0.0) if l.name == "F_K")
    assert np.abs(load.force - 3000.0 * p * on_working).max() <= 1e-7 * 3000.0
    # the kinks: K's reversals and every angle where x passes a break, found by brentq on the exact positions
    kinks = machine(MotionRequest(**motion_body([K | {"diagram": {"over": "stroke", "points": STROKE_POINTS}}]))).kinks()
    scan = np.linspace(0, 2 * np.pi, 721)
    expected_kinks = []
    for f in [lambda a: velocity(mech.linkage, 5, 0.1 - 0.05j, np.atleast_1d(a)).real] + \
            [lambda a, b=b: shaping_k_travel(np.atleast_1d(a))[1] - b for b in xs]:
        values = f(scan)
        f = (lambda g: lambda a: float(g(a)[0]))(f)
        expected_kinks += [brentq(f, scan[i], scan[i + 1], xtol=1e-14)
                           for i in np.flatnonzero(values[:-1] * values[1:] < 0)]
    assert len(expected_kinks) == 2 + 2 * len(xs)                 # two reversals, each break passed twice
    assert all(np.abs(kinks - a).min() <= 1e-8 for a in expected_kinks), (kinks, expected_kinks)


def test_crank_angle_diagram_and_a_link_moment_over_its_stroke():
    mech = GeneralMechanism(SHAPING["linkage"])
    over_phi = LoadDiagram("phi", ((1.0, 0.5), (2.0, 1.0), (3.0, 0.4)))
    force = PointForce(3, (0.5, 0.0), 400.0, math.pi / 2, "fixed", "always", over_phi, "L")
    moment = LinkMoment(3, 60.0, 0.25, -1, LoadDiagram("stroke", ((0.0, 0.2), (0.6, 1.0), (1.0, 0.5))))
    model = with_strokes(mech, MassModel(gravity=0.0, point_forces=(force,), moments=(moment,)))
    parts = reduced_loads(mech, compose(mech.linkage, PHI), model).parts
    p_phi = np.where((PHI >= 1.0) & (PHI <= 3.0), PchipInterpolator([1, 2, 3], [0.5, 1, 0.4])(np.clip(PHI, 1, 3)), 0)
    v = velocity(mech.linkage, 3, 0.5, PHI)
    assert np.abs(parts["force L"] + 400.0 * p_phi * v.imag).max() <= 1e-9 * 400.0 * np.abs(v).max()
    # the lever's angle between its extremes from the working stroke's start (σ = −1: the largest angle)
    theta = lambda phi: exact(mech.linkage, 3, 0j, phi)[1]
    turn = np.unwrap(theta(np.linspace(0, 2 * np.pi, 200_001)))
    middle = 0.5 * (turn.max() + turn.min())
    x = (turn.max() - middle - np.angle(np.exp(1j * (theta(PHI) - middle)))) / np.ptp(turn)
    rate = sum(c * np.angle(np.exp(1j * (theta(PHI + m * H) - theta(PHI)))) for m, c in FIVE.items()) / H
    p = PchipInterpolator([0, 0.6, 1], [0.2, 1, 0.5])(np.clip(x, 0, 1))
    expected = 60.0 * np.where(-rate >= 0, 1.0, 0.25) * p * np.abs(rate)
    assert np.abs(parts["moment 3"] - expected).max() <= 1e-7 * np.abs(expected).max()
    kinks = machine(MotionRequest(**motion_body(
        [{"link": 3, "point": [0.5, 0], "name": "L", "magnitude": 400.0, "acts": "always",
          "direction": {"kind": "fixed", "angle": math.pi / 2},
          "diagram": {"over": "phi", "points": [[1.0, 0.5], [2.0, 1.0], [3.0, 0.4]]}}]))).kinks()
    assert all(np.abs(kinks - a).min() <= 1e-12 for a in (1.0, 2.0, 3.0))


def test_motion_with_a_point_force_balances_its_energy():
    client = TestClient(app)
    answer = client.post("/api/v1/motion?precision=full", json=motion_body([K]) | {"rtol": 1e-10})
    assert answer.status_code == 200, answer.text
    works = answer.json()["works"]
    assert works["useful"] > 0
    balance = works["driving"] - works["useful"] - works["dry_friction"] - works["viscous_friction"]
    assert abs(balance) <= 1e-8 * works["driving"], works


def reduction(masses: dict, client: TestClient):
    body = {"mechanism": "general", "linkage": SHAPING["linkage"], "masses": masses, "inertias": {"J1": 0.5},
            "outputs": ["resisting"], "n": 73}
    return client.post("/api/v1/reduction?precision=full", json=body)


BAD = [
    (K | {"link": 9}, "masses.point_forces.0.link"),
    (K | {"point": [1200.0, 0.0]}, "masses.point_forces.0.point"),
    (K | {"diagram": {"over": "stroke", "points": [[0.2, 1.0]]}}, "masses.point_forces.0.diagram.points"),
    (K | {"diagram": {"over": "phi", "points": [[0.2, 1.0], [0.2, 0.5]]}}, "masses.point_forces.0.diagram.points"),
    (K | {"diagram": {"over": "stroke", "points": [[0.5, 1.0], [0.2, 0.5]]}}, "masses.point_forces.0.diagram.points"),
    (K | {"diagram": {"over": "stroke", "points": [[0.2, 1.0], [1.5, 0.5]]}}, "masses.point_forces.0.diagram.points"),
    (K | {"diagram": {"over": "phi", "points": [[0.2, 1.3], [1.5, 0.5]]}}, "masses.point_forces.0.diagram.points"),
    (K | {"direction": {"kind": "link", "angle": 0.0}, "diagram": {"over": "stroke", "points": [[0, 1], [1, 1]]}},
     "masses.point_forces.0.diagram.over"),
    (K | {"name": "too long a name"}, "masses.point_forces.0.name"),
]


@pytest.mark.parametrize("force, field", BAD)
def test_bad_point_forces_answer_422_naming_the_field(force, field):
    with TestClient(app) as client:
        answer = reduction(SHAPING["dynamics"]["masses"] | {"point_forces": [force]}, client)
    assert answer.status_code == 422, answer.text
    fields = [".".join(map(str, item["loc"][1:])) for item in answer.json()["detail"]]
    assert field in fields, fields
    assert all(item["msg"] for item in answer.json()["detail"])


def test_a_stroke_diagram_on_a_fully_turning_link_answers_422():
    moment = {"link": 1, "working": 10.0, "diagram": {"over": "stroke", "points": [[0, 1], [1, 1]]}}
    with TestClient(app) as client:
        answer = reduction(SHAPING["dynamics"]["masses"] | {"moments": [moment]}, client)
    assert answer.status_code == 422
    detail = answer.json()["detail"][0]
    assert detail["loc"][1:] == ["masses", "moments", "0", "diagram"] and detail["ctx"]["code"] == "link_no_stroke"


@pytest.mark.parametrize("force, field", [
    (PointForce(9, (0.1, 0.0), 1.0), "masses.point_forces.0.link"),
    (PointForce(5, (1000.0, 1.0), 1.0), "masses.point_forces.0.point"),
    (PointForce(5, (0.1, 0.0), 1.0, diagram=LoadDiagram("phi", ((1.0, 1.0),))), "masses.point_forces.0.diagram.points"),
    (PointForce(5, (0.1, 0.0), 1.0, diagram=LoadDiagram("phi", ((1.0, 1.0), (0.5, 1.0)))),
     "masses.point_forces.0.diagram.points"),
    (PointForce(5, (0.1, 0.0), 1.0, direction="link", diagram=LoadDiagram("stroke", ((0.0, 1.0), (1.0, 1.0)))),
     "masses.point_forces.0.diagram.over"),
])
def test_the_core_refuses_what_the_schema_refuses(force, field):
    mech = GeneralMechanism(SHAPING["linkage"])
    with pytest.raises(GeometryError) as refused:
        with_strokes(mech, MassModel(point_forces=(force,)))
        check_model(compose(mech.linkage, PHI), MassModel(point_forces=(force,)))
    assert refused.value.field == field and refused.value.reason


def test_load_factor_scales_a_point_force_linearly():
    masses = SHAPING["dynamics"]["masses"] | {"forces": [], "gravity": 0.0,
                                             "point_forces": [K | {"diagram": {"over": "stroke",
                                                                               "points": STROKE_POINTS}}]}
    with TestClient(app) as client:
        one = reduction(masses, client).json()["resisting"]["parts"]["force K"]
        factor = reduction(masses | {"load_factor": 2.5}, client).json()["resisting"]["parts"]["force K"]
        by_hand = reduction(masses | {"point_forces": [masses["point_forces"][0] | {"magnitude": 7500.0}]},
                            client).json()["resisting"]["parts"]["force K"]
    one, factor, by_hand = map(np.array, (one, factor, by_hand))
    assert np.abs(one).max() > 100
    assert np.abs(factor - 2.5 * one).max() <= 1e-12 * np.abs(factor).max()
    assert np.abs(factor - by_hand).max() <= 1e-12 * np.abs(factor).max()
