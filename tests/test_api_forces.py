"""The force-analysis API: reactions with the crank check of (3.2), wear beside the book's values, chains."""
import json

import pytest
from fastapi.testclient import TestClient

from server.api.app import app

client = TestClient(app)
MACHINE = {"params": {"l1": 0.1, "l2": 0.4, "a2": 0.3},
           "loads": {"m2": 3, "J_S2": 0.05, "m3": 2, "omega": 50, "force": 1000, "return_factor": 0.2}}


def strict(response):
    return json.loads(response.text, parse_constant=lambda name: pytest.fail(f"{name} in the response"))


def test_frictionless_crank_check_is_exact_and_friction_shows_its_share():
    free = strict(client.post("/api/v1/forces", json=MACHINE))
    assert free["crank_check"]["frictionless"] < 1e-9 and free["efficiency"] == pytest.approx(1.0, rel=1e-4)
    rough = strict(client.post("/api/v1/forces", json=MACHINE | {"pairs": {"f12": 0.1, "f23": 0.1, "f34": 0.15}}))
    assert rough["crank_check"]["with_friction"] > 1e-3 and rough["efficiency"] < free["efficiency"]
    assert rough["iteration"]["ratio"] < 1 and rough["friction_circles"]["A"] == pytest.approx(0.1 * 0.015)


def test_self_locking_slider_comes_back_as_words_and_nulls():
    body = {"params": {"l1": 0.1, "l2": 0.102}, "loads": {"force": 1000, "omega": 1, "gravity": False},
            "pairs": {"f34": 0.5}, "n": 73}
    data = strict(client.post("/api/v1/forces?lang=uk", json=body))
    assert None in data["balancing_moment"] and any("Самогальмування" in w for w in data["warnings"])


def test_wear_of_the_two_stroke_engine_stands_beside_the_book():
    body = {"params": {"l1": 0.045, "l2": 0.18, "a2": 0.38},
            "loads": {"m2": 1.8, "m3": 1.33, "J1": 0.09, "gas": {"kind": "indicator", "p_max": 3e6, "piston_diameter": 0.075}}}
    data = strict(client.post("/api/v1/wear", json=body))
    assert data["book"] == {"bush_23": 88.0, "pin_23": 36.0, "cylinder": 43.0, "piston": 76.0}
    for key in ("pin", "bush", "cylinder"):
        assert max(data[key]) > 0
    assert 0 < data["piston"] < data["allowed"][1]


def test_efficiency_of_chains():
    assert client.post("/api/v1/efficiency-chain", json={"efficiencies": [0.9, 0.8]}).json() == \
        {"series": pytest.approx(0.72)}
    both = client.post("/api/v1/efficiency-chain", json={"efficiencies": [0.9, 0.8], "works": [100, 300]}).json()
    assert both["parallel"] == pytest.approx((90 + 240) / 400)
    assert client.post("/api/v1/efficiency-chain", json={"efficiencies": [1.2]}).status_code == 422
