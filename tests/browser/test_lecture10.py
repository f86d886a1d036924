"""Lecture 10's induction motor and the flywheel's analysis problem in a real browser, one opening of each
Russian page: dragging the load moves the operating point along the characteristic (Fig. 10.14) and changes
the successive approximations' laws of motion; dragging the flywheel's I changes ω(φ) and the δ it gives. No
English sentence of the app on the page, no console error. Screenshots in ru at desktop and phone width."""
from __future__ import annotations

import sys

import pytest

from conftest import REPO, drag_slider, read_scene, screenshot

sys.path.insert(0, str(REPO / "tests"))
from test_translations import english_in  # noqa: E402

pytestmark = pytest.mark.browser

GRAPH = "document.querySelector(`#panel-${id} .graph`)"


def trace_y(page, panel: str, name_index: int) -> str:
    return page.evaluate(f"([id, k]) => JSON.stringify({GRAPH}.data[k].y)", [panel, name_index])


def wait_for_graphs(page, scene: dict, variant: dict) -> None:
    for panel in variant["panels"]:
        page.wait_for_selector(f"#panel-{panel}", state="visible")
        if scene["panels"][panel]["kind"] == "plot":
            page.locator(f"#panel-{panel}").scroll_into_view_if_needed()
            page.wait_for_function(f"id => {GRAPH}?.data?.length > 0", arg=panel)


def changed(page, panel: str, k: int, before: str) -> None:
    page.wait_for_function(f"([id, k, before]) => JSON.stringify({GRAPH}.data[k].y) !== before",
                           arg=[panel, k, before])


def operating_x(page) -> float:
    """ω of the operating point: the x of the markers trace's defined point."""
    return page.evaluate(f"""id => {{ const t = {GRAPH}.data.find(d => d.mode === "markers");
        return t.x[t.y.findIndex(v => v !== null)]; }}""", "characteristic")


def test_the_load_moves_the_operating_point_and_the_approximations(browser_page):
    page = browser_page
    scene = read_scene("induction_motor")
    page.goto("/scenes/induction-motor?lang=ru")
    wait_for_graphs(page, scene, scene["variants"][0])
    before_x, before_laws = operating_x(page), trace_y(page, "laws", 0)
    load_trace = page.evaluate(f"id => {GRAPH}.data.findIndex(d => d.mode !== 'markers' && d.line.dash === 'dot')",
                               "characteristic")
    before_load = trace_y(page, "characteristic", load_trace)
    drag_slider(page, "#slider-load", 0.6)
    changed(page, "characteristic", load_trace, before_load)
    changed(page, "laws", 0, before_laws)
    assert operating_x(page) < before_x                     # more load: lower speed along the stable branch
    screenshot(page, "lecture10_induction_ru")
    assert page.locator("#panel-steps tbody tr").count() > 3
    body = page.inner_text("body")
    assert "NaN" not in body and english_in(body, "ru") == []
    screenshot(page, "lecture10_induction_ru")
    page.set_viewport_size({"width": 390, "height": 844})
    page.wait_for_function(f"id => {GRAPH}?.data?.length > 0", arg="characteristic")
    screenshot(page, "lecture10_induction_ru_phone")
    assert page.problems == []


def test_the_flywheels_inertia_sets_the_delta(browser_page):
    page = browser_page
    scene = read_scene("flywheel_analysis")
    page.goto("/scenes/flywheel-analysis?lang=ru")
    wait_for_graphs(page, scene, scene["variants"][0])
    before = trace_y(page, "speed", 0)
    figures = {panel: trace_y(page, panel, 0) for panel in ("moment", "transfer")}     # Fig. 10.6, Fig. 10.5
    spread = lambda y: (lambda v: max(v) - min(v))(list(map(float, y.strip("[]").split(","))))
    drag_slider(page, "#slider-inertia", 0.1)               # a lighter flywheel
    changed(page, "speed", 0, before)
    assert spread(trace_y(page, "speed", 0)) > spread(before)      # less inertia: a larger swing of ω
    # the driving moment of the indicator diagram and the crank-slider's transfer functions are functions of φ
    # alone: the flywheel does not change them (to 1e-3 of the curve's largest value: a family member is drawn
    # at its preview rounding, 3-4 significant digits, until the exact answer replaces it)
    values = lambda y: list(map(float, y.strip("[]").split(",")))
    for panel, shown in figures.items():
        then = values(shown)
        page.wait_for_function(f"([id, n]) => {GRAPH}.data[0].y.length === n", arg=[panel, len(then)])
        now = values(trace_y(page, panel, 0))
        assert max(abs(a - b) for a, b in zip(now, then)) <= 1e-3 * max(map(abs, then)), panel
    body = page.inner_text("body")
    assert "NaN" not in body and english_in(body, "ru") == []
    screenshot(page, "lecture10_flywheel_analysis_ru")
    assert page.problems == []
