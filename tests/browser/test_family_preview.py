"""Dragging is a lookup (the family preview): grabbing a slider asks for its family (POST /api/v1/family), first the
coarse one ("stage": "coarse", the 9 start members) and, once it has arrived, the full one; the drag is drawn
from the best family there as a marked preview without a request, and the exact answer replaces the preview
when the slider rests. On the transfer-functions scene (crank-slider, λ), the equation-of-motion scene (λ, a
slider with a scale: params.l2 = λ·params.l1) and the flywheel scene ([δ], a logarithmic slider).

When the app has no /api/v1/family yet, or one that does not take "stage" (the two are built beside this
page), the tests answer it with a double (FamilyDouble): the contract's answer assembled from the app's own
answers of the scene's endpoint at evenly spaced members (9 for the coarse stage, 17 for the full one), so the
page is still checked against the app's exact answers. With the real endpoint present the double is not
installed.
"""
from __future__ import annotations

import copy
import json
import math
from urllib.parse import parse_qs, urlparse

import httpx
import numpy as np
import pytest

from conftest import PHONE, families_arrived, interface_texts, screenshot

pytestmark = pytest.mark.browser

GRAPH = "document.querySelector(`#panel-${id} .graph`)"
MEMBERS = {"coarse": 9, "full": 17}     # the double's families: the contract's 9 start members, then more


def set_path(body: dict, path: str, value) -> None:
    *parents, last = path.split(".")
    for key in parents:
        body = body.setdefault(key, {})
    body[last] = value


class FamilyDouble:
    """Answers POST /api/v1/family as the contract says, from the app's answers at MEMBERS values."""

    def __init__(self, page, app_url: str):
        self.app_url = app_url
        page.route("**/api/v1/family?*", self._answer)

    def _answer(self, route) -> None:
        family = json.loads(route.request.post_data)
        lang = parse_qs(urlparse(route.request.url).query).get("lang", ["ru"])[0]
        low, high = family["min"], family["max"]
        stage = family.get("stage", "full")
        count = MEMBERS[stage]
        values = [low * (high / low) ** (k / (count - 1)) if family["log"] else low + (high - low) * k / (count - 1)
                  for k in range(count)]
        answers, errors = [], []
        for value in values:
            body = copy.deepcopy(family["request"])
            for vary in family["vary"]:
                set_path(body, vary["path"], value * vary["factor"])
            reply = httpx.post(f"{self.app_url}/api/v1/{family['endpoint']}", params={"lang": lang}, json=body, timeout=120)
            refused = reply.status_code != 200
            detail = reply.json()["detail"][0] if refused else None
            answers.append(None if refused else reply.json())
            errors.append({"code": detail.get("ctx", {}).get("code"), "message": detail["msg"]} if refused else None)
        route.fulfill(status=200, content_type="application/json", body=json.dumps({
            "values": values, "answers": answers, "errors": errors, "interpolation_error": None, "tolerance": 0.005,
            "numerics": {"method": "test double: the app's answers at evenly spaced members", "points": count,
                         "checked": 0, "runtime_ms": 0, "message": "", "stage": stage}}))


def takes_stages(app_url: str) -> bool:
    """Whether the app's /api/v1/family exists and takes "stage" (its refusal of an empty body names no stage)."""
    reply = httpx.post(f"{app_url}/api/v1/family", json={"stage": "coarse"})
    return reply.status_code != 404 and not any(d["loc"][-1] == "stage" for d in reply.json()["detail"])


class HeldFull:
    """Holds the page's full-family requests (those without "stage": "coarse") until release(), so that a test
    sees the preview drawn from the coarse family first. Registered after the double, so it is asked first."""

    def __init__(self, page):
        self.held = []
        page.route("**/api/v1/family?*", self._hold)

    def _hold(self, route) -> None:
        if json.loads(route.request.post_data).get("stage") == "coarse":
            route.fallback()
        else:
            self.held.append(route)

    def release(self) -> None:
        for route in self.held:
            route.fallback()
        self.held = []


@pytest.fixture
def family_page(browser_page, app_url):
    """The browser page, with the family double when the app has no /api/v1/family, and a log of the
    computing requests it sends: page.sent = [(endpoint, body)]."""
    page = browser_page
    if not takes_stages(app_url):
        FamilyDouble(page, app_url)
    page.sent = []
    page.on("request", lambda r: "/api/v1/" in r.url and r.method == "POST" and page.sent.append(
        (urlparse(r.url).path.rsplit("/", 1)[-1], json.loads(r.post_data))))
    return page


def sent(page, endpoint: str, since: int = 0) -> list[dict]:
    return [body for name, body in page.sent[since:] if name == endpoint]


def plotted(page, panel: str) -> list:
    return page.evaluate(f"id => {GRAPH}.data[0].y", panel)


def curves(page, panel: str) -> list[str]:
    """The SVG paths of the panel's drawn curves (a preview moves them in place; gd.data is the exact answer's)."""
    return page.eval_on_selector_all(f"#panel-{panel} .scatterlayer path.js-line", "paths => paths.map((p) => p.getAttribute('d'))")


def marks(page, name: str) -> int:
    return page.evaluate("name => performance.getEntriesByName(name).length", name)


def thumb(page, selector: str):
    """x(fraction of the track) and y of the range input's thumb, as conftest.drag_slider finds them."""
    page.locator(selector).scroll_into_view_if_needed()
    box = page.locator(selector).bounding_box()
    return (lambda f: box["x"] + 8 + (box["width"] - 16) * f), box["y"] + box["height"] / 2


def fraction(page, selector: str) -> float:
    value, low, high = page.eval_on_selector(selector, "e => [e.value, e.min, e.max].map(Number)")
    return (value - low) / (high - low)


def grab(page, selector: str) -> tuple:
    """Press the mouse on the slider's thumb and wait for its family; returns x, y of the track."""
    x, y = thumb(page, selector)
    page.mouse.move(x(fraction(page, selector)), y)
    page.mouse.down()
    page.wait_for_function("() => performance.getEntriesByName('family-arrived').length > 0", timeout=60_000)
    return x, y


