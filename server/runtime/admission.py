"""Admission to the computing endpoints: each client has a few computations in flight at most; past that, 429.

A pure ASGI middleware (no numerics, no routes). A client is its address (uvicorn sets ``scope["client"]``
from ``X-Forwarded-For`` for a trusted proxy) together with the random id of the ``mdl_client`` cookie that
every HTML page gives a browser that has none — a class of 30 behind one NAT address is 30 clients, not one.
Each client may hold ``MDL_CLIENT_CONCURRENCY`` computing requests in flight (default 8: the busiest page asks
for a main answer, three overlays and a slider's family at once), of them ``MDL_CLIENT_HEAVY_CONCURRENCY``
(default 2: an elastic scene's answer and its work–precision study) of the heavy kind that queue for the heavy
process one after another, so that one client's heavy requests do not stand before every other client's; and
one address ``MDL_ADDRESS_CONCURRENCY`` (default 64), so that minting ids does not escape the limit; 0 switches
a limit off. A request past a limit is answered at once with 429, ``Retry-After: 1`` and a body in FastAPI's
error format; the page waits and resends. A request without the cookie (a script) counts as the address's
anonymous client. The counts are per worker (with two workers a client may hold twice as many).

A client that asks again before the Retry-After it was given has run out (a script resending at once; the
page never does) is not refused at once: its request waits out the rest of that second and is then admitted
if a place has come free, else refused again. So a client that ignores Retry-After gets its answers no sooner
than one that honours it, and its resends cost the server one sleeping coroutine each instead of a busy loop
of 429s that would take the event loop from everyone else (bench/results/fairness.md).

A client that goes away while its computation waits has the computation cancelled (a heavy one leaves the
process pool's queue) and its place released; a light one already running in a thread finishes unseen.
"""
from __future__ import annotations

import asyncio
import json
import os
import re
import secrets
import time
from collections import Counter
from collections.abc import Iterable

COOKIE = "mdl_client"
COOKIE_MAX_AGE_S = 365 * 24 * 3600
RETRY_AFTER_S = 1
# run in the heavy process (heavy.submit): elastic machines, slider families, live work–precision studies, the
# course project
HEAVY_NAMES = ("elastic", "family", r"work-precision/[a-z-]+", "course-project")
HEAVY = re.compile(rf"/api/v1/({'|'.join(HEAVY_NAMES)})")
_ID = re.compile(r"[A-Za-z0-9_-]{16,64}")
TOLD_TO_WAIT_KEPT = 4096        # past this many clients told to wait, those whose wait is over are forgotten


def _env_limit(name: str, default: int) -> int:
    return int(os.environ.get(name, str(default)))


def too_busy_detail(scope: str, limit: int) -> list[dict]:
    """The 429's body in FastAPI's validation-error format (the page reads detail[0].ctx.code); scope is the
    limit reached: "client", "heavy" (the client's heavy computations) or "address"."""
    who = "this address" if scope == "address" else "this client"
    kind = "heavy computations" if scope == "heavy" else "computations"
    return [{"loc": ["client"], "msg": f"{who} already has {limit} {kind} in flight; retry after "
                                       f"{RETRY_AFTER_S} s", "type": "too_many_requests",
             "ctx": {"code": "busy", "limit": limit, "scope": scope, "retry_after": RETRY_AFTER_S}}]


def client_id(scope) -> str | None:
    """The mdl_client cookie's id, if the request carries a well-formed one."""
    for name, value in scope.get("headers", []):
        if name == b"cookie":
            for part in value.decode("latin-1").split(";"):
                key, _, text = part.strip().partition("=")
                if key == COOKIE and _ID.fullmatch(text):
                    return text
    return None


