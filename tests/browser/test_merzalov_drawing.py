"""The drilling rig's Merzalov construction as the drawing sheet has it (Lecture 10 §10.6, (L15)–(L24)), in
Russian and English: one SVG in the sheet's millimetres with the diagrams of M_д (y_M), the works (y_A) and
ΔT_I (y_ΔTI), the pole P with a ray per interval, its titles and axes written with the scales (μ_φ, μ_M, μ_A,
μ_ω in mm per unit, k₁ in mm); every ordinate drawn equals the ordinates table's mm value on the same page
within 0.5 mm; each ray is parallel to its chord of the driving work's curve; no console error, no English app
words on the Russian page. A screenshot of the panel each (test-artifacts/merzalov_drawing_<lang>.png)."""
from __future__ import annotations

import sys

import pytest

from conftest import ARTIFACTS, REPO, screenshot

sys.path.insert(0, str(REPO / "tests"))
from test_translations import english_in  # noqa: E402

pytestmark = pytest.mark.browser

PANEL = "#panel-merzalov_drawing"
TABLE = "#panel-merzalov_ordinates"
KEYS = {"y_M": "yM", "y_A": "yA", "y_dTI": "yΔTI"}      # the drawing's data-key → the table's column head, as read

READ_TABLE = """([table, keys]) => {
  const heads = [...document.querySelectorAll(table + ' thead th')].map((th) => th.innerText.trim());
  const SUP = { '⁻': '-', '⁰': '0', '¹': '1', '²': '2', '³': '3', '⁴': '4', '⁵': '5', '⁶': '6', '⁷': '7', '⁸': '8', '⁹': '9' };
  const number = (text) => {          // "−9,2001", "5,68·10⁻¹⁴" (formatQuantity's small numbers)
    const [mantissa, power] = text.trim().replace(/\\u2212/g, '-').replace(/\\s/g, '').replace(',', '.').split('·10');
    return Number(mantissa) * (power ? 10 ** Number([...power].map((c) => SUP[c]).join('')) : 1);
  };
  const rows = [...document.querySelectorAll(table + ' tbody tr')].map((tr) => [...tr.children].map((td) => td.innerText));
  return Object.fromEntries(Object.entries(keys).map(([key, head]) => {
    const column = heads.indexOf(head);
    return [key, rows.map((cells) => number(cells[column]))];
  }));
}"""

READ_DRAWING = """(panel) => {
  const lines = [...document.querySelectorAll(panel + ' line.ordinate')];
  const drawn = {};
  for (const line of lines) {
    const key = line.dataset.key;
    (drawn[key] ??= [])[Number(line.dataset.position)] = Number(line.getAttribute('y1')) - Number(line.getAttribute('y2'));
  }
  const rays = [...document.querySelectorAll(panel + ' line.ray')].map((line) =>
    ['x1', 'y1', 'x2', 'y2'].map((a) => Number(line.getAttribute(a))));
  const chord = document.querySelector(panel + ' polyline.y_A_d').getAttribute('points').trim().split(/\\s+/)
    .map((p) => p.split(',').map(Number));
  return { drawn, rays, chord, text: [...document.querySelectorAll(panel + ' svg text')].map((t) => t.textContent) };
}"""


@pytest.mark.parametrize("lang", ["ru", "en"])
def test_merzalov_sheet_drawn_to_scale(browser_page, lang):
    page = browser_page
    page.goto(f"/scenes/flywheel?lang={lang}&variant=rig")
    page.wait_for_selector(f"{PANEL}:not([hidden]) svg line.ordinate", state="attached", timeout=60000)
    page.wait_for_selector(f"{TABLE}:not([hidden]) tbody tr", timeout=60000)
    table = page.evaluate(READ_TABLE, [TABLE, KEYS])
    sheet = page.evaluate(READ_DRAWING, PANEL)
    for key in KEYS:
        assert len(sheet["drawn"][key]) == len(table[key]) == 13, (key, sheet["drawn"].get(key), table[key])
        for position, (drawn, tabled) in enumerate(zip(sheet["drawn"][key], table[key])):
            assert abs(drawn - tabled) <= 0.5, (key, position, drawn, tabled)
    assert len(sheet["rays"]) == 12
    for (x1, y1, x2, y2), (a, b) in zip(sheet["rays"], zip(sheet["chord"][:-1], sheet["chord"][1:])):
        ray, chord = (y2 - y1) / (x2 - x1), (b[1] - a[1]) / (b[0] - a[0])      # from the pole, along the curve
        assert abs(ray - chord) <= 1e-6 * max(1.0, abs(ray)), (ray, chord)
    text = " ".join(sheet["text"])
    mm = "мм" if lang == "ru" else "mm"
    for scale in ("μφ =", "μM =", "μA =", "μω =", "yΔTImax =", "k1 ="):      # the tspans of μ_φ, … as read
        assert scale in text, (scale, text)
    for unit in (f"{mm}/рад" if lang == "ru" else "mm/rad", f"{mm}/(Н·м)" if lang == "ru" else "mm/(N·m)",
                 f"{mm}/Дж" if lang == "ru" else "mm/J", f"40 {mm}"):
        assert unit in text, (unit, text)
    assert "NaN" not in page.inner_text("body") and "undefined" not in text
    if lang == "ru":
        assert english_in(page.inner_text("body"), "ru") == []
    page.locator(PANEL).scroll_into_view_if_needed()
    page.locator(PANEL).screenshot(path=ARTIFACTS / f"merzalov_drawing_{lang}.png")
    screenshot(page, f"merzalov_sheet_page_{lang}")
    assert page.problems == []
