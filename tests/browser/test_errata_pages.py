"""The sources' misprints on screen, printed beside corrected, in the scenes whose formulas they touch; the
4φ-harmonic claim of Eremyants (2.17) under the spectrum of u′₃₁; Kuleshova–Tokhtar's method (a) beside (1)–(4).
One page load per scene, in Russian: the numbers shown, no English sentence of the app, a main slider dragged
changes the numbers, no console error; a screenshot each (test-artifacts/errata_<scene>_ru.png)."""
from __future__ import annotations

import sys

import pytest

from conftest import REPO, drag_slider, screenshot

sys.path.insert(0, str(REPO / "tests"))
from test_translations import english_in  # noqa: E402

pytestmark = pytest.mark.browser

ERRATA = "#panel-errata tbody"
# scene, variant, what holds the numbers, its rows (None: a caption), the slider dragged and where to
CASES = [
    ("reduced-inertia", "slider_crank", ERRATA, 2, "lambda", 0.1),
    ("resisting-moment", "slotted_link", ERRATA, 2, "lambda", 0.8),
    ("flywheel", "rig", ERRATA, 7, "delta", 0.5),
    ("forces-friction", "central", ERRATA, 5, "omega", 0.8),
    ("wear", "engine", ERRATA, 3, "p_max", 0.9),
    ("elastic-linkage", "dimensions", ERRATA, 1, "gear_ratio", 0.8),
    ("transfer-functions", "slider_crank", "#panel-harmonics_du31 .caption", None, "lambda", 0.6),
    ("angular-acceleration", "crank_slider", "#panel-method_a", None, "lam", 0.9),
]


@pytest.mark.parametrize("scene, variant, holder, rows, slider, fraction", CASES, ids=[c[0] for c in CASES])
def test_the_errata_show_in_russian_and_follow_the_slider(browser_page, scene, variant, holder, rows, slider,
                                                          fraction):
    page = browser_page
    page.goto(f"/scenes/{scene}?lang=ru&variant={variant}")
    page.wait_for_selector(holder, state="attached")
    page.locator(holder).scroll_into_view_if_needed()
    page.wait_for_function("sel => /\\d/.test(document.querySelector(sel)?.textContent ?? '')", arg=holder)
    if rows is not None:
        assert page.locator(f"{holder} tr").count() == rows
    before = page.inner_text(holder)
    if scene == "transfer-functions":
        assert "1/(4λ³)" in before and "1/(8λ³)" in before
    if scene == "angular-acceleration":
        names = page.evaluate("() => document.querySelector('#panel-components .graph').data.map(t => t.name)")
        assert any("(а)" in name for name in names)             # method (a)'s curve beside ε* + ε**
    parts = page.inner_text("#panel-parts") if scene == "elastic-linkage" else None    # compliances from dimensions
    drag_slider(page, f"#slider-{slider}", fraction)
    page.wait_for_function("([sel, before]) => document.querySelector(sel)?.innerText !== before",
                           arg=[holder, before])
    if parts is not None:       # the motor shaft's e_D reduced to the crank by the gear ratio's square (1.16)
        page.wait_for_function("before => document.querySelector('#panel-parts')?.innerText !== before", arg=parts)
    assert "NaN" not in page.inner_text("body")
    assert english_in(page.inner_text("body"), "ru") == []
    screenshot(page, f"errata_{scene}_ru")
    assert page.problems == []
