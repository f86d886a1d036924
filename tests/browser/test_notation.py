"""Say it right (notation and translation) in a real browser, on every scene:
- a page in ru shows no English sentence of the app's own strings (content/i18n/en.json, the server's
  templates), its default computation and its live study, where there is one, included (uk and en: every scene
  in test_scene_words);
- every variant's drawings in ru keep their labels apart and inside (the check of test_label_overlaps);
- the labels show real subscripts (<sub>, or shifted <tspan>s in drawings), no "_" anywhere on screen;
- numbers carry a true minus sign (U+2212) and a decimal comma, in the page and in Plotly's tick labels and
  hover, and never read "−0";
- the page's notation.js reads the markup exactly as the server's Jinja filter does.
Screenshots of two scenes in ru at desktop and phone width go to test-artifacts/.
"""
from __future__ import annotations

import re
import sys

import pytest

from conftest import ARTIFACTS, REPO, SCREEN_TEXT, read_scene, screenshot

sys.path.insert(0, str(REPO / "tests"))
from test_translations import STRINGS, english_in  # noqa: E402  (the same collection as the API test)
from test_label_overlaps import DRAWN_LABELS, PICTURES, label_problems  # noqa: E402
from test_label_overlaps import settle as drawn  # noqa: E402
from test_dynamics import SCENES as DYNAMICS_SCENES, assert_variant_shows_all_its_panels  # noqa: E402
from test_flywheel_elastic import ELASTIC_SCENES, assert_elastic_variant_answers  # noqa: E402
from test_scene import assert_variant_draws_its_linkage_and_plots  # noqa: E402
from test_scene_words import assert_speaks  # noqa: E402

from server.lessons.markup import notation_parts  # noqa: E402

pytestmark = pytest.mark.browser

SCENE_FILES = sorted(path.stem for path in (REPO / "content" / "scenes").glob("*.json"))
SCENES = [read_scene(name) for name in SCENE_FILES]
STUDY_TIMEOUT = 90_000
HYPHEN_NUMBER = re.compile(r"(?:^|[\s(=:;/\[])-\d")        # "-2,7": a hyphen where a minus belongs
SIGNED_ZERO = re.compile(r"(?<![\w,.])[−-]0(?:[,.]0+)?(?![\d,.])")
POINT_NUMBER = re.compile(r"\d\.\d")
DECIMAL_POINT = re.compile(r"(?<![(§\d.])(?<!табл\. )\d+\.\d")   # not an equation "(1.9)", a section "§3.2", a table "табл. 4.3"

TICKS = """() => [...document.querySelectorAll(
  ".main-svg g.xtick text, .main-svg g.ytick text, .main-svg g.x2tick text, .main-svg g.y2tick text, " +
  ".main-svg g.radialaxistick text, .main-svg g.angularaxistick text")].map((node) => node.textContent)"""
# the scenes whose Russian texts write a subscript ("_"); transfer functions use ₁₂₃ glyphs only
WITH_SUBSCRIPTS = {scene["id"] for name, scene in zip(SCENE_FILES, SCENES)
                   if any(where.startswith(f"{name}.") and lang == "ru" and "_" in text for where, lang, text in STRINGS)}
NUMBER_CELLS = """() => [...document.querySelectorAll("dd, td, output, .readout, .caption")]
  .map((node) => node.innerText)"""


def settle(page) -> None:
    """Wait until the page has asked for and drawn everything it asks for on its own."""
    page.wait_for_load_state("networkidle")
    page.wait_for_timeout(300)
    page.wait_for_load_state("networkidle")


def run_studies(page) -> None:
    """Click every live study's button and wait for its answer to be drawn."""
    buttons = page.locator(".study-run")
    for i in range(buttons.count()):
        buttons.nth(i).scroll_into_view_if_needed()
        buttons.nth(i).click()
    if buttons.count():
        page.wait_for_function("() => [...document.querySelectorAll('.study-run')].every((b) => !b.disabled)",
                               timeout=STUDY_TIMEOUT)
        settle(page)


