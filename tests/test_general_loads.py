"""Load diagrams on sliders and viscous β on single pairs of a general mechanism (structure/masses.py,
dynamics/general_machine.py), each against something that is not the code under test:

- a diagram's force: its magnitude against scipy's PchipInterpolator through the points at x computed here from
  the slide and its extremes over a 200 001-point turn (the extremes' grid error ~(Δφ)²|s″|/8 ≈ 1e-11 m: 1e-8 of
  the force), its reduced moment against the power −F·v with v from five-point central differences of the exact
  positions (truncation ~h⁴, round-off ~1e-16/h: 1e-8 relative), and its work over the turn against the
  diagram's area P_max H ∫(p_w + p_r)dx (PchipInterpolator.integrate; the trapezoid rule on 40 001 points over
  the moment's corners: 1e-6 relative);
- a pair's viscous moment: β S(φ) against Σ β_p rel_p² with every pair's relative motion from central
  differences of the positions of the two links' material points at the pair (1e-8 relative);
- the motion endpoint with both: a steady cycle whose energy balance is ≤ 1e-8 of the driving work, the works
  recomputed here from the answer; bad diagrams answer 422 naming the field.
"""
from __future__ import annotations

import numpy as np
import pytest
from scipy.interpolate import PchipInterpolator

from server.api.endpoints import compute, machine
from server.api.schemas_dynamics import MotionRequest
from server.core.mechanisms.general import GeneralMechanism
from server.core.structure.compose import compose
from server.core.structure.masses import MassModel, SliderForce, slider_loads, with_strokes
from server.core.structure.presets import presets
from server.core.structure.reduction import reduced_loads

NAME = "shaping_machine"
WORKING = (0.0, 0.2, 0.9, 1.0, 1.0, 0.95, 0.6, 0.1)
RETURN = (0.05, 0.05, 0.04)
FIVE = {-2: 1 / 12, -1: -8 / 12, 1: 8 / 12, 2: -1 / 12}
H = 2e-4


def mechanism():
    return GeneralMechanism(presets()[NAME]["linkage"])


@pytest.mark.parametrize("sense", [1, -1])
def test_diagram_force_against_pchip_and_power(sense):
    mech = mechanism()
    model = with_strokes(mech, MassModel(forces=(SliderForce("E/ram", 2500.0, sense=sense,
                                                             diagram=(WORKING, RETURN)),), gravity=0.0))
    phi = np.linspace(0, 2 * np.pi, 97)[:-1] + 0.0123
    comp = compose(mech.linkage, phi)
    load = slider_loads(comp, model)[0]
    # the magnitude: x from the slide and its extremes on a fine turn, then scipy's monotone cubic
    s_turn = compose(mech.linkage, np.linspace(0, 2 * np.pi, 200_001)).slides["E/ram"].s
    low, high = s_turn.min(), s_turn.max()
    s = comp.slides["E/ram"].s
    x = np.clip((s - low if sense > 0 else high - s) / (high - low), 0, 1)
    w = (comp.links[load.link][0].d1 * np.conj(load.unit)).real
    working = sense * w >= 0
    curve = lambda points: PchipInterpolator(np.linspace(0, 1, len(points)), points)(x)
    expected = 2500.0 * np.where(working, curve(WORKING), curve(RETURN))
    assert np.abs(load.magnitude - expected).max() <= 1e-8 * 2500.0
    # the reduced moment by power equality, the point's velocity by central differences of its positions
    moment = reduced_loads(mech, comp, model).parts["force E/ram"]
    v = sum(c * compose(mech.linkage, phi + m * H).links[load.link][0].z for m, c in FIVE.items()) / H
    power = -(np.conj(load.vector) * v).real
    assert np.abs(moment - power).max() <= 1e-8 * np.abs(moment).max()
    assert (moment >= -1e-9 * np.abs(moment).max()).all()          # it resists on both strokes


def test_diagram_work_is_its_area():
    mech = mechanism()
    model = with_strokes(mech, MassModel(forces=(SliderForce("E/ram", 2500.0, sense=-1, diagram=(WORKING, RETURN)),),
                                         gravity=0.0))
    phi = np.linspace(0, 2 * np.pi, 40_001)
    moment = reduced_loads(mech, compose(mech.linkage, phi), model).total
    low, high = model.forces[0].stroke
    area = sum(PchipInterpolator(np.linspace(0, 1, len(p)), p).integrate(0, 1) for p in (WORKING, RETURN))
    assert np.trapezoid(moment, phi) == pytest.approx(2500.0 * (high - low) * area, rel=1e-6)


