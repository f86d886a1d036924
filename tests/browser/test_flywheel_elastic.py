"""The flywheel and elastic scenes in a real browser: δ drives the exact inertia and the flywheel drawn to
scale, a machine type's permissible [δ] is checked, Wittenbauer's point follows the crank, the indicator
diagram is edited by dragging; the elastic four-bar answers a damping drag with its method and stiffness
ratio, the stiffest belt still gets an answer without NaN; every elastic variant shows all its panels
(assert_elastic_variant_answers, on test_notation's walk of every variant)."""
from __future__ import annotations

from urllib.parse import urlencode

import pytest

from conftest import drag_slider, interface_texts, read_scene, screenshot

pytestmark = pytest.mark.browser

FLYWHEEL = read_scene("flywheel")
FOUR_BAR = read_scene("elastic_four_bar")
TRANSMISSION = read_scene("elastic_transmission")
GRAPH = "document.querySelector(`#panel-${id} .graph`)"
ELASTIC_TIMEOUT = 120_000       # ms; a guard against a hang, not a speed bound: an elastic answer takes a few seconds,
                                # an elastic family (min and max always, then up to 5 s) several times that on a loaded machine
RESULT_KINDS = ("plot", "table", "figures", "numerics")     # the panels filled by the scene's own answer


def open_scene(page, scene: dict, lang: str, panels: list[str], **state) -> None:
    """Open the scene and wait until the given panels are shown (graphs with their curves)."""
    page.goto(f"/scenes/{scene['id']}?{urlencode({'lang': lang, **state})}")
    for panel in panels:
        page.wait_for_selector(f"#panel-{panel}", state="visible", timeout=ELASTIC_TIMEOUT)
        if page.locator(f"#panel-{panel} .graph").count():
            page.locator(f"#panel-{panel}").scroll_into_view_if_needed()
            page.wait_for_function(f"id => {GRAPH}?.data?.length > 0", arg=panel)


def trace(page, panel: str, key: str = "y") -> str:
    return page.evaluate(f"([id, key]) => JSON.stringify({GRAPH}.data[0][key])", [panel, key])


def wait_for_new_trace(page, panel: str, before: str) -> None:
    page.locator(f"#panel-{panel}").scroll_into_view_if_needed()
    page.wait_for_function(f"([id, before]) => JSON.stringify({GRAPH}?.data?.[0]?.y) !== before",
                           arg=[panel, before], timeout=ELASTIC_TIMEOUT)


def figure_value(page, label: str) -> str:
    return page.locator(".figures-list dt", has_text=label).locator("xpath=following-sibling::dd[1]").inner_text()


def wait_for_text_change(page, selector: str, before: str) -> str:
    page.wait_for_function("([selector, before]) => document.querySelector(selector)?.textContent !== before",
                           arg=[selector, before], timeout=ELASTIC_TIMEOUT)
    return page.inner_text(selector)


def crank_length(page) -> float:
    """Length of the drawn crank OA in drawing units: the scale of the machine with its flywheel."""
    return page.eval_on_selector("#panel-linkage .moving .bar",
                                 "bar => Math.hypot(bar.x2.baseVal.value - bar.x1.baseVal.value, "
                                 "bar.y2.baseVal.value - bar.y1.baseVal.value)")


def number(text: str) -> float:
    """The first number of a reading such as "38,54 кг·м²" or "0.7588 m"."""
    return float(text.split()[0].replace(",", ".").replace("−", "-"))


def test_dragging_delta_resizes_the_flywheel_and_its_drawing(browser_page):
    page = browser_page
    open_scene(page, FLYWHEEL, "ru", ["linkage", "figures", "comparison"])
    label = FLYWHEEL["panels"]["figures"]["items"][0]["label"]["ru"]
    inertia = figure_value(page, label)
    assert 38 < number(inertia) < 39                 # [δ] = 1/80: 38,54 кг·м² beside the crank's 2,72
    assert page.locator("#panel-comparison td", has_text="Мерцалов").count() == 1
    page.wait_for_selector("#panel-linkage .flywheel-disk")
    numbers = page.inner_text(".flywheel-numbers")
    crank = crank_length(page)
    drag_slider(page, "#slider-delta", 0.15)          # a smaller δ needs a larger flywheel
    page.wait_for_function("([label, before]) => [...document.querySelectorAll('.figures-list dt')]"
                           ".find(dt => dt.textContent === label).nextElementSibling.textContent !== before",
                           arg=[label, inertia])
    assert number(figure_value(page, label)) > number(inertia)
    after = wait_for_text_change(page, ".flywheel-numbers", numbers)
    assert number(after.split("D = ")[1]) > number(numbers.split("D = ")[1])
    assert crank_length(page) < crank                 # the larger disk, drawn to the same scale as the linkage
    assert "NaN" not in page.inner_text("body")
    screenshot(page, "flywheel_small_delta")
    assert page.problems == []


