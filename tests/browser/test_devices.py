"""Every device (phone and tablet) in a real browser, at phone (390 × 844) and tablet (768 × 1024) size.

- The parameters are a sheet fixed at the bottom of the screen: moving a slider from the keyboard or by
  dragging never scrolls the page, so the drawing in view stays in view, above the sheet; the sheet folds
  to its title bar and the page keeps room for it below its end.
- The force diagram (forces with friction) on a phone draws the links one below the other: at every crank
  angle of a turn no two of its symbols cover each other (their boxes as the browser lays them out) and
  every symbol is at least MIN_FONT CSS px high (its subscripts MIN_SUBSCRIPT_FONT).
- The page is no wider than a tablet's screen either (every scene is measured at 390 px in
  test_accessibility.py, one load each).
Screenshots at phone size of two scenes in ru, uk and en go to test-artifacts/devices-*.png.
"""
from __future__ import annotations

import itertools

import pytest

from conftest import ARTIFACTS, read_scene, screenshot

pytestmark = pytest.mark.browser

PHONE = {"width": 390, "height": 844}
TABLET = {"width": 768, "height": 1024}
MIN_FONT = 12.0              # CSS px of a symbol's letters on the phone
MIN_SUBSCRIPT_FONT = 9.0     # CSS px of its subscripts (75 % of the letters, notation.js)
SHEET_SHARE = 0.46           # the open sheet covers at most 45 % of the screen's height (app.css), + rounding

BOX = "(node) => { const r = node.getBoundingClientRect(); return { top: r.top, bottom: r.bottom, left: r.left, right: r.right }; }"

# the free-body symbols shown: their boxes, their font sizes in CSS px (drawing units × the drawing's scale)
FREE_BODY_LABELS = """() => {
  const svg = document.querySelector("#panel-free_body svg");
  const scale = svg.getScreenCTM().a;
  const shown = (node) => node.getClientRects().length > 0 && getComputedStyle(node).display !== "none"
    && node.closest(".force")?.style.display !== "none";
  return [...svg.querySelectorAll(".link-name, .joint-label, .force-label")].filter(shown)
    .filter((node) => !node.closest(".scale-legend") && node.textContent !== "").map((node) => {
      const r = node.getBoundingClientRect();
      return { text: node.textContent, box: [r.left, r.top, r.right, r.bottom],
        font: parseFloat(getComputedStyle(node).fontSize) * scale,
        smallest: Math.min(...[...node.querySelectorAll("tspan")].map((span) =>
          parseFloat(getComputedStyle(span).fontSize) * scale), Infinity) };
    });
}"""


@pytest.fixture
def open_page(chromium, app_url):
    """open_page(path, viewport): a fresh page there, settled; console errors kept in page.problems."""
    contexts = []

    def open_(path, viewport):
        context = chromium.new_context(base_url=app_url, viewport=viewport, device_scale_factor=1)
        contexts.append(context)
        page = context.new_page()
        page.problems = []
        page.on("console", lambda message: message.type == "error" and page.problems.append(message.text))
        page.on("pageerror", lambda error: page.problems.append(str(error)))
        page.goto(path)
        page.wait_for_load_state("networkidle")
        page.wait_for_timeout(300)
        return page
    yield open_
    for context in contexts:
        context.close()


def fits(page) -> bool:
    return page.evaluate("document.documentElement.scrollWidth <= innerWidth")


def overlap(a, b) -> float:
    """Area (CSS px²) common to two boxes [left, top, right, bottom]."""
    return max(0, min(a[2], b[2]) - max(a[0], b[0])) * max(0, min(a[3], b[3]) - max(a[1], b[1]))


