"""Safety at the edge: every response carries the security headers, bodies over 1 MiB are refused with 413.

The Content-Security-Policy allows scripts from our own files only (no inline script, no event-handler
attribute, no third-party origin), so the pages must not contain any: the rendered pages are checked too.
"""
from __future__ import annotations

from html.parser import HTMLParser
from pathlib import Path

import pytest
from fastapi.testclient import TestClient

from server.api.app import app
from server.lessons.scenes import scenes
from server.api.security import MAX_BODY_BYTES, SECURITY_HEADERS

API = "/api/v1"
TEMPLATES = Path(__file__).resolve().parents[1] / "web" / "templates"
TWO_MB = 2 * 1024 * 1024


@pytest.fixture(scope="module")
def client() -> TestClient:
    return TestClient(app)


def assert_security_headers(response) -> None:
    for name, value in SECURITY_HEADERS.items():
        assert response.headers.get(name) == value, name


def csp_directives() -> dict[str, list[str]]:
    directives = [d.split() for d in SECURITY_HEADERS["content-security-policy"].split(";")]
    return {d[0]: d[1:] for d in directives if d}


@pytest.mark.parametrize("method,path,status", [
    ("GET", "/", 200),
    ("GET", "/scenes/transfer-functions", 200),
    ("GET", "/static/css/app.css", 200),
    ("GET", "/vendor/plotly/plotly.min.js", 200),
    ("GET", f"{API}/mechanisms", 200),
    ("GET", f"{API}/scenes/no-such-scene", 404),
    ("POST", f"{API}/kinematics", 422),
])
def test_every_kind_of_response_carries_the_security_headers(client, method, path, status):
    response = client.request(method, path, json={} if method == "POST" else None)
    assert response.status_code == status
    assert_security_headers(response)


def test_content_security_policy_allows_no_inline_script_and_no_third_party_origin():
    directives = csp_directives()
    assert directives["script-src"] == ["'self'"]
    assert directives["object-src"] == ["'none'"] and directives["frame-ancestors"] == ["'none'"]
    for sources in directives.values():
        assert not any(s.startswith(("http:", "https:", "*")) or "://" in s for s in sources), sources
        assert "'unsafe-eval'" not in sources


def test_a_body_declared_over_the_limit_is_refused_with_413_before_it_is_read(client):
    response = client.post(f"{API}/kinematics", content=b"[" + b"0," * (TWO_MB // 2) + b"0]",
                           headers={"content-type": "application/json"})
    assert response.status_code == 413
    assert response.json() == {"detail": [{"loc": ["body"], "msg": f"request body larger than {MAX_BODY_BYTES} bytes",
                                           "type": "body_too_large", "ctx": {"limit": MAX_BODY_BYTES}}]}
    assert_security_headers(response)


def test_a_chunked_body_growing_past_the_limit_is_refused_with_413(client):
    def chunks():                                  # no Content-Length: sent with Transfer-Encoding: chunked
        yield b'{"mechanism": "sine", "n": 5, "outputs": ["s"], "phi_padding": "'
        for _ in range(TWO_MB // 65536):
            yield b"x" * 65536
        yield b'"}'

    response = client.post(f"{API}/kinematics", content=chunks(), headers={"content-type": "application/json"})
    assert response.status_code == 413
    detail = response.json()["detail"]
    assert detail[0]["loc"] == ["body"] and detail[0]["type"] == "body_too_large"
    assert_security_headers(response)


def test_a_body_under_the_limit_reaches_validation(client):
    padding = "x" * (MAX_BODY_BYTES - 1000)
    response = client.post(f"{API}/kinematics", json={"mechanism": "sine", "n": 5, "outputs": ["s"], "pad": padding})
    assert response.status_code == 422                 # refused by the schema (extra field), not by size


class ScriptFinder(HTMLParser):
    """Collects inline executable scripts and on* event-handler attributes, which the CSP would block."""

    def __init__(self):
        super().__init__()
        self.problems: list[str] = []
        self._in_inline_script = False

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        self.problems += [f"<{tag} {name}=…>" for name in attrs if name.startswith("on")]
        if any(str(value or "").strip().lower().startswith("javascript:") for value in attrs.values()):
            self.problems.append(f"<{tag}> with a javascript: URL")
        if tag == "script" and "src" not in attrs and attrs.get("type") != "application/json":
            self.problems.append("inline executable <script>")
        if tag == "script" and "src" in attrs and "://" in attrs["src"]:
            self.problems.append(f"third-party script {attrs['src']}")


@pytest.mark.parametrize("path", ["/", *(f"/scenes/{scene_id}" for scene_id in scenes())])
def test_pages_have_no_inline_scripts_or_event_handlers(client, path):
    finder = ScriptFinder()
    finder.feed(client.get(path).text)
    assert finder.problems == []


@pytest.mark.parametrize("template", sorted(p.name for p in TEMPLATES.glob("*.html")))
def test_templates_have_no_inline_scripts_or_event_handlers(template):
    finder = ScriptFinder()
    finder.feed((TEMPLATES / template).read_text(encoding="utf-8"))
    assert finder.problems == []
