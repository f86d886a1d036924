"""The equation of motion driven by a free law M_д(φ₁) (Chaika–Vasylenko §3.4, step 9), its points edited on the
page in Russian, Ukrainian and English: a moment typed (with a decimal comma in Russian and Ukrainian) and a row
added each change ω(φ)'s plot; an angle beyond the turn, and one not beyond the angle before it, are refused by
the server, and the reason is said below the table (and in the notices) in the page's language, naming the row
and the bound in the page's numbers (decimal comma, degrees as the table shows them); the scene's points come
back with a button. A table with rows added or removed stays in the page's address: a reload shows the same
table and the same plot; an address whose table is malformed shows the scene's points. No console error but
the refused requests' own lines (Chromium logs every 422 answer of a fetch). Screenshots in test-artifacts/:
free_law_editor_<lang>.png (the angle beyond the turn), free_law_refused_page_<lang>.png (the angles not
increasing, the whole page) and free_law_page_<lang>.png (the scene's points back)."""
from __future__ import annotations

import re

import pytest

from conftest import ARTIFACTS, screenshot

pytestmark = pytest.mark.browser

PANEL = "#panel-free_law_points"
CURVE = "() => JSON.stringify(document.querySelector('#panel-omega_phi .graph')?.data?.[0]?.y ?? null)"
CHANGED = "before => JSON.stringify(document.querySelector('#panel-omega_phi .graph')?.data?.[0]?.y ?? null) !== before"
SAME = "after => JSON.stringify(document.querySelector('#panel-omega_phi .graph')?.data?.[0]?.y ?? null) === after"
PLOTTED = "() => document.querySelector('#panel-omega_phi .graph')?.data?.length > 0"
TABLE = f"() => [...document.querySelectorAll('{PANEL} tbody input')].map((input) => input.value)"
REFUSED_LOAD = "the server responded with a status of 422"
BEYOND = {"ru": "Сервер не принял таблицу. Точка 3: угол φ₁ должен быть не меньше 0° и меньше 360°.",
          "uk": "Сервер не прийняв таблицю. Точка 3: кут φ₁ має бути не меншим за 0° і меншим за 360°.",
          "en": "The server refused the table. Point 3: the angle φ₁ must be at least 0° and less than 360°."}
NOT_INCREASING = {"ru": "Точка 3: угол φ₁ должен быть больше 30,5° — угла точки 2",
                  "uk": "Точка 3: кут φ₁ має бути більшим за 30,5° — кут точки 2",
                  "en": "Point 3: the angle φ₁ must be greater than 30.5°, the angle of point 2"}
LATIN_WORD = re.compile(r"[A-Za-z]{2,}")


def open_scene(page, query: str = "lang=ru") -> None:
    page.goto(f"/scenes/equation-of-motion?{query}&variant=free_law")
    page.wait_for_selector(f"{PANEL}:not([hidden]) input.point-moment", timeout=60000)
    page.wait_for_function(PLOTTED, timeout=60000)


def type_into(page, kind: str, row: int, text: str) -> None:
    field = page.locator(f"{PANEL} input.point-{kind}").nth(row)
    field.fill(text)
    field.press("Enter")


def refusal(page) -> str:
    page.wait_for_selector(f"{PANEL} .free-law-refusal:not([hidden])", timeout=60000)
    return page.inner_text(f"{PANEL} .free-law-refusal")


