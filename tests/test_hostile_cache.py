"""The response cache must never change what validation says.

Reproductions (they failed with the cache keyed on the raw body, rounded to 10 digits, in front of validation):
once l1 = 1.0 was cached, l1 = 1.00000000001 (above its bound of 1 m) answered 200 with l1: 1.0; after a hit,
the same body without a Content-Type (FastAPI reads such a body as text, 422) answered 200 too. The cache now
looks up only a request that validated, keyed on the validated model, exactly (no rounding of its numbers).
"""
from __future__ import annotations

import json

import pytest
from fastapi.testclient import TestClient

from server.api.app import create_app

API = "/api/v1"
AT_BOUND = {"mechanism": "slider_crank", "params": {"l1": 1.0, "l2": 3.0, "e": 0.0}, "n": 5, "outputs": ["s"]}


@pytest.fixture
def client(monkeypatch) -> TestClient:
    monkeypatch.delenv("MDL_CACHE_BYTES", raising=False)
    return TestClient(create_app())


def with_l1(l1: float) -> dict:
    return {**AT_BOUND, "params": {**AT_BOUND["params"], "l1": l1}}


def test_a_value_past_its_bound_is_refused_even_when_a_value_within_rounding_of_it_is_cached(client):
    cached = client.post(f"{API}/kinematics", json=AT_BOUND)
    assert cached.status_code == 200 and cached.headers["x-cache"] == "miss"
    past = client.post(f"{API}/kinematics", json=with_l1(1.00000000001))
    assert past.status_code == 422, past.text
    assert past.json()["detail"][0]["loc"][:2] == ["body", "params"]
    assert "x-cache" not in past.headers or past.headers["x-cache"] == "miss"


def test_a_value_within_rounding_of_a_cached_one_is_its_own_question(client):
    """Two valid values that differ past the 10th digit are two questions: the answer echoes the value asked."""
    client.post(f"{API}/kinematics", json=with_l1(0.5))
    near = client.post(f"{API}/kinematics", json=with_l1(0.50000000001))
    assert near.status_code == 200 and near.headers["x-cache"] == "miss"
    assert near.json()["params"]["l1"] == 0.50000000001


def test_a_geometry_refused_value_next_to_a_cached_one_is_still_refused(client):
    """The core's own check (the rod longer than the crank) is not bypassed by a neighbour in the cache."""
    almost = {**AT_BOUND, "params": {"l1": 0.1, "l2": 0.10000000001, "e": 0.0}}
    assert client.post(f"{API}/kinematics", json=almost).status_code == 200
    equal = client.post(f"{API}/kinematics", json={**AT_BOUND, "params": {"l1": 0.1, "l2": 0.1, "e": 0.0}})
    assert equal.status_code == 422 and equal.json()["detail"][0]["type"] == "geometry_error"


def test_after_a_hit_a_body_without_a_content_type_is_still_refused(client):
    assert client.post(f"{API}/kinematics", json=AT_BOUND).status_code == 200
    assert client.post(f"{API}/kinematics", json=AT_BOUND).headers["x-cache"] == "hit"
    bare = client.post(f"{API}/kinematics", content=json.dumps(AT_BOUND).encode())    # no Content-Type
    assert bare.status_code == 422 and bare.json()["detail"][0]["loc"] == ["body"]


def test_after_a_hit_an_invalid_query_is_still_refused(client):
    assert client.post(f"{API}/kinematics", json=AT_BOUND).status_code == 200
    for query in ("lang=xx", "precision=all"):
        refused = client.post(f"{API}/kinematics?{query}", json=AT_BOUND)
        assert refused.status_code == 422, query


def test_the_last_of_a_repeated_query_parameter_decides_like_the_route(client):
    """FastAPI reads the last value of a repeated parameter: lang=ru&lang=en is English, lang=en&lang=ru
    Russian, so they are two entries (the old key sorted the pairs and made them one)."""
    body = {**AT_BOUND, "params": {"l1": 0.1, "l2": 0.1000001, "e": 0.0}, "outputs": ["s", "u31"]}
    english = client.post(f"{API}/kinematics?lang=ru&lang=en", json=body)
    russian = client.post(f"{API}/kinematics?lang=en&lang=ru", json=body)
    assert russian.headers["x-cache"] == "miss"
    assert english.json()["warnings"] != russian.json()["warnings"]


def test_the_same_validated_request_hits_whatever_the_key_order_or_defaults_spelled_out(client):
    first = client.post(f"{API}/kinematics", json=AT_BOUND)
    reordered = client.post(f"{API}/kinematics", content=json.dumps(dict(reversed(AT_BOUND.items()))),
                            headers={"content-type": "application/json"})
    assert reordered.headers["x-cache"] == "hit" and reordered.content == first.content
