"""POST /api/v1/forces with friction: the issue's request answered with finite values and an honest numerics
entry, self-locking only where the guide's friction angle is reached, and bad input refused naming the field."""
import json

import numpy as np
import pytest
from fastapi.testclient import TestClient

from server.api.app import app

client = TestClient(app)
ISSUE = {"params": {"l1": 0.1, "l2": 0.13}, "loads": {"force": 1000, "gravity": False, "omega": 10},
         "pairs": {"f34": 0.8}, "n": 73}


def strict(response):
    assert response.status_code == 200, response.text
    return json.loads(response.text, parse_constant=lambda name: pytest.fail(f"{name} in the response"))


def test_issue_body_is_finite_with_efficiency_and_no_self_locking():
    """f·tan ψ ≤ 0.963: nothing locks.  Closed form of this case (massless rod, guide friction only):
    M_bal = |dx_B/dφ|·P/(1 − f|tan ψ|); compared to ε_R = 1e-9 (the request's default tolerance)."""
    data = strict(client.post("/api/v1/forces?precision=full", json=ISSUE))
    assert data["warnings"] == []
    assert all(value is not None for value in data["balancing_moment"])
    assert all(data["converged"])
    assert 0 < data["efficiency"] < 1
    phi = np.asarray(data["phi"])
    s = 0.1 * np.sin(phi)
    root = np.sqrt(0.13**2 - s**2)
    tan_psi = np.abs(s) / root
    dxB = 0.1 * np.sin(phi) - s * 0.1 * np.cos(phi) / root
    expected = np.abs(dxB) * 1000 / (1 - 0.8 * tan_psi)
    assert np.asarray(data["balancing_moment"]) == pytest.approx(expected, rel=1e-9, abs=1e-9 * expected.max())
    assert max(data["iteration"]["guide_ratio"]) == pytest.approx(0.963, abs=1e-3)
    numerics = data["numerics"]
    assert numerics["rtol"] == 1e-9 and numerics["error_estimate"] <= 1e-9
    assert numerics["message_code"] == "approximations_truncated" and data["iteration"]["approximations"] == 60


def test_numerics_and_self_locking_speak_ukrainian():
    body = ISSUE | {"pairs": {"f34": 1.0}}                 # f·tan ψ up to 1.2: locks around 90° and 270°
    data = strict(client.post("/api/v1/forces?lang=uk", json=body))
    assert any("Самогальмування" in w for w in data["warnings"])
    assert None in data["balancing_moment"] and data["efficiency"] is None
    assert "Ньютона" in data["numerics"]["method"] and "наближень" in data["numerics"]["message"]


@pytest.mark.parametrize("change, loc, words", [
    ({"pairs": {"f34": 2.5}}, ["body", "pairs", "f34"], ["less than or equal to 2"]),
    ({"pairs": {"f34": 0.8, "mu": 0.1}}, ["body", "pairs", "mu"], ["extra"]),
    ({"tolerance": 0}, ["body", "tolerance"], ["greater than or equal"]),
    ({"loads": {"force": -1}}, ["body", "loads", "force"], ["greater than or equal to 0"]),
    ({"n": 5}, ["body", "n"], ["greater than or equal to 13"]),
])
def test_bad_input_is_refused_naming_the_field(change, loc, words):
    response = client.post("/api/v1/forces", json=ISSUE | change)
    assert response.status_code == 422, response.text
    error = response.json()["detail"][0]
    assert error["loc"] == loc
    for word in words:
        assert word in error["msg"].lower()