def drag_through(page, x, y, fractions: list[float]) -> None:
    """Move the held thumb through fractions of the track, waiting for each preview to be drawn."""
    for f in fractions:
        drawn = marks(page, "plots-drawn")
        page.mouse.move(x(f), y)
        page.wait_for_function("n => performance.getEntriesByName('plots-drawn').length > n", arg=drawn)


def preview_shown(page) -> bool:
    return page.is_visible(".preview-note") and page.locator(".scene-layout.preview").count() == 1


def release_and_wait_for_exact(page, endpoint: str) -> dict:
    """Release the mouse; returns the exact answer the page asked for, once it is drawn."""
    drawn = marks(page, "exact-drawn")
    with page.expect_response(lambda r: f"/api/v1/{endpoint}?" in r.url) as response:
        page.mouse.up()
    answer = response.value.json()
    page.wait_for_function("n => performance.getEntriesByName('exact-drawn').length > n", arg=drawn)
    return answer


def test_transfer_functions_drag_is_drawn_from_the_family_and_ends_on_the_exact_answer(family_page):
    page = family_page
    page.goto("/scenes/transfer-functions?lang=ru&variant=slider_crank")
    page.wait_for_function(f"id => {GRAPH}?.data?.length > 0", arg="u31")
    page.wait_for_load_state("networkidle")
    before = len(page.sent)
    x, y = grab(page, "#slider-lambda")
    family = sent(page, "family", before)[0]
    assert family["stage"] == "coarse"
    assert family["endpoint"] == "kinematics" and family["log"] is False
    assert (family["min"], family["max"]) == (1.05, 8)
    assert family["vary"] == [{"path": "params.l2", "factor": family["request"]["params"]["l1"]}]
    assert not sent(page, "kinematics", before)

    in_view = page.evaluate("() => [...document.querySelectorAll('.panel')].filter((p) =>"
                            " p.getBoundingClientRect().top < innerHeight).map((p) => p.id.slice(6))")
    shown = {panel: curves(page, panel) for panel in in_view}
    linkage, status = page.inner_html("#linkage svg .moving"), page.inner_text("#status")
    drag_through(page, x, y, [0.30, 0.35, 0.42, 0.5])
    assert not sent(page, "kinematics", before)                  # the drag asked nothing
    assert len(in_view) >= 4
    for panel in in_view:                                         # every plot in view follows the preview
        assert curves(page, panel) != shown[panel], panel
        shown[panel] = curves(page, panel)
    drawn = marks(page, "plots-drawn")
    page.mouse.move(x(0.55), y)                                   # one more input: one preview frame
    page.wait_for_function("n => performance.getEntriesByName('plots-drawn').length > n", arg=drawn)
    assert all(curves(page, panel) != shown[panel] for panel in in_view)   # all of them in that one frame
    assert page.inner_html("#linkage svg .moving") != linkage
    assert preview_shown(page)
    assert page.inner_text("#status") == status                  # numbers stay those of the exact answer
    assert page.eval_on_selector("#status", "e => Number(getComputedStyle(e).opacity)") < 1
    screenshot(page, "family_preview_transfer_functions_ru")

    answer = release_and_wait_for_exact(page, "kinematics")
    exact, = sent(page, "kinematics", before)
    assert exact["params"]["l2"] == pytest.approx(float(page.input_value("#slider-lambda")) * exact["params"]["l1"])
    page.wait_for_function("() => !document.querySelector('.scene-layout.preview')")
    assert not page.is_visible(".preview-note")
    assert plotted(page, "u31") == answer["outputs"]["u31"]
    assert plotted(page, "position") == answer["outputs"]["s"]
    assert [body.get("stage") for body in sent(page, "family", before)] == ["coarse", None]   # then the full one
    assert page.problems == []


def test_a_second_grab_with_the_same_other_values_reuses_the_family(family_page):
    page = family_page
    page.goto("/scenes/transfer-functions?lang=en&variant=slider_crank")
    page.wait_for_function(f"id => {GRAPH}?.data?.length > 0", arg="u31")
    page.wait_for_load_state("networkidle")
    x, y = grab(page, "#slider-lambda")
    drag_through(page, x, y, [0.4])
    release_and_wait_for_exact(page, "kinematics")
    before = len(page.sent)

    page.mouse.move(x(fraction(page, "#slider-lambda")), y)
    page.mouse.down()
    drag_through(page, x, y, [0.6, 0.7])
    assert sent(page, "family", before) == [] and sent(page, "kinematics", before) == []
    release_and_wait_for_exact(page, "kinematics")
    assert len(sent(page, "kinematics", before)) == 1
    assert page.problems == []


def until(page, condition, timeout_s: float = 120) -> None:
    """Let the page run (its events reach the test's handlers) until condition() holds; fails past timeout_s."""
    for _ in range(int(timeout_s / 0.05)):
        if condition():
            return
        page.wait_for_timeout(50)
    raise AssertionError(f"not within {timeout_s} s")


