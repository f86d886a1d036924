"""Admission to the computing endpoints: a share of each lane per person, served in turn; past a cap, 429.

A pure ASGI middleware (no numerics, no routes). Who asks is its address (uvicorn sets ``scope["client"]`` from
``X-Forwarded-For`` only for a proxy named in ``MDL_FORWARDED_ALLOW_IPS``, server/__main__.py) and, within the
address, the random id of the ``mdl_client`` cookie that every HTML page gives a browser that has none. The
client chooses its cookie, so the cookie only divides its address's share among the address's browsers (a class
behind one NAT address is one address of many students): however many ids an address invents, it gets one share.

Lanes. A computing request is light (computed in the worker) or heavy (an elastic machine, a live work–precision
study, the course project: one heavy process per worker computes them, server/runtime/heavy.py). Each of these
lanes has a few places per worker: light ``MDL_LIGHT_PLACES`` (default 1: the worker's interpreter computes one at
a time anyway, and two at once only share it, a short answer waiting out a long one's time slices), heavy one more
than ``MDL_HEAVY_PROCESSES`` (the next answer ready when the process is free). One address may hold all but one of
a lane's places (at least one), so that a request from another address finds a place or is next; and with several
workers, while another address asks, what all the workers but one may hold, and no more computations of both lanes
than the server's CPUs but one, counted across the workers (server/runtime/server_shares.py): a flood from one
address then leaves a CPU to the others. The requests past that wait in the lane, which takes them in turn: address
after address, and within an address client (cookie) after client, each client's own in the order asked. The
requests a page sends while a slider is dragged and its family has not come (``X-MDL-Drag: 1``,
web/static/js/common/model/api.js) are previews, true answers of values the slider passes: they wait behind every
request at rest, so that the answer a student reads when the slider stops goes first and the drags share the time
that is left. A slider's family is not held in a lane (heavy.py runs its coarse stage in the previews' lane, its
full one in the refinements'); it counts towards the limits below.

Limits (per worker; 0 switches one off). A client may have ``MDL_CLIENT_CONCURRENCY`` computing requests in
flight, running or waiting (default 8: the busiest page asks for a main answer, three overlays and a slider's
family at once), of them ``MDL_CLIENT_HEAVY_CONCURRENCY`` heavy ones or families (default 2); an address
``MDL_ADDRESS_CONCURRENCY`` (default 32: its waiting requests cost no CPU, only a place in a queue; raise it for a
large class behind one NAT address). With the address cap off each cookie counts as an address of its own (a load
test of many students from one machine). A request past a limit is answered at once with 429, ``Retry-After: 1``
and a body in FastAPI's error format; the page waits and resends. A request without the cookie (a script) counts
as the address's anonymous client.

A client that asks again before the Retry-After it was given has run out (a script resending at once; the
page never does) is not refused at once: its request waits out the rest of that second and is then admitted
if a place has come free, else refused again. So a client that ignores Retry-After gets its answers no sooner
than one that honours it, and its resends cost the server one sleeping coroutine each instead of a busy loop
of 429s that would take the event loop from everyone else (bench/results/fairness.md).

A client that goes away while its request waits in a lane leaves the lane; one that goes away while its
computation runs has it cancelled (a heavy one leaves the process pool's queue) and its place released; a light
one already running in a thread finishes unseen. A place is held while the answer is computed, not while it is
sent: a client that reads its answer slowly holds no place of anyone's. ``CLIENT`` holds (address, cookie id) while a request is served,
for a queue further in that wants to serve clients in turn too.
"""
from __future__ import annotations

import asyncio
import contextvars
import json
import os
import re
import secrets
import time
from collections import Counter, OrderedDict, deque
from collections.abc import Iterable

from . import heavy
from .server_shares import ServerShares, from_worker

COOKIE = "mdl_client"
COOKIE_MAX_AGE_S = 365 * 24 * 3600
RETRY_AFTER_S = 1
# run in the heavy process (heavy.submit): elastic machines, slider families, live work–precision studies, the
# course project
HEAVY_NAMES = ("elastic", "family", r"work-precision/[a-z-]+", "course-project")
HEAVY = re.compile(rf"/api/v1/({'|'.join(HEAVY_NAMES)})")
FAMILY = re.compile(r"/api/v1/family")       # heavy, but in no lane of admission's (heavy.LaneQueue orders them)
DRAG_HEADER = b"x-mdl-drag"                    # "1": asked while a slider is dragged (api.js); waits behind the rest
_ID = re.compile(r"[A-Za-z0-9_-]{16,64}")
RECHECK_S = 0.002              # how often a lane with a free place looks again at a group held elsewhere
TOLD_TO_WAIT_KEPT = 4096        # past this many clients told to wait, those whose wait is over are forgotten
CLIENT: contextvars.ContextVar[tuple[str, str | None]] = contextvars.ContextVar("mdl_admitted_client")


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


