"""The start page and the transfer-functions scene in a real browser: languages, slider drags, the
invalid-geometry message, the animation, overlays and the approximation panel; every variant draws its linkage
and plots (assert_variant_draws_its_linkage_and_plots, on test_notation's walk of every variant)."""
from __future__ import annotations

import re
from urllib.parse import urlencode

import pytest

from conftest import SCENE, drag_slider, interface_texts, screenshot

pytestmark = pytest.mark.browser

VARIANTS = {variant["id"]: variant for variant in SCENE["variants"]}
GRAPH = "document.querySelector(`#panel-${id} .graph`)"
# Chromium reports every HTTP error answer on the console; the 422 that says why a mechanism cannot be
# assembled is the expected answer in the invalid-geometry test, and nothing else may appear there.
REFUSED_GEOMETRY = re.compile(r"Failed to load resource: the server responded with a status of 422")


def open_scene(page, lang: str = "ru", **state) -> None:
    page.goto(f"/scenes/{SCENE['id']}?{urlencode({'lang': lang, **state})}")
    wait_for_plot(page, "u31")


def wait_for_plot(page, panel: str) -> None:
    page.wait_for_function(f"id => {GRAPH}?.data?.length > 0", arg=panel)


def plot_data(page, panel: str) -> str:
    """The plotted values of a panel's first trace, as JSON text."""
    return page.evaluate(f"id => JSON.stringify({GRAPH}.data[0].y)", panel)


def wait_for_new_plot(page, panel: str, before: str) -> None:
    page.wait_for_function(f"([id, before]) => {GRAPH}?.data?.length > 0 && JSON.stringify({GRAPH}.data[0].y) !== before",
                           arg=[panel, before])


def drawing(page) -> str:
    """Every attribute of the moving parts of the linkage drawing."""
    return page.inner_html("#linkage svg .moving")


def shows_no_nan(page) -> bool:
    return "NaN" not in page.inner_text("body") and "NaN" not in page.inner_html("#linkage")


@pytest.mark.parametrize("lang", ["ru", "uk", "en"])
def test_start_page_is_translated_and_loads_no_plotly(browser_page, lang):
    page = browser_page
    requests = []
    page.on("request", lambda request: requests.append(request.url))
    page.goto(f"/?lang={lang}")
    t = interface_texts(lang)
    assert page.inner_text("h1") == t["app_title"]
    assert page.title() == t["app_title"]
    link = page.locator(f".scene-card h3 a[href='/scenes/{SCENE['id']}?lang={lang}']")
    assert link.inner_text() == SCENE["title"][lang]
    assert page.get_attribute(f"a[data-lang='{lang}']", "aria-current") == "true"
    assert page.evaluate("typeof window.Plotly") == "undefined"
    assert not [url for url in requests if "plotly" in url]
    screenshot(page, f"start_page_{lang}")
    assert page.problems == []


def assert_variant_draws_its_linkage_and_plots(page, variant: dict) -> None:
    """The open transfer-functions page in ru at `variant` draws its linkage and every plot panel of it, titled as
    the scene says, with the variant's text and no NaN. test_notation walks every variant of every scene in ru
    and calls this on this scene's pages, so that each page is opened once for both checks."""
    wait_for_plot(page, "u31")
    assert page.locator("#linkage svg .moving line").count() >= 1
    assert page.locator(".geometry-error").count() == 0
    titles = page.locator(".panel h2").all_inner_texts()
    plots = [panel for panel in variant["panels"] if SCENE["panels"][panel]["kind"] == "plot"]
    assert titles == [SCENE["panels"][panel]["title"]["ru"] for panel in plots]
    assert page.inner_text(".variant-text") == variant["text"]["ru"]
    assert shows_no_nan(page)
    screenshot(page, f"variant_{variant['id']}")


def test_lambda_drag_redraws_linkage_and_transfer_function(browser_page):
    page = browser_page
    open_scene(page, "ru", variant="slider_crank")
    t = interface_texts("ru")
    before_plot, before_drawing = plot_data(page, "u31"), drawing(page)
    drag_slider(page, "#slider-lambda", 0.1)
    wait_for_new_plot(page, "u31", before_plot)
    lam = float(page.input_value("#slider-lambda"))
    assert lam < 2.5
    assert drawing(page) != before_drawing
    readout = page.inner_text(".slider .readout >> nth=0")
    assert readout.startswith(f"λ = l₂/l₁ = {lam:.2f}".replace(".", ","))
    assert f"r/l = {1 / lam:.3g}".replace(".", ",") in readout
    assert t["units_m"] in page.inner_text(".slider .length >> nth=0")

    before_plot = plot_data(page, "u31")
    page.focus("#slider-offset")
    page.keyboard.press("ArrowRight")
    wait_for_new_plot(page, "u31", before_plot)
    assert page.input_value("#slider-offset") == "0.01"
    page.wait_for_url(re.compile(r"[?&]offset=0\.01(&|$)"))
    assert shows_no_nan(page)
    screenshot(page, "slider_crank_dragged")
    assert page.problems == []


