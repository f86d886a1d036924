"""A scene fits a phone (390 × 844, ru):
- the page never scrolls sideways (its scrollWidth is the window's width), and every table either fits or sits in a
  box that scrolls sideways itself, which the keyboard can reach (tabindex) and a screen reader names (axe-core's
  scrollable-region-focusable): TABLES and table_problems, checked on every scene by test_accessibility's phone
  walk (one load of each scene serves all its phone checks);
- the wear scene's polar plot writes its radial tick labels apart;
- the flywheel scene's drawing of the machine keeps its letters (A, φ, O at the crank, B, D, the scale) apart
  and inside it at every crank angle the animation shows.
Label boxes are collected and compared as tests/browser/test_label_overlaps.py does (its helpers, imported).
Phone screenshots of the bearings, wear and flywheel scenes (test_accessibility) go to test-artifacts/phone-*.png.
"""
from __future__ import annotations

import pytest

from conftest import ARTIFACTS
from test_label_overlaps import DRAWN_LABELS, label_problems, overlap, settle

pytestmark = pytest.mark.browser

PHOTOGRAPHED = {"bearings", "wear", "flywheel"}
CRANK_ANGLES = range(0, 360, 15)        # degrees: the animation's crank angle set on the scrub slider

# The page's widths, and every table: its width, and the nearest box around it that scrolls sideways (its width,
# tabindex, accessible name), if any. A table in a hidden panel (no size) is left out.
TABLES = """() => {
  const tables = [...document.querySelectorAll("main table")].filter((t) => t.getBoundingClientRect().width)
    .map((table) => {
      let frame = table.parentElement;
      while (frame && frame.tagName !== "MAIN" && !["auto", "scroll"].includes(getComputedStyle(frame).overflowX)) {
        frame = frame.parentElement;
      }
      const scroller = frame && frame.tagName !== "MAIN" ? frame : null;
      return { table: table.className || table.closest("[id]")?.id || "table",
               width: table.getBoundingClientRect().width, right: table.getBoundingClientRect().right,
               frame: scroller && { width: scroller.clientWidth, right: scroller.getBoundingClientRect().right,
                                    tabindex: scroller.tabIndex,
                                    name: (scroller.getAttribute("aria-label") ?? "").trim() } };
    });
  return { scrollWidth: document.documentElement.scrollWidth, innerWidth, tables };
}"""


def fold_sheet(page) -> None:
    """Fold the phone's parameter sheet to its title bar, so that a screenshot shows what lies under it."""
    toggle = page.locator(".sheet-toggle")
    if toggle.count() and toggle.is_visible() and toggle.get_attribute("aria-expanded") != "false":
        toggle.click()


def table_problems(found: dict) -> list[str]:
    """What of a page does not fit the phone's width, said by table."""
    problems = []
    if found["scrollWidth"] > found["innerWidth"]:
        problems.append(f"the page is {found['scrollWidth']} px wide in a {found['innerWidth']} px window")
    for table in found["tables"]:
        frame = table["frame"]
        if frame is None:
            if table["right"] > found["innerWidth"] + 1:
                problems.append(f"{table['table']}: {table['width']:.0f} px, cut at the window's edge")
        elif table["width"] > frame["width"] + 1:
            if frame["right"] > found["innerWidth"] + 1:
                problems.append(f"{table['table']}: its scrolling box reaches beyond the window")
            if frame["tabindex"] < 0 or not frame["name"]:
                problems.append(f"{table['table']}: its scrolling box is not focusable and named")
    return problems


def test_the_wear_polar_plot_writes_its_radial_ticks_apart(phone):
    page = phone
    page.goto("/scenes/wear?lang=ru")
    settle(page)
    polars = page.evaluate(DRAWN_LABELS)["polars"]
    assert polars and all(len(plot["ticks"]) > 8 for plot in polars)       # the angular 8 and some radial ones
    assert label_problems({"drawings": [], "polars": polars}) == []
    fold_sheet(page)
    page.locator("#panel-joint").scroll_into_view_if_needed()
    page.locator("#panel-joint").screenshot(path=ARTIFACTS / "phone-wear-polar.png")


def test_the_flywheel_drawing_keeps_its_letters_apart_at_every_crank_angle(phone):
    page = phone
    page.goto("/scenes/flywheel?lang=ru")
    settle(page)
    problems = {}
    for angle in CRANK_ANGLES:
        page.eval_on_selector("#crank-angle", """(scrub, angle) => { scrub.value = angle;
          scrub.dispatchEvent(new Event("input", { bubbles: true })); }""", angle)
        page.wait_for_function("""(angle) => Number(document.querySelector("#crank-angle").value) === angle""", arg=angle)
        drawings = [d for d in page.evaluate(DRAWN_LABELS)["drawings"] if d["where"] == "panel-linkage"]
        assert len(drawings) == 1 and {"A", "O", "φ"} <= {label["text"] for label in drawings[0]["labels"]}
        found = label_problems({"drawings": drawings, "polars": []})
        if found:
            problems[angle] = found
    assert problems == {}
    page.eval_on_selector("#crank-angle", """(scrub) => { scrub.value = 0;
      scrub.dispatchEvent(new Event("input", { bubbles: true })); }""")
    fold_sheet(page)
    page.locator("#panel-linkage").scroll_into_view_if_needed()
    page.locator("#panel-linkage").screenshot(path=ARTIFACTS / "phone-flywheel-drawing.png")


def test_table_problems_says_what_it_means():
    """A table wider than the window outside a scrolling box is cut; inside a focusable, named box it is not."""
    window = {"scrollWidth": 390, "innerWidth": 390}
    wide = {"table": "rows", "width": 700, "right": 720}
    assert table_problems(window | {"tables": [wide | {"frame": None}]}) != []
    framed = {"width": 343, "right": 367, "tabindex": 0, "name": "Опечатки"}
    assert table_problems(window | {"tables": [wide | {"frame": framed}]}) == []
    assert table_problems(window | {"tables": [wide | {"frame": framed | {"name": ""}}]}) != []
    assert table_problems({"scrollWidth": 400, "innerWidth": 390, "tables": []}) != []
    assert overlap({"left": 0, "top": 0, "right": 10, "bottom": 10}, {"left": 5, "top": 5, "right": 15, "bottom": 15})
