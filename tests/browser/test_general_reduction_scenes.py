"""The shaping machine (a six-bar of content/mechanisms) in the two reduction scenes in a real browser, in ru: the
reduced moment of inertia drawn link by link (one series per link of /reduction's inertia.parts, labelled
"звено k" by the panel's series_each words) and the resisting moment load by load; a dragged mass slider changes
J (or M_с) and that link's (or the weights') share, and no other share. No console problems; the ru page shows
no English words, neither the app's sentences (test_translations.english_in) nor the answer's keys ("link 3",
"force E/ram", "gravity", "constant"). Screenshots in ru at desktop and phone width."""
from __future__ import annotations

import re
import sys
from pathlib import Path

import pytest

from conftest import SCREEN_TEXT, drag_slider, families_arrived, plot_text, read_scene, screenshot, shown
from test_dynamics import GRAPH, figure_value, open_scene, trace, wait_for_new_trace

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from test_translations import english_in  # noqa: E402

pytestmark = pytest.mark.browser

INERTIA = read_scene("reduced_inertia")
RESISTING = read_scene("resisting_moment")
LINKS = [f"звено {k}" for k in (2, 3, 4, 5)]
ANSWER_KEYS = re.compile(r"\b(?:link|force|gravity|constant|moment)\b")


def names(page, panel: str) -> list[str]:
    return page.evaluate(f"id => {GRAPH}.data.map(d => d.name)", panel)


def traces(page, panel: str) -> dict[str, str]:
    return {name: trace(page, panel, name) for name in names(page, panel)}


def wait_until_unchanged(page, panel: str, before: dict[str, str]) -> None:
    """Until each of the panel's traces named in before shows exactly its values before (the exact answer drawn,
    not a family's preview of it)."""
    page.wait_for_function(f"""([id, before]) => {{
        const data = {GRAPH}?.data ?? [];
        return Object.entries(before).every(([name, y]) => JSON.stringify(data.find(t => t.name === name)?.y) === y);
    }}""", arg=[panel, before])


def no_english(page) -> None:
    text = page.evaluate(SCREEN_TEXT)
    assert english_in(text, "ru") == []
    assert ANSWER_KEYS.findall(text) == []
    assert "NaN" not in page.inner_html("#panels")


def phone_screenshot(page, panel: str, name: str) -> None:
    """At phone width, the parameters' sheet folded so that it hides no panel."""
    page.set_viewport_size({"width": 390, "height": 844})
    page.click(".sheet-toggle")
    page.wait_for_selector(".sheet-toggle[aria-expanded=false]")
    page.locator(f"#panel-{panel}").scroll_into_view_if_needed()
    page.wait_for_function(f"id => {GRAPH}.getBoundingClientRect().width < 390", arg=panel)   # Plotly resized
    screenshot(page, name)


def number(text: str) -> float:
    return float(text.split()[0].replace(",", ".").replace("\u2212", "-"))


def test_shaping_machine_reduced_inertia_link_by_link(browser_page):
    page = browser_page
    open_scene(page, INERTIA, "ru", variant="shaping")
    words = INERTIA["panels"]["link_parts"]["series_each"]["words"]
    assert names(page, "link_parts") == [plot_text(words["constant"]["ru"])] + LINKS
    assert names(page, "link_slopes") == [INERTIA["panels"]["link_slopes"]["series_each"]["words"]["constant"]["ru"]] + LINKS
    said = page.evaluate("""async (panel) => {      // the same keys said in uk and en by the page's own module
      const entry = document.querySelector('script[type="module"][src*="_scene.js"]').src;
      const { heldSeries } = await import(new URL("../dynamics/view/dynamics_figures.js", entry));
      const data = { inertia: { parts: { constant: [1], "link 2": [1], "link 5": [1] } } };
      return heldSeries(panel, data).map((series) => [series.label.uk, series.label.en]);
    }""", INERTIA["panels"]["link_parts"])
    assert said == [[words["constant"]["uk"], words["constant"]["en"]], ["ланка 2", "link 2"], ["ланка 5", "link 5"]]
    exact = shown(INERTIA["panels"]["general_inertia"]["series"][0]["label"]["ru"])
    mean_label = shown(INERTIA["panels"]["figures"]["items"][0]["label"]["ru"])
    J, parts, mean = trace(page, "general_inertia", exact), traces(page, "link_parts"), figure_value(page, mean_label)
    others = {name: y for name, y in parts.items() if name != "звено 3"}

    drag_slider(page, "#slider-m3", 0.8)                    # a heavier rocker (link 3): its share and J grow
    wait_for_new_trace(page, "link_parts", parts["звено 3"], name="звено 3")
    wait_for_new_trace(page, "general_inertia", J, name=exact)
    families_arrived(page)
    wait_until_unchanged(page, "link_parts", others)        # the crank's, links 2, 4 and 5's shares as they were
    page.wait_for_function("""([label, before]) => [...document.querySelectorAll('.figures-list dt')]
        .find(dt => dt.textContent === label)?.nextElementSibling.textContent !== before""", arg=[mean_label, mean])
    assert number(figure_value(page, mean_label)) > number(mean)
    assert float(page.input_value("#slider-m3")) > 11
    no_english(page)
    screenshot(page, "general_reduced_inertia_shaping_ru")
    phone_screenshot(page, "link_parts", "general_reduced_inertia_shaping_ru_phone")
    assert page.problems == []


def test_shaping_machine_resisting_moment_load_by_load(browser_page):
    page = browser_page
    open_scene(page, RESISTING, "ru", variant="shaping")
    words = RESISTING["panels"]["load_parts"]["series_each"]["words"]
    force, gravity = words["force E/ram"]["ru"], words["gravity"]["ru"]
    assert names(page, "load_parts") == [force, gravity]
    total = shown(RESISTING["panels"]["general_moment"]["series"][0]["label"]["ru"])
    M, parts = trace(page, "general_moment", total), traces(page, "load_parts")

    drag_slider(page, "#slider-m3", 0.1)                    # a lighter rocker: the weights' share changes
    wait_for_new_trace(page, "load_parts", parts[gravity], name=gravity)
    wait_for_new_trace(page, "general_moment", M, name=total)
    families_arrived(page)
    wait_until_unchanged(page, "load_parts", {force: parts[force]})     # the cutting force's share as it was
    no_english(page)
    screenshot(page, "general_resisting_moment_shaping_ru")
    phone_screenshot(page, "load_parts", "general_resisting_moment_shaping_ru_phone")
    assert page.problems == []
