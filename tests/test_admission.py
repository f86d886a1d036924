"""Per-client admission to the computing endpoints: the limit, who counts as a client, the 429, the cookie.

Behaviour only: requests are held in flight by events the test sets, never timed."""
from __future__ import annotations

import asyncio
import json
import threading
from concurrent.futures import ThreadPoolExecutor

from fastapi.routing import APIRoute
from fastapi.testclient import TestClient

from server.api.endpoints import ENDPOINTS
from server.runtime.admission import COOKIE, AdmissionMiddleware
from server.api.app import create_app
from admission_exchange import KINEMATICS, Exchange, settle
from event_loop import run_to_end
from tests.test_security import assert_security_headers

ID_A, ID_B, ID_C = "a" * 22, "b" * 22, "c" * 22
WIDE = {"light_places": 64, "heavy_places": 64}   # lanes wide enough that only the limits hold requests back


class HeldApp:
    """An ASGI app whose every request reads its body, then waits until the test releases (or fails) it."""

    def __init__(self):
        self.release = asyncio.Event()
        self.started = 0
        self.cancelled = 0
        self.fail = False

    async def __call__(self, scope, receive, send):
        await receive()
        self.started += 1
        try:
            await self.release.wait()
        except asyncio.CancelledError:
            self.cancelled += 1
            raise
        if self.fail:
            raise RuntimeError("the computation failed")
        await send({"type": "http.response.start", "status": 200, "headers": [(b"content-type", b"text/html")]})
        await send({"type": "http.response.body", "body": b"{}"})


def exchange(middleware, path=KINEMATICS, host="10.0.0.1", client_id=ID_A, method="POST") -> Exchange:
    """One request from a classroom browser, whose cookie header holds another cookie before the admission one."""
    return Exchange(middleware, path, host, client_id, method, other_cookies="theme=dark; ")


def run(scenario):
    run_to_end(scenario())


def test_past_the_client_limit_429_with_retry_after_while_another_client_is_admitted():
    async def scenario():
        app = HeldApp()
        middleware = AdmissionMiddleware(app, computing=ENDPOINTS, **WIDE, per_client=2, per_address=10)
        held = [exchange(middleware) for _ in range(2)]
        await settle()
        refused = exchange(middleware)
        other = exchange(middleware, client_id=ID_B)           # same classroom address, another browser
        await settle()
        assert app.started == 3 and refused.status == 429 and refused.task.done()
        assert refused.header(b"retry-after") == b"1"
        detail = json.loads(refused.sent[1]["body"])["detail"][0]
        assert detail["type"] == "too_many_requests" and detail["ctx"]["code"] == "busy"
        assert detail["ctx"]["scope"] == "client" and detail["ctx"]["limit"] == 2
        app.release.set()
        await asyncio.gather(*(e.task for e in held), other.task)
        assert [e.status for e in held] == [200, 200] and other.status == 200
        assert not middleware.in_flight                        # every place given back on completion
    run(scenario)


def test_a_place_is_given_back_on_error_and_on_disconnect():
    async def scenario():
        app = HeldApp()
        middleware = AdmissionMiddleware(app, computing=ENDPOINTS, **WIDE, per_client=1, per_address=10)
        gone = exchange(middleware)
        await settle()
        gone.hang_up.set()                                     # the student closed the tab
        await settle()
        assert gone.task.done() and app.cancelled == 1 and not middleware.in_flight
        failing = exchange(middleware)
        await settle()
        app.fail = True
        app.release.set()
        await asyncio.gather(failing.task, return_exceptions=True)
        assert not middleware.in_flight
        app.fail = False
        again = exchange(middleware)
        await again.task
        assert again.status == 200
    run(scenario)


