"""The page's coalescing of requests (web/static/js/common/model/api.js) in a real browser, against a slow server.
The requests sent while a slider is dragged say so (X-MDL-Drag: 1); the drag's last question, still waiting to be
sent when the slider comes to rest, is sent at rest (unmarked).

Every answer of the scene's compute endpoint is held back (Playwright's page.route) for DELAY_S, then
fulfilled with the server's real answer. While a slider is dragged quickly through many values the page
keeps at most one request in flight per panel key (the main request; each λ overlay of the kinematics page
has its own key), sends far fewer requests than there are input events, sends the final value last and
ends showing the answer to it. An answer that is overtaken (the slider moved on while it was awaited) is
dropped even when it arrives: the page shows the next one.

The slider's family (POST /api/v1/family, asked when a slider is grabbed) is never answered here: these
are the drags of a scene whose family is not there yet, which behave as before families.
"""
from __future__ import annotations

import json
import time
from collections import Counter

import pytest

from conftest import screenshot

pytestmark = pytest.mark.browser

DELAY_S = 0.4
HELD_MOVES = 5               # while a drag goes on, an answer also waits for this many more mouse positions
OVERLAY_OUTPUTS = ["s", "s2", "u31", "du31", "u21", "du21"]     # web/static/js/kinematics/model/scene_model.js
GRAPH = "document.querySelector(`#panel-${id} .graph`)"


def kinematics_key(body: dict) -> str:
    """The page's key of a kinematics request: "overlay <λ>" for an overlay table, else "main"."""
    if body["outputs"] == OVERLAY_OUTPUTS:
        return f"overlay {body['params']['l2'] / body['params']['l1']:.6g}"
    return "main"


class SlowEndpoint:
    """Holds every POST the page sends to one endpoint and answers it with the server's own answer once
    DELAY_S has passed, or, for a held request, when the test releases it. Counts requests in flight by key."""

    def __init__(self, page, endpoint: str, key=lambda body: "main", delay: float = DELAY_S):
        self.page, self.key, self.delay = page, key, delay
        self.requests: list[dict] = []       # in the order they were sent
        self.answered: list[dict] = []       # in the order their answers were delivered
        self.in_flight, self.most_in_flight = Counter(), Counter()
        self.holding: set[str] = set()
        self.moves, self.dragging = 0, False    # the mouse positions of the drag so far (drag_quickly)
        page.route(f"**/api/v1/{endpoint}?*", self._arrive)
        page.route("**/api/v1/family?*", lambda route: None)        # held: no family arrives

    def _arrive(self, route) -> None:
        body = json.loads(route.request.post_data)
        key = self.key(body)
        self.in_flight[key] += 1
        self.most_in_flight[key] = max(self.most_in_flight[key], self.in_flight[key])
        self.requests.append({"route": route, "body": body, "key": key, "arrived": time.monotonic(),
                              "move": self.moves, "held": key in self.holding, "answer": None,
                              "drag": route.request.headers.get("x-mdl-drag") == "1"})

    def due(self, request: dict) -> bool:
        """DELAY_S has passed and, during a drag, HELD_MOVES more positions too: the drag stays quick against
        the server however slowly a loaded machine moves the mouse."""
        return time.monotonic() >= request["arrived"] + self.delay and \
            (not self.dragging or self.moves >= request["move"] + HELD_MOVES)

    def pending(self, key: str | None = None) -> list[dict]:
        return [r for r in self.requests if r["answer"] is None and key in (None, r["key"])]

    def answer(self, request: dict) -> None:
        reply = request["route"].fetch()
        request["answer"], request["status"] = reply.json(), reply.status
        self.in_flight[request["key"]] -= 1
        self.answered.append(request)
        request["route"].fulfill(status=reply.status, body=reply.body(), content_type="application/json")

    def pump(self, seconds: float) -> None:
        """Let the page run for `seconds`, answering each request that is due and not held."""
        end = time.monotonic() + seconds
        while True:
            for request in self.pending():
                if not request["held"] and self.due(request):
                    self.answer(request)
            if time.monotonic() >= end:
                return
            self.page.wait_for_timeout(20)

    def pump_until(self, condition, what: str, limit: float = 60) -> None:
        """Pump until condition() holds: a loaded machine may take long to send, never forever."""
        deadline = time.monotonic() + limit
        while not condition():
            if time.monotonic() > deadline:
                raise AssertionError(f"{what}: not within {limit:g} s; requests {self.timeline()}")
            self.pump(0.05)

    def settle(self, quiet: float = 0.6, limit: float = 60) -> None:
        """Pump until the page's clients are idle (no element marked busy: ApiClient's onBusy), nothing unheld is
        pending and no request has come for `quiet` seconds. The page may take long to send the next request
        after an answer on a loaded machine, but it stays busy meanwhile."""
        deadline = time.monotonic() + limit
        while time.monotonic() < deadline:
            count = len(self.requests)
            self.pump(quiet)
            idle = self.page.evaluate("() => document.querySelector('.busy') === null")
            if idle and len(self.requests) == count and not [r for r in self.pending() if not r["held"]]:
                return
        raise AssertionError("the page kept sending requests")

    def main(self, since: int = 0) -> list[dict]:
        return [r for r in self.requests[since:] if r["key"] == "main"]

    def shown(self, key: str = "main") -> dict:
        """The last answer delivered for key that the page can show (a 429 is retried, never shown)."""
        return [r for r in self.answered if r["key"] == key and r["status"] == 200][-1]

    def timeline(self) -> list[tuple]:
        """(arrival order, key, status) in the order the answers were delivered, for a failure's message."""
        return [(self.requests.index(r), r["key"], r["status"]) for r in self.answered]


