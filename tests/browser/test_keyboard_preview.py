"""The keyboard previews as the mouse does: a slider's keys (arrows, PageUp/PageDown, Home/End) are drawn from the
slider's family, marked as a preview, without a request, and the exact answer is asked for once, when the keys rest
(released, and no key for a moment). The family is asked for once, when the slider takes the focus (a grab).

A key held down repeats (the keyboard's auto-repeat: Playwright's keyboard.down on a key already down sends a
repeated keydown), so while it is held the keys never rest, whatever the machine's speed: each repeat must draw a
preview and none may ask for the exact answer. On the transfer-functions scene (kinematics, λ, 8 plots) and on the
flywheel scene (a dynamics scene; [δ], a logarithmic slider whose keys the page steps itself).
"""
from __future__ import annotations

import json
from urllib.parse import urlparse

import pytest

from conftest import families_arrived, screenshot

pytestmark = pytest.mark.browser

GRAPH = "document.querySelector(`#panel-${id} .graph`)"


@pytest.fixture
def keyed_page(browser_page):
    """The browser page with a log of the computing requests it sends: page.sent = [(endpoint, body)]."""
    page = browser_page
    page.sent = []
    page.on("request", lambda r: "/api/v1/" in r.url and r.method == "POST" and page.sent.append(
        (urlparse(r.url).path.rsplit("/", 1)[-1], json.loads(r.post_data))))
    return page


def sent(page, endpoint: str, since: int = 0) -> list[dict]:
    return [body for name, body in page.sent[since:] if name == endpoint]


def marks(page, name: str) -> int:
    return page.evaluate("name => performance.getEntriesByName(name).length", name)


def curves(page, panel: str) -> list[str]:
    """The SVG paths of the panel's drawn curves (a preview moves them in place; gd.data stays the exact answer's)."""
    return page.eval_on_selector_all(f"#panel-{panel} .scatterlayer path.js-line",
                                     "paths => paths.map((p) => p.getAttribute('d'))")


def preview_shown(page) -> bool:
    return page.is_visible(".preview-note") and page.locator(".scene-layout.preview").count() == 1


def quiet(page) -> None:
    """Until the page has nothing on its way and no request waiting to be sent again (a 429's Retry-After: the
    page shows its "busy, retrying" note meanwhile, api.js), so that what it sends next is the keys' doing."""
    page.wait_for_load_state("networkidle")
    page.wait_for_function("() => !document.getElementById('busy-retrying') || "
                           "document.getElementById('busy-retrying').hidden")
    page.wait_for_load_state("networkidle")


def focus_and_wait_for_the_family(page, slider: str) -> None:
    """Focus the slider (a grab: its family is asked for) and wait until the full family has arrived."""
    page.focus(slider)
    page.wait_for_function("() => performance.getEntriesByName('family-arrived').length > 0")
    families_arrived(page)


def hold_key(page, key: str, repeats: int, slider: str, drawn, endpoint: str, since: int) -> list[str]:
    """Press key and keep it down for `repeats` keydowns; after each, a preview is drawn, marked, and nothing is
    asked of the endpoint. Returns the slider's values after each keydown."""
    values, shown = [], drawn(page)
    for _ in range(repeats):
        frames = marks(page, "plots-drawn")
        page.keyboard.down(key)
        page.wait_for_function("n => performance.getEntriesByName('plots-drawn').length > n", arg=frames)
        values.append(page.input_value(slider))
        assert preview_shown(page)
        assert drawn(page) != shown, values
        shown = drawn(page)
        assert sent(page, endpoint, since) == [], values            # no exact answer asked while the keys move
    assert len(set(values)) == repeats, values                        # every repeat stepped the slider
    return values


def rest_and_wait_for_exact(page, key: str, endpoint: str) -> dict:
    """Release the key; returns the exact answer the page asks for once the keys rest, once it is drawn."""
    drawn = marks(page, "exact-drawn")
    with page.expect_response(lambda r: f"/api/v1/{endpoint}?" in r.url) as response:
        page.keyboard.up(key)
    answer = response.value.json()
    page.wait_for_function("n => performance.getEntriesByName('exact-drawn').length > n", arg=drawn)
    page.wait_for_function("() => !document.querySelector('.scene-layout.preview')")
    page.wait_for_load_state("networkidle")                        # a second request would have been sent by now
    return answer


