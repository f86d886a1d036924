"""HEAD of a page, a GET route of the API or a static file: 200 with the GET's headers and no body (RFC 9110
§9.3.2); HEAD of a POST-only route: 405 as GET; the security headers on both."""
from __future__ import annotations

import pytest
from fastapi.testclient import TestClient

from server.api.app import app

GETTABLE = ["/", "/scenes/flywheel?lang=ru", "/editor", "/project", "/measurements", "/api/v1/scenes",
            "/api/v1/openapi.json", "/vendor/plotly/plotly.min.js", "/favicon.ico"]


@pytest.fixture(scope="module")
def client():
    with TestClient(app) as client:
        yield client


@pytest.mark.parametrize("path", GETTABLE)
def test_head_is_get_without_the_body(client, path):
    get = client.get(path)
    head = client.head(path)
    assert get.status_code == 200 and head.status_code == 200, (path, head.status_code)
    assert head.content == b""
    assert head.headers["content-type"] == get.headers["content-type"]
    assert head.headers.get("content-security-policy") == get.headers.get("content-security-policy")
    assert head.headers["x-content-type-options"] == "nosniff"
    if "content-length" in get.headers and "content-encoding" not in get.headers:
        assert head.headers["content-length"] == get.headers["content-length"]


def test_head_of_a_post_only_route_is_refused_as_get_is(client):
    assert client.get("/api/v1/kinematics").status_code == 405
    head = client.head("/api/v1/kinematics")
    assert head.status_code == 405 and head.content == b""
    assert head.headers["x-content-type-options"] == "nosniff"