def count_inputs(page, selector: str) -> None:
    page.eval_on_selector(selector, "e => { window.inputEvents = 0; e.addEventListener('input', () => window.inputEvents++); }")


def drag_quickly(page, slow: SlowEndpoint, selector: str, fractions: list[float]) -> None:
    """Press the thumb and move the mouse through `fractions` of the track, 30 ms a position, while the
    slow endpoint answers what is due."""
    page.locator(selector).scroll_into_view_if_needed()
    box = page.locator(selector).bounding_box()
    value, low, high = page.eval_on_selector(selector, "e => [e.value, e.min, e.max].map(Number)")
    x = lambda f: box["x"] + 8 + (box["width"] - 16) * f
    y = box["y"] + box["height"] / 2
    page.mouse.move(x((value - low) / (high - low)), y)
    page.mouse.down()
    slow.dragging = True
    for fraction in fractions:
        page.mouse.move(x(fraction), y)
        slow.moves += 1
        slow.pump(0.03)
    slow.dragging = False
    page.mouse.up()


def plotted(page, panel: str, trace: int = 0):
    return page.evaluate(f"([id, k]) => {GRAPH}.data[k].y", [panel, trace])


def wait_until_plotted(page, panel: str, y: list) -> None:
    """Wait until the panel's first trace shows exactly the values y."""
    page.wait_for_function(f"([id, y]) => {{ const shown = {GRAPH}?.data?.[0]?.y; "
                           "return shown?.length === y.length && y.every((v, i) => shown[i] === v); }",
                           arg=[panel, y])


