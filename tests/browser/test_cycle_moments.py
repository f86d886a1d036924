"""The reduced moments over the cycle (resisting-moment scene, variant cycle_moments: Chaika–Vasylenko steps 8–10,
Fig. 3.7) in a real browser, one opening of the Russian page: dragging p_max changes the moments, the works and
the graphical integration, the pole distance K moves the pole on the sheet; switching to the four-stroke engine doubles the cycle to 720°, to the compressor
turns the gas moment into M_кО (the motor's power appears). No English sentence of the app, no NaN, no console
error. Screenshots in ru at desktop and phone width (test-artifacts/)."""
from __future__ import annotations

import sys

import pytest

from conftest import REPO, drag_slider, families_arrived, read_scene, screenshot

sys.path.insert(0, str(REPO / "tests"))
from test_translations import english_in  # noqa: E402

pytestmark = pytest.mark.browser

GRAPH = "document.querySelector(`#panel-${id} .graph`)"
PLOTS = ("cycle_moments", "cycle_works", "graphical_sheet", "graphical_work")


def trace_y(page, panel: str, k: int) -> str:
    return page.evaluate(f"([id, k]) => JSON.stringify({GRAPH}.data[k].y)", [panel, k])


def last_x(page, panel: str) -> float:
    return page.evaluate(f"id => {GRAPH}.data[0].x.at(-1)", panel)


def changed(page, panel: str, k: int, before: str) -> None:
    page.wait_for_function(f"([id, k, before]) => JSON.stringify({GRAPH}?.data?.[k]?.y) !== before",
                           arg=[panel, k, before])


def figure(page, index: int) -> str:
    return page.locator("#panel-cycle_figures dd").nth(index).inner_text()


def test_the_cycle_moments_follow_the_pressure_and_the_machine(browser_page):
    page = browser_page
    scene = read_scene("resisting_moment")
    variant = next(v for v in scene["variants"] if v["id"] == "cycle_moments")
    page.goto("/scenes/resisting-moment?lang=ru&variant=cycle_moments")
    for panel in variant["panels"]:
        page.wait_for_selector(f"#panel-{panel}", state="visible")
    for panel in PLOTS:
        page.locator(f"#panel-{panel}").scroll_into_view_if_needed()
        page.wait_for_function(f"id => {GRAPH}?.data?.length > 0", arg=panel)
    assert last_x(page, "cycle_moments") == pytest.approx(360)
    before = {panel: trace_y(page, panel, 0) for panel in PLOTS}
    power = figure(page, 2)                               # N_инд
    assert page.locator("#panel-graphical_steps tbody tr").count() == 12

    drag_slider(page, "#slider-p_gas", 0.8)               # more pressure: every gas curve changes
    for panel in PLOTS:
        changed(page, panel, 0, before[panel])
    page.wait_for_function("before => document.querySelector('#panel-cycle_figures dd:nth-of-type(3)')"
                           ".innerText !== before", arg=power)
    families_arrived(page)
    rays = page.evaluate(f"id => JSON.stringify({GRAPH}.data[2].x)", "graphical_sheet")
    drag_slider(page, "#slider-pole", 0.9)                # a farther pole: the rays start farther left
    page.wait_for_function(f"([id, before]) => JSON.stringify({GRAPH}?.data?.[2]?.x) !== before",
                           arg=["graphical_sheet", rays])
    screenshot(page, "cycle_moments_ru")

    families_arrived(page)
    moments = trace_y(page, "cycle_moments", 0)
    page.locator("#toggle-mode input[value='four_stroke']").check()
    page.wait_for_function(f"id => {GRAPH}?.data?.[0]?.x?.at(-1) > 700", arg="cycle_moments")
    assert page.locator("#panel-graphical_steps tbody tr").count() == 24

    page.locator("#toggle-mode input[value='compressor']").check()
    page.wait_for_function(f"id => {GRAPH}?.data?.[0]?.x?.at(-1) < 400", arg="cycle_moments")
    changed(page, "cycle_moments", 0, moments)
    assert page.locator("#notices .warnings").count() == 1      # 6.4 MPa over 0.1: past the delivery limit
    compressor = trace_y(page, "cycle_moments", 1)
    drag_slider(page, "#slider-p_gas", 0.1)                       # about 1 MPa: a working compressor
    changed(page, "cycle_moments", 1, compressor)
    page.wait_for_function("() => !document.querySelector('#notices .warnings')")
    families_arrived(page)
    assert figure(page, 5) != "—" and figure(page, 4) == "—"     # N_дв of the compressor; no printed N_e
    assert not figure(page, 5).startswith("−")
    body = page.inner_text("body")
    assert "NaN" not in body and english_in(body, "ru") == []
    screenshot(page, "cycle_moments_compressor_ru")
    page.set_viewport_size({"width": 390, "height": 844})
    page.wait_for_function("() => [...document.querySelectorAll('.graph')].every((g) => g._fullLayout?.width <= 390)")
    screenshot(page, "cycle_moments_ru_phone")
    assert page.problems == []
