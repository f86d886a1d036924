"""The crank turned by hand in the dynamics scenes' drawings, in a real browser ("Turn the crank by
dragging it"): in the forces scene's free-body diagram and the flywheel scene's machine, a mouse drag about the
crank's pivot puts the crank where the pointer let go, and the crank-angle clock, the plots' cursors and the
per-angle readings follow; one arrow key steps the angle by 1°; nothing is asked of the server meanwhile. One
page load per scene. (The kinematics scene's drawing is turned in test_explore.py.)"""
from __future__ import annotations

import math

import pytest

from conftest import interface_texts, read_scene, screenshot
from test_dynamics import figure_value, open_scene

pytestmark = pytest.mark.browser

FORCES = read_scene("forces_friction")
FLYWHEEL = read_scene("flywheel")

PINS = """svg => [...svg.querySelectorAll('.moving circle.pin')].slice(0, 2)
    .map(p => p.getBoundingClientRect()).map(r => [r.x + r.width / 2, r.y + r.height / 2])"""


def degrees_of(text: str) -> float:
    """"φ = 123,4°" → 123.4."""
    return float(text.removeprefix("φ = ").removesuffix("°").replace(",", "."))


def screen_angle(centre, point) -> float:
    return math.degrees(math.atan2(point[1] - centre[1], point[0] - centre[0]))


def turn_crank(page, drawing: str, quarter: int = 1):
    """Drag the crank of the drawing (an svg selector) a quarter turn on the screen (quarter = ±1) about its
    pivot, pressing on the crank pin; returns the pivot and the point where the pointer let go."""
    page.locator(drawing).scroll_into_view_if_needed()
    pivot, pin = page.eval_on_selector(drawing, PINS)          # the crank's pivot and its pin, drawn first
    radius = math.dist(pivot, pin)
    start = math.atan2(pin[1] - pivot[1], pin[0] - pivot[0])
    at = lambda angle: (pivot[0] + radius * math.cos(angle), pivot[1] + radius * math.sin(angle))
    page.mouse.move(*at(start))
    page.mouse.down()
    for step in range(1, 10):                                  # 10° on the screen at a time: the short way each
        page.mouse.move(*at(start + quarter * step * math.pi / 18))
    end = at(start + quarter * math.pi / 2)
    page.mouse.move(*end)
    page.mouse.up()
    return pivot, end


def assert_turned(page, drawing: str, graph_panel: str, before: dict) -> float:
    """The crank is where the pointer let go, the clock and the plot's cursor are at its angle; φ in degrees."""
    pivot, end = before["pivot"], before["end"]
    _, pin = page.eval_on_selector(drawing, PINS)
    turn = (screen_angle(pivot, pin) - screen_angle(pivot, end) + 180) % 360 - 180
    # the pin is drawn from the answer's joints interpolated on a grid of 1° or finer: well within 2°
    assert abs(turn) < 2, f"the crank pin is {turn:.1f}° from where the pointer let go"
    text = page.get_attribute(drawing, "aria-valuetext")
    assert text == page.inner_text(".phi-readout")             # the drawing announces the clock's angle
    phi = degrees_of(text)
    # a quarter turn on the screen is a quarter turn of the crank (either sense, wrapped into the cycle)
    moved = (phi - before["phi"]) % 360
    assert min(abs(moved - 90), abs(moved - 270)) < 2, (before["phi"], phi)
    assert page.get_attribute(drawing, "aria-valuenow") == str(round(phi) % 361)
    assert abs(float(page.get_attribute(drawing, "aria-valuenow")) - phi) <= 0.55
    assert_cursor_at(page, graph_panel, phi)
    return phi