def test_language_switch_keeps_the_scene_and_its_settings(browser_page):
    page = browser_page
    open_scene(page, "ru", variant="four_bar")
    before = plot_data(page, "u31")
    page.focus("#slider-lambda0")
    page.keyboard.press("ArrowLeft")
    wait_for_new_plot(page, "u31", before)
    with page.expect_navigation():                       # the old page holds the same plots
        page.click("a[data-lang='uk']")
    wait_for_plot(page, "u31")
    t = interface_texts("uk")
    assert page.inner_text("h1") == SCENE["title"]["uk"]
    assert page.input_value("#variant") == "four_bar"
    assert page.input_value("#slider-lambda0") == "3.99"
    assert page.inner_text(".info dt >> nth=0") == t["grashof_class"]
    assert page.inner_text(".info dd >> nth=0") == t["crank_rocker"]
    assert page.inner_text(".play") == t["play"]
    screenshot(page, "four_bar_uk")
    assert page.problems == []


@pytest.mark.parametrize("lang", ["ru", "uk", "en"])
def test_invalid_geometry_says_why_instead_of_drawing(browser_page, lang):
    page = browser_page
    open_scene(page, lang, variant="slider_crank", offset="0.9")
    page.focus("#slider-lambda")
    page.keyboard.press("Home")               # λ = 1.05 < 1 + e/l₁ = 1.9: the crank cannot turn
    reason = interface_texts(lang)["err_slider_crank_no_full_turn"]
    page.wait_for_selector(".linkage .geometry-error")
    assert reason in page.inner_text(".linkage .geometry-error")
    assert interface_texts(lang)["invalid_geometry"] in page.inner_text(".linkage .geometry-error")
    assert reason in page.inner_text(".plots-message")
    assert page.locator("#linkage svg").is_hidden()
    assert page.locator(".panel").first.is_hidden()
    screenshot(page, f"invalid_geometry_{lang}")

    page.keyboard.press("End")                # λ = 8 assembles again
    page.wait_for_selector(".linkage .geometry-error", state="detached")
    wait_for_plot(page, "u31")
    assert page.locator("#linkage svg").is_visible()
    assert shows_no_nan(page)
    assert [text for text in page.problems if not REFUSED_GEOMETRY.search(text)] == []


def test_animation_moves_the_crank_and_the_plot_cursor(browser_page):
    page = browser_page
    open_scene(page, "en", variant="slotted_oscillating")
    page.wait_for_function("() => document.querySelector('#panel-u31 .cursor')?.style.transform")
    cursor = page.get_attribute("#panel-u31 .cursor", "style")
    linkage = drawing(page)
    page.click(".play")
    page.wait_for_function("() => Number(document.querySelector('#crank-angle').value) > 30")
    page.click(".play")
    assert page.get_attribute("#panel-u31 .cursor", "style") != cursor
    assert drawing(page) != linkage
    angle = page.input_value("#crank-angle")
    page.wait_for_timeout(200)
    assert page.input_value("#crank-angle") == angle          # paused
    assert page.inner_text(".play") == interface_texts("en")["play"]
    assert "u₃₁ = " in page.inner_text("#panel-u31 .cursor-readout")
    screenshot(page, "slotted_oscillating_animated")
    assert page.problems == []


def test_four_pi_cycle_of_a_change_point_four_bar(browser_page):
    page = browser_page
    open_scene(page, "en", variant="special_1")
    page.wait_for_function(f"id => {GRAPH}.data[0].x.length === 721", arg="u31")
    assert page.evaluate(f"id => {GRAPH}.layout.xaxis.range", "u31") == [0, 720]
    assert page.get_attribute("#crank-angle", "max") == "720"
    before = plot_data(page, "u31")
    page.check("input[name='toggle-limiter'][value='1']")
    wait_for_new_plot(page, "u31", before)
    page.wait_for_function(f"id => {GRAPH}.data[0].x.length === 361", arg="u31")
    assert page.get_attribute("#crank-angle", "max") == "360"
    assert page.problems == []


def test_overlay_and_approximations_of_the_crank_slider(browser_page):
    page = browser_page
    t = interface_texts("en")
    open_scene(page, "en", variant="slider_crank")
    page.check("#overlay")
    overlays = len(VARIANTS["slider_crank"]["overlay_values"])
    page.wait_for_function(f"([id, n]) => {GRAPH}.data.length === 1 + n", arg=["u31", overlays])
    names = page.evaluate(f"id => {GRAPH}.data.map(trace => trace.name)", "u31")
    assert names[1:] == ["λ = 1.5", "λ = 3", "λ = 5"]
    assert page.evaluate(f"id => {GRAPH}.data.slice(1).every(trace => trace.line.dash !== 'solid')", "u31")

    page.locator("#panel-approximations").scroll_into_view_if_needed()
    wait_for_plot(page, "approximations")
    caption = page.inner_text("#panel-approximations .caption")
    assert caption.startswith(f"{t['max_error']}: u₃₁ ")
    assert page.inner_text("#panel-approximations .note") == SCENE["panels"]["approximations"]["note"]["en"]
    page.locator("#panel-harmonics").scroll_into_view_if_needed()
    wait_for_plot(page, "harmonics")
    assert page.evaluate("id => " + GRAPH + ".data[0].type", "harmonics") == "bar"
    assert shows_no_nan(page)
    screenshot(page, "slider_crank_overlay_en")
    assert page.problems == []