def test_grabbing_another_slider_aborts_the_family_on_its_way_and_keeps_the_coarse_one(family_page):
    """The full family of λ is held on its way (HeldFull); grabbing the offset slider aborts it (the server, seeing
    the request gone, stops computing it: server/runtime/heavy.py), with nothing on the console; grabbing λ again
    previews from the coarse family kept and asks for λ's full family anew (not the coarse one)."""
    page = family_page
    held = HeldFull(page)
    failed = []
    page.on("requestfailed", lambda r: "/api/v1/family" in r.url and failed.append(
        (json.loads(r.post_data).get("stage"), r.failure)))
    page.goto("/scenes/transfer-functions?lang=ru&variant=slider_crank")
    page.wait_for_function(f"id => {GRAPH}?.data?.length > 0", arg="u31")
    page.wait_for_load_state("networkidle")
    x, y = grab(page, "#slider-lambda")                          # the coarse family has arrived
    page.wait_for_function("() => performance.getEntriesByName('family-requested').length === 1")
    page.wait_for_timeout(100)
    assert len(held.held) == 1                                    # λ's full family, on its way
    page.mouse.up()
    before = len(page.sent)
    grab(page, "#slider-offset")
    page.wait_for_function("() => performance.getEntriesByName('family-requested').length === 2")
    until(page, lambda: failed and len(held.held) == 2)           # the offset's coarse family came, its full one held
    assert failed == [(None, "net::ERR_ABORTED")]                 # λ's full family given up
    assert [body["vary"][0]["path"] for body in sent(page, "family", before)] == ["params.e", "params.e"]
    assert [body.get("stage") for body in sent(page, "family", before)] == ["coarse", None]
    page.mouse.up()
    held.release()                                                # the aborted route and the offset's full one

    before = len(page.sent)
    x, y = thumb(page, "#slider-lambda")                          # where it is now
    page.mouse.move(x(fraction(page, "#slider-lambda")), y)
    page.mouse.down()
    drag_through(page, x, y, [0.45])                              # drawn from the coarse family kept
    assert preview_shown(page)
    again = sent(page, "family", before)
    assert len(again) == 1 and again[0].get("stage") is None      # the full one, asked anew
    assert again[0]["vary"][0]["path"] == "params.l2"
    release_and_wait_for_exact(page, "kinematics")
    assert page.problems == []


@pytest.mark.parametrize("outcome", ["unrefined", "failed"])
def test_a_full_family_not_given_is_asked_again_at_the_next_grab(family_page, outcome):
    """The full stage of λ's family comes back without the full family, once: a busy server's coarse family in its
    place (server/api/routers/family.py: unrefined), or a 503. The page ends that family as it came (the helpers
    that wait for the page's families see it end), previews from the coarse family it holds, and the next grab of
    the slider asks for the full family again."""
    page = family_page
    answered = []

    def full_family_once(route):
        body = json.loads(route.request.post_data)
        if "stage" in body or answered:
            route.fallback()
            return
        answered.append(body)
        if outcome == "unrefined":
            route.fulfill(response=route.fetch(post_data=json.dumps(body | {"stage": "coarse"})))
        else:
            route.fulfill(status=503, content_type="application/json", body=json.dumps({"detail": "unavailable"}))

    page.route("**/api/v1/family?*", full_family_once)
    page.goto("/scenes/transfer-functions?lang=en&variant=slider_crank")
    page.wait_for_function(f"id => {GRAPH}?.data?.length > 0", arg="u31")
    page.wait_for_load_state("networkidle")
    x, y = grab(page, "#slider-lambda")
    families_arrived(page)
    assert (marks(page, f"family-{outcome}"), marks(page, "family-full-arrived")) == (1, 0) and len(answered) == 1
    drag_through(page, x, y, [0.4])
    assert preview_shown(page) and marks(page, "preview-coarse") > 0 and marks(page, "preview-full") == 0
    release_and_wait_for_exact(page, "kinematics")

    before = len(page.sent)
    page.focus("#slider-offset")                       # another slider, then λ again at the same other values
    families_arrived(page)
    page.focus("#slider-lambda")
    families_arrived(page)
    assert [body.get("stage") for body in sent(page, "family", before) if body["vary"][0]["path"] == "params.l2"] \
        == [None]                                      # λ's full family, asked again
    # the browser reports the 503 itself as a console error; nothing else may appear
    assert [problem for problem in page.problems if "503" not in problem] == []


def test_a_family_the_page_let_go_is_asked_again(family_page):
    """The page keeps the last four families; a fifth pushes out the first, and grabbing that slider again at
    the same values asks the server again (the page does not send a question it has answered: the family's
    answered questions go with it) and previews from the new family."""
    page = family_page
    page.goto("/scenes/transfer-functions?lang=en&variant=four_bar")
    page.wait_for_function(f"id => {GRAPH}?.data?.length > 0", arg="u31")
    page.wait_for_load_state("networkidle")

    def focus(slider: str) -> None:
        page.focus(f"#slider-{slider}")
        families_arrived(page)

    def press(key: str) -> None:
        drawn = marks(page, "exact-drawn")
        page.keyboard.press(key)
        page.wait_for_function("n => performance.getEntriesByName('exact-drawn').length > n", arg=drawn)

    first = len(page.sent)
    focus("lambda0")
    asked = sent(page, "family", first)[0]
    for slider in ("lambda2", "lambda3"):
        focus(slider)
    press("ArrowRight")                                  # λ₃ moved: λ₀'s and λ₂'s families at other values
    focus("lambda0")
    focus("lambda2")                                     # the fifth: λ₀'s first family is let go
    focus("lambda3")
    press("ArrowLeft")                                   # λ₃ back where it was
    before = len(page.sent)
    focus("lambda0")
    again = sent(page, "family", before)
    assert again and again[0]["request"] == asked["request"] and again[0]["vary"] == asked["vary"]
    assert page.problems == []


def test_keyboard_focus_asks_for_the_family_and_a_key_press_shows_the_exact_answer_at_rest(family_page):
    page = family_page
    page.goto("/scenes/transfer-functions?lang=uk&variant=slider_crank")
    page.wait_for_function(f"id => {GRAPH}?.data?.length > 0", arg="u31")
    page.wait_for_load_state("networkidle")
    before = len(page.sent)
    page.focus("#slider-lambda")
    page.wait_for_function("() => performance.getEntriesByName('family-arrived').length > 0", timeout=60_000)
    assert sent(page, "family", before)[0]["stage"] == "coarse"
    with page.expect_response(lambda r: "/api/v1/kinematics?" in r.url) as response:
        page.keyboard.press("ArrowRight")                          # λ 3.00 → 3.01
    answer = response.value.json()
    assert sent(page, "kinematics", before)[-1]["params"]["l2"] == pytest.approx(0.301)
    page.wait_for_function("y => { const shown = document.querySelector('#panel-u31 .graph').data[0].y;"
                           " return !document.querySelector('.scene-layout.preview')"
                           " && shown.every((v, i) => v === y[i]); }", arg=answer["outputs"]["u31"])
    assert page.problems == []


