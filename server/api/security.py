"""Safety at the edge of the app, for classroom use: security headers on every response and a cap on request bodies.

A pure ASGI middleware (no numerics, no routes): it adds the headers to every HTTP response (pages, static
files, the JSON API, errors), marks HTML pages ``Cache-Control: no-cache`` (a page names the current versioned
static URLs, and a result page carries a private token: always revalidated), and refuses a request body over MAX_BODY_BYTES with HTTP 413 in FastAPI's error
format — at once when Content-Length says so, or as soon as a chunked body grows past the limit while read.
"""
from __future__ import annotations

import json

from fastapi import HTTPException

MAX_BODY_BYTES = 1024 * 1024  # 1 MiB; the largest honest body (10001 angles) is about 0.2 MiB

# Everything this app loads is its own (plotly.js included, served from /vendor/plotly): no third-party origin.
# Scripts only from files (no inline scripts, no event-handler attributes, no eval); the pages' embedded data
# sits in <script type="application/json">, which is never executed. Plotly injects <style> elements, hence
# 'unsafe-inline' for styles only; it draws images from data: and blob: URLs.
CONTENT_SECURITY_POLICY = "; ".join((
    "default-src 'self'", "script-src 'self'", "style-src 'self' 'unsafe-inline'", "img-src 'self' data: blob:",
    "connect-src 'self'", "font-src 'self'", "object-src 'none'", "base-uri 'none'", "frame-ancestors 'none'",
    "form-action 'self'"))


def policy_with_script_hashes(hashes: list[str]) -> str:
    """The policy for a page of our own with inline scripts (the stored figures at /bench-results): those
    scripts, by their sha256, may run too; a response that carries its own policy keeps it."""
    sources = " ".join(f"'sha256-{h}'" for h in hashes)
    return CONTENT_SECURITY_POLICY.replace("script-src 'self'", f"script-src 'self' {sources}".rstrip(), 1)


SECURITY_HEADERS = {
    "content-security-policy": CONTENT_SECURITY_POLICY,
    "x-content-type-options": "nosniff",
    "referrer-policy": "no-referrer",            # private result links carry a token in their path
    "x-frame-options": "DENY",
    "cross-origin-opener-policy": "same-origin",
}
_RAW_HEADERS = [(name.encode("latin-1"), value.encode("latin-1")) for name, value in SECURITY_HEADERS.items()]


def body_too_large_detail(limit: int = MAX_BODY_BYTES) -> list[dict]:
    """The 413's body in FastAPI's validation-error format, so clients read one kind of error."""
    return [{"loc": ["body"], "msg": f"request body larger than {limit} bytes", "type": "body_too_large",
             "ctx": {"limit": limit}}]


class BodyTooLarge(HTTPException):
    """Raised while a body is read past the limit; an HTTPException so that FastAPI's body parsing lets it
    through (it turns other exceptions into 400) and the default handler answers 413 with this detail."""

    def __init__(self, limit: int):
        super().__init__(status_code=413, detail=body_too_large_detail(limit))


class SecurityMiddleware:
    """Security headers on every HTTP response, and request bodies capped at `max_body` bytes."""

    def __init__(self, app, max_body: int = MAX_BODY_BYTES):
        self.app = app
        self.max_body = max_body

    async def __call__(self, scope, receive, send):
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        started = False

        async def send_with_headers(message):
            nonlocal started
            if message["type"] == "http.response.start":
                started = True
                headers = message.get("headers", [])
                present = {name.lower(): value for name, value in headers}
                extra = [h for h in _RAW_HEADERS if h[0] not in present]
                if present.get(b"content-type", b"").startswith(b"text/html") and b"cache-control" not in present:
                    extra.append((b"cache-control", b"no-cache"))
                message = {**message, "headers": [*headers, *extra]}
            await send(message)

        if self._declared_length(scope) > self.max_body:
            await self._refuse(send_with_headers)
            return

        received = 0

        async def receive_limited():
            nonlocal received
            message = await receive()
            if message["type"] == "http.request":
                received += len(message.get("body", b""))
                if received > self.max_body:
                    raise BodyTooLarge(self.max_body)
            return message

        try:
            await self.app(scope, receive_limited, send_with_headers)
        except BodyTooLarge:
            if started:  # a streaming reader that had already answered: nothing more to say
                raise
            await self._refuse(send_with_headers)

    @staticmethod
    def _declared_length(scope) -> int:
        for name, value in scope.get("headers", []):
            if name.lower() == b"content-length":
                try:
                    return int(value)
                except ValueError:
                    return 0
        return 0

    async def _refuse(self, send) -> None:
        body = json.dumps({"detail": body_too_large_detail(self.max_body)}).encode()
        await send({"type": "http.response.start", "status": 413, "headers": [
            (b"content-type", b"application/json"), (b"content-length", str(len(body)).encode()),
            (b"connection", b"close")]})
        await send({"type": "http.response.body", "body": body})
