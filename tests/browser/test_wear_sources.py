"""The wear scene's sources in a real browser, one opening of the Russian page: a material picked from Table 1.1
(a drop-down list) changes the bush's wear coefficient and its polar wear; the variant driven by the reaction
columns of the book's Table 4.3 shows the book's printed results beside the sums from its table, its misprints
and how it was summed; dragging the service life moves the distributions and the readouts. No English sentence
of the app, no console error; screenshots in ru at desktop and phone width."""
from __future__ import annotations

import json
import sys

import pytest

from conftest import REPO, drag_slider, read_scene, screenshot

sys.path.insert(0, str(REPO / "tests"))
from test_translations import english_in  # noqa: E402

pytestmark = pytest.mark.browser

SCENE = read_scene("wear")
GRAPH = "document.querySelector(`#panel-${id} .graph`)"


def series(page, panel: str, index: int, key: str) -> str:
    return page.evaluate(f"([id, i, key]) => JSON.stringify({GRAPH}.data[i][key])", [panel, index, key])


def changed(page, panel: str, index: int, key: str, before: str) -> None:
    page.wait_for_function(f"([id, i, key, before]) => {GRAPH}?.data?.[i] && "
                           f"JSON.stringify({GRAPH}.data[i][key]) !== before", arg=[panel, index, key, before])


def peak_reaches(page, panel: str, index: int, key: str, expected: float) -> None:
    """Wait until the trace's largest value is expected (rel 1e-3): the exact answer for the slider's final value,
    not a preview or the answer to a value the drag passed through."""
    page.wait_for_function(f"([id, i, key, expected]) => {{ const v = ({GRAPH}?.data?.[i]?.[key] ?? []).filter((x) => x !== null);"
                           " return v.length > 0 && Math.abs(Math.max(...v) - expected) <= 1e-3 * expected; }",
                           arg=[panel, index, key, expected])


def text_changed(page, selector: str, before: str) -> None:
    page.wait_for_function("([s, before]) => document.querySelector(s)?.innerText !== before", arg=[selector, before])


def test_a_material_and_the_books_table_drive_the_wear(browser_page):
    page = browser_page
    page.goto("/scenes/wear?lang=ru")
    table = next(v for v in SCENE["variants"] if v["id"] == "table_4_3")   # the others: engine (default), shaping
    page.wait_for_function(f"id => {GRAPH}?.data?.length === 2", arg="joint")
    page.wait_for_function("() => document.querySelector('#panel-coefficients')?.innerText.includes('·10')")
    bush_before, k_before = series(page, "joint", 1, "r"), page.inner_text("#panel-coefficients")
    options = page.locator("#toggle-bush option")
    assert options.count() == 7 and "бронза" in options.nth(0).inner_text()
    page.select_option("#toggle-bush", index=1)                # ICE bush, bronze: I_s ≈ 4·10⁻¹⁰ (was 1·10⁻¹⁰)
    changed(page, "joint", 1, "r", bush_before)
    text_changed(page, "#panel-coefficients", k_before)
    peak = lambda r: max(v for v in json.loads(r) if v is not None)
    peak_reaches(page, "joint", 1, "r", 4 * peak(bush_before))        # δ ∝ I_s

    page.select_option("#variant", table["id"])
    page.wait_for_function("() => document.querySelectorAll('#panel-comparison tbody tr').length === 4")
    page.wait_for_function(f"id => {GRAPH}?.data?.length > 0", arg="cylinder")
    printed = page.locator("#panel-comparison tbody tr td:nth-child(2)").all_inner_texts()
    assert [float(p.replace(",", ".")) for p in printed] == [88, 36, 76, 43]
    assert page.locator("#panel-errata tbody tr").count() == 7
    assert page.locator("#panel-numerics").inner_text().strip()
    page.wait_for_function(f"id => {GRAPH}?.data?.length === 2", arg="joint")
    cylinder_before, points_before = series(page, "cylinder", 0, "y"), page.inner_text("#panel-book_points")
    joint_before = series(page, "joint", 1, "r")
    constant_before = page.inner_text("#panel-constant")        # the constant-load models (4.3)–(4.4), (4.14)–(4.15)
    assert constant_before.count("(4.") == 4
    drag_slider(page, "#slider-hours", 1.0)                    # 1000 h → 5000 h
    changed(page, "cylinder", 0, "y", cylinder_before)
    text_changed(page, "#panel-book_points", points_before)
    text_changed(page, "#panel-constant", constant_before)     # the wear of (4.14), (4.15) grows with the hours
    hours = float(page.input_value("#slider-hours"))
    assert hours > 4000
    peak_reaches(page, "cylinder", 0, "y", hours / 1000 * peak(cylinder_before))           # δ ∝ hours
    page.locator("#panel-joint").scroll_into_view_if_needed()
    changed(page, "joint", 1, "r", joint_before)
    peak_reaches(page, "joint", 1, "r", hours / 1000 * peak(joint_before))
    radial = page.evaluate(f"id => {GRAPH}._fullLayout.polar.radialaxis.range[1]", "joint")
    assert radial >= peak(series(page, "joint", 1, "r"))         # the whole distribution is drawn
    frame = page.locator("#panel-wear_classes .table-frame")    # the book's reference table: named in plain text
    assert frame.get_attribute("role") == "region" and frame.get_attribute("tabindex") == "0"
    assert frame.get_attribute("aria-label") and not set("_^") & set(frame.get_attribute("aria-label"))
    marked = page.evaluate("""async () => {                    // a title with markup, as a scene may write one
        const src = document.querySelector('script[type=module][src*="_scene.js"]').src;
        const { ReferenceTableView } = await import(new URL("../dynamics/view/reference_table_view.js", src));
        const body = document.createElement("div");
        new ReferenceTableView(body, { title: { ru: "I_м и M_{с0}^пр" }, columns: [], rows: [] }, { lang: "ru" });
        return body.querySelector(".table-frame").getAttribute("aria-label");
    }""")
    assert marked == "Iм и Mс₀пр"
    body = page.inner_text("body")
    assert "NaN" not in body and english_in(body, "ru") == []
    screenshot(page, "wear_table_4_3_ru")
    page.set_viewport_size({"width": 390, "height": 844})
    page.wait_for_function(f"id => {GRAPH}?.data?.length === 2", arg="joint")
    screenshot(page, "wear_table_4_3_ru_phone")
    assert page.problems == []
