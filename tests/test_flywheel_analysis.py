"""Lecture 10 §10.4, step 8: the analysis problem (the flywheel's I given, δ found) against the synthesis
(I for [δ], flywheel.exact and Merzalov) and against the notes' worked numbers for the drilling rig (§4.2:
the transfer functions and I_II of (L12)–(L14), (L18)) and the analytic case of §4.3."""
from __future__ import annotations

import json

import numpy as np
import pytest
from fastapi.testclient import TestClient

from server.api.app import create_app
from server.core.dynamics import flywheel as fw
from server.core.dynamics.flywheel_analysis import merzalov_delta
from server.core.mechanisms import MECHANISMS

RIG = {"mechanism": "slider_crank", "params": {"l1": 0.12, "l2": 0.528, "e": 0, "a2": 0.32008},
       "inertias": {"J1": 2.72, "m2": 24.2, "J_S2": 1.21, "m3": 36.2},
       "motor": {"kind": "indicator", "p_max": 4.4e6, "piston_diameter": 0.1, "strokes": 2},
       "omega_mean": 47.124, "delta": 0.0125, "inertia": 38.0,
       "outputs": ["analysis", "synthesis", "driving_moment", "transfer_functions"]}


@pytest.fixture(scope="module")
def client():
    return TestClient(create_app())


def post(client, **change):
    answer = client.post("/api/v1/flywheel-analysis?precision=full", json={**RIG, **change})
    assert answer.status_code == 200, answer.text
    assert "NaN" not in answer.text and "Infinity" not in answer.text
    return answer.json()


def test_analysis_then_synthesis_returns_the_given_inertia(client):
    """I → δ (analysis) → I (synthesis with that δ as [δ], the exact method): the same flywheel to 1e-7
    (both Brent's method to 1e-14 on the same grid; the round trip is limited by δ's sensitivity to I)."""
    given = post(client)
    delta = given["analysis"]["delta_exact"]
    back = post(client, delta=delta)["synthesis"]
    assert back["flywheel_exact"] == pytest.approx(38.0, rel=1e-7)
    assert given["analysis"]["inertia_i"] == pytest.approx(38.0 + 2.72, rel=1e-15)


def test_merzalov_analysis_inverts_merzalov_synthesis_and_overstates_delta(client):
    """(L6) read both ways: the Merzalov inertia for [δ] gives back exactly [δ] by (L6) (an identity, 1e-12);
    the exact δ of that inertia is smaller: Merzalov is conservative (Lecture 10 §10.7)."""
    merz = post(client)["synthesis"]["merzalov"]
    check = post(client, inertia=merz - 2.72)["analysis"]
    assert check["delta_merzalov"] == pytest.approx(0.0125, rel=1e-12)
    assert check["delta_exact"] < 0.0125


def test_the_analytic_case_of_the_notes():
    """An analytic case: I_II = 0, M_Σ = M_a sin φ, M_a = 100 N·m, ω = 47.124 rad/s: I_I = 7.2050 kg·m² gives
    δ = 2M_a/(I_I ω²) = 1/80, Merzalov exact here (printed to 5 digits: rel 1e-4)."""
    phi = np.linspace(0, 2 * np.pi, 4097)
    cycle = fw.Cycle(phi, 100 * (1 - np.cos(phi)), np.zeros_like(phi))
    assert merzalov_delta(cycle, 7.2050, 47.124) == pytest.approx(1 / 80, rel=1e-4)
    assert fw.achieved_delta(cycle, 7.2050, 47.124) == pytest.approx(1 / 80, rel=1e-4)


def test_the_rigs_reduced_inertia_of_group_two_as_the_notes_compute_it():
    """Lecture 10's rig (§10.5) by (L12)–(L14), (L18): I_II max 0.90191 at φ₁ ≈ 168°, min 0.22360 at the dead centres,
    cycle mean 0.55079 kg·m², max|V_qC| = 0.12307 m (5 digits printed: abs 2e-5; 36 000 points, the
    sampling error at the peak ~1e-9)."""
    phi = np.linspace(0, 2 * np.pi, 36001)
    values = MECHANISMS["slider_crank"].evaluate(RIG["params"], phi, set()).values
    inertia_ii = 24.2 * values["chi21"] ** 2 + 1.21 * values["u21"] ** 2 + 36.2 * values["u31"] ** 2
    assert inertia_ii.max() == pytest.approx(0.90191, abs=2e-5)
    assert inertia_ii.min() == pytest.approx(0.22360, abs=2e-5)
    assert np.mean(inertia_ii[:-1]) == pytest.approx(0.55079, abs=2e-5)
    assert np.abs(values["u31"]).max() == pytest.approx(0.12307, abs=2e-5)


