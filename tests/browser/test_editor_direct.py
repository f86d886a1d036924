"""Direct manipulation in the mechanism editor (/editor), in Chromium: the six-bar "crank, RRR, then RRP to a slider"
built from an empty editor in at most 12 actions (every click counted), its slider's joint dragged (the rod's
length in its field and the plans change; the length read back against |BC| of the joints the page shows), undone
and redone; the view zoomed by the buttons and the wheel and panned by dragging the background (the world point
under the pointer kept, as the view's data say), the pointer's coordinates readout equal to the point a click
there places; the dynamics scenes opened from the editor with the mechanism in their address. A frame joint
dragged until the crank no longer turns and then past where the group closes: the drawing stops at the last
assembling geometry (marked while dragging, kept on release), the dynamics links disabled, no "{" in any visible
text. The same six-bar built with the keyboard only (typed coordinates, Tab and Enter, arrows and Escape). On a
390 × 844 and an 820 × 1180 touch screen a joint dragged by a finger and the drawing pinched and panned with two,
the controls on the screen. Screenshots in ru, en and at phone and tablet size.
"""
from __future__ import annotations

import json
import math
import re
from urllib.parse import parse_qs, urlparse

import pytest

from server.lessons.scenes import scene_documents
from conftest import PHONE, interface_texts, screenshot
from test_dynamics import wait_for_panels
from test_editor import REFUSED, act, answers, number, plans_ready, settled

pytestmark = pytest.mark.browser

# the six-bar: crank OA about O, an RRR from A to a support at (0.35, 0), an RRP from its inner joint to a slider
# on a guide along x through (0.55, 0.1); every point on the 5 mm grid a click is written to (model/linkage.js)
PIVOT, PIN, SUPPORT, ROCKER_PIN, SLIDER = (0, 0), (0.1, 0), (0.35, 0), (0.25, 0.2), (0.55, 0.1)
LINKAGE = """() => { const m = new URLSearchParams(location.search).get("m").replace(/-/g, "+").replace(/_/g, "/");
    return JSON.parse(new TextDecoder().decode(Uint8Array.from(atob(m), (c) => c.charCodeAt(0)))); }"""
CLIENT = """([x, y]) => { const svg = document.querySelector("#editor-drawing svg");
    const [x0, y0, k] = svg.dataset.view.split(" ").map(Number);
    const p = svg.createSVGPoint(); p.x = (x - x0) * k; p.y = (y0 - y) * k;
    const q = p.matrixTransform(svg.getScreenCTM()); return [q.x, q.y]; }"""
VISIBLE_TEXT = """() => { const walker = document.createTreeWalker(document.body, NodeFilter.SHOW_TEXT);
    const texts = [];
    for (let node = walker.nextNode(); node; node = walker.nextNode()) {
        const parent = node.parentElement;
        if (parent && !parent.closest("script, style, option") && parent.checkVisibility()) texts.push(node.textContent);
    }
    return texts.join(" "); }"""
ROD = '[data-group="1"] > label.field input[type="text"]'       # the RRP group's length |BC|
WRITTEN = 1e-4            # m: the data are written to 0.1 mm
TABLET = {"width": 820, "height": 1180}


def rod(page) -> float:
    """The RRP's length |BC| as its field shows it."""
    return number(page.locator(ROD).first.input_value())


def linkage(page) -> dict:
    return page.evaluate(LINKAGE)


def client(page, x: float, y: float) -> tuple[float, float]:
    """Where the world point (x, y) (m) is on the screen (CSS px), by the view the drawing writes (data-view)."""
    return tuple(page.evaluate(CLIENT, [x, y]))


def view(page) -> tuple[float, float, float]:
    return tuple(map(float, page.get_attribute("#editor-drawing svg", "data-view").split()))


def world(v: tuple[float, float, float], unit: float, px: tuple[float, float]) -> tuple[float, float]:
    """The world point at px CSS px from the drawing's top left corner: x = x₀ + X/k, y = y₀ − Y/k."""
    x0, y0, k = v
    return x0 + px[0] * unit / k, y0 - px[1] * unit / k


