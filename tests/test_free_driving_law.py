"""A free law M_P(φ₁) of the driving moment for the transient regime (Chaika–Vasylenko §3.4, step 9: the
driving moment given as a function of the crank angle): a table of points (φ_j, M_j) in the request, linear
between them and periodic over a turn; checked against the constant motor it must equal, the cycle's work
balance, the interpolation by hand, and refused with 422 naming the field for bad tables."""
import json

import numpy as np
import pytest
from fastapi.testclient import TestClient

from server.api.endpoints import compute
from server.api.app import app
from server.core.dynamics.motors import Motor, table_moment

client = TestClient(app)
MACHINE = {"mechanism": "slider_crank", "params": {"l1": 0.1, "l2": 0.4},
           "inertias": {"J1": 0.5, "m2": 3.0, "J_S2": 0.05, "m3": 2.0}, "load": {"force": 300.0}}
NODES = np.linspace(0, 2 * np.pi, 13)[:-1]


def table(moments) -> dict:
    return {"kind": "table", "table_phi": NODES.tolist(), "table_moment": list(map(float, moments))}


def test_interpolation_between_the_points_and_across_the_turn_by_hand():
    """Linear between φ_j; from the last point (330°) back to the first (0° + 360°); periodic in φ."""
    motor = Motor(kind="table", table_phi=(0.5, 2.0, 4.0), table_moment=(10.0, -20.0, 40.0))
    at = table_moment(motor, np.array([0.5, 1.25, 3.0, 4.0, 2 * np.pi + 1.25]))
    np.testing.assert_allclose(at, [10.0, -5.0, 10.0, 40.0, -5.0], rtol=0, atol=1e-12)
    wrap = 0.5 + 2 * np.pi - 4.0                            # from φ = 4.0 to 0.5 + 2π
    middle = table_moment(motor, np.array([4.0 + wrap / 2, 0.0]))
    np.testing.assert_allclose(middle, [25.0, 40.0 + (10.0 - 40.0) * (2 * np.pi - 4.0) / wrap], atol=1e-12)


def test_a_flat_table_is_the_constant_motor():
    """M_j = 40 N·m everywhere: the start-up ω(φ) equals the constant motor's M₀ = 40 at every dead centre
    φ = kπ, a node of both integrations (rel 1e-8: both integrated to rtol 1e-8; the table's points add nodes)."""
    body = MACHINE | {"omega0": 5.0, "outputs": ["startup"]}
    flat = compute("motion", body | {"motor": table(np.full(NODES.size, 40.0))})["startup"]
    constant = compute("motion", body | {"motor": {"kind": "constant", "M0": 40.0}})["startup"]
    def at_dead_centres(answer):      # the load's kinks, φ = kπ, are nodes of every integration
        phi, omega = np.asarray(answer["phi"]), np.asarray(answer["omega"])
        k = np.round(phi / np.pi)
        on = np.abs(phi - k * np.pi) < 1e-9
        return dict(zip(k[on].astype(int), omega[on]))
    flat_nodes, constant_nodes = at_dead_centres(flat), at_dead_centres(constant)
    common = sorted(set(flat_nodes) & set(constant_nodes))
    assert len(common) > 20
    np.testing.assert_allclose([flat_nodes[k] for k in common], [constant_nodes[k] for k in common], rtol=1e-8)


def test_a_balanced_law_has_a_steady_cycle_whose_driving_work_is_the_tables_integral():
    """M_j = 30 + 15 sin 3φ_j over 12 points: the trapezoid of the sine over the nodes is 0, so the turn's
    driving work is 30·2π = 188.496 J (rel 1e-9); the slider's 300 N over two strokes of 0.2 m takes 120 J, the
    balancing moment (balance) is (188.496 − 120)/(2π) = 10.9014 N·m; at ω_m = 20 rad/s."""
    moments = 30 + 15 * np.sin(3 * NODES)
    answer = compute("motion", MACHINE | {"outputs": ["steady"], "balance": True, "omega_mean": 20.0,
                                          "motor": table(moments)})
    assert answer["works"]["driving"] == pytest.approx(60 * np.pi, rel=1e-9)
    assert answer["works"]["balancing_moment"] == pytest.approx((60 * np.pi - 120) / (2 * np.pi), rel=1e-9)
    assert answer["omega_mean"] == pytest.approx(20.0, rel=1e-9) and answer["delta"] > 0


@pytest.mark.parametrize("motor, field", [
    ({"kind": "table", "table_phi": [0.0, 2.0, 1.0], "table_moment": [1.0, 2.0, 3.0]}, "table_phi"),
    ({"kind": "table", "table_phi": [0.0, 7.0], "table_moment": [1.0, 2.0]}, "table_phi"),
    ({"kind": "table", "table_phi": [0.0, 1.0], "table_moment": [1.0, 2e8]}, "table_moment"),
    ({"kind": "table", "table_phi": [0.0], "table_moment": [1.0]}, "table_phi"),
    ({"kind": "table", "table_phi": [0.0, 1.0], "table_moment": [1.0, 2.0, 3.0]}, "motor"),
    ({"kind": "table", "table_phi": [0.0, 1.0]}, "motor"),
    ({"kind": "constant", "M0": 5.0, "table_phi": [0.0, 1.0], "table_moment": [1.0, 2.0]}, "motor"),
    ({"kind": "table", "table_phi": [0.0, "NaN"], "table_moment": [1.0, 2.0]}, "table_phi"),
])
def test_bad_free_laws_are_422_naming_the_field(motor, field):
    response = client.post("/api/v1/motion?lang=en", json=MACHINE | {"motor": motor, "outputs": ["steady"]})
    assert response.status_code == 422
    assert field in json.dumps([e["loc"] for e in response.json()["detail"]])


def test_elastic_models_refuse_the_free_law():
    body = {"mechanism": "slider_crank", "params": {"l1": 0.1, "l2": 0.4}, "inertias": {"J1": 0.5, "m3": 2.0},
            "motor": table(np.full(NODES.size, 40.0))}
    response = client.post("/api/v1/elastic?lang=en", json=body)
    assert response.status_code == 422


def test_the_equation_of_motion_scene_has_a_free_law_variant():
    """The variant 'free_law' drives the crank-slider by 12 points (20 … 100 … 0 N·m); its steady cycle at
    ω_m = 30 rad/s: the driving work is the table's trapezoid over the turn, 2π·mean(M_j) = 2π·470/12 J (rel 1e-6:
    the scene's angles are written to 6 decimals, so their steps differ from 30° by up to 1e-6 rad)."""
    from server.lessons.requests import scene_request
    from server.lessons.scenes import scenes
    scene = scenes()["equation-of-motion"]
    variant = next(v for v in scene.variants if v.id == "free_law")
    request = scene_request(scene, variant)
    assert request["motor"]["kind"] == "table" and len(request["motor"]["table_phi"]) == 12
    answer = compute("motion", request)
    assert answer["warnings"] == []
    assert answer["works"]["driving"] == pytest.approx(2 * np.pi * 470 / 12, rel=1e-6)
    assert 0 < answer["delta"] < 0.1
