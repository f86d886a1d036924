"""Every float field of every request model refuses NaN and ±inf as "not a finite number", whatever its bounds
(a bounded field used to say "less than or equal to 100000" of a NaN, which no bound explains): the request
models carry pydantic's ``allow_inf_nan=False``.  JSON as Python reads it accepts the literals NaN and Infinity;
the raw bodies below send them so."""
from __future__ import annotations

import importlib
import math
import types
import typing

import pytest
from fastapi.testclient import TestClient
from pydantic import BaseModel

from server.api.app import app


SCHEMAS = ("schemas", "schemas_angular", "schemas_bearings", "schemas_cycle", "schemas_dynamics", "schemas_elastic",
           "schemas_forces", "schemas_friction_influence", "schemas_motor", "schemas_project", "schemas_wear",
           "schemas_assignments", "routers.family")


def request_models() -> list[type[BaseModel]]:
    """Every request model of the API (those that forbid unknown fields; the answers' models do not), and every
    model nested in them."""
    found, todo = {}, []
    for module in SCHEMAS:
        names = vars(importlib.import_module(f"server.api.{module}"))
        todo += [kind for kind in names.values() if isinstance(kind, type) and issubclass(kind, BaseModel)
                 and kind.model_config.get("extra") == "forbid"]
    while todo:
        model = todo.pop()
        if model.__name__ in found:
            continue
        found[model.__name__] = model
        for field in model.model_fields.values():
            todo += [kind for kind in _leaves(field.annotation)
                     if isinstance(kind, type) and issubclass(kind, BaseModel)]
    return sorted(found.values(), key=lambda m: m.__name__)


def _leaves(annotation) -> list:
    """The types inside an annotation (unions, lists, dicts, Annotated)."""
    args = typing.get_args(annotation)
    if not args:
        return [annotation]
    origin = typing.get_origin(annotation)
    if origin is typing.Literal:
        return []
    return [leaf for arg in args for leaf in _leaves(arg)]


def float_sample(annotation):
    """(a value holding one non-finite float where the annotation takes a number, the loc suffix to it) or None:
    float, float | None, list[float], tuple[float, ...], dict[str, float]."""
    origin, args = typing.get_origin(annotation), typing.get_args(annotation)
    if annotation is float:
        return math.nan, ()
    if origin in (typing.Union, types.UnionType):
        members = [a for a in args if a is not type(None)]
        return float_sample(members[0]) if len(members) == 1 else None
    if origin is typing.Annotated:
        return float_sample(args[0])
    if origin in (list, tuple) and args and args[0] is float:
        return [math.nan] * (len(args) if origin is tuple and Ellipsis not in args else 1), (0,)
    if origin is dict and args[1] is float:
        return {"k": math.nan}, ("k",)
    return None


FIELDS = [(model, name, *sample) for model in request_models() for name, field in model.model_fields.items()
          if (sample := float_sample(field.annotation)) is not None]


def test_the_walk_finds_the_bounded_mass_fields():
    names = {(m.__name__, n) for m, n, *_ in FIELDS}
    assert ("LinkMassInput", "mass") in names and ("InertiaInput", "m2") in names and len(FIELDS) > 100


@pytest.mark.parametrize("value", [math.nan, math.inf, -math.inf], ids=["nan", "inf", "-inf"])
@pytest.mark.parametrize("model, name, sample, suffix", FIELDS, ids=[f"{m.__name__}.{n}" for m, n, *_ in FIELDS])
def test_non_finite_number_is_refused_as_not_finite(model, name, sample, suffix, value):
    replaced = value if sample is not None and not isinstance(sample, (list, dict)) else (
        [value] * len(sample) if isinstance(sample, list) else {"k": value})
    try:
        model.model_validate({name: replaced})
    except Exception as error:                       # pydantic.ValidationError
        errors = [e for e in error.errors() if e["loc"][:1 + len(suffix)] == (name, *suffix)]
    else:
        errors = []
    assert errors, f"{model.__name__}.{name} accepts {value}"
    assert all(e["type"] == "finite_number" and "finite number" in e["msg"] for e in errors), errors


@pytest.fixture(scope="module")
def client():
    with TestClient(app) as c:
        yield c


@pytest.mark.parametrize("literal", ["NaN", "Infinity", "-Infinity"])
def test_raw_body_with_a_nan_mass_says_not_a_finite_number(client, literal):
    body = ('{"mechanism": "slider_crank", "params": {"l1": 0.1, "l2": 0.4}, "inertias": {"m2": %s}, '
            '"outputs": ["inertia"]}' % literal)
    answer = client.post("/api/v1/reduction", content=body, headers={"content-type": "application/json"})
    assert answer.status_code == 422
    detail = [d for d in answer.json()["detail"] if d["loc"][-2:] == ["inertias", "m2"]]
    assert detail and detail[0]["msg"] == "Input should be a finite number", answer.text[:400]
    assert "less than" not in answer.text


def test_raw_body_link_mass_nan(client):
    body = ('{"mechanism": "general", "linkage": {"frame": {"joints": {"O": [0, 0], "C": [0.3, 0]}}, "input": '
            '{"link": 1, "pivot": "O", "joint": "A", "length": 0.1}, "groups": [{"kind": "RRR", "links": [2, 3], '
            '"outer": ["A", "C"], "inner": "B", "lengths": [0.3, 0.2], "branch": 1}]}, '
            '"masses": {"links": [{"link": 2, "mass": NaN}]}, "outputs": ["inertia"]}')
    answer = client.post("/api/v1/reduction", content=body, headers={"content-type": "application/json"})
    assert answer.status_code == 422
    assert "finite number" in answer.text and "less than" not in answer.text, answer.text[:400]
