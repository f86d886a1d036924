"""Fairness per person in admission: an address gets one share of a lane however many cookie ids it invents, and
the waiting requests are served in turn (address after address, within an address cookie after cookie).

Behaviour only: each request is held in flight by an event of its own that the test sets, never timed."""
from __future__ import annotations

import asyncio
import re
import json

from server.api.endpoints import ENDPOINTS
from server.runtime.admission import CLIENT, AdmissionMiddleware
from admission_exchange import KINEMATICS, Exchange, settle
from event_loop import run_to_end


class HeldApp:
    """An ASGI app that reads its body, notes who it serves (admission's CLIENT) and its label, and answers when
    the test releases that label."""

    def __init__(self):
        self.order: list[str] = []
        self.clients: list[tuple] = []
        self.releases: dict[str, asyncio.Event] = {}

    async def __call__(self, scope, receive, send):
        await receive()
        label = dict(scope["headers"])[b"x-label"].decode()
        self.order.append(label)
        self.clients.append(CLIENT.get())
        await self.releases.setdefault(label, asyncio.Event()).wait()
        await send({"type": "http.response.start", "status": 200, "headers": []})
        await send({"type": "http.response.body", "body": b"{}"})

    def release(self, label: str) -> None:
        self.releases.setdefault(label, asyncio.Event()).set()


def exchange(middleware, label, host, client_id, path=KINEMATICS, reading=None, dragging=False) -> Exchange:
    """The request `label` from `host` with the cookie id `client_id`."""
    return Exchange(middleware, path, host, client_id, label=label, reading=reading, dragging=dragging)


def cookie(n: int) -> str:
    return f"{n:022d}"


def test_invented_cookies_get_an_address_no_more_than_its_share_and_another_address_is_served_at_once():
    async def scenario():
        app = HeldApp()
        middleware = AdmissionMiddleware(app, computing=ENDPOINTS, per_client=8, per_address=12, per_client_heavy=2,
                                         light_places=2, heavy_places=2)
        flood = [exchange(middleware, f"f{n}", "10.0.0.9", cookie(n)) for n in range(12)]
        await settle()
        minted = exchange(middleware, "h", "10.0.0.9", cookie(100), path="/api/v1/elastic")
        await settle()
        assert app.order == ["f0"]                   # one of two light places: the other is kept for another address
        assert minted.status == 429                  # 12 in flight: the address's cap, whatever the cookies
        detail = json.loads(minted.sent[1]["body"])["detail"][0]
        assert detail["ctx"]["scope"] == "address" and detail["ctx"]["limit"] == 12
        student = exchange(middleware, "s", "10.0.0.2", cookie(999))
        await settle()
        assert app.order == ["f0", "s"]              # another student's request finds its place free
        assert app.clients[-1] == ("10.0.0.2", cookie(999))
        app.release("s")
        await student.task
        app.release("f0")
        await settle()
        assert app.order == ["f0", "s", "f1"] and student.status == 200
        for n in range(12):
            app.release(f"f{n}")
        await asyncio.gather(*(e.task for e in flood))
        assert app.order[2:] == [f"f{n}" for n in range(1, 12)] and not middleware.in_flight
    run_to_end(scenario())


def served_in_turn(asked: list[tuple]) -> list[str]:
    """The labels in the order one light place serves them: a blocker "x" holds it while the requests `asked`
    ((label, host, cookie number, dragging), in this order) come and wait; then each is answered in turn."""
    async def scenario():
        app = HeldApp()
        middleware = AdmissionMiddleware(app, computing=ENDPOINTS, per_client=8, per_address=32, light_places=1)
        blocker = exchange(middleware, "x", "10.0.0.7", cookie(7))
        await settle()
        waiting = []
        for label, host, n, drag in asked:           # in this order: first come would serve them so
            waiting.append(exchange(middleware, label, host, cookie(n), dragging=drag))
            await settle()
        assert app.order == ["x"]
        served = ["x"]
        while len(app.order) < 1 + len(asked):
            app.release(served[-1])                  # one place: the next goes when the one before is answered
            await settle()
            served = list(app.order)
        app.release(served[-1])
        await asyncio.gather(blocker.task, *(e.task for e in waiting))
        assert all(e.status == 200 for e in waiting) and not middleware.in_flight
        return served
    return run_to_end(scenario())


def test_waiting_requests_are_served_address_after_address_then_cookie_after_cookie():
    asked = [("a1", "10.0.0.1", 1), ("a2", "10.0.0.1", 1), ("a3", "10.0.0.1", 2),   # address 1: cookies 1, 2
             ("b1", "10.0.0.2", 3), ("b2", "10.0.0.2", 3),
             ("c1", "10.0.0.3", 4), ("c2", "10.0.0.3", 4)]
    assert served_in_turn([(*a, False) for a in asked]) == ["x", "a1", "b1", "c1", "a3", "b2", "c2", "a2"]


def test_a_request_at_rest_goes_before_the_drags_that_wait_and_the_drags_are_served_in_turn():
    """The answers a page asks for while a slider is dragged (X-MDL-Drag: 1) are previews: every request at rest
    goes before them, whenever it came; among themselves they go address after address as the others do."""
    asked = [("a1", "10.0.0.1", 1, True), ("a2", "10.0.0.1", 1, True), ("b1", "10.0.0.2", 2, True),
             ("r1", "10.0.0.3", 3, False), ("a3", "10.0.0.1", 1, False), ("r2", "10.0.0.3", 3, False)]
    assert served_in_turn(asked) == ["x", "r1", "a3", "r2", "a1", "b1", "a2"]