def test_a_machine_type_sets_delta_and_the_design_is_checked_against_it(browser_page):
    page = browser_page
    t = interface_texts("en")
    open_scene(page, FLYWHEEL, "en", ["figures"])
    pumps = next(i for i, p in enumerate(FLYWHEEL["presets"]) if p["label"]["en"] == "pumps")
    page.select_option("#preset", str(pumps))
    page.wait_for_function("() => document.querySelectorAll('.preset-check li').length === 2")
    assert page.inner_text(".slider .readout >> nth=0") == "[δ] = 0.05"
    page.wait_for_function("() => document.querySelector('.preset-check').textContent.includes('δ = 0.05 ')")
    lines = page.locator(".preset-check li").all_inner_texts()
    assert lines[0].startswith(f"✓ {t['method_exact']}: δ = 0.05 — {t['preset_within']} 0.03…0.05")
    assert lines[1].startswith(f"✓ {t['method_merzalov']}: δ = 0.04")      # on the safe side
    screenshot(page, "flywheel_preset_pumps")
    page.focus("#slider-delta")
    page.keyboard.press("End")                        # δ = 0.2: too rough for a pump, and no flywheel needed
    page.wait_for_selector(".preset-check .preset-above")
    assert page.inner_text(".preset-check li >> nth=0").startswith(f"✗ {t['method_exact']}: δ = 0.2 — {t['preset_above']}")
    page.wait_for_selector(".flywheel-numbers.no-flywheel")
    assert page.inner_text(".flywheel-numbers") == t["flywheel_not_needed"]
    assert page.locator("#panel-linkage .flywheel-disk").count() == 0
    assert "No flywheel needed" in page.inner_text("#notices")
    screenshot(page, "flywheel_no_flywheel_needed")
    assert page.problems == []


def test_wittenbauer_point_runs_round_the_curve_with_the_crank(browser_page):
    page = browser_page
    open_scene(page, FLYWHEEL, "en", ["wittenbauer"])
    page.locator("#panel-wittenbauer").scroll_into_view_if_needed()
    page.wait_for_selector(".energy-mass-point", state="visible")
    names = page.evaluate(f"id => {GRAPH}.data.map(trace => trace.name)", "wittenbauer")
    assert any(name and name.startswith("ab = 1145") for name in names)
    assert "far off the plot" in page.inner_text("#panel-wittenbauer .caption")
    point = lambda: page.eval_on_selector(".energy-mass-point", "e => e.style.transform")
    spoke = lambda: page.eval_on_selector("#panel-linkage .flywheel-spoke", "e => e.getAttribute('x2')")
    start, start_spoke = point(), spoke()
    page.fill("#crank-angle", "120")
    page.dispatch_event("#crank-angle", "input")
    assert point() != start and spoke() != start_spoke
    assert page.inner_text(".point-readout").startswith("φ = 120.0°")
    at_120 = point()
    page.click("#animation .play")
    page.wait_for_function("before => document.querySelector('.energy-mass-point').style.transform !== before", arg=at_120)
    page.click("#animation .play")
    screenshot(page, "flywheel_wittenbauer_moving")
    assert page.problems == []


def test_dragging_an_indicator_point_changes_the_work(browser_page):
    page = browser_page
    open_scene(page, FLYWHEEL, "en", ["indicator", "work"])
    work = trace(page, "work")
    point = page.locator(".diagram-point[data-stroke='expansion'][data-index='2']")
    point.scroll_into_view_if_needed()
    box = point.bounding_box()
    x, y = box["x"] + box["width"] / 2, box["y"] + box["height"] / 2
    page.mouse.move(x, y)
    page.mouse.down()
    page.mouse.move(x, y - 60, steps=4)
    page.mouse.up()
    table_value = float(page.input_value(".indicator-table tbody tr:nth-child(3) td:nth-child(2) input"))
    assert table_value > 0.4                          # the assumed polytrope has 0.2397 there
    wait_for_new_trace(page, "work", work)
    screenshot(page, "flywheel_indicator_edited")
    assert page.problems == []


