"""A crank that cannot turn fully is refused by the dynamics estimate as by the four dynamics endpoints: 422 naming
the group (``linkage.groups.1``) and the angles where it does not assemble (server/core/mechanisms/general.py:
GeneralMechanism.require_full_turn)."""
from __future__ import annotations

import copy

import pytest
from fastapi.testclient import TestClient

from server.api.app import app
from server.core.structure.estimate import estimated_dynamics

# A six-bar whose second group (the RRP dyad from D to the guide g) is 0.015 m long: D's distance from g runs over
# 0.0008…0.030 m, so the dyad assembles only on part of the turn.
SIX_BAR = {
    "frame": {"joints": {"O": [0.0, 0.0], "C": [0.28, -0.05]}, "guides": {"g": {"through": [0.0, 0.32], "angle": 0}}},
    "input": {"link": 1, "pivot": "O", "joint": "A", "length": 0.08},
    "groups": [
        {"kind": "RRR", "links": [2, 3], "outer": ["A", "C"], "inner": "B", "lengths": [0.3, 0.25], "branch": 1,
         "points": {"D": {"link": 3, "along": 0.4}}},
        {"kind": "RRP", "links": [4, 5], "outer": ["D"], "guide": "g", "inner": "E", "length": 0.2, "branch": 1},
    ],
}
PART_TURN = copy.deepcopy(SIX_BAR)
PART_TURN["groups"][1]["length"] = 0.015


@pytest.fixture(scope="module")
def client():
    with TestClient(app) as c:
        yield c


def refusal(answer) -> dict:
    assert answer.status_code == 422, answer.text[:300]
    return answer.json()["detail"][0]


def test_estimate_refuses_a_crank_that_cannot_turn_fully_as_the_dynamics_endpoints_do(client):
    estimate = refusal(client.post("/api/v1/dynamics-estimate", json={"linkage": PART_TURN}))
    assert estimate["loc"] == ["body", "linkage", "groups", "1"]
    assert "cannot turn fully" in estimate["msg"] and estimate["ctx"]["code"] == "no_full_turn"
    first = estimated_dynamics(SIX_BAR)          # a machine for the full six-bar, sent with the short dyad
    body = {"mechanism": "general", "linkage": PART_TURN, "masses": first["masses"], "inertias": first["inertias"]}
    others = {"reduction": {"outputs": ["inertia"]}, "motion": {"motor": first["motor"], "outputs": ["steady"]},
              "flywheel": first["flywheel"]}
    for endpoint, extra in others.items():
        detail = refusal(client.post(f"/api/v1/{endpoint}", json={**body, **extra}))
        assert detail["loc"] == estimate["loc"] and detail["msg"] == estimate["msg"], endpoint


def test_estimate_still_answers_the_full_six_bar(client):
    answer = client.post("/api/v1/dynamics-estimate", json={"linkage": SIX_BAR})
    assert answer.status_code == 200 and answer.json()["masses"]["links"]
