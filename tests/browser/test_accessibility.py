"""Every student (accessibility) in a real browser.

Every scene is loaded once, on a phone (390 × 844, ru), and that one load serves all its checks:
- the phone screenshots in ru of test_devices and test_scene_words are taken of it;
- the page is no wider than the screen, and every table fits or scrolls sideways in a box of its own that the
  keyboard reaches and a screen reader names (test_screen_fit.table_problems); the bearings, wear and flywheel
  pages are photographed (test-artifacts/phone-*.png);
- axe-core (vendored from the npm registry in tests/browser/vendor/, injected by the test, never served by the
  app) finds no violation of any impact (the panels are headed h2 under the page's h1, so the headings do not
  skip a level);
- every curve drawn reaches 3:1 contrast against the plot's background (WCAG 2.1, 1.4.11), computed from the
  colour, stroke opacity and trace opacity Plotly actually drew, blended over the background it drew;
- the curves of one plot all differ by dash (so they differ by more than colour);
- every plot is an image named by its panel's title and described by a summary of its curves that holds their
  numbers, with a table of values a button shows;
- a course-project scene (kind "project") draws no plot by design: it shows a card per preset, headed by the
  preset's name, with its design data and a link to /project.
Then on the flywheel scene: the logarithmic slider [δ] announces its value as the page writes it and steps
by fractions of a decade from the keyboard; a plot's table of values holds the numbers Plotly draws.
"""
from __future__ import annotations

import itertools
import re

import pytest

from conftest import ARTIFACTS, REPO, read_scene, screenshot
from test_screen_fit import PHOTOGRAPHED, TABLES, fold_sheet, table_problems
from test_devices import PHONE_SCENES
from test_scene_words import PHONE_SHOTS, SEED

pytestmark = pytest.mark.browser

AXE = REPO / "tests" / "browser" / "vendor" / "axe.min.js"
SCENE_FILES = sorted(path.stem for path in (REPO / "content" / "scenes").glob("*.json"))
MIN_CONTRAST = 3.0          # WCAG 2.1 SC 1.4.11 for graphical objects needed to understand the content

# every line, bar and marker Plotly drew: its paint, the opacities on the way, the plot's background
DRAWN_TRACES = """() => [...document.querySelectorAll(".js-plotly-plot")].map((graph) => {
  const plane = [...graph.querySelectorAll(".plotbg path, rect.bg")]
    .find((node) => Number(getComputedStyle(node).fillOpacity) > 0);       // the paper is clear over the white card
  const background = plane ? getComputedStyle(plane).fill : "rgb(255, 255, 255)";
  const opacity = (node) => { let o = 1; for (let n = node; n && n !== graph; n = n.parentElement)
    o *= Number(getComputedStyle(n).opacity); return o; };
  const lines = [...graph.querySelectorAll("g.trace path.js-line")].filter((p) => p.getAttribute("d"))
    .map((p) => { const s = getComputedStyle(p); return { paint: s.stroke, alpha: opacity(p) * Number(s.strokeOpacity),
      dash: s.strokeDasharray, trace: p.closest("g.trace").getAttribute("class") }; });
  const bars = [...graph.querySelectorAll("g.trace.bars path")].map((p) => { const s = getComputedStyle(p);
    return { paint: s.fill, alpha: opacity(p) * Number(s.fillOpacity) }; });
  return { id: graph.closest("figure")?.id, background, lines, bars };
})"""
ALTERNATIVES = """() => [...document.querySelectorAll(".js-plotly-plot")].map((graph) => ({
  id: graph.closest("figure")?.id, role: graph.getAttribute("role"), name: graph.getAttribute("aria-label"),
  title: graph.closest("figure")?.querySelector("h2")?.textContent.trim(),
  summary: document.getElementById(graph.getAttribute("aria-describedby"))?.textContent ?? "",
  button: graph.closest("figure")?.querySelector(".plot-table-toggle")?.getAttribute("aria-controls") ?? null }))"""

