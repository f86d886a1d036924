"""The equation of motion driven by a free law M_д(φ₁) (Chaika–Vasylenko §3.4, step 9), its points edited on the
page in Russian and English: a moment typed (with a decimal comma in Russian) and a row added each change ω(φ)'s
plot; an angle beyond the turn is refused by the server, and its reason, naming motor.table_phi, is shown beside
the table; the scene's points come back with a button. No console error but the refused request's own line
(Chromium logs every 422 answer of a fetch). A screenshot each (test-artifacts/free_law_editor_<lang>.png)."""
from __future__ import annotations

import pytest

from conftest import ARTIFACTS, screenshot

pytestmark = pytest.mark.browser

PANEL = "#panel-free_law_points"
CURVE = "() => JSON.stringify(document.querySelector('#panel-omega_phi .graph')?.data?.[0]?.y ?? null)"
CHANGED = "before => JSON.stringify(document.querySelector('#panel-omega_phi .graph')?.data?.[0]?.y ?? null) !== before"
REFUSED_LOAD = "the server responded with a status of 422"


@pytest.mark.parametrize("lang", ["ru", "en"])
def test_free_law_points_edited_on_the_page(browser_page, lang):
    page = browser_page
    page.goto(f"/scenes/equation-of-motion?lang={lang}&variant=free_law")
    page.wait_for_selector(f"{PANEL}:not([hidden]) input.point-moment", timeout=60000)
    page.wait_for_function("() => document.querySelector('#panel-omega_phi .graph')?.data?.length > 0", timeout=60000)
    assert page.locator(f"{PANEL} tbody tr").count() == 12
    assert page.input_value(f"{PANEL} input.point-phi >> nth=1") == "30"

    before = page.evaluate(CURVE)
    moment = page.locator(f"{PANEL} input.point-moment").nth(3)
    moment.fill("150,5" if lang == "ru" else "150.5")
    moment.press("Enter")
    page.wait_for_function(CHANGED, arg=before, timeout=60000)

    before = page.evaluate(CURVE)
    page.click(f"{PANEL} button.add-point")
    assert page.locator(f"{PANEL} tbody tr").count() == 13
    assert page.input_value(f"{PANEL} input.point-phi >> nth=12") == "345"
    page.wait_for_function(CHANGED, arg=before, timeout=60000)
    assert page.locator(f"{PANEL} .free-law-refusal").is_hidden()

    angle = page.locator(f"{PANEL} input.point-phi").nth(2)
    angle.fill("400")
    angle.press("Enter")
    page.wait_for_selector(f"{PANEL} .free-law-refusal:not([hidden])", timeout=60000)
    reason = page.inner_text(f"{PANEL} .free-law-refusal")
    assert "motor.table_phi" in reason and ("таблицу" if lang == "ru" else "refused") in reason, reason
    assert "NaN" not in page.inner_text("body")
    page.locator(PANEL).screenshot(path=ARTIFACTS / f"free_law_editor_{lang}.png")

    page.click(f"{PANEL} button.reset")
    page.wait_for_selector(f"{PANEL} .free-law-refusal", state="hidden", timeout=60000)
    assert page.locator(f"{PANEL} tbody tr").count() == 12
    screenshot(page, f"free_law_page_{lang}")
    assert [p for p in page.problems if REFUSED_LOAD not in p] == [], page.problems
