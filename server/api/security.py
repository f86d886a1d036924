"""Safety at the edge of the app, for classroom use: security headers on every response, a cap on request bodies,
and JSON bodies checked for what would break the parsers and walkers behind.

A pure ASGI middleware (no numerics, no routes), the outermost layer of the app (app.py wraps Starlette's
ServerErrorMiddleware in it, so a 500 carries the headers too): it adds the headers to every HTTP response
(pages, static files, the JSON API, errors), marks HTML pages ``Cache-Control: no-cache`` (a page names the
current versioned static URLs, and a result page carries a private token: always revalidated), and refuses a
request body over MAX_BODY_BYTES with HTTP 413 in FastAPI's error format — at once when Content-Length says so,
or as soon as a chunked body grows past the limit while read.

A body that FastAPI will parse as JSON (Content-Type application/json or …+json) is read whole first and
refused with HTTP 422 naming the body when it is not UTF-8 (Python's parser would guess UTF-16 or UTF-32), when
its brackets nest deeper than MAX_JSON_DEPTH (1 KB of brackets would otherwise reach Python's recursion limit in
the validation echo and every walker over the data), or when a string holds a lone UTF-16 surrogate (``"\\ud800"``
is valid JSON but no character: it cannot be written back as UTF-8, nor stored), or when an integer has more
digits than Python converts (``sys.get_int_max_str_digits()``, 4300: its parser would refuse the whole body
with a bare 400). The depth is counted without
recursion: string literals are cut out by a regular expression, and the running sum of opening minus closing
brackets is taken over the bytes left (numpy).
"""
from __future__ import annotations

import json
import re
import sys

import numpy as np
from fastapi import HTTPException

MAX_BODY_BYTES = 1024 * 1024  # 1 MiB; the largest honest body (10001 angles) is about 0.2 MiB
MAX_JSON_DEPTH = 64           # the deepest honest body (a family of a nested request) has 4 levels
_STRING = re.compile(rb'"[^"\\]*(?:\\.[^"\\]*)*"', re.DOTALL)       # a JSON string literal, escapes included
_OPEN, _CLOSE = list(b"[{"), list(b"]}")
MAX_INT_DIGITS = sys.get_int_max_str_digits() or 4300   # 0 would mean no limit; keep the default's
_LONG_DIGITS = re.compile(rb"\d{%d}" % (MAX_INT_DIGITS + 1))
# an integer literal (no fraction, no exponent: those are floats, which have no such limit)
_INTEGER = re.compile(rb"(?<![\d.eE+-])-?(\d+)(?![\d.eE])")

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
# The pages an LMS shows in its frame after an LTI launch may be framed by the registered LMSs (their origins from
# the provider the LTI router installs, allow_framing_by); X-Frame-Options cannot name an origin and is left off.
FRAMED_PATHS = ("/assignments/", "/scenes/", "/lti/")
_framing_origins = tuple


def allow_framing_by(origins) -> None:
    """Install the function that gives the origins allowed to frame FRAMED_PATHS (called per response: cache it)."""
    global _framing_origins
    _framing_origins = origins


def framed(headers: list, origins) -> list:
    """The default headers with frame-ancestors opened to `origins` (none: unchanged)."""
    if not origins:
        return headers
    policy = CONTENT_SECURITY_POLICY.replace("frame-ancestors 'none'", "frame-ancestors 'self' " + " ".join(origins))
    return [(name, policy.encode("latin-1")) if name == b"content-security-policy" else (name, value)
            for name, value in headers if name != b"x-frame-options"]


def body_too_large_detail(limit: int = MAX_BODY_BYTES) -> list[dict]:
    """The 413's body in FastAPI's validation-error format, so clients read one kind of error."""
    return [{"loc": ["body"], "msg": f"request body larger than {limit} bytes", "type": "body_too_large",
             "ctx": {"limit": limit}}]


class BodyTooLarge(HTTPException):
    """Raised while a body is read past the limit; an HTTPException so that FastAPI's body parsing lets it
    through (it turns other exceptions into 400) and the default handler answers 413 with this detail."""

    def __init__(self, limit: int):
        super().__init__(status_code=413, detail=body_too_large_detail(limit))


def _is_json(headers) -> bool:
    """Whether FastAPI reads the body as JSON: a Content-Type application/json or application/…+json (strict:
    a body without a Content-Type is not JSON to it)."""
    for name, value in headers:
        if name.lower() == b"content-type":
            media = value.split(b";")[0].strip().lower()
            return media == b"application/json" or (media.startswith(b"application/") and media.endswith(b"+json"))
    return False