class Lane:
    """A lane's places, of which one group (an address) holds at most `share` at once, and its waiting requests,
    given the places in turn: group after group, within a group client after client, a client's own in order.
    The requests of a slider being dragged (``DRAG_HEADER``) wait behind all others: an answer at rest first."""

    def __init__(self, places: int, share: int | None = None, server: ServerShares | None = None,
                 name: str = "light"):
        self.places = max(places, 1)
        self.share = max(self.places - 1, 1) if share is None else share
        # the count of the server's workers together (server_shares): a group's places in every worker
        self.server, self.name = server, name
        self._recheck: asyncio.TimerHandle | None = None
        self.running: Counter = Counter()            # group → places it holds
        # per priority (0: at rest, 1: a drag's), group → client → its waiting requests' futures; both dicts in
        # turn order (the next to serve first)
        self.waiting: tuple[OrderedDict[object, OrderedDict[object, deque]], ...] = (OrderedDict(), OrderedDict())

    def __len__(self) -> int:
        return sum(self.running.values())

    async def enter(self, group, client, dragging: bool = False) -> None:
        """Wait for a place (in turn); cancelled while waiting, the request leaves the queue."""
        place = asyncio.get_running_loop().create_future()
        if self.server is not None:
            self.server.asked(group)
        waiting = self.waiting[int(dragging)]
        waiting.setdefault(group, OrderedDict()).setdefault(client, deque()).append(place)
        self._hand_over()
        try:
            await place
        except asyncio.CancelledError:
            if place.done() and not place.cancelled():
                self.leave(group)                    # given a place as it was cancelled: pass it on
            else:
                self._forget(waiting, group, client, place)
            raise

    def leave(self, group) -> None:
        self.running[group] -= 1
        if not self.running[group]:
            del self.running[group]
        if self.server is not None:
            self.server.give_back(self.name, group)
        self._hand_over()

    def _hand_over(self) -> None:
        """Give the free places to the waiting requests in turn, those at rest before a drag's. A group that holds
        its share of the server's places in the other workers waits; the lane looks again every ``RECHECK_S``
        while it has a free place (another worker frees its places unseen)."""
        held_elsewhere = False
        while len(self) < self.places:
            chosen = None
            for waiting in self.waiting:
                for group in waiting:
                    if self.running[group] >= self.share:
                        continue
                    if self.server is not None and not self.server.take(self.name, group, self.share):
                        held_elsewhere = True
                        continue
                    chosen = waiting, group
                    break
                if chosen:
                    break
            if chosen is None:
                break
            waiting, group = chosen
            clients = waiting[group]
            client, places = next(iter(clients.items()))
            place = places.popleft()
            clients.move_to_end(client)                  # its next request after the other clients'
            if not places:
                del clients[client]
            waiting.move_to_end(group)                   # the group's next after the other groups'
            if not clients:
                del waiting[group]
            if not place.done():                         # (one cancelled already is leaving the queue)
                self.running[group] += 1
                place.set_result(None)
            elif self.server is not None:
                self.server.give_back(self.name, group)
        if held_elsewhere and len(self) < self.places and self._recheck is None:
            self._recheck = asyncio.get_running_loop().call_later(RECHECK_S, self._look_again)

    def _look_again(self) -> None:
        self._recheck = None
        self._hand_over()

    @staticmethod
    def _forget(waiting: OrderedDict, group, client, place) -> None:
        places = waiting.get(group, {}).get(client)
        if places is not None and place in places:
            places.remove(place)
            if not places:
                del waiting[group][client]
                if not waiting[group]:
                    del waiting[group]


