"""A slider as the input link: A = P + s u along a frame guide, the displacement s the generalised coordinate
(every analog with respect to s), composed with the same groups (Chaika–Vasylenko §3.1: the class-I input link
on the frame may be a slider).

Independent checks (as tests/test_general_presets.py and test_general_fsolve.py for a crank):
- structure: the input's prismatic pair counted, W = 3n − 2p₅ − p₄ = 1;
- the preset (the crank-slider inverted: the slider drives the crank through the rod) against the cosine law
  cos θ₃ = (s² + l₃² − l₂²)/(2 s l₃) of the triangle O A B, evaluated apart from the group modules: 1e-12 rad
  (both closed forms, only round-off);
- a six-bar driven by a slider (slider + RPR + RRP): lengths and guide constraints to 1e-12 m over the travel;
  analogs against Richardson-extrapolated central differences of the exact positions (h = 1e-3 m; rel 1e-6,
  floor 1e-7, as for a crank); positions against fsolve of the whole loop closure written here from the
  definition (xtol 1e-14: 1e-10 m, the root's round-off amplified by 1/|det| ≤ 10);
- the velocity and acceleration plans' equations to 1e-12 (v₁ the slider's velocity, a₁ its acceleration);
- the API: the answer's `phi` is s over the travel, the documented example answers, and the dynamics and the
  kinetostatics refuse a slider input (422 naming linkage.input.kind).
"""
from __future__ import annotations

import numpy as np
import pytest
from fastapi.testclient import TestClient
from scipy.optimize import fsolve

from server.api.app import app
from server.core.mechanisms.general import GeneralMechanism, compute_general
from server.core.structure.compose import compose
from server.core.structure.plans import plans
from server.core.structure.presets import presets

from structure_checks import analog_errors, constraint_residuals, fsolve_errors

GUIDE = 0.3                                       # the input guide's angle, rad
SIX_BAR = {"frame": {"joints": {"D": [0.05, 0.25]},
                     "guides": {"g": {"through": [0, 0], "angle": GUIDE}, "ram": {"through": [0, 0.55], "angle": 0}}},
           "input": {"kind": "slider", "link": 1, "guide": "g", "joint": "B", "travel": [-0.1, 0.12]},
           "groups": [{"kind": "RPR", "links": [2, 3], "outer": ["B", "D"], "offset": 0.02, "branch": 1,
                       "points": {"E": {"link": 3, "along": -0.35}}},
                      {"kind": "RRP", "links": [4, 5], "outer": ["E"], "guide": "ram", "inner": "F", "length": 0.3,
                       "branch": 1}]}


def test_structure_counts_the_input_slider():
    for linkage, formula in ((SIX_BAR, "I(0,1) → II₃(2,3) → II₂(4,5)"),
                             (presets()["slider_driven_crank"]["linkage"], "I(0,1) → II₁(2,3)")):
        structure = GeneralMechanism(linkage).structure
        assert structure["W"] == 1 and structure["formula"] == formula and structure["input"] == "slider"
        assert structure["pairs"][0]["kind"] == "P" and structure["pairs"][0]["links"] == [0, 1]
        n = 1 + 2 * len(linkage["groups"])
        assert structure["n"] == n and structure["p5"] == 1 + 3 * len(linkage["groups"])


def test_preset_against_the_cosine_law():
    mech = GeneralMechanism(presets()["slider_driven_crank"]["linkage"])
    s = mech.turn(141)
    comp = compose(mech.linkage, s)
    l2, l3 = 0.3, 0.1
    cos = (s**2 + l3**2 - l2**2) / (2 * s * l3)
    theta3 = comp.links[3][1].th
    assert np.all(theta3 > 0)                     # branch −1: the crank above the guide
    assert np.max(np.abs(theta3 - np.arccos(cos))) <= 1e-12
    assert np.max(np.abs(comp.joints["B"].z - s)) == 0.0