# a course-project scene's cards: the preset's name, how many data it lists, its link to /project
PROJECT_CARDS = """() => [...document.querySelectorAll("#project-variants .project-variant")].map((card) => ({
  id: card.id, title: card.querySelector("h2")?.textContent ?? "", data: card.querySelectorAll("li").length,
  link: card.querySelector("a")?.getAttribute("href") ?? "" }))"""


def rgb(css: str) -> tuple[float, float, float]:
    """'rgb(31, 78, 121)' → (31, 78, 121)."""
    return tuple(float(v) for v in re.findall(r"[\d.]+", css)[:3])


def luminance(colour) -> float:
    """WCAG 2.1 relative luminance of an sRGB colour (0–255 channels)."""
    def linear(channel):
        c = channel / 255
        return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4
    r, g, b = (linear(c) for c in colour)
    return 0.2126 * r + 0.7152 * g + 0.0722 * b


def contrast(paint: str, alpha: float, background: str) -> float:
    """Contrast ratio of a paint drawn with opacity alpha over the background, as the eye sees the blend."""
    back = rgb(background)
    seen = [alpha * f + (1 - alpha) * b for f, b in zip(rgb(paint), back)]
    light, dark = sorted((luminance(seen), luminance(back)), reverse=True)
    return (light + 0.05) / (dark + 0.05)


def test_contrast_formula_matches_wcag_examples():
    """The formula against values WCAG's own tools give: black on white 21:1, #767676 on white 4.54:1."""
    assert contrast("rgb(0, 0, 0)", 1, "rgb(255, 255, 255)") == pytest.approx(21, abs=1e-9)
    assert contrast("rgb(118, 118, 118)", 1, "rgb(255, 255, 255)") == pytest.approx(4.54, abs=0.01)
    assert contrast("rgb(0, 0, 0)", 0.5, "rgb(255, 255, 255)") < contrast("rgb(0, 0, 0)", 1, "rgb(255, 255, 255)")


def settle(page) -> None:
    """Wait until the page has drawn what it asks for and described its plots."""
    page.wait_for_load_state("networkidle")
    page.wait_for_function("""() => [...document.querySelectorAll(".js-plotly-plot")].every((g) =>
        (document.getElementById(g.getAttribute("aria-describedby"))?.textContent ?? "") !== ""
        || g.closest("[hidden]"))""")


@pytest.mark.parametrize("name", SCENE_FILES)
def test_scene_on_a_phone_fits_and_reads_without_sight(phone, name):
    scene = read_scene(name)
    phone.goto(f"/scenes/{scene['id']}?lang=ru")
    settle(phone)
    assert phone.evaluate("document.documentElement.scrollWidth <= innerWidth"), \
        f"{name}: the page is {phone.evaluate('document.documentElement.scrollWidth')} px wide on a 390 px screen"
    assert table_problems(phone.evaluate(TABLES)) == [], name
    if name in PHONE_SCENES:              # what the phone shows, for a person to look at (test_devices: uk, en)
        phone.screenshot(path=ARTIFACTS / f"devices-{name}-ru-phone.png")
        screenshot(phone, f"devices-{name}-ru-phone-full")
    if name in PHONE_SHOTS:               # the scene's words at phone size (test_scene_words: desktop)
        screenshot(phone, f"scene_words_{name}_ru_phone")
        assert SEED.findall(phone.evaluate("() => document.body.innerText")) == []

    phone.add_script_tag(path=str(AXE))
    violations = phone.evaluate("""() => axe.run(document, { resultTypes: ["violations"] }).then((r) =>
        r.violations.map((v) => `${v.id} (${v.impact}): ${v.nodes.map((n) => n.target.join(" ")).slice(0, 3).join(", ")}`))""")
    assert violations == [], f"{name}: axe-core finds {violations}"
    if name in PHOTOGRAPHED:
        fold_sheet(phone)
        phone.screenshot(path=ARTIFACTS / f"phone-{name}.png", full_page=True)

    if scene.get("kind") == "project":
        cards = phone.evaluate(PROJECT_CARDS)
        presets = [variant["id"] for variant in scene["variants"] if not variant.get("address")]
        assert [card["id"] for card in cards] == [f"project-variant-{v}" for v in presets], f"{name}: {cards}"
        assert all(card["title"] and card["data"] and card["link"].startswith("/project?") for card in cards), cards
        assert phone.evaluate(DRAWN_TRACES) == [] and phone.problems == []
        return
    graphs = phone.evaluate(DRAWN_TRACES)
    assert graphs, f"{name}: no plot drawn"
    for graph in graphs:
        for trace in graph["lines"] + graph["bars"]:
            ratio = contrast(trace["paint"], trace["alpha"], graph["background"])
            assert ratio >= MIN_CONTRAST, f"{name} {graph['id']}: {trace} has contrast {ratio:.2f}"
        curves = {line["trace"]: line for line in graph["lines"]}     # a curve with gaps is several paths
        for a, b in itertools.combinations(curves.values(), 2):
            assert a["dash"] != b["dash"], f"{name} {graph['id']}: two curves drawn with the same dash {a['dash']}"

    for plot in phone.evaluate(ALTERNATIVES):
        if plot["summary"] == "" and plot["name"] is None:
            continue                                        # a hidden panel (the answer holds nothing for it)
        assert plot["role"] == "img" and plot["name"] == plot["title"], plot
        assert re.search(r"\d", plot["summary"]) and ":" in plot["summary"], plot
        assert plot["button"], f"{name} {plot['id']}: no table of values"
    assert phone.problems == []