def test_new_ids_on_one_address_count_toward_the_address_cap():
    async def scenario():
        app, time = HeldApp(), FakeTime()
        middleware = AdmissionMiddleware(app, computing=ENDPOINTS, **WIDE, per_client=2, per_address=3, clock=time.clock, sleep=time.sleep)
        held = [exchange(middleware, client_id=ID_A), exchange(middleware, client_id=ID_A),
                exchange(middleware, client_id=ID_B)]
        await settle()
        minted = exchange(middleware, client_id=ID_C)
        elsewhere = exchange(middleware, host="10.0.0.2", client_id=ID_C)
        await settle()
        assert minted.status == 429
        assert json.loads(minted.sent[1]["body"])["detail"][0]["ctx"]["scope"] == "address"
        assert elsewhere.status is None and app.started == 4   # another address is admitted
        anonymous = exchange(middleware, client_id=None)       # the address was told to wait: so does it
        time.wake.set()
        await anonymous.task
        assert time.asked == [1.0] and anonymous.status == 429
        app.release.set()
        await asyncio.gather(*(e.task for e in held), elsewhere.task)
    run(scenario)


def test_heavy_requests_have_a_smaller_limit_of_their_own():
    """A client's elastic runs and studies queue for the heavy process: two at most, its light requests still go."""
    async def scenario():
        app = HeldApp()
        middleware = AdmissionMiddleware(app, computing=ENDPOINTS, **WIDE, per_client=8, per_address=64, per_client_heavy=2)
        held = [exchange(middleware, path=path) for path in ("/api/v1/elastic", "/api/v1/work-precision/motion")]
        await settle()
        third = exchange(middleware, path="/api/v1/elastic")
        light = exchange(middleware, path="/api/v1/kinematics")
        other = exchange(middleware, path="/api/v1/elastic", client_id=ID_B)
        await settle()
        assert third.status == 429 and json.loads(third.sent[1]["body"])["detail"][0]["ctx"]["scope"] == "heavy"
        assert light.status is None and other.status is None and app.started == 4
        app.release.set()
        await asyncio.gather(*(e.task for e in held), light.task, other.task)
        assert not middleware.in_flight
    run(scenario)


def test_only_computing_posts_are_counted():
    async def scenario():
        app = HeldApp()
        middleware = AdmissionMiddleware(app, computing=ENDPOINTS, **WIDE, per_client=1, per_address=1)
        held = exchange(middleware, path="/api/v1/work-precision/elastic")
        others = [exchange(middleware, path=path) for path in ("/api/v1/assignments", "/api/v1/scenes/x")]
        await settle()
        assert app.started == 3 and all(e.status is None for e in (held, *others))
        family = exchange(middleware, path="/api/v1/family")
        await settle()
        assert family.status == 429                            # the work-precision study holds the one place
        app.release.set()
        await asyncio.gather(held.task, *(e.task for e in others))
    run(scenario)


def test_an_html_page_gives_a_browser_without_one_a_random_http_only_strict_id():
    async def scenario():
        app = HeldApp()
        app.release.set()
        middleware = AdmissionMiddleware(app, computing=ENDPOINTS)
        first, second = (exchange(middleware, path="/scenes/x", method="GET", client_id=None) for _ in range(2))
        known = exchange(middleware, path="/scenes/x", method="GET", client_id=ID_A)
        await asyncio.gather(first.task, second.task, known.task)
        cookies = [e.header(b"set-cookie").decode() for e in (first, second)]
        assert cookies[0] != cookies[1] and known.header(b"set-cookie") is None
        for cookie in cookies:
            attributes = {part.strip().split("=")[0] for part in cookie.split(";")}
            assert cookie.startswith(f"{COOKIE}=") and {"HttpOnly", "SameSite", "Path"} <= attributes
            assert "SameSite=Strict" in cookie
    run(scenario)