def test_equation_of_motion_lambda_drag_is_drawn_from_the_family(family_page):
    page = family_page
    page.goto("/scenes/equation-of-motion?lang=ru&variant=linear")
    page.wait_for_function(f"id => {GRAPH}?.data?.length > 0", arg="omega_phi")
    page.wait_for_load_state("networkidle")
    before = len(page.sent)
    x, y = grab(page, "#slider-lambda")
    family = sent(page, "family", before)[0]
    assert family["endpoint"] == "motion"
    assert family["vary"] == [{"path": "params.l2", "factor": family["request"]["params"]["l1"]}]

    omega, figures = curves(page, "omega_phi"), page.inner_text("#panel-figures")
    drag_through(page, x, y, [0.25, 0.3, 0.4])
    assert not sent(page, "motion", before)
    assert curves(page, "omega_phi") != omega
    assert preview_shown(page)
    assert page.inner_text("#panel-figures") == figures           # numbers stay those of the exact answer
    assert page.eval_on_selector("#panel-figures", "e => Number(getComputedStyle(e).opacity)") < 1
    # t(φ) lies below the fold: drawn from the exact answer in an idle moment, so the whole page shows it
    page.wait_for_function("() => document.querySelector('#panel-time .graph path.js-line')?.getAttribute('d')?.length > 100")
    assert page.is_visible("#panel-time") and plotted(page, "time")
    screenshot(page, "family_preview_equation_of_motion_ru")
    time_curve = curves(page, "time")
    page.locator("#panel-time").scroll_into_view_if_needed()       # scrolled into view: the preview drawn there
    page.wait_for_function("d => document.querySelector('#panel-time .graph path.js-line').getAttribute('d') !== d",
                           arg=time_curve[0])

    answer = release_and_wait_for_exact(page, "motion")
    exact, = sent(page, "motion", before)
    assert exact["params"]["l2"] == pytest.approx(float(page.input_value("#slider-lambda")) * exact["params"]["l1"])
    page.wait_for_function("() => !document.querySelector('.scene-layout.preview')")
    # ω(φ), scrolled out of view above, gets the exact answer in an idle moment
    page.wait_for_function("y => { const shown = document.querySelector('#panel-omega_phi .graph').data[0].y;"
                           " return shown.length === y.length && shown.every((v, i) => v === y[i]); }", arg=answer["omega"])
    assert page.inner_text("#panel-figures") != figures

    page.set_viewport_size(PHONE)          # the window made narrow after a drag: every plot keeps its height
    page.wait_for_function("""() => [...document.querySelectorAll('.panel:not([hidden]) .graph')].filter((g) => g._fullLayout)
        .every((g) => g.layout.autosize === true && g._fullLayout.height > 100
                      && Math.round(g.getBoundingClientRect().height) === g._fullLayout.height)""")
    assert page.problems == []


def wittenbauer_paths(page) -> list[str]:
    return page.eval_on_selector_all("#panel-wittenbauer .scatterlayer path.js-line", "ps => ps.map((p) => p.getAttribute('d'))")


@pytest.mark.parametrize("scene, variant, slider, ready, drawn", [
    ("transfer-functions", "slider_crank", "lambda", "#panel-u31 .graph path.js-line", lambda page: curves(page, "u31")),
    ("flywheel", "rig", "delta", "#panel-wittenbauer .graph path.js-line",
     lambda page: [page.get_attribute(".flywheel-disk", "r"), *wittenbauer_paths(page)])])
def test_the_preview_is_drawn_from_the_coarse_family_then_from_the_full_one(family_page, scene, variant, slider, ready, drawn):
    """The coarse family is asked first; the full one only once the coarse one has arrived (the server reuses
    its members); the drag is drawn from the coarse one until the full one arrives, which redraws the preview
    and draws the rest of the drag. The flywheel's own views (its drawing's disk, Wittenbauer's diagram) follow."""
    page = family_page
    held = HeldFull(page)
    page.goto(f"/scenes/{scene}?lang=ru&variant={variant}")
    page.wait_for_selector(ready, state="attached")
    page.wait_for_load_state("networkidle")
    before = len(page.sent)
    x, y = grab(page, f"#slider-{slider}")
    page.wait_for_function("() => performance.getEntriesByName('family-coarse-arrived').length === 1")
    page.wait_for_function("() => performance.getEntriesByName('family-full-arrived').length === 0")
    coarse, full = sent(page, "family", before)
    assert coarse["stage"] == "coarse" and "stage" not in full       # the full family: the server's default
    assert {**coarse, "stage": None} == {**full, "stage": None}
    assert held.held                                                  # on its way

    shown = drawn(page)
    numbers = page.inner_text(".flywheel-numbers") if scene == "flywheel" else None
    start = fraction(page, f"#slider-{slider}")
    step = 0.06 if start < 0.5 else -0.06
    drag_through(page, x, y, [start + step, start + 2 * step])
    assert drawn(page) != shown
    assert marks(page, "preview-coarse") > 0 and marks(page, "preview-full") == 0
    assert preview_shown(page)
    texts = interface_texts("ru")           # the badge says the preview is coarse, its title the stated error
    assert page.inner_text(".preview-note") == texts["preview_coarse"]
    if numbers:                                  # the disk's numbers stay those of the exact answer, dimmed
        assert page.inner_text(".flywheel-numbers") == numbers
        assert page.eval_on_selector(".flywheel-numbers", "e => Number(getComputedStyle(e).opacity)") < 1

    shown = drawn(page)
    held.release()
    page.wait_for_function("() => performance.getEntriesByName('preview-full').length > 0")   # redrawn, not moved
    page.wait_for_function("() => performance.getEntriesByName('family-full-arrived').length === 1")
    coarse_frames = marks(page, "preview-coarse")
    drag_through(page, x, y, [start + 3 * step])
    assert drawn(page) != shown
    assert marks(page, "preview-coarse") == coarse_frames and preview_shown(page)
    assert page.inner_text(".preview-note") == texts["preview"]
    screenshot(page, f"family_preview_{scene}_full_family_ru")
    release_and_wait_for_exact(page, scene_endpoint(scene))
    assert len(sent(page, "family", before)) == 2
    assert page.problems == []