def material_motion(comp_of, comp, pair, phi):
    """The pair's relative motion by central differences: the two links' material points at the pair's point,
    their relative displacement along u (prismatic), or the relative turn of the links (revolute)."""
    def state(c, link):
        if link == 0:
            return 0j, 0.0
        origin, angle = c.links[link]
        return origin.z, angle.th
    if pair.kind == "R":
        def rel_angle(c):
            return state(c, pair.b)[1] - state(c, pair.a)[1]
        base = rel_angle(comp)
        return sum(k * np.angle(np.exp(1j * (rel_angle(comp_of(m)) - base))) for m, k in FIVE.items()) / H
    material = {}
    for link in (pair.a, pair.b):
        origin, th = state(comp, link)
        material[link] = (pair.z - origin) * np.exp(-1j * th)

    def spot(c, link):
        origin, th = state(c, link)
        return origin + material[link] * np.exp(1j * th) if link else pair.z
    d = sum(k * (spot(comp_of(m), pair.b) - spot(comp_of(m), pair.a)) for m, k in FIVE.items()) / H
    return (np.conj(pair.u) * d).real


def test_viscous_pairs_against_differences():
    from server.core.kinetostatics.groups.pairs import crank_pair, group_pairs
    dynamics = presets()[NAME]["dynamics"]
    betas = {"C": 2.0, "s23": 35.0, "E": 0.5, "O": 1.5}
    body = {"mechanism": "general", "linkage": presets()[NAME]["linkage"], "masses": dynamics["masses"],
            "inertias": dynamics["inertias"], "motor": dynamics["motor"], "outputs": ["steady"],
            "load": {"beta": 12.0}, "pair_friction": {name: {"beta": b} for name, b in betas.items()}}
    built = machine(MotionRequest(**body))
    phi = np.linspace(0, 2 * np.pi, 61)[:-1] + 0.031
    tables = built.tables(phi)
    mech = built.linkage
    comp = compose(mech.linkage, phi)
    shifted = {m: compose(mech.linkage, phi + m * H) for m in FIVE}
    pairs = [p for g in group_pairs(mech.linkage, comp) for p in g.pairs] + [crank_pair(mech.linkage, comp)]
    expected = sum(betas[p.name] * material_motion(shifted.get, comp, p, phi) ** 2 for p in pairs if p.name in betas)
    expected = expected + 12.0 * sum(material_motion(shifted.get, comp, p, phi) ** 2 for p in pairs if p.kind == "P")
    assert np.abs(built.load.beta * tables.sliding - expected).max() <= 1e-8 * np.abs(expected).max()


def test_motion_with_a_diagram_and_viscous_pairs():
    dynamics = presets()[NAME]["dynamics"]
    masses = dynamics["masses"] | {"forces": [{"joint": "E/ram", "working": 3000.0, "sense": -1,
                                               "diagram": {"working_stroke": list(WORKING),
                                                           "return_stroke": list(RETURN)}}]}
    body = {"mechanism": "general", "linkage": presets()[NAME]["linkage"], "masses": masses,
            "inertias": dynamics["inertias"], "motor": dynamics["motor"], "outputs": ["steady"], "rtol": 1e-10,
            "pair_friction": {"C": {"beta": 2.0}, "E": {"beta": 0.5}}}
    steady = compute("motion", body)
    works = steady["works"]
    assert works["viscous_friction"] > 0 and works["useful"] > 0
    balance = works["driving"] - works["useful"] - works["dry_friction"] - works["viscous_friction"]
    assert abs(balance) <= 1e-8 * works["driving"], works


@pytest.mark.parametrize("force, field", [
    ({"k": 0.5, "diagram": {"working_stroke": [0, 1], "return_stroke": [0, 0]}}, "forces"),
    ({"diagram": {"working_stroke": [0, 1.5], "return_stroke": [0, 0]}}, "working_stroke"),
    ({"diagram": {"working_stroke": [1], "return_stroke": [0, 0]}}, "working_stroke"),
])
def test_bad_diagrams(force, field):
    from fastapi.testclient import TestClient
    from server.api.app import app
    dynamics = presets()[NAME]["dynamics"]
    masses = dynamics["masses"] | {"forces": [{"joint": "E/ram", "working": 3000.0} | force]}
    body = {"mechanism": "general", "linkage": presets()[NAME]["linkage"], "masses": masses,
            "inertias": dynamics["inertias"], "motor": dynamics["motor"], "outputs": ["steady"]}
    with TestClient(app) as client:
        answer = client.post("/api/v1/motion", json=body)
    assert answer.status_code == 422
    assert any(field in ".".join(map(str, d["loc"])) for d in answer.json()["detail"]), answer.text[:300]