def open_scene(page, scene: dict, lang: str, variant: str | None = None) -> None:
    query = f"lang={lang}" + (f"&variant={variant}" if variant else "")
    page.goto(f"/scenes/{scene['id']}?{query}")
    settle(page)


def english_on_the_page_after_its_studies(page, lang: str) -> list[str]:
    """The app's English sentences on the open page once its live studies (if any) have run."""
    run_studies(page)
    return english_in(page.evaluate(SCREEN_TEXT), lang)


def test_the_russian_texts_write_subscripts_on_most_scenes():
    """The check below that subscripts show as <sub> has something to check: most scenes' Russian texts write one."""
    assert len(WITH_SUBSCRIPTS) >= 8


@pytest.mark.parametrize("name", SCENE_FILES)
def test_russian_pages_write_subscripts_a_true_minus_and_a_decimal_comma_on_every_variant(browser_page, name):
    """Every variant of the scene in ru (the first opened, the others picked from its list where it has one): no "_" on the screen and the subscripts as <sub>; numbers
    with a true minus, a decimal comma (plots' tick labels included) and no signed zero; the labels of its
    drawings apart and inside them (test_label_overlaps.label_problems; uk and en at the default state: test_scene_words);
    on the default variant's page the scene words' checks in ru as well (test_scene_words.assert_speaks);
    on the dynamics scenes every panel of the variant (test_dynamics.assert_variant_shows_all_its_panels), on
    the elastic ones every answer without NaN (test_flywheel_elastic.assert_elastic_variant_answers), on the
    transfer functions the linkage and plots (test_scene.assert_variant_draws_its_linkage_and_plots).
    On the scene's default (first) variant its live studies are then run, and no English sentence of the app may
    show. (The Ukrainian and English pages' words: test_scene_words.)"""
    page = browser_page
    scene = read_scene(name)
    underscores, problems, english, unreadable = {}, {}, [], {}
    subscripts = plots = checked_ticks = 0
    for variant in scene["variants"]:
        if variant is scene["variants"][0] or not page.locator("#variant").count():
            open_scene(page, scene, "ru", variant["id"])
        else:                       # the next variant as a reader picks it: the page stays, its panels change
            page.select_option("#variant", variant["id"])
            page.wait_for_url(f"**variant={variant['id']}**")
            settle(page)
        where = variant["id"]
        text = page.evaluate(SCREEN_TEXT)
        found = sorted(set(re.findall(r"\S*_\S*", text)))
        if found:
            underscores[where] = found
        subscripts += page.locator("sub").count()
        plots += page.locator(".js-plotly-plot").count()
        ticks = page.evaluate(TICKS)
        checked_ticks += len(ticks)
        cells = page.evaluate(NUMBER_CELLS)
        found = ([f"tick {tick!r}" for tick in ticks if "-" in tick or POINT_NUMBER.search(tick)]
                 + [f"cell {cell!r}" for cell in cells if DECIMAL_POINT.search(cell)]
                 + [f"hyphen {m.group(0)!r}" for m in HYPHEN_NUMBER.finditer(text)]
                 + [f"zero {m.group(0)!r}" for m in SIGNED_ZERO.finditer(text)])
        if found:
            problems[where] = found[:6]
        drawn(page)
        if scene["id"] in DYNAMICS_SCENES:          # the same page: every panel of the variant shown (test_dynamics)
            assert_variant_shows_all_its_panels(page, scene, variant)
        if scene["id"] in ELASTIC_SCENES:           # the same page: its answers complete (test_flywheel_elastic)
            assert_elastic_variant_answers(page, scene, variant, "ru")
        if name == "transfer_functions":            # the same page: its linkage and plots drawn (test_scene)
            assert_variant_draws_its_linkage_and_plots(page, variant)
        labels = label_problems(page.evaluate(DRAWN_LABELS))
        if labels:
            unreadable[where] = labels
        for _, _, panel, picture in (p for p in PICTURES if p[:2] == (name, variant["id"])):
            target = page.locator(f"#{panel}")
            target.scroll_into_view_if_needed()
            target.screenshot(path=ARTIFACTS / f"labels-{picture}.png")
        if variant is scene["variants"][0]:
            assert_speaks(page, name, scene, "ru")        # the scene words' checks, on this page (test_scene_words)
            english = english_on_the_page_after_its_studies(page, "ru")
    assert english == []
    assert underscores == {}
    assert unreadable == {}
    if scene["id"] in WITH_SUBSCRIPTS:               # its Russian texts write a subscript: shown as <sub>
        assert subscripts > 0
    assert problems == {}
    assert checked_ticks > 0 or plots == 0           # the ticks of every plot drawn were read
    if name == "flywheel":      # negative ticks exist and are written with U+2212 (the work A_Σ dips below zero)
        open_scene(page, scene, "ru")
        assert any(tick.startswith("−") for tick in page.evaluate(TICKS))
    assert page.problems == []