def drawn(page, name: str) -> tuple[float, float]:
    """A joint's drawn place in metres: its circle's centre mapped back through the view."""
    x0, y0, k = view(page)
    cx, cy = (float(page.get_attribute(f'#editor-drawing [data-joint="{name}"]', a)) for a in ("cx", "cy"))
    return x0 + cx / k, y0 - cy / k


class Actions:
    """The student's actions, counted: a click on a control or on the drawing at a world point."""

    def __init__(self, page):
        self.page, self.count = page, 0

    def click(self, selector: str) -> None:
        self.count += 1
        self.page.click(selector)

    def at(self, x: float, y: float, settle: bool = False) -> None:
        self.count += 1
        go = lambda: self.page.mouse.click(*client(self.page, x, y))
        act(self.page, go) if settle else go()


def build_six_bar(actions: Actions) -> dict:
    """Crank, RRR, RRP with the mouse: each new support and guide made by clicking the plane where a tool wants
    one. Gives the mechanism as the address holds it."""
    page = actions.page
    actions.click('[data-mode="crank"]')
    actions.at(*PIVOT, settle=True)            # the crank's support O, a new frame joint
    actions.at(*PIN, settle=True)              # its pin A: |OA| = 0.1 m
    actions.click('[data-mode="RRR"]')
    actions.at(*PIN)                           # on A
    actions.at(*SUPPORT, settle=True)          # a new support there
    actions.at(*ROCKER_PIN, settle=True)       # the inner joint: |AB| = 0.25 m, |BO₁| = 0.224 m
    actions.click('[data-mode="RRP"]')
    actions.at(*ROCKER_PIN)                    # on the RRR's inner joint
    actions.at(*SLIDER, settle=True)           # a new guide along x through there
    actions.at(*SLIDER, settle=True)           # the slider's joint on it
    assert page.get_attribute("#editor-drawing", "data-state") == "ready"
    return linkage(page)


def six_bar_address(lang: str) -> str:
    """The six-bar as its address (what build_six_bar gives, written out)."""
    import base64
    six = {"frame": {"joints": {"O": [0, 0], "O1": [0.35, 0]}, "guides": {"g1": {"through": [0.55, 0.1], "angle": 0}}},
           "input": {"kind": "crank", "link": 1, "pivot": "O", "joint": "A", "length": 0.1, "angle0": 0, "sense": 1},
           "groups": [{"kind": "RRR", "links": [2, 3], "outer": ["A", "O1"], "inner": "B", "lengths": [0.25, 0.224],
                       "branch": 1},
                      {"kind": "RRP", "links": [4, 5], "outer": ["B"], "guide": "g1", "inner": "C", "length": 0.316,
                       "branch": 1}]}
    return f"/editor?lang={lang}&m=" + base64.urlsafe_b64encode(json.dumps(six).encode()).decode().rstrip("=")


def drag(page, start: tuple[float, float], to: tuple[float, float], steps: int = 12, release: bool = True) -> None:
    """Press at the world point start, move to `to` in steps a frame or two apart, and let go (or not)."""
    page.mouse.move(*client(page, *start))
    page.mouse.down()
    for i in range(1, steps + 1):
        f = i / steps
        page.mouse.move(*client(page, start[0] + (to[0] - start[0]) * f, start[1] + (to[1] - start[1]) * f))
        page.wait_for_timeout(40)
    if release:
        page.mouse.up()