def test_drawing_stays_in_view_while_a_slider_moves_on_a_phone(open_page):
    page = open_page(f"/scenes/{read_scene('transfer_functions')['id']}?lang=ru&variant=slider_crank", PHONE)
    assert fits(page)
    sheet = page.eval_on_selector(".controls-sheet", BOX)
    assert page.eval_on_selector(".controls-sheet", "(s) => getComputedStyle(s).position") == "fixed"
    assert sheet["bottom"] == pytest.approx(PHONE["height"], abs=1)
    assert sheet["bottom"] - sheet["top"] <= SHEET_SHARE * PHONE["height"]
    page.eval_on_selector(".stage", "(stage) => stage.scrollIntoView({ block: 'start' })")
    scrolled = page.evaluate("scrollY")
    drawing = page.eval_on_selector("#linkage svg", BOX)
    assert 0 <= drawing["top"] and drawing["bottom"] <= sheet["top"], (drawing, sheet)

    slider = page.locator("#controls input[type=range]").first
    before = slider.input_value()
    slider.focus()                                           # the keyboard: arrows
    for _ in range(5):
        slider.press("ArrowRight")
    box = slider.bounding_box()                               # and the finger: a drag along the track
    page.mouse.move(box["x"] + box["width"] * 0.3, box["y"] + box["height"] / 2)
    page.mouse.down()
    page.mouse.move(box["x"] + box["width"] * 0.7, box["y"] + box["height"] / 2, steps=6)
    page.mouse.up()
    page.wait_for_load_state("networkidle")
    assert slider.input_value() != before
    assert page.evaluate("scrollY") == scrolled
    assert page.eval_on_selector("#linkage svg", BOX) == drawing     # not moved, not covered
    assert box["y"] >= sheet["top"]                                  # the slider was in the sheet, in view

    toggle = page.locator(".sheet-toggle")
    toggle.click()                                                   # fold: only the title bar stays
    assert toggle.get_attribute("aria-expanded") == "false"
    assert not page.locator("#controls").is_visible()
    folded = page.eval_on_selector(".controls-sheet", BOX)
    assert folded["bottom"] - folded["top"] < 60
    toggle.click()
    assert page.locator("#controls").is_visible()
    page.wait_for_function("""() => parseFloat(getComputedStyle(document.documentElement)      // measured again
        .getPropertyValue('--sheet-height')) >= document.querySelector('.controls-sheet').offsetHeight - 1""")

    page.evaluate("window.scrollTo(0, document.documentElement.scrollHeight)")   # the page's end clears the sheet
    last = page.eval_on_selector("#plots > figure:last-of-type", BOX)
    assert last["bottom"] <= page.eval_on_selector(".controls-sheet", BOX)["top"] + 1
    assert page.problems == []


def test_force_diagram_stays_in_view_on_a_tablet(open_page):
    page = open_page(f"/scenes/{read_scene('forces_friction')['id']}?lang=uk", TABLET)
    assert fits(page)
    page.eval_on_selector("#panel-free_body", "(panel) => panel.scrollIntoView({ block: 'start' })")
    drawing = page.eval_on_selector("#panel-free_body svg", BOX)
    sheet = page.eval_on_selector(".controls-sheet", BOX)
    assert drawing["top"] >= 0 and drawing["bottom"] <= sheet["top"], (drawing, sheet)
    scrolled = page.evaluate("scrollY")
    slider = page.locator("#controls input[type=range]").first
    slider.focus()
    for _ in range(3):
        slider.press("ArrowRight")
    page.wait_for_load_state("networkidle")
    assert page.evaluate("scrollY") == scrolled
    assert page.eval_on_selector("#panel-free_body svg", BOX)["top"] == pytest.approx(drawing["top"], abs=1)
    assert fits(page)
    assert page.problems == []


def test_force_diagram_symbols_apart_and_legible_on_a_phone(open_page):
    """Over a turn (every 15°), including the textbook's crowded places (Φ₃ on B, R₂₃ on the slider, O under
    the balancing moment's arc): no two symbols' boxes meet, and none is smaller than MIN_FONT CSS px."""
    page = open_page(f"/scenes/{read_scene('forces_friction')['id']}?lang=ru", PHONE)
    assert fits(page)
    page.locator("#panel-free_body").scroll_into_view_if_needed()
    checked = 0
    for degrees in range(0, 360, 15):
        page.eval_on_selector("#crank-angle", """(scrub, value) => {
            scrub.value = value; scrub.dispatchEvent(new Event("input")); }""", degrees)
        page.evaluate("() => new Promise((done) => requestAnimationFrame(() => requestAnimationFrame(done)))")
        labels = page.evaluate(FREE_BODY_LABELS)
        assert len(labels) >= 10, labels
        for label in labels:
            assert label["font"] >= MIN_FONT, (degrees, label)
            assert label["smallest"] >= MIN_SUBSCRIPT_FONT, (degrees, label)
        for a, b in itertools.combinations(labels, 2):
            assert overlap(a["box"], b["box"]) == 0, (degrees, a, b)
        checked += 1
    assert checked == 24
    page.eval_on_selector("#crank-angle", "(s) => { s.value = 30; s.dispatchEvent(new Event('input')); }")
    page.locator(".sheet-toggle").click()                   # folded, so that the picture shows the whole panel
    page.locator("#panel-free_body").screenshot(path=ARTIFACTS / "devices-free-body-ru-phone.png")
    assert page.problems == []


PHONE_SCENES = ("transfer_functions", "equation_of_motion")


@pytest.mark.parametrize("lang", ["uk", "en"])
def test_phone_screenshots(open_page, lang):
    """Two scenes at phone size in uk and en, for a person to look at; each fits the screen (in ru: on
    test_accessibility's phone page of every scene)."""
    ARTIFACTS.mkdir(exist_ok=True)
    for name in PHONE_SCENES:
        page = open_page(f"/scenes/{read_scene(name)['id']}?lang={lang}", PHONE)
        assert fits(page)
        page.screenshot(path=ARTIFACTS / f"devices-{name}-{lang}-phone.png")          # what the phone shows
        screenshot(page, f"devices-{name}-{lang}-phone-full")
        assert page.problems == []