def test_six_bar_constraints_analogs_and_fsolve():
    mech = GeneralMechanism(SIX_BAR)
    mech.check_geometry({})
    travel = mech.turn(221)
    comp = compose(mech.linkage, travel)
    assert all(g.closes.all() and np.min(np.abs(g.determinant)) >= 0.1 for g in comp.groups)
    assert max(constraint_residuals(mech.linkage, comp)) <= 1e-12
    u = np.exp(1j * GUIDE)
    assert np.max(np.abs(comp.joints["B"].z - travel * u)) <= 1e-15
    for k in range(0, 221, 20):
        assert max(fsolve_errors(mech.linkage, comp, k)) <= 1e-10
        assert whole_loop_error(travel[k], comp, k) <= 1e-10
    for s0 in travel[5:-5:20] + 1.3e-4:
        for label, error, size in analog_errors(mech.linkage, s0):
            assert error <= 1e-6 * size + 1e-7, (label, s0)
        plan = plans(compose(mech.linkage, np.array([s0])), 0.8, 3.0)
        for equation in plan["velocity"] + plan["acceleration"]:
            assert equation["residual"] <= 1e-12 * (max(v["value"] for v in equation["vectors"]) + 1.0)


def whole_loop_error(s: float, comp, k: int) -> float:
    """Every unknown of the six-bar (lever θ₃ and slot s₂₃, rod θ₄ and ram x_F) from its two loop closures at
    once: B = s u; B = D + (σ + ie) e^{iθ₃}; E = D − 0.35 e^{iθ₃}; E + 0.3 e^{iθ₄} = (x_F, 0.55); solved by
    fsolve from the code's answer perturbed by 1e-2, the distance of the root's joints from the code's (m)."""
    b = s * np.exp(1j * GUIDE)
    d = 0.05 + 0.25j

    def closure(x):
        th3, s23, th4, xf = x
        lever = np.exp(1j * th3)
        e = d - 0.35 * lever
        gaps = [d + (s23 + 0.02j) * lever - b, e + 0.3 * np.exp(1j * th4) - (xf + 0.55j)]
        return [g.real for g in gaps] + [g.imag for g in gaps]
    code = [comp.links[3][1].th[k], comp.slides["s23"].s[k], comp.links[4][1].th[k], comp.joints["F"].z[k].real]
    root = fsolve(closure, np.array(code) + 1e-2, xtol=1e-14)
    e_root = d - 0.35 * np.exp(1j * root[0])
    return max(abs(e_root - comp.joints["E"].z[k]), abs(root[3] - code[3]))


@pytest.fixture(scope="module")
def client():
    with TestClient(app) as c:
        yield c


def test_api_documents_and_answers_a_slider_input(client):
    example = client.get("/api/v1/mechanisms/general").json()["example_slider_input"]
    body = client.post("/api/v1/kinematics?precision=full", json=example).json()
    travel = example["linkage"]["input"]["travel"]
    assert body["phi"][0] == travel[0] and body["phi"][-1] == travel[1] and len(body["phi"]) == example["n"]
    assert body["outputs"]["structure"]["input"] == "slider" and body["warnings"] == []
    direct = compute_general(example["linkage"], ["angles_d1"], n=example["n"])
    assert np.allclose(body["outputs"]["angles_d1"]["3"], direct.outputs["angles_d1"]["3"], rtol=0, atol=1e-15)


MASSES = {"links": [{"link": k, "mass": 1.0, "centre": [0.0, 0.0], "inertia": 0.01} for k in range(1, 6)]}


@pytest.mark.parametrize("endpoint, extra", [
    ("reduction", {"masses": MASSES, "outputs": ["inertia"], "n": 37}),
    ("forces", {"masses": MASSES, "loads": {"omega": 10.0, "epsilon": 0.0}, "n": 37}),
])
def test_dynamics_and_forces_refuse_a_slider_input(client, endpoint, extra):
    request = {"mechanism": "general", "linkage": SIX_BAR} | extra
    answer = client.post(f"/api/v1/{endpoint}", json=request)
    assert answer.status_code == 422, answer.text[:300]
    detail = answer.json()["detail"][0]
    assert detail["loc"][1:4] == ["linkage", "input", "kind"], detail
    assert detail["ctx"]["code"] == "slider_input_kinematics_only", detail