def test_a_six_bar_in_twelve_actions_dragged_undone_zoomed_and_opened_in_dynamics(browser_page):
    page = browser_page
    page.goto("/editor?lang=ru")
    page.wait_for_function("() => document.querySelector('#editor-drawing')?.dataset.answers !== undefined")
    view_before = view(page)
    actions = Actions(page)
    six = build_six_bar(actions)
    assert actions.count <= 12, f"{actions.count} actions"
    assert view(page) == view_before, "adding elements moved the view"
    assert [g["kind"] for g in six["groups"]] == ["RRR", "RRP"]
    assert page.inner_text("#editor-mobility").endswith("= 1")
    rrr, rrp = six["groups"]
    assert rrr["lengths"] == [0.25, 0.224]                     # |AB|, |BO₁| as clicked, to the 1 mm written
    b, c = rrr["inner"], rrp["inner"]
    built = rrp["length"]
    assert built == pytest.approx(math.dist(drawn(page, b), SLIDER), abs=5e-4)    # |BC| from B as assembled
    plans_ready(page)
    plans = page.inner_text("#editor-plans")
    screenshot(page, "editor_direct_ru")

    before = answers(page)                     # the slider's joint dragged 50 mm along its guide
    drag(page, SLIDER, (SLIDER[0] + 0.05, SLIDER[1] + 0.03))
    settled(page, before)
    plans_ready(page)
    dragged = linkage(page)["groups"][1]["length"]
    assert rod(page) == pytest.approx(dragged, abs=5e-4)     # the field, 3 decimals written
    bx, by = drawn(page, b)
    cx, cy = drawn(page, c)
    assert cy == pytest.approx(SLIDER[1], abs=WRITTEN)                 # C stayed on its guide (the 0.03 m off dropped)
    assert cx == pytest.approx(SLIDER[0] + 0.05, abs=0.003)            # where the pointer left it, to a pixel or two
    assert dragged == pytest.approx(math.hypot(cx - bx, cy - by), abs=WRITTEN)   # |BC| of the drawn joints
    assert page.inner_text("#editor-plans") != plans, "the plans did not follow the drag"

    act(page, lambda: page.click("#editor-undo"))              # the drag is one step back …
    assert linkage(page)["groups"][1]["length"] == built and rod(page) == pytest.approx(built)
    act(page, lambda: page.click("#editor-redo"))              # … and forth
    assert linkage(page)["groups"][1]["length"] == dragged

    x0, y0, k = view(page)
    page.click("#editor-zoom-in")
    assert view(page)[2] == pytest.approx(1.5 * k, rel=1e-12)
    page.locator("#editor-drawing svg").scroll_into_view_if_needed()
    box = page.locator("#editor-drawing svg").bounding_box()
    unit = 800 / box["width"]                                  # drawing units per CSS px
    pointer = (round(box["x"] + box["width"] * 0.12), round(box["y"] + box["height"] * 0.1))   # an empty corner,
    corner = (pointer[0] - box["x"], pointer[1] - box["y"])    # on whole pixels as the mouse events have it
    page.mouse.move(*pointer)
    under = world(view(page), unit, corner)
    page.mouse.wheel(0, -240)                                  # zoomed in about the pointer
    page.wait_for_function("k => Number(document.querySelector('#editor-drawing svg').dataset.view.split(' ')[2]) > k",
                           arg=1.5 * k)
    # to a thousandth of a pixel: the SVG's screen matrix is single precision
    assert world(view(page), unit, corner) == pytest.approx(under, abs=1e-3 * unit / view(page)[2])
    panned_from, mechanism = view(page), linkage(page)
    page.mouse.down()                                          # the background dragged: the view panned
    page.mouse.move(pointer[0] + 60, pointer[1] + 40, steps=4)
    page.mouse.up()
    x0, y0, k = view(page)
    assert (x0, y0) == pytest.approx((panned_from[0] - 60 * unit / k, panned_from[1] + 40 * unit / k),
                                     abs=1e-3 * unit / k)
    assert linkage(page) == mechanism                          # (a pan is no edit)

    page.click("#editor-snap")                                 # on the grid: the readout says where a click places
    page.click('[data-mode="joint"]')
    page.locator("#editor-drawing svg").scroll_into_view_if_needed()
    box = page.locator("#editor-drawing svg").bounding_box()
    spot = (round(box["x"] + box["width"] * 0.2), round(box["y"] + box["height"] * 0.8))
    page.mouse.move(*spot)
    shown = tuple(float(page.get_attribute("#editor-pointer", a)) for a in ("data-x", "data-y"))
    assert page.inner_text("#editor-pointer").startswith("x = ")
    act(page, lambda: page.mouse.click(*spot))
    placed = [p for name, p in linkage(page)["frame"]["joints"].items() if name not in six["frame"]["joints"]]
    assert placed == [list(shown)], f"placed at {placed}, the readout said {shown}"
    act(page, lambda: page.click("#editor-undo"))

    page.wait_for_function("() => document.querySelector('#editor-open-dynamics a[data-scene]') !== null")
    scene_link = page.locator("#editor-open-dynamics a[data-scene]").first
    scene_id = scene_link.get_attribute("data-scene")
    shown_linkage = linkage(page)
    with page.expect_navigation(url=re.compile(r"/scenes/")):       # not the editor's own address rewritten meanwhile
        scene_link.click()
    scene = next(s for s in scene_documents().values() if s["id"] == scene_id)
    wait_for_panels(page, scene, next(v for v in scene["variants"] if v["id"] == "own"))
    assert page.evaluate(LINKAGE) == shown_linkage             # the scene has the mechanism in its address
    assert [p for p in page.problems if not REFUSED.search(p)] == []


