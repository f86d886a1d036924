"""The classroom refuses in its own exceptions (server/classroom/refusals.py) and server/api/errors.py answers each
over HTTP exactly as FastAPI answers the HTTPException that stands for it: the same status, body and headers
(404 {"detail": "no such assignment"}; 503 and 429 with the error list and Retry-After)."""
from __future__ import annotations


import pytest
from fastapi import HTTPException
from fastapi.exception_handlers import http_exception_handler
from fastapi.testclient import TestClient
from starlette.requests import Request

from server.api import errors
from server.api.app import create_app
from server.api.security import SECURITY_HEADERS
from server.classroom import assignment_answers, assignment_store
from server.classroom.refusals import Busy, NotFound, TooOften
from server.runtime import heavy
from event_loop import run_to_end

API = "/api/v1/assignments"
REQUEST = Request({"type": "http", "method": "GET", "path": "/", "headers": [], "query_string": b""})
SPEC = {"scene": "transfer-functions", "variant": "slider_crank", "questions": [{"id": "u31_max"}]}


def answered(handler, error):
    response = run_to_end(handler(REQUEST, error))
    return response.status_code, bytes(response.body), dict(response.headers)


@pytest.mark.parametrize("refusal, handler, same", [
    (NotFound("no such assignment"), errors.not_found, HTTPException(404, "no such assignment")),
    (Busy("answers_busy", "try again", retry_after=2), errors.busy,
     HTTPException(503, [{"loc": [], "type": "answers_busy", "msg": "try again"}], {"Retry-After": "2"})),
    (Busy("answers_not_ready", "later", retry_after=10), errors.busy,
     HTTPException(503, [{"loc": [], "type": "answers_not_ready", "msg": "later"}], {"Retry-After": "10"})),
    (TooOften("rate_limited", "wait", retry_after=600, limit=20), errors.too_often,
     HTTPException(429, [{"loc": ["body"], "type": "rate_limited", "ctx": {"limit": 20}, "msg": "wait"}],
                   {"Retry-After": "600"})),
])
def test_each_refusal_is_answered_as_its_http_exception_was(refusal, handler, same):
    assert answered(handler, refusal) == answered(http_exception_handler, same)


@pytest.fixture
def client(tmp_path, monkeypatch) -> TestClient:
    monkeypatch.setenv("MDL_DATA_DIR", str(tmp_path))
    monkeypatch.setattr(heavy, "HEAVY_PROCESSES", 0)
    assignment_store.store.cache_clear()
    yield TestClient(create_app())
    assignment_store.store.cache_clear()


def test_over_http_the_refusals_keep_their_status_body_and_headers(client):
    missing = client.get(f"{API}/nowhere")
    assert missing.status_code == 404 and missing.json() == {"detail": "no such assignment"}
    assert all(missing.headers[name] == value for name, value in SECURITY_HEADERS.items())
    places = [assignment_answers._computing.acquire(blocking=False)
              for _ in range(assignment_answers.ANSWER_COMPUTATIONS)]
    try:
        assert all(places)
        busy = client.post(API, json=SPEC)             # its checked variants' answers wait for a place: none is free
    finally:
        for _ in places:
            assignment_answers._computing.release()
    assert busy.status_code == 503 and busy.headers["retry-after"] == "2"
    assert [d["type"] for d in busy.json()["detail"]] == ["answers_busy"]
    made = client.post(API, json=SPEC).json()
    wrong = client.get(f"{API}/{made['id']}/results/wrong-token")
    assert wrong.status_code == 404 and wrong.json() == {"detail": "no such results page"}
    token = f"{API}/{made['id']}/results/{made['results_token']}"
    assert client.delete(f"{token}/students/0123456789abcdef").json() == {"detail": "no such student"}