def scene_endpoint(scene: str) -> str:
    return "kinematics" if scene == "transfer-functions" else scene.replace("-", "_")


def test_a_server_without_stages_gets_one_full_family(family_page):
    """A server that refuses "stage" (422, an older one) is asked for the full family without it, and the
    drag is drawn from that family; the next grab asks for the full family at once."""
    page = family_page

    def refuse_stage(route):
        if "stage" in json.loads(route.request.post_data):
            route.fulfill(status=422, content_type="application/json", body=json.dumps({"detail": [
                {"type": "extra_forbidden", "loc": ["body", "stage"], "msg": "Extra inputs are not permitted"}]}))
        else:
            route.fallback()

    page.route("**/api/v1/family?*", refuse_stage)
    page.goto("/scenes/transfer-functions?lang=en&variant=slider_crank")
    page.wait_for_function(f"id => {GRAPH}?.data?.length > 0", arg="u31")
    page.wait_for_load_state("networkidle")
    before = len(page.sent)
    x, y = grab(page, "#slider-lambda")
    assert [body.get("stage") for body in sent(page, "family", before)] == ["coarse", None]
    shown = curves(page, "u31")
    drag_through(page, x, y, [0.35, 0.4])
    assert curves(page, "u31") != shown and marks(page, "preview-full") > 0 and marks(page, "preview-coarse") == 0
    release_and_wait_for_exact(page, "kinematics")

    again = len(page.sent)
    page.focus("#slider-offset")                                      # another slider, another family
    page.wait_for_function("() => performance.getEntriesByName('family-arrived').length > 1", timeout=60_000)
    assert [body.get("stage") for body in sent(page, "family", again)] == [None]
    # the browser reports the refused request itself as a console error; nothing else may appear
    assert [p for p in page.problems if "422" not in p] == []


@pytest.mark.parametrize("scene, variant, slider, panel, ready", [
    ("transfer-functions", "slider_crank", "lambda", "u31", "#linkage svg .moving line"),
    ("equation-of-motion", "linear", "lambda", "omega_phi", "#panel-portrait:not([hidden])"),
    ("flywheel", "rig", "delta", "wittenbauer", "#panel-wittenbauer .graph path.js-line")])
def test_preview_on_a_phone(family_page, scene, variant, slider, panel, ready):
    """On a phone the plots are below the controls: the slider and the mark are in view during the drag, and
    a plot scrolled into view while the slider is held shows the preview."""
    page = family_page
    page.set_viewport_size({"width": 390, "height": 844})
    page.goto(f"/scenes/{scene}?lang=ru&variant={variant}")
    page.wait_for_selector(ready, state="attached")
    page.wait_for_load_state("networkidle")
    x, y = grab(page, f"#slider-{slider}")
    drag_through(page, x, y, [0.3, 0.45])
    assert preview_shown(page)
    texts = interface_texts("ru")                                    # drawn from the coarse family, or the full one
    assert page.inner_text(".preview-note") in (texts["preview_coarse"], texts["preview"])
    box = page.locator(".preview-note").bounding_box()               # the mark is in view beside the slider
    assert 0 <= box["x"] and box["x"] + box["width"] <= 390 and 0 <= box["y"] and box["y"] + box["height"] <= 844
    sheet, title = page.locator(".controls-sheet").bounding_box(), page.locator(".site-header").bounding_box()
    assert box["y"] + box["height"] <= sheet["y"]                    # above the controls sheet, not under it
    assert box["y"] >= title["y"] + title["height"]                  # and not over the site's title
    page.screenshot(path=f"test-artifacts/family_preview_{scene}_phone_ru.png")
    page.locator(f"#panel-{panel}").scroll_into_view_if_needed()
    page.wait_for_function(f"id => {GRAPH}?.data?.length > 0", arg=panel)
    assert preview_shown(page)
    screenshot(page, f"family_preview_{scene}_phone_ru_full")
    page.mouse.up()
    assert page.problems == []


