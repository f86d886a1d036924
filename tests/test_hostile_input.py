"""Hostile and broken bodies answer 422 naming the body, and every error, a 500 included,
carries the security headers and a JSON body.

Reproductions (each answered a plain-text 500 without the security headers on every POST endpoint before):
478 levels of nested brackets (1 KB) overflowed the recursion of the cache's key and the validation echo; a lone
surrogate ``{"mechanism": "\\ud800"}`` failed in the cache key and in the validation error echo. The list of
POST endpoints is read from the app's routes, so a new endpoint is covered without editing this file.
"""
from __future__ import annotations

import re

import pytest
from fastapi.testclient import TestClient

from server.api.app import create_app
from server.api.errors import plain
from server.api.security import MAX_JSON_DEPTH, SECURITY_HEADERS, json_depth

from openapi_document import openapi_document


@pytest.fixture(scope="module")
def app(tmp_path_factory):
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv("MDL_DATA_DIR", str(tmp_path_factory.mktemp("mdl-data")))
        yield create_app()


@pytest.fixture(scope="module")
def client(app) -> TestClient:
    return TestClient(app, raise_server_exceptions=False)


def post_paths() -> list[str]:
    """Every POST operation of the app's OpenAPI document, path parameters filled with a harmless word."""
    paths = openapi_document()["paths"]
    return sorted({re.sub(r"\{[^}]+\}", "x", path) for path, operations in paths.items() if "post" in operations})


def admin_paths() -> set[str]:
    """The POST operations secured by the administrator's token (MDL_ADMIN_TOKEN; 403 while it is unset, 401
    without it), as filled in post_paths."""
    paths = openapi_document()["paths"]
    return {re.sub(r"\{[^}]+\}", "x", path) for path, operations in paths.items() if "post" in operations
            and any("admin_token" in requirement for requirement in operations["post"].get("security", []))}


POSTS = post_paths()
ADMIN_POSTS = admin_paths()
JSON = {"content-type": "application/json"}
DEEP = b'{"mechanism":' + b"[" * 478 + b"]" * 478 + b"}"                # 1 KB
SURROGATE = b'{"mechanism":"\\ud800"}'


def assert_json_error_with_headers(response, status: int | range) -> dict:
    assert response.status_code in (status if isinstance(status, range) else (status,)), response.text[:300]
    for name, value in SECURITY_HEADERS.items():
        assert response.headers.get(name) == value, name
    assert response.headers["content-type"].startswith("application/json")
    return response.json()


def test_the_routes_list_every_post_endpoint():
    assert {"/api/v1/kinematics", "/api/v1/elastic", "/api/v1/family", "/api/v1/assignments",
            "/api/v1/work-precision/elastic"} <= set(POSTS)


@pytest.mark.parametrize("path", POSTS)
@pytest.mark.parametrize("body, kind", [(DEEP, "body_too_deep"), (SURROGATE, "body_lone_surrogate"),
                                        (b'\xff\xfe{\x00}\x00', "body_not_utf8"),
                                        ('{"mechanism": "s\u00e9"}'.encode("latin-1"), "body_not_utf8")])
def test_a_broken_json_body_is_refused_with_422_naming_the_body(client, path, body, kind):
    detail = assert_json_error_with_headers(client.post(path, content=body, headers=JSON), 422)["detail"]
    assert detail[0]["loc"] == ["body"] and detail[0]["type"] == kind and detail[0]["msg"]


@pytest.mark.parametrize("path", POSTS)
@pytest.mark.parametrize("body", [DEEP, SURROGATE, b"\xff\xfe\x80", b'{"a": "\\udc00\\ud800"}'])
def test_the_same_bodies_as_text_are_refused_by_validation_and_echoed_safely(client, path, body):
    """Sent as text/plain, FastAPI validates the raw bytes and echoes them: the echo is made valid UTF-8 (a route
    that takes no body answers as it would without one: 404 for the made-up assignment)."""
    response = client.post(path, content=body, headers={"content-type": "text/plain"})
    assert_json_error_with_headers(response, range(400, 500))


@pytest.mark.parametrize("path", POSTS)
def test_a_body_nested_exactly_to_the_limit_passes_every_walker(client, path):
    """64 levels pass the edge and reach validation, the cache key and the error echo: 422, never 500 (nor the
    edge's 400 or 413). An administrator's route without the token (unset here) may refuse it first: 401/403."""
    body = b'{"mechanism":' + b"[" * (MAX_JSON_DEPTH - 1) + b"]" * (MAX_JSON_DEPTH - 1) + b"}"
    assert json_depth(body) == MAX_JSON_DEPTH
    allowed = (404, 422) + ((401, 403) if path in ADMIN_POSTS else ())
    response = client.post(path, content=body, headers=JSON)
    assert response.status_code in allowed, response.text[:300]


def test_the_admin_routes_are_the_lti_administration():
    assert {"/api/v1/lti/platforms", "/api/v1/lti/registration-links", "/api/v1/lti/scores/retry"} <= ADMIN_POSTS
    assert not {"/api/v1/kinematics", "/api/v1/family", "/api/v1/assignments"} & ADMIN_POSTS


def test_a_surrogate_pair_is_a_character_and_an_escaped_backslash_is_no_surrogate(client):
    for text in (b'"\\ud83d\\ude00"', b'"\\\\ud800"'):
        response = client.post("/api/v1/kinematics", content=b'{"mechanism": %s}' % text, headers=JSON)
        assert response.json()["detail"][0]["loc"] == ["body", "mechanism"]   # refused by its field, not the body


def test_depth_is_counted_outside_strings_without_recursion():
    assert json_depth(b'{"a": "[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[["}') == 1
    assert json_depth(b'["\\"[", [[1]]]') == 3
    assert json_depth(b"[" * 200_000) == 200_000


def test_the_echo_is_rebuilt_without_recursion():
    deep: list = []
    for _ in range(100_000):
        deep = [deep]
    rebuilt = plain({"input": deep, "bytes": b"\xff", "text": "a\ud800", "wide": 2**100})
    assert rebuilt["bytes"] == "\ufffd" and rebuilt["text"] == "a\ufffd" and rebuilt["wide"] == float(2**100)


def test_an_unexpected_error_answers_500_in_json_with_the_security_headers(monkeypatch, tmp_path):
    monkeypatch.setenv("MDL_DATA_DIR", str(tmp_path))
    app = create_app()

    @app.get("/api/v1/broken")
    def broken():
        raise RuntimeError("a bug")

    response = TestClient(app, raise_server_exceptions=False).get("/api/v1/broken")
    detail = assert_json_error_with_headers(response, 500)["detail"]
    assert detail[0]["type"] == "server_error" and "a bug" not in response.text      # no internals leak