def json_depth(raw: bytes) -> int:
    """How deep the brackets of a JSON text nest, outside its strings; computed without recursion."""
    codes = np.frombuffer(_STRING.sub(b"", raw), dtype=np.uint8)
    steps = np.isin(codes, _OPEN).astype(np.int32) - np.isin(codes, _CLOSE).astype(np.int32)
    return int(np.cumsum(steps).max(initial=0))


def lone_surrogate(raw: bytes) -> str | None:
    """The first string literal that holds a lone UTF-16 surrogate escape (no character), or None."""
    if b"\\u" not in raw:
        return None
    for match in _STRING.finditer(raw):
        literal = match.group()
        if b"\\u" in literal:
            try:
                json.loads(literal).encode("utf-8")
            except UnicodeEncodeError:
                return literal[:80].decode("ascii", "replace")
            except ValueError:          # not a valid string: the JSON parser names it
                continue
    return None


def longest_integer(raw: bytes) -> int:
    """The number of digits of the longest integer literal of a JSON text, outside its strings."""
    return max((len(match.group(1)) for match in _INTEGER.finditer(_STRING.sub(b'""', raw))), default=0)


def body_problem(raw: bytes) -> dict | None:
    """What makes a JSON body unreadable before it is parsed, as one error in FastAPI's format, or None."""
    try:
        raw.decode("utf-8")
    except UnicodeDecodeError as error:
        return {"loc": ["body"], "type": "body_not_utf8", "ctx": {"position": error.start},
                "msg": f"the body is not UTF-8 text (byte {error.start}); JSON must be sent in UTF-8"}
    brackets = raw.count(b"[") + raw.count(b"{")        # a bound of the depth: most bodies stop here
    depth = json_depth(raw) if brackets > MAX_JSON_DEPTH else 0
    if depth > MAX_JSON_DEPTH:
        return {"loc": ["body"], "type": "body_too_deep", "ctx": {"limit": MAX_JSON_DEPTH, "depth": depth},
                "msg": f"the body's brackets nest {depth} deep; at most {MAX_JSON_DEPTH} levels are accepted"}
    digits = longest_integer(raw) if _LONG_DIGITS.search(raw) else 0
    if digits > MAX_INT_DIGITS:
        return {"loc": ["body"], "type": "body_integer_too_long", "ctx": {"limit": MAX_INT_DIGITS, "digits": digits},
                "msg": f"an integer of the body has {digits} digits; at most {MAX_INT_DIGITS} are accepted"}
    literal = lone_surrogate(raw)
    if literal is not None:
        return {"loc": ["body"], "type": "body_lone_surrogate", "ctx": {"string": literal},
                "msg": "a string of the body holds a lone UTF-16 surrogate escape (such as \\ud800), which is no "
                       "character"}
    return None


class SecurityMiddleware:
    """Security headers on every HTTP response, request bodies capped at `max_body` bytes, JSON bodies checked
    (body_problem)."""

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
                if scope["path"].startswith(FRAMED_PATHS) and b"content-security-policy" not in present:
                    extra = framed(extra, _framing_origins())
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
            app_receive = receive_limited
            if scope["method"] in ("POST", "PUT", "PATCH") and _is_json(scope.get("headers", [])):
                app_receive = await self._read_checked(receive_limited, receive, send_with_headers)
                if app_receive is None:
                    return
            await self.app(scope, app_receive, send_with_headers)
        except BodyTooLarge:
            if started:  # a streaming reader that had already answered: nothing more to say
                raise
            await self._refuse(send_with_headers)

    @staticmethod
    async def _read_checked(receive, then, send):
        """Read the JSON body whole with `receive` (BodyTooLarge past the cap); answer 422 and return None if
        body_problem finds one, else return a receive that replays it and then passes on to `then`."""
        chunks = []
        while True:
            message = await receive()
            if message["type"] != "http.request":
                return None                           # the client left before its body was complete
            chunks.append(message.get("body", b""))
            if not message.get("more_body", False):
                break
        raw = b"".join(chunks)
        problem = body_problem(raw)
        if problem is not None:
            body = json.dumps({"detail": [problem]}).encode()
            await send({"type": "http.response.start", "status": 422, "headers": [
                (b"content-type", b"application/json"), (b"content-length", str(len(body)).encode())]})
            await send({"type": "http.response.body", "body": body})
            return None
        pending = [{"type": "http.request", "body": raw, "more_body": False}]

        async def replay():
            return pending.pop() if pending else await then()
        return replay

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