def test_a_drag_that_waits_and_whose_page_gives_it_up_leaves_its_lane_unrun():
    async def scenario():
        app = HeldApp()
        middleware = AdmissionMiddleware(app, computing=ENDPOINTS, per_client=8, per_address=32, light_places=1)
        blocker = exchange(middleware, "x", "10.0.0.7", cookie(7))
        await settle()
        drag = exchange(middleware, "d", "10.0.0.1", cookie(1), dragging=True)
        await settle()
        drag.hang_up.set()                           # its page went away (a closed tab): the drag leaves the lane
        rest = exchange(middleware, "r", "10.0.0.1", cookie(1))      # the same client, at rest
        await settle()
        app.release("x")
        await settle()
        assert app.order == ["x", "r"]
        app.release("r")
        await asyncio.gather(blocker.task, rest.task, drag.task)
        assert rest.status == 200 and not middleware.in_flight and not any(middleware.lanes["light"].waiting)
    run_to_end(scenario())


def test_a_heavy_lane_serves_addresses_in_turn_too():
    async def scenario():
        app = HeldApp()
        middleware = AdmissionMiddleware(app, computing=ENDPOINTS, per_client=8, per_client_heavy=8,
                                         per_address=32, heavy_places=2)
        asked = [("a1", "10.0.0.1", 1), ("a2", "10.0.0.1", 2), ("a3", "10.0.0.1", 3),
                 ("b1", "10.0.0.2", 4), ("b2", "10.0.0.2", 4)]
        exchanges = []
        for label, host, n in asked:
            exchanges.append(exchange(middleware, label, host, cookie(n), path="/api/v1/elastic"))
            await settle()
        assert app.order == ["a1", "b1"]             # each address one of the two places
        for label in ("a1", "b1", "a2"):
            app.release(label)
            await settle()
        assert app.order == ["a1", "b1", "a2", "b2", "a3"]
        for label in ("b2", "a3"):
            app.release(label)
        await asyncio.gather(*(e.task for e in exchanges))
        assert not middleware.in_flight
    run_to_end(scenario())


def test_a_request_whose_client_goes_away_while_it_waits_leaves_its_lane_unrun():
    async def scenario():
        app = HeldApp()
        middleware = AdmissionMiddleware(app, computing=ENDPOINTS, per_client=8, per_address=32, light_places=1)
        held = exchange(middleware, "x", "10.0.0.1", cookie(1))
        gone = exchange(middleware, "gone", "10.0.0.2", cookie(2))
        later = exchange(middleware, "later", "10.0.0.3", cookie(3))
        await settle()
        gone.hang_up.set()
        await settle()
        assert gone.task.done() and gone.status is None and middleware.in_flight[("address", "10.0.0.2")] == 0
        app.release("x")
        app.release("later")
        await asyncio.gather(held.task, later.task)
        assert app.order == ["x", "later"] and not any(middleware.lanes["light"].waiting)
    run_to_end(scenario())


def test_with_the_address_cap_off_each_cookie_is_served_as_an_address_of_its_own():
    """A load test of many students from one machine (MDL_ADDRESS_CONCURRENCY=0)."""
    async def scenario():
        app = HeldApp()
        middleware = AdmissionMiddleware(app, computing=ENDPOINTS, per_client=8, per_address=0, light_places=3)
        exchanges = [exchange(middleware, f"s{n}", "127.0.0.1", cookie(n)) for n in range(3)]
        await settle()
        assert app.order == ["s0", "s1", "s2"]
        for n in range(3):
            app.release(f"s{n}")
        await asyncio.gather(*(e.task for e in exchanges))
    run_to_end(scenario())


def test_a_client_reading_its_answer_slowly_holds_no_place():
    """The place is the computation's: once the answer starts, the next request is computed, however slowly the
    first client reads (a send that does not return stands for a reader that does not drain its socket)."""
    async def scenario():
        app = HeldApp()
        middleware = AdmissionMiddleware(app, computing=ENDPOINTS, per_client=8, per_address=32, light_places=1)
        reading = asyncio.Event()
        slow = exchange(middleware, "slow", "10.0.0.1", cookie(1), reading=reading)
        await settle()
        other = exchange(middleware, "other", "10.0.0.2", cookie(2))
        await settle()
        assert app.order == ["slow"]
        app.release("slow")
        await settle()
        assert slow.status == 200 and not slow.task.done()          # its answer still being read
        assert app.order == ["slow", "other"]                       # computed meanwhile
        app.release("other")
        await other.task
        assert other.status == 200
        reading.set()
        await slow.task
        assert not middleware.in_flight and len(middleware.lanes["light"]) == 0
    run_to_end(scenario())


def test_an_answer_tells_how_long_it_waited_in_its_lane_and_how_long_it_was_computed():
    """Server-Timing: lane (waiting for a place) and compute (from the place to the first byte). The request
    behind one held for at least HELD_S waited at least that long; the one held computed at least that long.
    Lower bounds only: a slow machine makes both longer, never shorter."""
    held_s = 0.05

    async def scenario():
        app = HeldApp()
        middleware = AdmissionMiddleware(app, computing=ENDPOINTS, per_client=8, per_address=32, light_places=1)
        first = exchange(middleware, "first", "10.0.0.1", cookie(1))
        await settle()
        second = exchange(middleware, "second", "10.0.0.2", cookie(2))
        await settle()
        assert app.order == ["first"]
        await asyncio.sleep(held_s)
        app.release("first")
        await first.task
        app.release("second")
        await second.task
        timings = {}
        for name, done in (("first", first), ("second", second)):
            header = done.header(b"server-timing").decode()
            timings[name] = {key: float(value) for key, value in re.findall(r"(lane|compute);dur=([0-9.]+)", header)}
        assert timings["first"]["compute"] >= 1e3 * held_s and timings["first"]["lane"] >= 0
        assert timings["second"]["lane"] >= 1e3 * held_s
    run_to_end(scenario())