def test_interpolation_rule_of_the_page(family_page):
    """The page's rule (web/static/js/common/model/family_model.js) against the contract's rule worked by hand, and on a
    family with cubic intervals against the server's rule (server/families/family.py interpolate_family): a cubic
    through 4 members reproduces x³ exactly, and numbers one of the 4 members lacks (null, another kind of
    object, an array of another length) are linear."""
    page = family_page
    page.goto("/scenes/transfer-functions?lang=en")
    family = {"values": [1, 2, 4], "log": False, "answers": [
        {"x": 1.0, "y": [0, 10, None], "s": "one", "n": [1, 2], "warnings": ["a"], "numerics": {"steps": 10},
         "joints": {"A": [[0, 0], [1, 1]]}, "special": [{"kind": "dead", "phi": 0.0}, {"kind": "max", "phi": 2.0}]},
        {"x": 3.0, "y": [2, 20, 5], "s": "two", "n": [1, 2, 3], "warnings": ["b"], "numerics": {"steps": 20},
         "joints": {"A": [[2, 2], [3, 5]]}, "special": [{"kind": "dead", "phi": 1.0}, {"kind": "min", "phi": 3.0}]},
        None]}
    from server.families.family import interpolate_family                  # the server checks with the same rule
    result = page.evaluate("""async ([family, log]) => {
        const src = document.querySelector('script[type=module][src*="_scene.js"]').src;
        const { interpolate } = await import(new URL("../common/model/family_model.js", src));
        const at = (v, f = family) => interpolate(f, v);
        const [cubic, cubicValues] = [CUBIC, CUBIC_VALUES];
        return { quarter: at(1.25), near: at(1.75), member: at(2), refused: at(3), outside: at(0.5),
                 first: at(1), log: interpolate({ ...family, values: [1, 4, 16], log: true }, 2),
                 cubic: cubicValues.map((v) => interpolate(cubic, v)),
                 cubicLog: cubicValues.map((v) => interpolate({ ...cubic, log: true }, v)) };
    }""".replace("CUBIC_VALUES", json.dumps(CUBIC_VALUES)).replace("CUBIC", json.dumps(cubic_family())), [family, True])
    cubic = cubic_family()
    for name, log in (("cubic", False), ("cubicLog", True)):
        for value, ours in zip(CUBIC_VALUES, result[name]):
            theirs = interpolate_family(cubic["values"], cubic["answers"], value, log, cubic["orders"])
            assert json.dumps(ours) == json.dumps(theirs, allow_nan=False) or _close(ours, theirs), (name, value)
    x = CUBIC_VALUES[0]                                            # inside the first (cubic) interval
    assert result["cubic"][0]["z"] == pytest.approx(x ** 3, rel=1e-12) == result["cubic"][0]["y"][1]
    assert result["cubic"][0]["y"][2] == pytest.approx((2 - x) * 1 + (x - 1) * 2 ** 2)   # null at member 3: linear
    assert result["cubic"][0]["special"][0]["phi"] == pytest.approx((2 - x) * 1 + (x - 1) * 8)  # another kind there
    quarter = result["quarter"]                                    # w = 0.25: (1 − w)·a + w·b
    assert quarter["x"] == 1.5 and quarter["y"] == [0.5, 12.5, None]
    assert quarter["s"] == "one" and quarter["n"] == [1, 2]        # nearer member's leaf
    assert quarter["warnings"] == ["a"] and quarter["numerics"] == {"steps": 10}
    assert quarter["joints"] == {"A": [[0.5, 0.5], [1.5, 2]]}
    # objects of one kind are one quantity; another kind at the same index is the nearer member's object
    assert quarter["special"] == [{"kind": "dead", "phi": 0.25}, {"kind": "max", "phi": 2.0}]
    assert result["near"]["special"][1] == {"kind": "min", "phi": 3.0}
    for value, key in ((1.25, "quarter"), (1.75, "near")):
        assert interpolate_family(family["values"][:2], family["answers"][:2], value, False)["special"] == \
            result[key]["special"]
    near = result["near"]                                          # w = 0.75
    assert near["x"] == 2.5 and near["s"] == "two" and near["n"] == [1, 2, 3] and near["warnings"] == ["b"]
    assert result["member"] == family["answers"][1]
    assert result["refused"] is None and result["outside"] is None
    assert result["first"] == family["answers"][0]
    assert result["log"]["x"] == pytest.approx(1 + 2 * math.log(2) / math.log(4))   # halfway in log v
    assert page.problems == []


CUBIC_VALUES = [1.5, 2.6, 4.5, 5.5, 6.9]


def cubic_family() -> dict:
    """5 members, intervals cubic, cubic, linear, cubic: x³ in numbers and arrays, a null at one member, a
    special position whose kind changes at one member, an array of another length at the last."""
    values = [1.0, 2.0, 4.0, 5.0, 7.0]
    answers = [{"z": x ** 3, "y": [x, x ** 3, None if x == 4.0 else x ** 2], "s": "t",
                "special": [{"kind": "dead" if x != 5.0 else "max", "phi": x ** 3}],
                "n": [x ** 2, x] if x != 7.0 else [x ** 2, x, 0.5]} for x in values]
    return {"values": values, "log": False, "orders": [3, 3, 1, 3], "answers": answers}


def _close(a, b) -> bool:
    if isinstance(a, dict):
        return isinstance(b, dict) and a.keys() == b.keys() and all(_close(a[k], b[k]) for k in a)
    if isinstance(a, list):
        return isinstance(b, list) and len(a) == len(b) and all(_close(x, y) for x, y in zip(a, b))
    if isinstance(a, float) or isinstance(b, float):
        return a == pytest.approx(b, rel=1e-12, abs=1e-12)
    return a == b


