"""A force at a point of a link in the editor's "Masses and loads", in a real browser: on the shaping machine's preset
(Russian page) the student adds a force at a point of the ram (link 5), puts it at the tool's point K (0,1 m along,
−0,05 m across), P = 3000 N, α = 0° from +x (the cutting resistance, against the ram's working stroke along −x),
on the working stroke; the address's d and every dynamics scene's link keep it as the API takes it (SI: α in
rad); the resisting-moment scene opened from the editor draws its part "force K" beside the others without a
notice; back in the editor, removing it takes it out of the address. No console errors; a screenshot of the table in ru (test-artifacts/editor_point_force_ru.png)."""
from __future__ import annotations

import base64
import json
from urllib.parse import parse_qs, urlsplit

import pytest

from conftest import ARTIFACTS, screenshot
from test_editor import act, number
from test_own_mechanism_dynamics import MOMENT, open_from_editor

pytestmark = pytest.mark.browser

TOOL = {"link": 5, "point": [0.1, -0.05], "name": "K", "magnitude": 3000.0,
        "direction": {"kind": "fixed", "angle": 0.0}, "acts": "working"}
ROW = "masses.point_forces.0"


def dynamics_in(address: str) -> dict:
    """The dynamics an address carries in d (base64url JSON)."""
    encoded = parse_qs(urlsplit(address).query)["d"][0]
    return json.loads(base64.urlsafe_b64decode(encoded + "=" * (-len(encoded) % 4)))


def typed(page, path: str, text: str) -> None:
    """Type text into the cell at path and leave it (the table takes a cell's text on leaving it)."""
    cell = f'#editor-masses-points input[data-path="{path}"]'
    page.fill(cell, text)
    page.press(cell, "Tab")


def test_a_force_at_the_tool_point_is_kept_in_the_address(browser_page):
    page = browser_page
    page.goto("/editor?lang=ru")
    page.wait_for_function("() => document.querySelector('#editor-drawing')?.dataset.state !== undefined")
    act(page, lambda: page.select_option("#editor-preset", "shaping_machine"))
    page.wait_for_function("() => document.querySelector('#editor-open-dynamics a[data-scene]') !== null",
                           timeout=30_000)
    assert page.locator("#editor-masses-points").count() == 0             # the preset has none
    page.select_option("#editor-load-place", "point:5")
    page.click("#editor-load-add")
    page.wait_for_selector("#editor-masses-points")
    assert page.input_value(f'input[data-path="{ROW}.direction.angle"]') == "180"   # the new one: along −x, in °
    page.fill(f'input[data-path="{ROW}.name"]', "K")
    page.press(f'input[data-path="{ROW}.name"]', "Tab")
    typed(page, f"{ROW}.point.0", "0,1")
    typed(page, f"{ROW}.point.1", "−0,05")
    typed(page, f"{ROW}.magnitude", "3000")
    typed(page, f"{ROW}.direction.angle", "0")
    assert page.input_value(f'select[data-path="{ROW}.direction.kind"]') == "fixed"
    assert page.input_value(f'select[data-path="{ROW}.acts"]') == "working"
    page.wait_for_function("""() => { const d = new URLSearchParams(location.search).get('d');
        const f = d && JSON.parse(atob(d.replace(/-/g, '+').replace(/_/g, '/'))).masses.point_forces?.[0];
        return f && f.magnitude === 3000 && f.direction.angle === 0 && f.name === 'K'; }""")
    assert dynamics_in(page.url)["masses"]["point_forces"] == [TOOL]
    assert dynamics_in(page.url)["masses"]["forces"] == [{"joint": "E/ram", "working": 3000.0, "k": 0.05,
                                                          "sense": -1}]        # the preset's load stays beside it
    hrefs = page.eval_on_selector_all("#editor-open-dynamics a[data-scene]", "links => links.map((a) => a.href)")
    assert hrefs and all(dynamics_in(href)["masses"]["point_forces"] == [TOOL] for href in hrefs)
    assert number(page.input_value(f'input[data-path="{ROW}.point.1"]')) == -0.05
    page.locator("#editor-dynamics").screenshot(path=ARTIFACTS / "editor_point_force_ru.png")
    screenshot(page, "editor_point_force_page_ru")

    open_from_editor(page, MOMENT)                 # the resisting moment of the student's loads, each apart
    assert page.inner_text("#notices") == ""
    page.wait_for_function("""() => (document.querySelector('#panel-load_parts .graph')?.data ?? [])
        .some((t) => /\\bK$/.test(t.name ?? ''))""")
    screenshot(page, "editor_point_force_resisting_moment_ru")
    page.go_back()
    page.wait_for_selector("#editor-masses-points")
    page.click(f'button[data-remove="point_forces.0"]')
    page.wait_for_function("""() => { const d = new URLSearchParams(location.search).get('d');
        return d && JSON.parse(atob(d.replace(/-/g, '+').replace(/_/g, '/'))).masses.point_forces.length === 0; }""")
    assert page.locator("#editor-masses-points").count() == 0
    assert page.problems == []