def test_a_joint_dragged_past_where_the_mechanism_closes_stops_there(browser_page):
    page = browser_page
    texts = interface_texts("ru")
    page.goto(six_bar_address("ru"))
    page.wait_for_function("() => document.querySelector('#editor-drawing')?.dataset.state === 'ready'")
    page.wait_for_function("() => document.querySelector('#editor-open-dynamics a[data-scene]') !== null")
    # O₁ to the right: the RRR closes while |O₁A| ≤ |AB| + |BO₁| = 0.474 m; at φ = 180° |O₁A| = x + 0.1, so beyond
    # x = 0.374 m the crank no longer turns fully, and at φ = 0 (shown) it closes while x ≤ 0.574 m; the pointer rests at 0.54 m (answered: there it
    # assembles) and goes on to 0.8 m
    before = answers(page)
    drag(page, SUPPORT, (0.54, 0), steps=20, release=False)
    page.wait_for_function("""() => {        // O₁ drawn at 0.54 m: this geometry answered, and it assembles
        const svg = document.querySelector("#editor-drawing svg"), [x0, , k] = svg.dataset.view.split(" ").map(Number);
        const o = svg.querySelector('[data-joint="O1"]');
        return o && Math.abs(x0 + o.cx.baseVal.value / k - 0.54) < 1e-3 && !svg.querySelector(".stop-ring"); }""")
    for i in range(1, 27):
        page.mouse.move(*client(page, 0.54 + 0.01 * i, 0))
        page.wait_for_timeout(40)
    page.wait_for_selector("#editor-drawing .stop-ring")
    assert page.inner_text("#editor-prompt") == texts["editor_drag_stopped"]
    x, _ = drawn(page, "O1")
    assert 0.5 < x <= 0.574 + WRITTEN, f"O₁ drawn at x = {x}"
    page.mouse.up()
    settled(page, before)
    kept = linkage(page)["frame"]["joints"]["O1"]
    assert 0.5 < kept[0] <= 0.574 + WRITTEN and kept[1] == 0, kept
    assert page.locator("#editor-drawing .stop-ring").count() == 0
    assert page.locator("#editor-open-dynamics a[data-scene]").count() == 0
    assert page.locator("#editor-open-dynamics .disabled").count() > 0
    assert page.get_attribute("#editor-course-project", "aria-disabled") == "true"
    page.wait_for_function("() => document.querySelector('#editor-readiness').dataset.state === 'partial'")
    assert texts["editor_ready_no_full_turn"] in page.inner_text("#editor-readiness")   # the readiness line says so
    text = page.evaluate(VISIBLE_TEXT)
    assert "{" not in text, re.findall(r".{30}\{.{30}", text)
    screenshot(page, "editor_direct_stopped_ru")
    assert [p for p in page.problems if not REFUSED.search(p)] == []