def test_curves_moved_in_place_lie_where_plotly_draws_them(family_page):
    """family_plot.js redraws a preview's lines through Plotly's laid-out axes (cartesian and polar): given the
    figure Plotly has just drawn, its paths start and end where Plotly's do (Plotly may drop collinear points
    in between) and pass through Plotly's points, to a tenth of a pixel."""
    page = family_page
    page.goto("/scenes/equation-of-motion?lang=en&variant=linear")
    for panel in ("portrait", "omega_phi"):
        page.wait_for_function(f"id => {GRAPH}?.data?.length > 0", arg=panel)
    result = page.evaluate("""async () => {
        const src = document.querySelector('script[type=module][src*="_scene.js"]').src;
        const { moveCurves } = await import(new URL("../common/view/family_plot.js", src));
        const paths = (graph) => [...graph.querySelectorAll(".scatterlayer path.js-line")].map((p) => p.getAttribute("d"));
        const out = {};
        for (const id of ["portrait", "omega_phi"]) {
          const graph = document.querySelector(`#panel-${id} .graph`);
          const plotly = paths(graph);
          const moved = moveCurves(graph, graph.data);
          out[id] = { moved, plotly, ours: paths(graph) };
        }
        return out;
    }""")
    points = lambda d: [tuple(map(float, p.split(","))) for p in d.replace("M", "L").split("L") if p]
    for panel, drawn in result.items():
        assert drawn["moved"], panel
        assert len(drawn["ours"]) == len(drawn["plotly"]) > 0
        for ours, plotly in zip(drawn["ours"], drawn["plotly"]):
            ours, plotly = points(ours), points(plotly)
            assert ours[0] == pytest.approx(plotly[0], abs=0.1) and ours[-1] == pytest.approx(plotly[-1], abs=0.1), panel
            ours_set = {(round(x), round(y)) for x, y in ours}
            assert all((round(x), round(y)) in ours_set for x, y in plotly[:: max(1, len(plotly) // 50)]), panel
    assert page.problems == []


def test_markers_and_labels_moved_in_place_lie_where_plotly_draws_them(family_page):
    """On Wittenbauer's diagram (curve, tangents reaching past the axes, the touch points' markers, the segment ab
    with its markers and labels a, b) family_plot.js places every marker and label where Plotly placed it, given
    the figure Plotly has just drawn, to a tenth of a pixel; the lines as in the test above."""
    page = family_page
    page.goto("/scenes/flywheel?lang=en&variant=rig")
    page.wait_for_function("() => document.querySelector('#panel-wittenbauer .graph')?._fullData?.length > 0")
    result = page.evaluate("""async () => {
        const src = document.querySelector('script[type=module][src*="_scene.js"]').src;
        const { moveCurves } = await import(new URL("../common/view/family_plot.js", src));
        const graph = document.querySelector("#panel-wittenbauer .graph");
        const placed = () => ({
          markers: [...graph.querySelectorAll(".scatterlayer .points path.point")].map((p) => p.getAttribute("transform")),
          texts: [...graph.querySelectorAll(".scatterlayer .text text")].map((t) => [t.getAttribute("x"), t.getAttribute("y")]),
          lines: [...graph.querySelectorAll(".scatterlayer path.js-line")].length });
        const plotly = placed();
        return { plotly, moved: moveCurves(graph, graph.data), ours: placed() };
    }""")
    assert result["moved"]
    plotly, ours = result["plotly"], result["ours"]
    assert len(plotly["markers"]) >= 4 and len(plotly["texts"]) >= 2 and ours["lines"] == plotly["lines"] >= 3
    numbers = lambda transform: [float(v) for v in transform.replace("translate(", "").rstrip(")").split(",")]
    for mine, theirs in zip(ours["markers"], plotly["markers"], strict=True):
        assert numbers(mine) == pytest.approx(numbers(theirs), abs=0.1)
    for mine, theirs in zip(ours["texts"], plotly["texts"], strict=True):
        assert [float(v) for v in mine] == pytest.approx([float(v) for v in theirs], abs=0.1)
    assert page.problems == []


# ---- what the preview draws: fields, packed families, and the curves drawn against the exact answers ----------

SCENE_SLIDERS = [   # every scene, the first variant with sliders and its first slider, and a panel drawn in a preview
    ("transfer-functions", "slider_crank", "lambda", "#panel-u31 .graph path.js-line"),
    ("resisting-moment", "sine", "f", "#panel-moment .graph path.js-line"),
    ("reduced-inertia", "slider_crank", "lambda", "#panel-inertia .graph path.js-line"),
    ("equation-of-motion", "linear", "lambda", "#panel-omega_phi .graph path.js-line"),
    ("flywheel", "rig", "delta", "#panel-wittenbauer .graph path.js-line"),
    ("elastic-transmission", "belt", "c", "#panel-speeds .graph path.js-line"),
    ("elastic-linkage", "slider_crank", "e1", "#panel-stiffness .graph path.js-line"),
    ("elastic-four-bar", "dialog", "b", "#panel-motor .graph path.js-line"),
    ("forces-friction", "central", "lambda", "#panel-free_body svg .forces"),
    ("wear", "engine", "hours", "#panel-cylinder .graph path.js-line"),
    ("angular-acceleration", "crank_slider", "lam", "#panel-gear_train svg .moving"),
]


def page_fields(page, variant: str) -> list[str]:
    """What family_fields.js gives for the page's scene and variant (the scene as the page has it)."""
    return page.evaluate("""async (variantId) => {
        const src = document.querySelector('script[type=module][src*="_scene.js"]').src;
        const { previewFields } = await import(new URL("../common/model/family_fields.js", src));
        const scene = JSON.parse(document.getElementById("scene-data").textContent);
        return previewFields(scene, scene.variants.find((v) => v.id === variantId));
    }""", variant)


@pytest.mark.parametrize("scene, variant, slider, ready", SCENE_SLIDERS, ids=[s[0] for s in SCENE_SLIDERS])
def test_every_scene_asks_for_what_its_panels_draw_and_previews_the_drag(family_page, app_url, scene, variant,
                                                                          slider, ready):
    """The family request names the variant's drawn leaves (family_fields.js) and asks for the family packed;
    the drag is drawn from it as a marked preview, without a request of the endpoint, and nothing is logged."""
    if not takes_stages(app_url):
        pytest.skip("the app has no /api/v1/family of its own")
    page = family_page
    page.goto(f"/scenes/{scene}?lang=en&variant={variant}")
    page.wait_for_selector(ready, state="attached", timeout=60_000)
    page.wait_for_load_state("networkidle")
    before = len(page.sent)
    x, y = grab(page, f"#slider-{slider}")
    family = sent(page, "family", before)[0]
    fields = page_fields(page, variant)
    assert family["fields"] == fields and family["packed"] is True and len(fields) >= 2
    endpoint = family["endpoint"]
    start = fraction(page, f"#slider-{slider}")
    step = 0.07 if start < 0.5 else -0.07
    drag_through(page, x, y, [start + step, start + 2 * step])
    assert preview_shown(page)
    assert not sent(page, endpoint, before)                          # the drag asked nothing
    release_and_wait_for_exact(page, endpoint)
    assert page.problems == []


def drawn_trace(page, panel: str) -> dict:
    """The first curve of a plot panel as drawn now, in data units: the points of its SVG path through the
    laid-out axes when the preview moved it in place (as many points as the trace), else the figure Plotly was
    given (the preview redrawn with Plotly.react, gd.data)."""
    return page.evaluate("""(id) => {
        const graph = document.querySelector(`#panel-${id} .graph`);
        const d = graph.querySelector(".scatterlayer path.js-line").getAttribute("d");
        const trace = graph._fullData[0];
        const [xa, ya] = [graph._fullLayout.xaxis, graph._fullLayout[`yaxis${trace.yaxis.slice(1)}`]];
        const pixels = d.replace(/M/g, "L").split("L").filter(Boolean).map((p) => p.split(",").map(Number));
        return { moved: pixels.length === graph.data[0].x.length,
                 x: pixels.map(([px]) => xa.p2c(px)), y: pixels.map(([, py]) => ya.p2c(py)),
                 figure: { x: graph.data[0].x, y: graph.data[0].y }, pixel: Math.abs(ya.p2c(1) - ya.p2c(0)) };
    }""", panel)


@pytest.mark.parametrize("scene, variant, slider, panel, x_path, y_path", [
    ("transfer-functions", "slider_crank", "lambda", "u31", "phi", "outputs.u31"),
    ("elastic-linkage", "slider_crank", "e1", "twist", "t", "twist")])
def test_the_curve_drawn_during_a_drag_is_the_exact_answer_within_the_tolerance(family_page, app_url, scene, variant,
                                                                                slider, panel, x_path, y_path):
    """Once the full family has arrived, a curve drawn in a preview at a slider value between members lies within
    0.5 % of that quantity's span over the family (the contract; plus half a unit of its 5th significant digit)
    of the endpoint's exact answer at that value, asked separately at full precision; a point moved in place is
    read back through Plotly's axes (its pixels are written to 0.01 px, at most a hundredth of a pixel's worth)."""
    if not takes_stages(app_url):
        pytest.skip("the app has no /api/v1/family of its own")
    from server.families import family as contract
    page = family_page
    page.goto(f"/scenes/{scene}?lang=en&variant={variant}")
    page.wait_for_selector(f"#panel-{panel} .graph path.js-line", state="attached", timeout=60_000)
    page.wait_for_load_state("networkidle")
    before = len(page.sent)
    x, y = grab(page, f"#slider-{slider}")
    page.wait_for_function("() => performance.getEntriesByName('family-full-arrived').length > 0", timeout=120_000)
    asked = sent(page, "family", before)[-1]
    page.locator(f"#panel-{panel}").scroll_into_view_if_needed()
    x, y = thumb(page, f"#slider-{slider}")
    start = fraction(page, f"#slider-{slider}")
    drag_through(page, x, y, [start + 0.1, start + 0.237])
    drawn = drawn_trace(page, panel)
    value = page.evaluate("""async ([position, slider]) => {        // the thumb's value, as the page reads it
        const src = document.querySelector('script[type=module][src*="_scene.js"]').src;
        const { sliderScale } = await import(new URL("../common/model/slider_scale.js", src));
        return sliderScale(slider).value(position);
    }""", [float(page.input_value(f"#slider-{slider}")), {k: asked[k] for k in ("min", "max", "log")}])

    full = httpx.post(f"{app_url}/api/v1/family", params={"lang": "en"}, json=asked, timeout=300).json()
    shared = contract.unpacked(full["shared"])
    members = [None if a is None else contract.as_tree(contract.merged(shared, contract.unpacked(a)), sent=False)
               for a in full["answers"]]
    assert full["interpolation_error"] <= 0.005 and value not in full["values"]
    span = contract.spans(members)[tuple(y_path.split("."))]
    body = copy.deepcopy(asked["request"])
    for vary in asked["vary"]:
        set_path(body, vary["path"], value * vary["factor"])
    reply = httpx.post(f"{app_url}/api/v1/{asked['endpoint']}", params={"precision": "full"}, json=body, timeout=120)
    assert reply.status_code == 200, reply.text[:500]
    exact = reply.json()
    leaf = lambda path: contract._leaf(exact, tuple(path.split(".")))
    xs, ys = leaf(x_path), leaf(y_path)
    xs = [math.degrees(v) for v in xs] if x_path == "phi" else xs
    if drawn["moved"]:
        shown_x, shown_y, slack = drawn["x"], drawn["y"], drawn["pixel"] / 100
    else:
        shown_x, shown_y, slack = drawn["figure"]["x"], drawn["figure"]["y"], 0.0
    assert len(shown_y) == len(ys)
    assert max(abs(a - b) for a, b in zip(shown_x, xs)) <= 1e-3 * (max(xs) - min(xs))
    bound = [0.005 * span + 5e-5 * abs(v) + slack for v in ys]
    worst = max(abs(a - b) - limit for a, b, limit in zip(shown_y, ys, bound))
    assert worst <= 0, (value, worst)
    assert any(abs(a - b) > 0 for a, b in zip(shown_y, ys)) or drawn["moved"]     # a preview, not the exact one
    assert preview_shown(page)
    page.mouse.up()
    assert page.problems == []


def test_the_page_unpacks_a_packed_family_as_the_server_does(family_page, app_url):
    """family_model.js received() against server/families/family.py unpacked + merged, on a packed family with
    shared arrays, nulls and two-column arrays (the forces' points and reactions)."""
    if not takes_stages(app_url):
        pytest.skip("the app has no /api/v1/family of its own")
    from server.families import family as contract
    page = family_page
    page.goto("/scenes/forces-friction?lang=en&variant=central")
    page.wait_for_selector("#panel-free_body svg .forces", state="attached", timeout=60_000)
    page.wait_for_load_state("networkidle")
    scene_body = next(b for name, b in page.sent if name == "forces")        # the page's exact request
    packed = httpx.post(f"{app_url}/api/v1/family", params={"lang": "en"}, timeout=300, json={
        "endpoint": "forces", "request": scene_body, "vary": [{"path": "params.l2", "factor": scene_body["params"]["l1"]}],
        "min": 2.5, "max": 6.0, "stage": "coarse", "fields": page_fields(page, "central"), "packed": True}).json()
    assert packed["shared"]
    page_answers = page.evaluate("""async (family) => {
        const src = document.querySelector('script[type=module][src*="_scene.js"]').src;
        const { received } = await import(new URL("../common/model/family_model.js", src));
        return received(family).answers;
    }""", packed)
    shared = contract.unpacked(packed["shared"])
    for ours, theirs in zip(page_answers, packed["answers"]):
        mine = contract.flatten(contract.as_tree(json.loads(json.dumps(ours), parse_int=float), sent=False))
        server = contract.flatten(contract.as_tree(contract.merged(shared, contract.unpacked(theirs)), sent=False))
        assert mine.keys() == server.keys()
        for path, leaf in server.items():
            assert np.allclose(mine[path], leaf, rtol=1e-12, atol=0, equal_nan=True), path
    assert page.problems == []