def test_transfer_functions_keys_preview_from_the_family_and_ask_the_exact_answer_once_at_rest(keyed_page):
    page = keyed_page
    page.goto("/scenes/transfer-functions?lang=ru&variant=slider_crank")
    page.wait_for_function(f"id => {GRAPH}?.data?.length > 0", arg="u31")
    quiet(page)
    before = len(page.sent)
    focus_and_wait_for_the_family(page, "#slider-lambda")
    assert [body.get("stage") for body in sent(page, "family", before)] == ["coarse", None]
    exact_before = page.evaluate(f"id => {GRAPH}.data[0].y", "u31")

    drawn = lambda page: curves(page, "u31") + curves(page, "position")
    values = hold_key(page, "ArrowRight", 5, "#slider-lambda", drawn, "kinematics", before)
    assert values == ["3.01", "3.02", "3.03", "3.04", "3.05"]
    assert page.input_value("#slider-lambda") == "3.05"
    screenshot(page, "keyboard_preview_transfer_functions_ru")

    answer = rest_and_wait_for_exact(page, "ArrowRight", "kinematics")
    exact, = sent(page, "kinematics", before)                       # one exact answer, for the value at rest
    assert exact["params"]["l2"] == pytest.approx(3.05 * exact["params"]["l1"])
    assert not page.is_visible(".preview-note")
    shown = page.evaluate(f"id => {GRAPH}.data[0].y", "u31")
    assert shown == answer["outputs"]["u31"] != exact_before
    assert page.evaluate(f"id => {GRAPH}.data[0].y", "position") == answer["outputs"]["s"]

    since = len(page.sent)                                           # one press (down and up): a preview, then exact
    frames = marks(page, "plots-drawn")
    page.keyboard.down("ArrowLeft")
    page.wait_for_function("n => performance.getEntriesByName('plots-drawn').length > n", arg=frames)
    assert preview_shown(page) and sent(page, "kinematics", since) == []
    answer = rest_and_wait_for_exact(page, "ArrowLeft", "kinematics")
    exact, = sent(page, "kinematics", since)
    assert exact["params"]["l2"] == pytest.approx(3.04 * exact["params"]["l1"])
    assert page.evaluate(f"id => {GRAPH}.data[0].y", "u31") == answer["outputs"]["u31"]

    assert marks(page, "family-requested") == 1                      # the family of the focus served every key
    assert [body.get("stage") for body in sent(page, "family", before)] == ["coarse", None]
    assert page.problems == []


def flywheel_drawn(page) -> list:
    """What a flywheel preview moves: the drawing's disk and Wittenbauer's diagram."""
    return [page.get_attribute(".flywheel-disk", "r"),
            *page.eval_on_selector_all("#panel-wittenbauer .scatterlayer path.js-line", "ps => ps.map((p) => p.getAttribute('d'))")]


def test_flywheel_log_slider_keys_preview_from_the_family_and_ask_the_exact_answer_once_at_rest(keyed_page):
    page = keyed_page
    page.goto("/scenes/flywheel?lang=en&variant=rig")
    page.wait_for_selector("#panel-wittenbauer .graph path.js-line", state="attached")
    quiet(page)
    before = len(page.sent)
    focus_and_wait_for_the_family(page, "#slider-delta")
    family, full = sent(page, "family", before)
    assert family["endpoint"] == "flywheel" and family["log"] is True and full.get("stage") is None
    numbers = page.inner_text(".flywheel-numbers")

    hold_key(page, "ArrowRight", 3, "#slider-delta", flywheel_drawn, "flywheel", before)
    assert "[δ] = 0.0158" in page.get_attribute("#slider-delta", "aria-valuetext")     # 0.0125 → 3 steps of 10^(1/20)
    assert page.inner_text(".flywheel-numbers") == numbers            # numbers stay those of the exact answer
    screenshot(page, "keyboard_preview_flywheel_en")

    rest_and_wait_for_exact(page, "ArrowRight", "flywheel")
    exact, = sent(page, "flywheel", before)
    assert exact["delta"] == pytest.approx(0.0158)
    assert page.inner_text(".flywheel-numbers") != numbers
    assert marks(page, "family-requested") == 1
    assert page.problems == []
