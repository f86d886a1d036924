"""The sources' numbers the app shows beside its own, on screen in Russian and English: Chaika–Vasylenko
Fig. 4.7's maxima on the wear scene (Table 4.3 variant) with the note saying why they are half of ours, and
Eremyants (3.34) beside (3.33) on the resisting-moment scene (crank-slider).  No English app words on the Russian
page, no console error; a screenshot each (test-artifacts/sources_<scene>_<lang>.png)."""
from __future__ import annotations

import sys

import pytest

from conftest import REPO, screenshot

sys.path.insert(0, str(REPO / "tests"))
from test_translations import english_in  # noqa: E402

pytestmark = pytest.mark.browser

CASES = [("wear", "table_4_3", "#panel-figure_4_7", ("68", "59", "36", "69,0", "58,8")),
         ("resisting-moment", "slider_crank", "#panel-viscous", ("(3.34)", "(3.33)"))]


@pytest.mark.parametrize("lang", ["ru", "en"])
@pytest.mark.parametrize("scene, variant, panel, expected", CASES, ids=[c[0] for c in CASES])
def test_sources_numbers_beside_ours(browser_page, scene, variant, panel, expected, lang):
    page = browser_page
    page.goto(f"/scenes/{scene}?lang={lang}&variant={variant}")
    page.wait_for_selector(f"{panel}:not([hidden])")
    page.locator(panel).scroll_into_view_if_needed()
    page.wait_for_function("sel => /\\d/.test(document.querySelector(sel)?.innerText ?? '')", arg=panel)
    if scene == "resisting-moment":
        page.wait_for_function("sel => document.querySelector(sel + ' .graph')?.data?.length === 2", arg=panel)
    text = page.inner_text(panel)
    for number in expected:
        assert (number if lang == "ru" else number.replace(",", ".")) in text, text
    assert page.locator(f"{panel} p.note").count() == 1
    if lang == "ru":
        assert english_in(page.inner_text("body"), "ru") == []
    assert "NaN" not in page.inner_text("body")
    screenshot(page, f"sources_{scene}_{lang}")
    assert page.problems == []


@pytest.mark.parametrize("lang", ["ru", "en"])
def test_elastic_four_bar_shows_its_grashof_class(browser_page, lang):
    """Drakunov–Tuleshova's four-bar: the class in words and the inequality's numbers, 1,3 < 1,8."""
    page = browser_page
    page.goto(f"/scenes/elastic-four-bar?lang={lang}")
    panel = "#panel-grashof"
    page.wait_for_selector(f"{panel}:not([hidden])", timeout=60000)
    page.wait_for_function("sel => /\\d/.test(document.querySelector(sel)?.innerText ?? '')", arg=panel)
    text = page.inner_text(panel)
    assert ("кривошипно-коромысловый" if lang == "ru" else "crank-rocker") in text
    assert ("1,3" if lang == "ru" else "1.3") in text and ("1,8" if lang == "ru" else "1.8") in text and "<" in text
    assert "crank_rocker" not in text
    screenshot(page, f"sources_grashof_{lang}")
    assert page.problems == []


def test_flywheel_sheet_tables_in_russian(browser_page):
    """The drilling rig's Merzalov sheet: the scales in Russian units and the 13 rows of ordinates."""
    page = browser_page
    page.goto("/scenes/flywheel?lang=ru&variant=rig")
    page.wait_for_selector("#panel-merzalov_ordinates:not([hidden])", timeout=60000)
    page.locator("#panel-merzalov_scales").scroll_into_view_if_needed()
    scales = page.inner_text("#panel-merzalov_scales")
    assert "мм/Дж" in scales and "(L19)" in scales and "mm/" not in scales
    assert page.locator("#panel-merzalov_ordinates tbody tr").count() == 13
    assert english_in(page.inner_text("body"), "ru") == []
    screenshot(page, "sources_merzalov_sheet_ru")
    assert page.problems == []


def test_free_law_variant_draws_its_speed(browser_page):
    """The equation of motion driven by a free law M_d(φ₁) of 12 points: ω(φ) drawn, no console error."""
    page = browser_page
    page.goto("/scenes/equation-of-motion?lang=uk&variant=free_law")
    page.wait_for_function("() => document.querySelector('#panel-omega_phi .graph')?.data?.length > 0", timeout=60000)
    assert "NaN" not in page.inner_text("body")
    assert english_in(page.inner_text("body"), "uk") == []
    screenshot(page, "sources_free_law_uk")
    assert page.problems == []


def test_shaping_machine_pairs_wear_in_russian(browser_page):
    """The wear of every pair of the shaping machine: 14 rows, elements in Russian, no console error."""
    page = browser_page
    page.goto("/scenes/wear?lang=ru&variant=shaping")
    page.wait_for_selector("#panel-pairs_wear:not([hidden])", timeout=60000)
    assert page.locator("#panel-pairs_wear tbody tr").count() == 14
    text = page.inner_text("#panel-pairs_wear")
    assert "цапфа" in text and "втулка" in text and "ползун" in text and "journal" not in text
    assert english_in(page.inner_text("body"), "ru") == []
    screenshot(page, "sources_pairs_wear_ru")
    assert page.problems == []