@pytest.mark.parametrize("lang", ["ru", "uk", "en"])
def test_free_law_points_edited_on_the_page(browser_page, lang):
    page = browser_page
    comma = lang != "en"
    open_scene(page, f"lang={lang}")
    assert page.locator(f"{PANEL} tbody tr").count() == 12
    assert page.input_value(f"{PANEL} input.point-phi >> nth=1") == "30"

    before = page.evaluate(CURVE)
    type_into(page, "moment", 3, "150,5" if comma else "150.5")
    page.wait_for_function(CHANGED, arg=before, timeout=60000)

    before = page.evaluate(CURVE)
    page.click(f"{PANEL} button.add-point")
    assert page.locator(f"{PANEL} tbody tr").count() == 13
    assert page.input_value(f"{PANEL} input.point-phi >> nth=12") == "345"
    page.wait_for_function(CHANGED, arg=before, timeout=60000)
    assert page.locator(f"{PANEL} .free-law-refusal").is_hidden()

    type_into(page, "phi", 2, "400")
    reason = refusal(page)
    assert reason == BEYOND[lang], reason
    notice = page.inner_text("#notices")
    assert BEYOND[lang].split(". ", 1)[1] in notice, notice
    if lang != "en":
        assert not LATIN_WORD.search(reason + notice), reason + notice
    page.locator(PANEL).screenshot(path=ARTIFACTS / f"free_law_editor_{lang}.png")

    type_into(page, "phi", 1, "30,5" if comma else "30.5")
    type_into(page, "phi", 2, "20")
    page.wait_for_function(f"text => document.querySelector('{PANEL} .free-law-refusal').innerText.includes(text)",
                           arg=NOT_INCREASING[lang], timeout=60000)
    if lang != "en":
        assert not LATIN_WORD.search(refusal(page)), refusal(page)
    assert "NaN" not in page.inner_text("body")
    screenshot(page, f"free_law_refused_page_{lang}")

    page.click(f"{PANEL} button.reset")
    page.wait_for_selector(f"{PANEL} .free-law-refusal", state="hidden", timeout=60000)
    assert page.locator(f"{PANEL} tbody tr").count() == 12
    screenshot(page, f"free_law_page_{lang}")
    assert [p for p in page.problems if REFUSED_LOAD not in p] == [], page.problems


@pytest.mark.parametrize("change, rows", [("add", 13), ("remove", 10)])
def test_a_table_of_another_length_is_kept_by_a_reload(browser_page, change, rows):
    page = browser_page
    open_scene(page, "lang=uk")
    for _ in range(12 - rows if change == "remove" else rows - 12):
        before = page.evaluate(CURVE)
        page.click(f"{PANEL} button.{'remove-point' if change == 'remove' else 'add-point'} >> nth=0")
        page.wait_for_function(CHANGED, arg=before, timeout=60000)
    before = page.evaluate(CURVE)
    with page.expect_response(lambda answer: answer.request.method == "POST"
                              and "42.25" in (answer.request.post_data or ""), timeout=60000):
        type_into(page, "moment", 1, "42,25")
    page.wait_for_function(CHANGED, arg=before, timeout=60000)   # the exact answer of the typed table drawn
    page.wait_for_function("() => new URLSearchParams(location.search).get('edit.motor.table_moment')"
                           "?.split(',').includes('42.25')", timeout=60000)
    table, curve = page.evaluate(TABLE), page.evaluate(CURVE)
    assert len(table) == 2 * rows and "42,25" in table

    page.reload()
    page.wait_for_selector(f"{PANEL}:not([hidden]) input.point-moment", timeout=60000)
    page.wait_for_function(PLOTTED, timeout=60000)
    assert page.evaluate(TABLE) == table
    page.wait_for_function(SAME, arg=curve, timeout=60000)
    assert page.locator(f"{PANEL} .free-law-refusal").is_hidden()
    assert page.problems == []


@pytest.mark.parametrize("edits", [
    "edit.motor.table_phi=0,1,2&edit.motor.table_moment=1,2",           # a moment short
    "edit.motor.table_phi=0,2,1&edit.motor.table_moment=1,2,3",         # angles not increasing
    "edit.motor.table_phi=0,7&edit.motor.table_moment=1,2",             # beyond the turn
    "edit.motor.table_phi=0&edit.motor.table_moment=1",                 # one point
    "edit.motor.table_phi=0,x,2&edit.motor.table_moment=1,2,3",         # not a number
    "edit.motor.table_phi=0,0.5,1,1.5,2,2.5,3,3.5,4,4.5,5,7",           # the scene's length, the last beyond the turn
])
def test_a_malformed_table_in_the_address_gives_the_scenes_points(browser_page, edits):
    page = browser_page
    open_scene(page, f"lang=ru&{edits}")
    assert page.locator(f"{PANEL} tbody tr").count() == 12
    assert page.input_value(f"{PANEL} input.point-phi >> nth=1") == "30"
    assert page.locator(f"{PANEL} .free-law-refusal").is_hidden()
    assert page.inner_text("#notices").strip() == ""
    assert page.problems == []