def assert_cursor_at(page, panel: str, phi: float) -> None:
    """The plot's cursor is at φ (degrees) on the plot's own x axis (Plotly's plot area; 1 px: φ is read
    to 0.05°, a few hundred pixels span the cycle)."""
    x, expected = page.evaluate("""([panel, phi]) => {
        const graph = document.querySelector(`#panel-${panel} .graph`);
        const cursor = document.querySelector(`#panel-${panel} .cursor`);
        const { l, w } = graph._fullLayout._size, [x0, x1] = graph._fullLayout.xaxis.range;
        return [Number(cursor.style.transform.match(/translateX\\(([-\\d.e]+)px\\)/)[1]), l + (phi - x0) / (x1 - x0) * w]; }""",
        [panel, phi])
    assert abs(x - expected) < 1, (panel, x, expected)


def before_turning(page, drawing: str) -> dict:
    return {"phi": degrees_of(page.get_attribute(drawing, "aria-valuetext"))}


def step_with_key(page, drawing: str, phi: float) -> float:
    """Focus the drawing and press → once: the crank turns 1°."""
    page.focus(drawing)
    page.keyboard.press("ArrowRight")
    stepped = degrees_of(page.get_attribute(drawing, "aria-valuetext"))
    assert abs((stepped - phi - 1 + 180) % 360 - 180) < 0.06        # 1°, φ read to 0.1°
    return stepped


def no_requests_while(page, endpoints: list[str], action) -> None:
    """Run action; assert the page asked nothing of the endpoints meanwhile."""
    asked = []
    listener = lambda request: any(f"/api/v1/{e}" in request.url for e in endpoints) and asked.append(request.url)
    page.on("request", listener)
    action()
    page.remove_listener("request", listener)
    assert asked == []


def test_free_body_diagram_turns_by_hand_and_the_readings_follow(browser_page):
    page = browser_page
    t = interface_texts("ru")
    open_scene(page, FORCES, "ru")
    drawing = "#panel-free_body svg"
    page.wait_for_selector(f"{drawing}.turnable")
    assert page.get_attribute(drawing, "role") == "slider"
    title = FORCES["panels"]["free_body"]["title"]["ru"]
    assert page.get_attribute(drawing, "aria-label") == f"{title}: {t['crank_turn']}"
    arrows = page.inner_html(f"{drawing} .forces")
    state = before_turning(page, drawing)

    def drag():
        state["pivot"], state["end"] = turn_crank(page, drawing, quarter=-1)
    no_requests_while(page, ["forces"], drag)
    phi = assert_turned(page, drawing, "reactions", state)
    assert page.inner_html(f"{drawing} .forces") != arrows                 # the loads at the new angle
    assert figure_value(page, t["crank_angle"]) == f"{phi:.1f}°".replace(".", ",")
    assert_cursor_at(page, "moment", phi)
    phi = step_with_key(page, drawing, phi)
    assert figure_value(page, t["crank_angle"]) == f"{phi:.1f}°".replace(".", ",")
    screenshot(page, "crank_drag_forces_ru")
    assert page.problems == []


def test_flywheel_machine_turns_by_hand_and_the_cursors_follow(browser_page):
    page = browser_page
    open_scene(page, FLYWHEEL, "en")
    drawing = "#panel-linkage svg"
    page.wait_for_selector(f"{drawing} .moving circle.pin")
    assert page.get_attribute(drawing, "aria-label") == interface_texts("en")["crank_drag"]
    cursors = page.eval_on_selector_all(".panel .cursor", "cs => cs.map(c => c.style.transform)")
    state = before_turning(page, drawing)

    def drag():
        state["pivot"], state["end"] = turn_crank(page, drawing)
    no_requests_while(page, ["flywheel", "kinematics"], drag)
    phi = assert_turned(page, drawing, "speed", state)
    moved = page.eval_on_selector_all(".panel .cursor", "cs => cs.map(c => c.style.transform)")
    assert len(moved) == len(cursors) >= 4 and all(a != b for a, b in zip(moved, cursors))   # every plot's cursor
    stepped = step_with_key(page, drawing, phi)
    assert page.get_attribute(drawing, "aria-valuetext") == f"φ = {stepped:.1f}°"       # en: decimal point
    assert page.problems == []
