"""The words and symbols of every scene as a reader sees them, in ru, uk and en, in a real browser (the ru pages
of the scenes are checked on test_notation's walk, which opens them anyway: assert_speaks):
- a ru/uk page shows no English sentence of the app's own strings (test_translations.english_in: the en texts
  of content/i18n that ru/uk do not write themselves), /measurements included, whose study plots (drawn by the
  page from their tables' points) say no Latin word but the solvers' names and write a decimal comma;
- no page names a source by its file: the word "seed" is nowhere on screen;
- the labels of its drawings apart and inside them at the scene's default state (test_label_overlaps'
  label_problems; every variant in ru: test_notation);
- one notation per quantity: the page's text read back into markup (<sub> as _{…}, <sup> as ^{…}, the shifted
  <tspan>s of drawings and plots alike) holds no other form of a quantity than tests/notation.json's, and the
  list of the forms each scene shows is written to test-artifacts/scene_notation_<scene>_<lang>.json;
- the short intros fold the sources' details (wear, angular acceleration).
Screenshots of four scenes in ru and en at desktop width and of two in ru at phone size (390 × 844, taken on
test_accessibility's phone page) go to
test-artifacts/ (scene_words_*.png), /measurements in ru, uk and en to measurements_<lang>.png.
"""
from __future__ import annotations

import json
import re
import sys

import pytest

from conftest import ARTIFACTS, REPO, SCREEN_TEXT, interface_texts, read_scene, screenshot

sys.path.insert(0, str(REPO / "tests"))
from test_notation_forms import NOTATION, other_forms  # noqa: E402  (the one list, read as the API test reads it)
from test_translations import english_in  # noqa: E402
from test_label_overlaps import DRAWN_LABELS, label_problems  # noqa: E402
from test_label_overlaps import settle as drawn  # noqa: E402

pytestmark = pytest.mark.browser

SCENE_FILES = sorted(path.stem for path in (REPO / "content" / "scenes").glob("*.json"))
LANGUAGES = ("ru", "uk", "en")
SCENE_LANGUAGES = ("uk", "en")      # ru: test_notation's walk calls assert_speaks on its default variant's page
SHOTS = {"flywheel", "resisting_moment", "bearings", "wear"}        # desktop in ru and en
PHONE_SHOTS = ("flywheel", "wear")       # ru at 390 × 844, on test_accessibility's phone page of the scene
SEED = re.compile(r"\bseeds?\b", re.IGNORECASE)

# Every text on screen read back into the notation markup: <sub>/<sup> in the page, in a drawing or a plot the
# smaller <tspan>s moved by dy (down: a subscript, up: a superscript, no dy: as the run before). The errata
# panels (a book's printed forms quoted beside the corrected ones) are left out.
MARKUP = r"""() => {
  const skip = (el) => el.closest("script, style, template, .printed, [class*='printed'], [id*='errata'], [hidden]");
  const out = [];
  const walk = (node) => {
    for (const child of node.childNodes) {
      if (child.nodeType === Node.TEXT_NODE) { out.push(child.textContent); continue; }
      if (child.nodeType !== Node.ELEMENT_NODE || skip(child)) continue;
      const tag = child.tagName.toLowerCase();
      if (tag === "sub" || tag === "sup") { out.push((tag === "sub" ? "_{" : "^{") + child.textContent + "}"); continue; }
      if (tag === "text") { out.push(" " + svgText(child) + " "); continue; }
      if (["p", "div", "li", "td", "th", "h1", "h2", "h3", "dt", "dd", "label", "summary", "figcaption", "br"].includes(tag))
        out.push("\n");
      walk(child);
    }
  };
  const svgText = (text) => {
    const spans = [...text.querySelectorAll("tspan")].filter((s) => !s.querySelector("tspan"));
    if (!spans.length) return text.textContent;
    let level = 0, shift = "";
    return spans.map((span) => {
      const dy = parseFloat(span.getAttribute("dy") || "0");
      const small = /font-size/.test(span.getAttribute("style") || "") || span.hasAttribute("font-size");
      if (!small) { level = 0; shift = ""; return span.textContent; }
      if (dy > 0) shift = "sub"; else if (dy < 0) shift = "sup";
      return span.textContent.trim() ? (shift === "sup" ? "^{" : "_{") + span.textContent + "}" : "";
    }).join("");
  };
  walk(document.body);
  return out.join("");
}"""


def settle(page) -> None:
    page.wait_for_load_state("networkidle")
    page.wait_for_timeout(300)
    page.wait_for_load_state("networkidle")


def forms_shown(markup: str, lang: str) -> list[str]:
    """The list's quantities whose form the page shows."""
    return sorted({entry["quantity"] for entry in NOTATION if entry["forms"][lang] in markup})


def assert_speaks(page, name: str, scene: dict, lang: str) -> None:
    """The scene's page in `lang`, open and drawn at its default state: the labels of its drawings apart, no
    "seed", no English sentence in ru/uk, one form per quantity; the forms it shows written to
    test-artifacts/scene_notation_<scene>_<lang>.json, and a screenshot of the SHOTS in ru and en."""
    assert label_problems(page.evaluate(DRAWN_LABELS)) == [], lang
    text = page.evaluate(SCREEN_TEXT)
    markup = page.evaluate(MARKUP)
    assert SEED.findall(text) == [], lang
    if lang != "en":
        assert english_in(text, lang) == [], lang
    assert other_forms(markup, lang, scene["id"]) == [], lang
    (ARTIFACTS / f"scene_notation_{name}_{lang}.json").write_text(
        json.dumps(forms_shown(markup, lang), ensure_ascii=False, indent=1), "utf-8")
    if name in SHOTS and lang in ("ru", "en"):
        screenshot(page, f"scene_words_{name}_{lang}")