class AdmissionMiddleware:
    """At most `per_client` computing requests in flight per (address, mdl_client id) and `per_address` per
    address; the cookie handed to HTML pages that arrive without one."""

    def __init__(self, app, per_client: int | None = None, per_address: int | None = None,
                 per_client_heavy: int | None = None, clock=time.monotonic, sleep=asyncio.sleep,
                 computing: Iterable[str] = ()):
        self.app = app
        # the computing endpoints (`computing`: their names under /api/v1, the app's registry) and the heavy ones
        self.computing = re.compile(rf"/api/v1/({'|'.join([*map(re.escape, computing), *HEAVY_NAMES])})")
        self.clock, self.sleep = clock, sleep
        self.told_to_wait: dict[tuple, float] = {}   # client → the time its Retry-After runs out
        self.per_client = _env_limit("MDL_CLIENT_CONCURRENCY", 8) if per_client is None else per_client
        self.per_client_heavy = (_env_limit("MDL_CLIENT_HEAVY_CONCURRENCY", 2) if per_client_heavy is None
                                 else per_client_heavy)
        self.per_address = _env_limit("MDL_ADDRESS_CONCURRENCY", 64) if per_address is None else per_address
        self.in_flight: Counter = Counter()   # ("address", host), ("client"|"heavy", host, id) → requests in flight

    async def __call__(self, scope, receive, send):
        if scope["type"] != "http":
            await self.app(scope, receive, send)
        elif scope["method"] == "POST" and self.computing.fullmatch(scope["path"]):
            await self._admit(scope, receive, send)
        elif scope["method"] == "GET" and client_id(scope) is None:
            await self.app(scope, receive, _with_cookie(send, scope.get("scheme") == "https"))
        else:
            await self.app(scope, receive, send)

    async def _admit(self, scope, receive, send) -> None:
        host, who = (scope.get("client") or ("",))[0], client_id(scope)
        limits = {("address", host): self.per_address, ("client", host, who): self.per_client}
        if HEAVY.fullmatch(scope["path"]):
            limits[("heavy", host, who)] = self.per_client_heavy
        keys = tuple(limits)
        full = self._full(limits)
        if full and (early := max(self.told_to_wait.get(key, 0.0) for key in keys) - self.clock()) > 0:
            await self.sleep(early)             # asked again too soon: answered when it should have asked
            full = self._full(limits)
        if full:
            self._tell_to_wait(full[0])
            await _refuse(send, full[0][0], full[1])
            return
        for key in keys:
            self.in_flight[key] += 1
        try:
            await _run_until_disconnect(self.app, scope, receive, send)
        finally:
            for key in keys:
                self.in_flight[key] -= 1
                if not self.in_flight[key]:
                    del self.in_flight[key]


    def _full(self, limits: dict) -> tuple | None:
        """(key, limit) of the first limit the client has reached, or None."""
        return next(((key, limit) for key, limit in limits.items() if limit and self.in_flight[key] >= limit), None)

    def _tell_to_wait(self, key: tuple) -> None:
        """Note when the Retry-After given to the client (or address) whose limit `key` is runs out."""
        now = self.clock()
        if len(self.told_to_wait) >= TOLD_TO_WAIT_KEPT:
            self.told_to_wait = {known: until for known, until in self.told_to_wait.items() if until > now}
        self.told_to_wait[key] = now + RETRY_AFTER_S


async def _run_until_disconnect(app, scope, receive, send) -> None:
    """app(scope, receive, send), cancelled if the client disconnects after its body has been read and before
    the answer is complete. Once the body is in, one pending receive() listens for the disconnect."""
    listening: asyncio.Future | None = None
    answered = False

    async def receive_and_listen():
        nonlocal listening
        if listening is not None:
            return await asyncio.shield(listening)
        message = await receive()
        if message["type"] == "http.request" and not message.get("more_body", False):
            listening = asyncio.ensure_future(receive())
            listening.add_done_callback(on_message)
        return message

    async def send_and_note(message):
        nonlocal answered
        if message["type"] == "http.response.body" and not message.get("more_body", False):
            answered = True
        await send(message)

    def on_message(future: asyncio.Future) -> None:
        if not future.cancelled() and future.exception() is None and not answered \
                and future.result()["type"] == "http.disconnect":
            task.cancel()

    task = asyncio.ensure_future(app(scope, receive_and_listen, send_and_note))
    try:
        await asyncio.shield(task)
    except asyncio.CancelledError:
        if not task.done():            # we are cancelled ourselves: so is the computation
            task.cancel()
            raise
        if not task.cancelled():
            raise
    finally:
        if listening is not None and not listening.done():
            listening.cancel()


async def _refuse(send, scope: str, limit: int) -> None:
    body = json.dumps({"detail": too_busy_detail(scope, limit)}).encode()
    await send({"type": "http.response.start", "status": 429, "headers": [
        (b"content-type", b"application/json"), (b"content-length", str(len(body)).encode()),
        (b"retry-after", str(RETRY_AFTER_S).encode()), (b"cache-control", b"no-store")]})
    await send({"type": "http.response.body", "body": body})


def _with_cookie(send, secure: bool):
    """send, adding a new random mdl_client cookie to an HTML answer."""
    async def send_with_cookie(message):
        if message["type"] == "http.response.start":
            headers = message.get("headers", [])
            html = any(name.lower() == b"content-type" and value.startswith(b"text/html") for name, value in headers)
            if html:
                cookie = (f"{COOKIE}={secrets.token_urlsafe(16)}; Max-Age={COOKIE_MAX_AGE_S}; Path=/; HttpOnly; "
                          f"SameSite=Strict" + ("; Secure" if secure else ""))
                message = {**message, "headers": [*headers, (b"set-cookie", cookie.encode("latin-1"))]}
        await send(message)
    return send_with_cookie