def sweep(start: float, stop: float, back_to: float, steps: int = 40) -> list[float]:
    """Fractions of the track: from start to stop and back to back_to, like a hand looking for a value."""
    there = [start + (stop - start) * k / steps for k in range(1, steps + 1)]
    back = [stop + (back_to - stop) * k / (steps // 2) for k in range(1, steps // 2 + 1)]
    return there + back


def assert_one_in_flight_per_key(slow: SlowEndpoint) -> None:
    assert slow.most_in_flight and max(slow.most_in_flight.values()) == 1, slow.most_in_flight


def test_kinematics_page_keeps_one_request_in_flight_per_key_and_ends_on_the_final_value(browser_page):
    page = browser_page
    slow = SlowEndpoint(page, "kinematics", kinematics_key)
    page.goto("/scenes/transfer-functions?lang=en&variant=slider_crank&overlay=1")
    slow.settle()
    page.wait_for_function(f"id => {GRAPH}?.data?.length === 4", arg="u31")     # u₃₁ and three overlays
    assert set(slow.most_in_flight) == {"main", "overlay 1.5", "overlay 3", "overlay 5"}

    count_inputs(page, "#slider-offset")
    before = len(slow.requests)
    drag_quickly(page, slow, "#slider-offset", sweep(0.5, 0.75, 0.6))   # e/l₁ ≤ 0.45: λ = 1.5 turns
    slow.settle()
    inputs = page.evaluate("window.inputEvents")
    final = float(page.input_value("#slider-offset"))
    sent = slow.main(before)

    assert_one_in_flight_per_key(slow)
    print(f"transfer functions: {inputs} input events, {len(sent)} main requests")
    assert inputs >= 40 and 2 <= len(sent) <= inputs / 3, (inputs, len(sent))
    assert final != 0 and sent[-1]["body"]["params"]["e"] == pytest.approx(final * 0.1, abs=1e-12)
    for key in ("overlay 1.5", "overlay 3", "overlay 5"):             # the overlays follow the offset too
        last = [r for r in slow.requests if r["key"] == key][-1]
        assert last["body"]["params"]["e"] == pytest.approx(final * 0.1, abs=1e-12)
        assert max(r["arrived"] for r in slow.requests if r["key"] == key) > sent[0]["arrived"]

    shown = slow.shown()
    assert shown["body"] == sent[-1]["body"], slow.timeline()          # the last answer shown is to the last asked
    wait_until_plotted(page, "u31", shown["answer"]["outputs"]["u31"])
    assert plotted(page, "u31") != slow.main()[0]["answer"]["outputs"]["u31"]
    overlays = {r["key"]: r for r in slow.answered if r["key"] != "main"}
    assert plotted(page, "u31", 2) == overlays["overlay 3"]["answer"]["outputs"]["u31"]
    assert page.inner_text(".slider .readout >> nth=1").startswith(f"e/l₁ (offset) = {final:.2f}")
    screenshot(page, "coalescing_transfer_functions")
    assert page.problems == []


def test_kinematics_answer_overtaken_while_awaited_is_dropped_when_it_arrives(browser_page):
    page = browser_page
    slow = SlowEndpoint(page, "kinematics", kinematics_key)
    page.goto("/scenes/transfer-functions?lang=en&variant=slider_crank")
    slow.settle()
    page.wait_for_function(f"id => {GRAPH}?.data?.length > 0", arg="u31")
    shown_before = plotted(page, "u31")

    slow.holding.add("main")
    page.focus("#slider-lambda")
    page.keyboard.press("ArrowRight")                 # λ 3.00 → 3.01: asked, its answer held
    slow.pump_until(lambda: slow.pending("main"), "3.01 asked")
    page.keyboard.press("ArrowRight")                 # 3.02: waits, since 3.01 is still in flight
    slow.pump(0.3)
    first, = slow.pending("main")
    assert first["body"]["params"]["l2"] == pytest.approx(0.301)
    slow.answer(first)                                # 3.01's answer arrives late: 3.02 was asked meanwhile
    slow.pump_until(lambda: slow.pending("main"), "3.02 asked")
    second, = slow.pending("main")
    assert second["body"]["params"]["l2"] == pytest.approx(0.302)
    assert plotted(page, "u31") == shown_before       # the overtaken answer is not shown
    slow.answer(second)
    wait_until_plotted(page, "u31", second["answer"]["outputs"]["u31"])
    assert first["answer"]["outputs"]["u31"] != second["answer"]["outputs"]["u31"] != shown_before
    assert_one_in_flight_per_key(slow)
    assert page.problems == []


def open_motion_scene(page) -> "SlowEndpoint":
    """The equation-of-motion scene (linear motor) with /motion held, its first answer plotted."""
    slow = SlowEndpoint(page, "motion")
    page.goto("/scenes/equation-of-motion?lang=en&variant=linear")
    slow.settle()
    page.wait_for_function(f"id => {GRAPH}?.data?.length > 0", arg="omega_phi")
    return slow


def test_dynamics_page_keeps_one_request_in_flight_and_ends_on_the_final_value(browser_page):
    page = browser_page
    slow = open_motion_scene(page)

    count_inputs(page, "#slider-M0")
    before = len(slow.requests)
    drag_quickly(page, slow, "#slider-M0", sweep(0.4, 0.9, 0.6))
    slow.settle()
    inputs = page.evaluate("window.inputEvents")
    final = float(page.input_value("#slider-M0"))
    sent = slow.main(before)

    assert_one_in_flight_per_key(slow)
    print(f"equation of motion: {inputs} input events, {len(sent)} requests")
    assert inputs >= 40 and 2 <= len(sent) <= inputs / 3, (inputs, len(sent))
    assert sent[-1]["body"]["motor"]["M0"] == pytest.approx(final)
    shown = slow.shown()
    assert shown["body"] == sent[-1]["body"], slow.timeline()          # the last answer shown is to the last asked
    omega = shown["answer"]["omega"]
    wait_until_plotted(page, "omega_phi", omega)
    assert plotted(page, "omega_phi") != sent[0]["answer"]["omega"]
    screenshot(page, "coalescing_equation_of_motion")
    assert page.problems == []


def test_a_drags_last_question_still_waiting_when_the_keys_rest_is_sent_at_rest(browser_page):
    """A key press on a slider is a drag with no family here: its request says so (X-MDL-Drag: 1, the server
    serves it after the answers at rest). The next press's question waits for that answer; when the keys have
    come to rest meanwhile, it is sent unmarked, and its answer is shown."""
    page = browser_page
    slow = open_motion_scene(page)
    slow.holding.add("main")
    page.focus("#slider-M0")
    page.keyboard.press("ArrowRight")                 # M₀ 60 → 61 N·m, held
    slow.pump_until(lambda: slow.pending(), "61 asked")
    page.keyboard.press("ArrowRight")                 # 62 waits for 61's answer
    slow.pump(1.0)                                    # the keys rest (250 ms)
    first, = slow.pending()
    assert first["drag"] and first["body"]["motor"]["M0"] == 61
    slow.answer(first)
    slow.pump_until(lambda: slow.pending(), "62 sent")
    second, = slow.pending()
    assert not second["drag"] and second["body"]["motor"]["M0"] == 62
    slow.answer(second)
    wait_until_plotted(page, "omega_phi", second["answer"]["omega"])
    assert_one_in_flight_per_key(slow)
    assert page.problems == []


def test_dynamics_answer_overtaken_while_awaited_is_dropped_when_it_arrives(browser_page):
    page = browser_page
    slow = open_motion_scene(page)
    shown_before = plotted(page, "omega_phi")

    slow.holding.add("main")
    page.focus("#slider-M0")
    page.keyboard.press("ArrowRight")                 # M₀ 60 → 61 N·m, held
    slow.pump_until(lambda: slow.pending(), "61 asked")
    page.keyboard.press("ArrowRight")                 # 62 waits
    slow.pump(0.3)
    first, = slow.pending()
    slow.answer(first)
    slow.pump_until(lambda: slow.pending(), "62 asked")
    second, = slow.pending()
    assert (first["body"]["motor"]["M0"], second["body"]["motor"]["M0"]) == (61, 62)
    assert plotted(page, "omega_phi") == shown_before
    slow.answer(second)
    wait_until_plotted(page, "omega_phi", second["answer"]["omega"])
    assert first["answer"]["omega"] != second["answer"]["omega"]
    assert_one_in_flight_per_key(slow)
    assert page.problems == []