@pytest.mark.parametrize("name", SCENE_FILES)
def test_every_scene_speaks_the_readers_language_names_no_seed_and_writes_one_form_per_quantity(browser_page, name):
    """In uk and en here; in ru on the notation walk's page of the default variant (test_notation), which opens
    that page anyway."""
    page = browser_page
    scene = read_scene(name)
    for lang in SCENE_LANGUAGES:
        page.goto(f"/scenes/{scene['id']}?lang={lang}")
        drawn(page)
        assert_speaks(page, name, scene, lang)
    assert page.problems == []


# Each study's plot on /measurements as drawn: its SVG texts (legend, axis titles, ticks), and per trace the
# method's name as the legend writes it and the markers drawn, beside the rows of the study's table.
STUDY_PLOTS = r"""() => {
const read = (node) => {                     // a text as read: the lines of a long legend name joined by a space
  const lines = [...node.querySelectorAll('tspan.line')].map((line) => line.textContent);
  return lines.length ? lines.join(' ') : node.textContent;
};
return [...document.querySelectorAll('.measurements [data-figure]')].map((graph) => {
  let table = graph.closest('figure');
  while (table && table.tagName !== 'TABLE') table = table.nextElementSibling;
  const traces = [...graph.querySelectorAll('.scatterlayer .trace')];
  return {
    texts: [...graph.querySelectorAll('.main-svg text')].map(read),
    legend: [...graph.querySelectorAll('.legend .legendtext')].map(read),
    x_title: graph.querySelector('.xtitle')?.textContent, y_title: graph.querySelector('.ytitle')?.textContent,
    points: traces.map((trace) => trace.querySelectorAll('.points .point').length),
    rows: table ? [...table.querySelectorAll('tbody tr')].map((row) => row.cells[0].textContent) : [],
  };
});
}"""
PROPER_NAMES = {"RK45", "DOP853", "Radau", "LSODA", "SciPy", "BDF"}     # the solvers' own names, said as is


def latin_words(text: str) -> list[str]:
    """Runs of Latin letters and digits with two letters or more ("RK4", "ms"), the solvers' names left out."""
    return [run for run in re.findall(r"[A-Za-z0-9]+", text)
            if len(re.findall(r"[A-Za-z]", run)) >= 2 and run not in PROPER_NAMES]


@pytest.mark.parametrize("lang", LANGUAGES)
def test_the_measurements_page_speaks_the_readers_language(browser_page, lang):
    """/measurements in the reader's words, its six studies' plots drawn by the page (plotly.js) from the points
    of their tables: legend and axis titles in lang (in ru/uk no Latin word but the solvers' names, a decimal
    comma), every method one trace with a marker per row of the table; a marker's hover text says its row's method
    and tolerance as the table writes them. Screenshot measurements_<lang>.png."""
    page = browser_page
    texts = interface_texts(lang)
    page.goto(f"/measurements?lang={lang}")
    assert page.locator(".measurements [data-figure]").count() == 6
    page.wait_for_function("() => document.querySelectorAll('.measurements [data-figure][data-drawn]').length === 6")
    settle(page)
    text = page.evaluate("() => document.body.innerText")
    if lang != "en":
        assert english_in(text, lang) == []
        assert not re.search(r"\b(?:Reference|Fastest|ours|interactive|tolerance|Elastic|Flywheel)\b", text)
    assert SEED.findall(text) == []
    assert page.locator("article.measurements img").count() == 0
    plots = page.evaluate(STUDY_PLOTS)
    for plot in plots:
        assert (plot["x_title"], plot["y_title"]) == (texts["measurements_axis_run_time"], texts["measurements_axis_error"])
        methods = list(dict.fromkeys(plot["rows"]))
        assert plot["legend"] == methods and len(methods) >= 4
        assert plot["points"] == [plot["rows"].count(method) for method in methods]
    said = "\n".join(text for plot in plots for text in plot["texts"])
    if lang == "en":
        assert texts["measurements_method_shooting"] in said and re.search(r"\d\.\d", said)
    else:
        assert latin_words(said) == []
        assert not re.search(r"\d\.\d", said) and re.search(r"\d,\d", said)   # "2,5" in a method's name
    first = page.locator(".measurements [data-figure]").first
    first.scroll_into_view_if_needed()
    marker = first.locator(".scatterlayer .trace .points .point").first.bounding_box()
    page.mouse.move(marker["x"] + marker["width"] / 2, marker["y"] + marker["height"] / 2)
    page.wait_for_function("() => document.querySelector('.measurements .hoverlayer .hovertext')")
    hover = first.locator(".hoverlayer .hovertext").first.text_content()
    row = page.locator(".measurements table").first.locator("tbody tr").first.locator("td")
    assert f"{texts['measurements_column_tolerance']}: {row.nth(1).text_content()}" in hover   # "Допуск: 0,001"
    assert row.nth(0).text_content() in hover
    if lang != "en":
        assert latin_words(hover) == [] and not re.search(r"\d\.\d", hover)
    page.mouse.move(0, 0)
    screenshot(page, f"measurements_{lang}")
    assert page.problems == []


@pytest.mark.parametrize("name", ["wear", "angular_acceleration"])
def test_the_short_intro_comes_first_and_the_sources_details_open_on_demand(browser_page, name):
    page = browser_page
    scene = read_scene(name)
    page.goto(f"/scenes/{scene['id']}?lang=ru")
    settle(page)
    folded = page.locator("#intro-details > p")
    assert not folded.is_visible()
    page.locator("#intro-details > summary").click()
    assert folded.is_visible()
    assert page.locator(".intro > p").first.inner_text().startswith(scene["text"]["ru"][:20])