ELASTIC_SCENES = ("elastic-transmission", "elastic-linkage", "elastic-four-bar")


def assert_elastic_variant_answers(page, scene: dict, variant: dict, lang: str) -> None:
    """The open page of an elastic scene at `variant` shows all its result panels without NaN, "undefined" or a
    refusal; a variant with the bearings' iteration says that its series converges (ratio < 1) and to what.
    test_notation walks every variant of every scene in ru and calls this on the elastic scenes' pages, so that
    each page is opened once for both checks."""
    for panel in (p for p in variant["panels"] if scene["panels"][p]["kind"] in RESULT_KINDS):
        page.wait_for_selector(f"#panel-{panel}", state="visible", timeout=ELASTIC_TIMEOUT)
        if page.locator(f"#panel-{panel} .graph").count():
            page.locator(f"#panel-{panel}").scroll_into_view_if_needed()
            page.wait_for_function(f"id => {GRAPH}?.data?.length > 0", arg=panel)
    text = page.inner_text(".results")
    assert "NaN" not in text and "undefined" not in text
    assert page.locator(".refusal").count() == 0
    if "bearings" in variant["panels"]:
        summary = page.inner_text("#panel-bearings .series-summary")   # a contraction: its ratio and limit
        texts = interface_texts(lang)
        assert texts["series_converges"] in summary and "< 1" in summary and texts["series_limit"] in summary
    screenshot(page, f"elastic_{scene['id']}_{variant['id']}")


def test_elastic_four_bar_answers_a_damping_drag_with_its_method(browser_page):
    page = browser_page
    t = interface_texts("en")
    open_scene(page, FOUR_BAR, "en", ["twist", "phase", "modal", "numerics"])
    twist = trace(page, "twist")
    drag_slider(page, "#slider-b", 0.9)               # b_n up to about 0.05 N·m·s/rad on the log scale
    assert float(page.inner_text(".slider .readout >> nth=0").split("= ")[1].split()[0]) > 0.02
    wait_for_new_trace(page, "twist", twist)
    numerics = page.inner_text("#panel-numerics")
    assert t["numerics_method"] in numerics and t["numerics_stiffness_ratio"] in numerics
    assert page.inner_text("#panel-numerics .numerics-method td").startswith(("DOP853", "Radau"))
    assert number(page.inner_text("#panel-numerics .numerics-stiffness_ratio td")) > 0
    assert page.inner_text("#panel-numerics .numerics-why td")
    assert page.evaluate(f"id => {GRAPH}.layout.yaxis2 !== undefined", "modal")      # ζ on its own axis
    assert "NaN" not in page.inner_text("body")
    screenshot(page, "elastic_four_bar_damped")
    assert page.problems == []


def test_stiffest_belt_still_gets_an_answer_without_nan(browser_page):
    page = browser_page
    open_scene(page, TRANSMISSION, "ru", ["twist", "numerics"])
    twist = trace(page, "twist")
    runtime = page.inner_text("#panel-numerics .numerics-runtime_ms td")
    drag_slider(page, "#slider-c", 1.0)
    assert page.inner_text(".slider .readout >> nth=0") == "жёсткость c = 1·10⁷ Н·м/рад"
    wait_for_new_trace(page, "twist", twist)
    wait_for_text_change(page, "#panel-numerics .numerics-runtime_ms td", runtime)
    page.wait_for_function("() => !document.querySelector('.results').classList.contains('busy')",
                           timeout=ELASTIC_TIMEOUT)
    assert page.locator(".refusal").count() == 0
    for panel in ("speeds", "twist", "twist_rate", "drive", "numerics"):
        assert page.locator(f"#panel-{panel}").is_visible()
    assert "NaN" not in page.inner_text("body")
    screenshot(page, "elastic_transmission_stiffest")
    assert page.problems == []