def test_the_links_to_the_scenes_stay_under_the_pointer_and_the_focus_as_the_mechanism_changes(browser_page):
    """Every edit and answer gives the links to the dynamics scenes new addresses: the links are rewritten in
    place, so a link pressed as an answer arrives is still the one released (it was replaced before, and the click
    was lost), and one focused from the keyboard keeps the focus through an undo (Ctrl+Z) and points at the
    mechanism now shown."""
    page = browser_page
    page.goto(six_bar_address("ru"))
    page.wait_for_function("() => document.querySelector('#editor-drawing')?.dataset.state === 'ready'")
    page.wait_for_function("() => document.querySelector('#editor-open-dynamics a[data-scene]') !== null")
    before = answers(page)
    drag(page, SUPPORT, (0.36, 0))                             # O₁ 10 mm to the right: the crank still turns
    settled(page, before)
    page.focus("#editor-open-dynamics a[data-scene]")
    moved = page.evaluate("() => { window.focusedLink = document.activeElement; return focusedLink.href; }")
    act(page, lambda: page.keyboard.press("Control+z"))
    assert linkage(page)["frame"]["joints"]["O1"] == [0.35, 0]
    kept, focused, href = page.evaluate("() => [focusedLink.isConnected, document.activeElement === focusedLink, "
                                        "focusedLink.href]")
    assert kept and focused
    assert href != moved and parse_qs(urlparse(href).query)["m"] == parse_qs(urlparse(page.url).query)["m"]
    assert [p for p in page.problems if not REFUSED.search(p)] == []


def tab_to(page, selector: str, back: bool = False, presses: int = 250) -> None:
    """Press Tab (Shift+Tab) until the focus is on `selector`."""
    for _ in range(presses):
        if page.evaluate("s => document.activeElement?.matches(s) ?? false", selector):
            return
        page.keyboard.press("Shift+Tab" if back else "Tab")
    raise AssertionError(f"{selector} not reached by the keyboard")


def test_the_six_bar_built_with_the_keyboard_only(browser_page):
    page = browser_page
    page.goto("/editor?lang=en")
    page.wait_for_function("() => document.querySelector('#editor-drawing')?.dataset.answers !== undefined")

    def tool(kind: str) -> None:
        tab_to(page, f'[data-mode="{kind}"]', back=True)
        page.keyboard.press("Enter")

    def typed(x: str, y: str, settle: bool = True) -> None:
        tab_to(page, "#editor-place-x")
        page.keyboard.press("Control+A")
        page.keyboard.type(x)
        page.keyboard.press("Tab")
        page.keyboard.press("Control+A")
        page.keyboard.type(y)
        (lambda go: act(page, go) if settle else go())(lambda: page.keyboard.press("Enter"))

    tool("crank")
    typed("0", "0")
    typed("0.1", "0")
    tool("RRR")
    page.keyboard.press("Escape")                              # Escape: the tool given up
    assert page.get_attribute('[data-mode="select"]', "aria-pressed") == "true"
    tool("RRR")
    typed("0.1", "0", settle=False)                            # on the crank's pin (typed where it is)
    typed("0.35", "0")
    typed("0.25", "0.2")
    tool("RRP")
    b = linkage(page)["groups"][0]["inner"]
    tab_to(page, f'#editor-drawing [data-joint="{b}"]')        # the RRR's joint picked in the drawing
    page.keyboard.press("Enter")
    typed("0.55", "0.1")
    typed("0.55", "0.1")
    six = linkage(page)
    assert [g["kind"] for g in six["groups"]] == ["RRR", "RRP"]
    assert six["groups"][0]["lengths"] == [0.25, 0.224]
    assert six["groups"][1]["length"] == pytest.approx(math.dist(drawn(page, b), SLIDER), abs=5e-4)
    assert page.inner_text("#editor-mobility").endswith("= 1")

    c = six["groups"][1]["inner"]                              # the slider's joint moved by the arrow keys
    tab_to(page, f'#editor-drawing [data-joint="{c}"]', back=True)
    step = float(page.get_attribute("#editor-drawing svg", "data-step"))
    cx, cy = drawn(page, c)
    act(page, lambda: page.keyboard.press("ArrowRight"))
    assert page.evaluate("() => document.activeElement.dataset.joint") == c    # the focus stays on it
    bx, by = drawn(page, six["groups"][0]["inner"])
    assert drawn(page, c) == pytest.approx((cx + step, cy), abs=WRITTEN)       # one grid step to the right
    assert linkage(page)["groups"][1]["length"] == pytest.approx(math.hypot(cx + step - bx, cy - by), abs=WRITTEN)
    screenshot(page, "editor_direct_keyboard_en")
    assert [p for p in page.problems if not REFUSED.search(p)] == []