def test_through_the_app_the_429_has_the_security_headers_and_pages_hand_out_the_cookie(monkeypatch):
    """The real middleware stack with /kinematics replaced by an endpoint held on a threading.Event."""
    monkeypatch.setenv("MDL_CLIENT_CONCURRENCY", "2")
    monkeypatch.setenv("MDL_LIGHT_PLACES", "4")          # both held requests running, not one waiting its turn
    app = create_app()
    release, entered = threading.Event(), threading.Semaphore(0)

    def held_kinematics():
        entered.release()
        release.wait(30)
        return {"held": True}

    app.router.routes.insert(0, APIRoute("/api/v1/kinematics", held_kinematics, methods=["POST"]))
    with TestClient(app) as client, ThreadPoolExecutor(2) as pool:
        page = client.get("/")
        assert page.status_code == 200 and COOKIE in page.cookies
        assert "set-cookie" not in client.get("/api/v1/scenes").headers
        in_flight = [pool.submit(client.post, "/api/v1/kinematics", json={}) for _ in range(2)]
        for _ in in_flight:
            assert entered.acquire(timeout=30)
        refused = client.post("/api/v1/kinematics", json={})
        assert refused.status_code == 429 and refused.headers["retry-after"] == "1"
        assert refused.json()["detail"][0]["ctx"]["code"] == "busy"
        assert_security_headers(refused)
        release.set()
        answers = [future.result(30) for future in in_flight]
        assert all(a.status_code == 200 and "set-cookie" not in a.headers for a in answers)
        assert client.post("/api/v1/kinematics", json={}).status_code == 200


class FakeTime:
    """The middleware's clock and sleep: time stands still until the test moves it; a sleep is held until the
    test lets it end (what it asked for is recorded)."""

    def __init__(self):
        self.now = 100.0
        self.asked: list[float] = []
        self.wake = asyncio.Event()

    def clock(self) -> float:
        return self.now

    async def sleep(self, seconds: float) -> None:
        self.asked.append(seconds)
        await self.wake.wait()
        self.now += seconds


async def one_place_held():
    """A middleware with one place per client on a fake clock, and that place held by a computation."""
    app, time = HeldApp(), FakeTime()
    middleware = AdmissionMiddleware(app, computing=ENDPOINTS, **WIDE, per_client=1, per_address=10, clock=time.clock, sleep=time.sleep)
    held = exchange(middleware)
    await settle()
    return app, time, middleware, held


def test_a_client_that_asks_again_before_its_retry_after_waits_it_out_and_then_is_admitted_if_a_place_is_free():
    async def scenario():
        app, time, middleware, held = await one_place_held()
        first = exchange(middleware)                            # refused at once, told to wait 1 s
        await settle()
        assert first.status == 429 and time.asked == []
        time.now += 0.25
        again = exchange(middleware)                            # ignores Retry-After: waits the remaining 0.75 s
        await settle()
        assert again.status is None and not again.task.done() and time.asked == [0.75]
        app.release.set()                                       # meanwhile the held computation ends
        await held.task
        time.wake.set()
        await again.task
        assert again.status == 200 and app.started == 2         # admitted after its wait, not refused
        assert not middleware.in_flight
    run(scenario)


def test_a_client_that_waited_its_retry_after_is_answered_at_once_and_a_still_full_one_is_refused_after_the_wait():
    async def scenario():
        app, time, middleware, held = await one_place_held()
        assert exchange(middleware).task is not None
        await settle()
        time.now += 1.0                                         # honoured Retry-After: 1
        honest = exchange(middleware)
        await settle()
        assert honest.status == 429 and time.asked == []        # refused at once, no waiting imposed
        impatient = exchange(middleware)                        # at once again: waits out the new second
        time.wake.set()
        await impatient.task
        assert time.asked == [1.0] and impatient.status == 429  # still full after the wait: refused
        other = exchange(middleware, client_id=ID_B)            # another student on the address: not slowed
        await settle()
        assert other.status is None and app.started == 2
        app.release.set()
        await asyncio.gather(held.task, other.task)
        assert other.status == 200
    run(scenario)