class AdmissionMiddleware:
    """At most `per_client` computing requests in flight per (address, mdl_client id) and `per_address` per
    address, waiting in turn for a place in their lane; the cookie handed to HTML pages that arrive without one."""

    def __init__(self, app, per_client: int | None = None, per_address: int | None = None,
                 per_client_heavy: int | None = None, clock=time.monotonic, sleep=asyncio.sleep,
                 computing: Iterable[str] = (), light_places: int | None = None, heavy_places: int | None = None,
                 shares: ServerShares | None = None):
        self.app = app
        # the computing endpoints (`computing`: their names under /api/v1, the app's registry) and the heavy ones
        self.computing = re.compile(rf"/api/v1/({'|'.join([*map(re.escape, computing), *HEAVY_NAMES])})")
        self.clock, self.sleep = clock, sleep
        self.told_to_wait: dict[tuple, float] = {}   # client → the time its Retry-After runs out
        self.per_client = _env_limit("MDL_CLIENT_CONCURRENCY", 8) if per_client is None else per_client
        self.per_client_heavy = (_env_limit("MDL_CLIENT_HEAVY_CONCURRENCY", 2) if per_client_heavy is None
                                 else per_client_heavy)
        self.per_address = _env_limit("MDL_ADDRESS_CONCURRENCY", 32) if per_address is None else per_address
        server = from_worker() if shares is None else shares
        self.lanes = {
            "light": Lane(_env_limit("MDL_LIGHT_PLACES", 1) if light_places is None else light_places,
                          server=server, name="light"),
            "heavy": Lane(max(_env_limit("MDL_HEAVY_PROCESSES", 1), 1) + 1 if heavy_places is None
                          else heavy_places, server=server, name="heavy")}
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

    def lane_of(self, path: str) -> Lane | None:
        if FAMILY.fullmatch(path):
            return None
        return self.lanes["heavy" if HEAVY.fullmatch(path) else "light"]

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
            await self._serve(scope, receive, send, host, who)
        finally:
            for key in keys:
                self.in_flight[key] -= 1
                if not self.in_flight[key]:
                    del self.in_flight[key]

    async def _serve(self, scope, receive, send, host: str, who: str | None) -> None:
        """The request waits for its place in its lane (leaving if its client goes away), then is computed."""
        lane, group = self.lane_of(scope["path"]), host if self.per_address else (host, who)
        token = CLIENT.set((host, who))
        try:
            if lane is None:
                await _run_until_disconnect(self.app, scope, receive, send)
                return
            body, listening = await _read_body(receive)
            if listening is None:
                return                                   # gone before its body was in
            try:
                arrived = time.perf_counter()
                if await _entered(lane, group, who, listening, dragging(scope)):
                    held, entered, in_heavy = [True], time.perf_counter(), {}
                    heavy.TIMING.set(in_heavy)

                    async def send_freeing_the_place(message):
                        if held[0] and message["type"] == "http.response.start":
                            held[0] = False                  # computed: a slow reader holds no place
                            lane.leave(group)
                            message = with_timing(message, entered - arrived, time.perf_counter() - entered,
                                                  in_heavy)
                        await send(message)
                    try:
                        await _run_until_disconnect(self.app, scope, _replay(body, listening), send_freeing_the_place)
                    finally:
                        if held[0]:
                            lane.leave(group)
            finally:
                listening.cancel()
        finally:
            CLIENT.reset(token)

    def _full(self, limits: dict) -> tuple | None:
        """(key, limit) of the first limit the client has reached, or None."""
        return next(((key, limit) for key, limit in limits.items() if limit and self.in_flight[key] >= limit), None)

    def _tell_to_wait(self, key: tuple) -> None:
        """Note when the Retry-After given to the client (or address) whose limit `key` is runs out."""
        now = self.clock()
        if len(self.told_to_wait) >= TOLD_TO_WAIT_KEPT:
            self.told_to_wait = {known: until for known, until in self.told_to_wait.items() if until > now}
        self.told_to_wait[key] = now + RETRY_AFTER_S


def with_timing(message: dict, waited_s: float, computed_s: float, in_heavy: dict | None = None) -> dict:
    """The response's start with a Server-Timing header (W3C Server Timing; the browser's developer tools show
    it, bench/classroom.py reads it): the time the request waited for its place in the lane and the time from
    its place to its answer's first byte (the computation, a cache's lookup, the serialisation); for an answer
    computed in a heavy process, what `heavy.TIMING` recorded of that (queue, run, cpu), part of the compute."""
    timing = server_timing({"lane": waited_s, "compute": computed_s, **(in_heavy or {})}).encode()
    return {**message, "headers": [*message.get("headers", []), (b"server-timing", timing)]}


def server_timing(parts: dict[str, float]) -> str:
    """A Server-Timing header's value: each part's name and its duration in ms (parts in seconds)."""
    return ", ".join(f"{name};dur={1e3 * seconds:.1f}" for name, seconds in parts.items())


def dragging(scope) -> bool:
    """Whether the request says it was asked while a slider is dragged (DRAG_HEADER: 1)."""
    return any(name == DRAG_HEADER and value == b"1" for name, value in scope.get("headers", []))


async def _entered(lane: Lane, group, who, listening: asyncio.Future, drag: bool = False) -> bool:
    """Whether the request got its place in the lane before `listening` heard its client go away."""
    entering = asyncio.ensure_future(lane.enter(group, who, drag))
    try:
        await asyncio.wait((entering, listening), return_when=asyncio.FIRST_COMPLETED)
    except BaseException:                            # we are cancelled ourselves
        await _give_up(entering, lane, group)
        raise
    if entering.done():
        return True
    await _give_up(entering, lane, group)            # gone while waiting: leaves the queue
    return False


async def _give_up(entering: asyncio.Task, lane: Lane, group) -> None:
    """Cancel a wait for a place; a place given meanwhile is passed on."""
    entering.cancel()
    await asyncio.gather(entering, return_exceptions=True)
    if not entering.cancelled() and entering.exception() is None:
        lane.leave(group)


async def _read_body(receive) -> tuple[list[dict], asyncio.Future | None]:
    """The request's body messages, and a pending receive() that will hear of a disconnect (None: the client went
    away before its body was in)."""
    messages = []
    while True:
        message = await receive()
        if message["type"] != "http.request":
            return messages, None
        messages.append(message)
        if not message.get("more_body", False):
            return messages, asyncio.ensure_future(receive())


def _replay(messages: list[dict], listening: asyncio.Future):
    """A receive() that gives the body read already, then what `listening` hears."""
    pending = deque(messages)

    async def receive():
        if pending:
            return pending.popleft()
        return await asyncio.shield(listening)
    return receive


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