def touch(cdp, kind: str, points: list[tuple[float, float]]) -> None:
    cdp.send("Input.dispatchTouchEvent", {"type": kind,
                                           "touchPoints": [{"x": x, "y": y, "id": i} for i, (x, y) in enumerate(points)]})


@pytest.mark.parametrize("screen", [PHONE, TABLET], ids=["phone", "tablet"])
def test_touch_drag_pinch_and_two_finger_pan_on_a_phone_and_a_tablet(chromium, app_url, screen):
    context = chromium.new_context(base_url=app_url, viewport=screen, has_touch=True, is_mobile=True,
                                   device_scale_factor=1)
    page = context.new_page()
    problems = []
    page.on("pageerror", lambda error: problems.append(str(error)))
    try:
        page.goto(six_bar_address("ru"))
        page.wait_for_function("() => document.querySelector('#editor-drawing')?.dataset.state === 'ready'")
        page.locator("#editor-drawing").scroll_into_view_if_needed()
        cdp = context.new_cdp_session(page)
        start = client(page, *SLIDER)                          # a finger drags the slider's joint along its guide
        end = client(page, SLIDER[0] - 0.05, SLIDER[1])
        before = answers(page)
        touch(cdp, "touchStart", [start])
        for i in range(1, 9):
            touch(cdp, "touchMove", [(start[0] + (end[0] - start[0]) * i / 8, start[1])])
            page.wait_for_timeout(40)
        touch(cdp, "touchEnd", [])
        settled(page, before)
        assert linkage(page)["groups"][1]["length"] < 0.316 - 0.03      # |BC| shorter by about the 50 mm dragged

        box = page.locator("#editor-drawing svg").bounding_box()
        unit = 800 / box["width"]
        mid = (box["x"] + box["width"] / 2, box["y"] + box["height"] / 2)
        x0, y0, k = view(page)
        under = world((x0, y0, k), unit, (box["width"] / 2, box["height"] / 2))
        touch(cdp, "touchStart", [(mid[0] - 30, mid[1]), (mid[0] + 30, mid[1])])
        for i in range(1, 7):                                  # fingers apart: 60 → 120 px, the midpoint still
            touch(cdp, "touchMove", [(mid[0] - 30 - 5 * i, mid[1]), (mid[0] + 30 + 5 * i, mid[1])])
        touch(cdp, "touchEnd", [])
        zoomed = view(page)
        assert zoomed[2] == pytest.approx(2 * k, rel=1e-6)
        assert world(zoomed, unit, (box["width"] / 2, box["height"] / 2)) == pytest.approx(under, abs=1e-3 * unit / k)
        touch(cdp, "touchStart", [(mid[0] - 30, mid[1]), (mid[0] + 30, mid[1])])
        for i in range(1, 5):                                  # two fingers together 40 px down: a pan
            touch(cdp, "touchMove", [(mid[0] - 30, mid[1] + 10 * i), (mid[0] + 30, mid[1] + 10 * i)])
        touch(cdp, "touchEnd", [])
        panned = view(page)
        assert panned[2] == pytest.approx(zoomed[2], rel=1e-9)
        assert panned[1] == pytest.approx(zoomed[1] + 40 * unit / zoomed[2], abs=1e-3 * unit / zoomed[2])
        for control in ("#editor-zoom-in", "#editor-fit", "#editor-place-x", '[data-mode="RRR"]'):
            box = page.locator(control).bounding_box()
            assert box and box["x"] >= 0 and box["x"] + box["width"] <= screen["width"], control
        width = page.evaluate("() => document.documentElement.scrollWidth")
        assert width <= screen["width"], f"the editor is {width} px wide"
        screenshot(page, f"editor_direct_{screen['width']}_ru")
        assert problems == []
    finally:
        context.close()