# Lecture 10's rig by (L12)–(L14), (L18), every 30° of the lecture's φ₁: u₂₁, V_qC, V_qS2, I_II^пр
TABLE = [(0, 0.0000, 0.1200, 0.1200, 0.8698), (30, -0.1159, 0.1160, 0.1152, 0.8245),
         (60, -0.1981, 0.0719, 0.0952, 0.4539),
         (90, -0.2273, 0.0000, 0.0816, 0.2236), (120, -0.1981, -0.0719, 0.0952, 0.4539),
         (150, -0.1159, -0.1160, 0.1152, 0.8245), (180, 0.0000, -0.1200, 0.1200, 0.8698),
         (210, 0.1159, -0.0919, 0.1081, 0.6044), (240, 0.1981, -0.0481, 0.0903, 0.3285),
         (270, 0.2273, 0.0000, 0.0816, 0.2236),
         (300, 0.1981, 0.0481, 0.0903, 0.3285), (330, 0.1159, 0.0919, 0.1081, 0.6044)]


def test_the_transfer_functions_are_the_notes_table():
    """The table of §4.2 (4 decimals: abs 6e-5). This app measures φ from the inner dead centre with the
    piston on x, the lecture φ₁ from x with the piston on y, so φ = φ₁ + 90°; the signs of u₂₁ and V_qC
    follow each one's sense of rotation, so their magnitudes are compared."""
    lecture = np.radians([row[0] for row in TABLE])
    values = MECHANISMS["slider_crank"].evaluate(RIG["params"], lecture + np.pi / 2, set()).values
    u21, vc, vs2, inertia = (np.array([row[k] for row in TABLE]) for k in (1, 2, 3, 4))
    assert np.allclose(np.abs(values["u21"]), np.abs(u21), atol=6e-5)
    assert np.allclose(np.abs(values["u31"]), np.abs(vc), atol=6e-5)
    assert np.allclose(values["chi21"], vs2, atol=6e-5)
    computed = 24.2 * values["chi21"] ** 2 + 1.21 * values["u21"] ** 2 + 36.2 * values["u31"] ** 2
    assert np.allclose(computed, inertia, atol=6e-5)


def test_the_answer_draws_those_transfer_functions(client):
    """The answer's curves are the mechanism's at the answer's angles (bit for bit: the same closed forms)."""
    data = post(client)
    values = MECHANISMS["slider_crank"].evaluate(RIG["params"], np.array(data["phi"]), set()).values
    for name, key in (("u21", "u21"), ("u31", "u31"), ("v_s2", "chi21")):
        assert np.array(data["transfer_functions"][name]) == pytest.approx(values[key], rel=1e-15, abs=1e-15)


def test_the_driving_moment_balances_the_resisting_one_over_the_cycle(client):
    """Fig. 10.6: ∫M_д dφ = ∫M_с dφ over the cycle (L1), by the trapezoid rule on the answer's points, 0.88°
    apart (rel 3e-3: the gas force's steep expansion after the dead centre, 1.5e-3 measured; the answer's own
    balance is Simpson's on 4096 intervals)."""
    data = post(client)
    phi, moments = np.array(data["phi"]), data["driving_moment"]
    driving = np.trapezoid(moments["driving"], phi)
    assert driving > 0
    assert np.trapezoid(moments["resisting"], phi) == pytest.approx(driving, rel=3e-3)


@pytest.mark.parametrize("change, field", [({"inertia": -1}, "inertia"), ({"outputs": []}, "outputs"),
                                           ({"motor": {"kind": "linear", "M0": 30, "b": 1}}, "motor.kind")])
def test_bad_input_is_refused_naming_the_field(client, change, field):
    answer = client.post("/api/v1/flywheel-analysis", json={**RIG, **change})
    assert answer.status_code == 422
    assert field.split(".")[0] in json.dumps(answer.json())