def test_log_slider_announces_its_value_and_steps_by_decades(phone):
    """[δ] runs from 0,001 to 0,2 on a logarithmic slider: its aria-valuetext is the readout's text with the
    decimal comma; arrows step 1/20 of a decade, PageUp/PageDown 5 such steps, Home/End go to the ends.
    The plot of ω(φ)'s table of values holds the numbers Plotly was given (independent of the page's
    formatting: parsed back and compared within their 4 significant digits)."""
    phone.goto(f"/scenes/{read_scene('flywheel')['id']}?lang=ru")
    settle(phone)
    slider = phone.locator("#slider-delta")
    value = lambda: float(re.search(r"= ([\d,]+)", slider.get_attribute("aria-valuetext"))[1].replace(",", "."))
    assert re.fullmatch(r"\[δ\] = 0,0125", slider.get_attribute("aria-valuetext"))
    slider.focus()
    slider.press("Home")
    assert value() == 0.001
    for _ in range(20):                                     # one decade in 20 presses (was 250 and more)
        slider.press("ArrowRight")
    assert value() == pytest.approx(0.01, rel=1e-9)
    slider.press("ArrowLeft")
    assert value() == pytest.approx(10 ** -2.05, rel=5e-3)
    slider.press("PageUp")                                  # a quarter of a decade up from 10^-2.05
    assert value() == pytest.approx(10 ** -1.8, rel=5e-3)
    slider.press("End")
    assert value() == 0.2
    slider.press("ArrowRight")
    assert value() == 0.2
    assert phone.evaluate("document.getElementById('slider-delta').value") == "1000"
    settle(phone)

    button = phone.locator("#panel-speed .plot-table-toggle")
    button.scroll_into_view_if_needed()
    button.click()
    assert button.get_attribute("aria-expanded") == "true"
    shown = phone.evaluate("""() => {
      const graph = document.querySelector("#panel-speed .js-plotly-plot");
      const rows = [...document.querySelectorAll("#panel-speed .plot-table tbody tr")].map((row) =>
        [...row.children].map((cell) => cell.textContent));
      return { rows, x: graph.data[0].x, y: graph.data.map((trace) => trace.y) };
    }""")
    assert len(shown["rows"]) >= 20
    number = lambda text: float(text.replace("−", "-").replace(",", ".").replace("·10", "e").translate(
        str.maketrans("⁻⁰¹²³⁴⁵⁶⁷⁸⁹", "-0123456789")))
    xs = shown["x"]
    for row in shown["rows"]:
        i = min(range(len(xs)), key=lambda k: abs(xs[k] - number(row[0])))
        assert number(row[0]) == pytest.approx(xs[i], rel=1e-3, abs=1e-9)
        assert number(row[1]) == pytest.approx(shown["y"][0][i], rel=1e-3)
    assert phone.problems == []