@pytest.mark.parametrize("name, panel, curve, symbol", [
    ("flywheel", "work", 2, "Σ"),                 # A_Σ at its lowest: a negative work, its subscript lowered
    ("transfer_functions", "u31", 0, "₃₁")])      # u₃₁ at its lowest
def test_hover_reads_in_the_textbooks_notation_with_comma_and_minus(browser_page, name, panel, curve, symbol):
    page = browser_page
    open_scene(page, read_scene(name), "ru")
    graph = f"#panel-{panel} .graph"
    page.locator(graph).scroll_into_view_if_needed()
    index = page.evaluate(f"""() => {{
        const y = document.querySelector("{graph}").data[{curve}].y;
        return y.indexOf(Math.min(...y)); }}""")
    page.evaluate(f"""i => Plotly.Fx.hover(document.querySelector("{graph}"), [{{curveNumber: {curve}, pointNumber: i}}])""",
                  index)
    page.wait_for_selector(f"{graph} .hoverlayer .hovertext")
    hover = page.evaluate(f"() => document.querySelector('{graph} .hoverlayer').textContent")
    assert symbol in hover and "_" not in hover
    assert re.search(r"−\d+(,\d+)?", hover), hover
    assert "-" not in hover and not POINT_NUMBER.search(hover)
    if symbol == "Σ":                                                     # the subscript Σ is lowered
        assert page.locator(f"{graph} .hoverlayer tspan[style*='baseline-shift'], "
                            f"{graph} .hoverlayer tspan[dy]").count() > 0
    assert page.problems == []


def test_the_page_reads_the_markup_as_the_server_does(browser_page):
    page = browser_page
    open_scene(page, read_scene("flywheel"), "ru")
    texts = sorted({text for _, _, text in STRINGS} | {"x_", "_y", "solve\\_ivp", "a_{}b", "ω_ср²", "R^{1/3})"})
    parts = page.evaluate("""async (texts) => {
        const src = document.querySelector('script[type="module"]').src.replace(/[^/]+$/, "../common/view/notation.js");
        const { notationParts } = await import(src);
        return texts.map((text) => notationParts(text).map((part) => [part.text, part.shift]));
    }""", texts)
    python = [[list(part) for part in notation_parts(text)] for text in texts]
    assert [t for t, js, py in zip(texts, parts, python) if js != py] == []


@pytest.mark.parametrize("name", ["flywheel", "forces_friction"])
@pytest.mark.parametrize("width", [1400, 390])
def test_screenshots_in_russian(chromium, app_url, name, width):
    """For a person to look at: the notation at desktop and phone width."""
    ARTIFACTS.mkdir(exist_ok=True)
    context = chromium.new_context(base_url=app_url, viewport={"width": width, "height": 900})
    page = context.new_page()
    open_scene(page, read_scene(name), "ru")
    assert page.locator("sub").count() > 0
    screenshot(page, f"notation_{name}_ru_{width}")
    context.close()
