"""The OpenAPI schema tells the truth: answers that once contradicted it, each checked against the schema the
app publishes at /api/v1/openapi.json (JSON Schema 2020-12, as OpenAPI 3.1 uses it).

1. /reduction asked for errata only answers without φ (errata are values of the cycle, not of φ): the schema
   says φ may be absent, and describes the errata.
2. /angular-acceleration's times are bounded (±T_MAX_S): a time of -1.6e306 s, where the accelerating law's
   t² overflowed to inf and the answer held nulls where the schema says numbers, is 422 naming the field and
   the reason; the extremes of every law within the bounds answer numbers only.
3. An integer of more than 4300 digits (Python's int_max_str_digits) in any JSON body is the documented 422
   naming the body and the reason, with the security headers, not a bare 400.
"""
from __future__ import annotations

import json
from functools import lru_cache

import jsonschema
import pytest
from fastapi.testclient import TestClient

from server.api.app import app
from server.api.schemas_angular import T_MAX_S
from server.api.security import SECURITY_HEADERS

API = "/api/v1"
client = TestClient(app)


@lru_cache(maxsize=1)
def openapi() -> dict:
    return client.get(f"{API}/openapi.json").json()


def check_against_schema(path: str, response, status: int | None = None) -> None:
    """The answer's JSON is valid against the schema the OpenAPI document gives for `path` and its status."""
    status = status or response.status_code
    documented = openapi()["paths"][path]["post"]["responses"][str(status)]
    if "content" in documented:
        schema = documented["content"]["application/json"]["schema"]
    else:                   # a 422 described in words: FastAPI's validation error format, as the API says
        assert status == 422, f"{path} documents no body for {status}"
        schema = {"$ref": "#/components/schemas/HTTPValidationError"}
    validator = jsonschema.Draft202012Validator({**schema, "components": openapi()["components"]})
    errors = sorted(validator.iter_errors(response.json()), key=lambda e: list(e.path))
    assert not errors, [f"{list(e.path)}: {e.message[:200]}" for e in errors[:5]]


def finite_numbers_only(value) -> bool:
    if isinstance(value, dict):
        return all(finite_numbers_only(v) for k, v in value.items() if k != "points")
    if isinstance(value, list):
        return all(finite_numbers_only(v) for v in value)
    return value is not None


# --- 1. /reduction: φ absent when only errata are asked ------------------------------------------------------

@pytest.mark.parametrize("mechanism", ["sine", "slider_crank", "slotted_link"])
@pytest.mark.parametrize("outputs", [["errata"], ["errata", "inertia"]])
def test_reduction_answers_as_its_schema_says(mechanism, outputs):
    response = client.post(f"{API}/reduction", json={"mechanism": mechanism, "outputs": outputs})
    assert response.status_code == 200, response.text
    check_against_schema(f"{API}/reduction", response)
    assert ("phi" in response.json()) == ("inertia" in outputs)


def test_the_reduction_schema_requires_no_phi_and_describes_the_errata():
    schema = openapi()["components"]["schemas"]["ReductionResponse"]
    assert "phi" not in schema.get("required", [])
    assert "errata" in schema["properties"]


# --- 2. /angular-acceleration: times within physical bounds -------------------------------------------------

@pytest.mark.parametrize("law", ["constant", "accelerating", "harmonic"])
@pytest.mark.parametrize("t", [-1.6e306, 1.6e306, -T_MAX_S * 1.001, 1e300])
def test_a_time_beyond_the_bound_is_422_naming_the_field(law, t):
    response = client.post(f"{API}/angular-acceleration", json={"law": law, "epsilon0": 1.0, "t": [0.0, t]})
    assert response.status_code == 422, response.text[:300]
    error = response.json()["detail"][0]
    assert error["loc"] == ["body", "t", 1]
    assert f"{T_MAX_S:g}" in error["msg"].replace("10000.0", "10000") and error["type"] in ("less_than_equal",
                                                                                         "greater_than_equal")
    check_against_schema(f"{API}/angular-acceleration", response, 422)


EXTREMES = [{"law": "constant", "omega0": 1e3}, {"law": "accelerating", "omega0": 1e3, "epsilon0": 1e3},
            {"law": "harmonic", "omega0": 1e3, "amplitude": 0.999, "frequency": 1e3},
            {"law": "harmonic", "omega0": 1e-3, "amplitude": 0.999, "frequency": 1e-9}]


@pytest.mark.parametrize("mechanism", ["crank_slider", "trammel"])
@pytest.mark.parametrize("law", EXTREMES, ids=lambda law: law["law"])
def test_the_extremes_within_the_bounds_answer_numbers_as_the_schema_says(mechanism, law):
    body = {"mechanism": mechanism, **law, "lam": 0.99, "t": [-T_MAX_S, -1.0, 0.0, 1.0, T_MAX_S]}
    response = client.post(f"{API}/angular-acceleration", json=body, params={"precision": "full"})
    assert response.status_code == 200, response.text[:300]
    check_against_schema(f"{API}/angular-acceleration", response)
    answer = response.json()
    assert finite_numbers_only({k: v for k, v in answer.items() if k not in ("numerics", "warnings", "psi")})


# --- 3. an integer past Python's limit of digits ------------------------------------------------------------

LONG = "1" * 5000


@pytest.mark.parametrize("path, body", [
    ("/angular-acceleration", '{"t": [%s]}' % LONG),
    ("/reduction", '{"mechanism": "sine", "outputs": ["errata"], "n": -%s}' % LONG),
    ("/assignments", '{"scene": "flywheel", "attempts": %s}' % LONG),
    ("/kinematics", '{"mechanism": "slider_crank", "params": {"r": %s}}' % LONG)])
def test_an_integer_of_more_than_4300_digits_is_the_documented_422(path, body):
    response = client.post(f"{API}{path}", content=body.encode(), headers={"Content-Type": "application/json"})
    assert response.status_code == 422, response.text[:200]
    error = response.json()["detail"][0]
    assert error["loc"] == ["body"] and error["type"] == "body_integer_too_long"
    assert "5000 digits" in error["msg"] and "4300" in error["msg"]
    for name, value in SECURITY_HEADERS.items():
        assert response.headers[name] == value
    check_against_schema(f"{API}{path}", response, 422)


def test_long_numbers_that_python_reads_pass_to_validation():
    """A float of many digits, an exponent of many digits, and digits in a string are not integers: Python
    reads them, and validation answers them as usual."""
    for t in (f"1.{LONG}", f"1e{LONG}", json.dumps(LONG), "-" + "1" * 4300):
        response = client.post(f"{API}/angular-acceleration", content=('{"t": [%s]}' % t).encode(),
                               headers={"Content-Type": "application/json"})
        assert response.status_code in (200, 422), response.text[:200]
        if response.status_code == 422:
            assert response.json()["detail"][0].get("type") != "body_integer_too_long", t[:20]
