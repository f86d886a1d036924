"""POST /api/v1/kinematics with mechanism 'general' and GET /api/v1/mechanisms/general: the documented example
round-trips, outputs come by name, the plan is one more output, and bad input answers 422 naming the field
and the reason (a group on an element that does not exist yet, a loop, W ≠ 1, a rigid group, more than 20
links, lengths that close nowhere)."""
from __future__ import annotations

import copy

import numpy as np
import pytest
from fastapi.testclient import TestClient

from server.api.app import app
from server.core.structure.compose import compose
from server.core.structure.presets import presets
from server.core.structure.spec import parse


@pytest.fixture(scope="module")
def client() -> TestClient:
    with TestClient(app) as c:
        yield c


@pytest.fixture(scope="module")
def example(client) -> dict:
    answer = client.get("/api/v1/mechanisms/general")
    assert answer.status_code == 200
    body = answer.json()
    assert body["schema"]["title"] == "LinkageModel" and len(body["presets"]) == len(presets())
    return body["example"]


def test_the_example_answers_every_output_it_asks(client, example):
    answer = client.post("/api/v1/kinematics?precision=full", json=example)
    assert answer.status_code == 200, answer.text[:300]
    body = answer.json()
    assert list(body["outputs"]) == example["outputs"] and body["warnings"] == []
    assert body["outputs"]["structure"]["formula"] == "I(0,1) → II₃(2,3) → II₂(4,5)"
    assert body["outputs"]["structure"]["W"] == 1
    comp = compose(parse(example["linkage"]), np.asarray(body["phi"]))
    assert np.allclose(np.asarray(body["outputs"]["joints_d1"]["E"]), np.c_[comp.joints["E"].d1.real,
                                                                              comp.joints["E"].d1.imag], rtol=0, atol=0)
    plan = body["outputs"]["plan"]
    names = {v["name"] for eq in plan["acceleration"] for v in eq["vectors"]}
    assert {"k_A3A2", "r_A3A2", "n_A3C", "τ_A3C", "n_ED", "τ_ED"} <= names
    assert max(eq["residual"] for eq in plan["velocity"] + plan["acceleration"]) <= 1e-12


def test_only_the_requested_outputs(client, example):
    body = client.post("/api/v1/kinematics", json=example | {"outputs": ["slides_d2"], "n": 5}).json()
    assert list(body["outputs"]) == ["slides_d2"] and set(body["outputs"]["slides_d2"]) == {"s23", "E/ram"}


def refused(client, request, loc, words):
    answer = client.post("/api/v1/kinematics", json=request)
    assert answer.status_code == 422, answer.text[:300]
    detail = answer.json()["detail"][0]
    assert detail["loc"][:len(loc)] == loc and words in detail["msg"], detail


def with_groups(example, change):
    request = copy.deepcopy(example)
    change(request["linkage"]["groups"])
    return request


def test_unknown_element(client, example):
    def change(groups):
        groups[1]["outer"] = ["Q"]
    refused(client, with_groups(example, change), ["body", "linkage", "groups", "1", "outer", "0"], "does not exist")


def test_a_loop_through_a_later_group(client, example):
    def change(groups):
        groups[0]["outer"] = ["E", "C"]
    refused(client, with_groups(example, change), ["body", "linkage", "groups", "0", "outer", "0"],
            "only by the later group 1")


def test_a_group_on_its_own_joint(client, example):
    def change(groups):
        groups[1]["outer"] = ["E"]
    refused(client, with_groups(example, change), ["body", "linkage", "groups", "1", "outer", "0"],
            "its own joint")


def test_mobility_other_than_one(client, example):
    def change(groups):
        groups[1]["links"] = [3, 5]            # link 3 declared twice: n = 4, p₅ = 7, W = −2
    refused(client, with_groups(example, change), ["body", "linkage", "groups"], "W = 3n − 2p₅ − p₄ = 3·4 − 2·7 − 0 = -2")


def test_a_rigid_group(client, example):
    def change(groups):
        groups[1] = {"kind": "RRR", "links": [4, 5], "outer": ["D", "S3"], "inner": "E", "lengths": [0.1, 0.2]}
    refused(client, with_groups(example, change), ["body", "linkage", "groups", "1", "outer"], "rigid triangle")


def test_more_than_twenty_links(client, example):
    def change(groups):
        groups.extend({"kind": "RRR", "links": [6 + 2 * k, 7 + 2 * k], "outer": ["E", "C"], "inner": f"X{k}",
                       "lengths": [0.3, 0.3]} for k in range(10))
    refused(client, with_groups(example, change), ["body", "linkage", "groups"], "at most 20")


def test_lengths_that_close_nowhere(client, example):
    request = with_groups(example, lambda groups: groups[1].update(length=0.1))
    request["linkage"]["frame"]["guides"]["ram"]["through"] = [0, 0.5]   # the lever's end D stays below y = 0.25
    refused(client, request, ["body", "linkage", "groups", "1"], "cannot be assembled at any")


def test_partly_assembled_says_which_angles(client, example):
    request = with_groups(example, lambda groups: groups[1].update(length=0.01))
    body = client.post("/api/v1/kinematics", json=request | {"outputs": ["joints"], "n": 361}).json()
    assert any("Group II₂(4,5) RRP cannot be assembled at φ =" in w for w in body["warnings"])
    assert any(x is None for x, _ in body["outputs"]["joints"]["E"])


def test_bad_kind_and_branch(client, example):
    refused(client, with_groups(example, lambda g: g[1].update(kind="RRRR")),
            ["body", "linkage", "groups", 1, "kind"], "")
    refused(client, with_groups(example, lambda g: g[1].update(branch=0)),
            ["body", "linkage", "groups", 1, "branch"], "")


def test_plan_needs_its_angle(client, example):
    request = copy.deepcopy(example)
    del request["plan"]
    refused(client, request, ["body"], "the output 'plan' needs the field `plan`")


def test_linkage_only_with_general(client, example):
    refused(client, example | {"mechanism": "slider_crank"}, ["body"], "`linkage` goes with mechanism 'general'")
    refused(client, example | {"params": {"l1": 0.1}}, ["body"], "not in `params`")


def test_absurd_numbers(client, example):
    refused(client, with_groups(example, lambda g: g[1].update(length=1e308)),
            ["body", "linkage", "groups", "1", "length"], "between")
