"""The words of a drawing can be read: on every scene (each variant as it opens in ru, in test_notation's walk of
every variant; the default state in ru, uk and en, in test_scene_words' walk: those walks open the pages anyway,
and call label_problems here)
- no two text labels of a drawing (the SVG <text>s of linkages, free bodies, models and diagrams) cover each
  other, and none is cut by the edge of its drawing;
- on a polar plot, the radial axis's title covers no tick label and no tick label another;
- a free-body drawing's arrows stay inside its drawing;
and while a slider is being dragged, the preview badge covers none of the page's tool buttons.
Boxes are the browser's client rectangles of the texts; two boxes that share at most TOUCH px in either
direction touch, they do not overlap. Screenshots of the drawings these checks were written for go to
test-artifacts/labels-*.png for a person to look at.
"""
from __future__ import annotations

import pytest

from conftest import ARTIFACTS, families_arrived

pytestmark = pytest.mark.browser

TOUCH = 1.0             # px: boxes that meet within this much touch
# the drawings looked at by a person (photographed in ru by test_notation): (scene file, variant, element id,
# picture name); the own-mechanism variant draws its group free bodies as the shaping machine's (its example) does
PICTURES = [("forces_friction", "central", "panel-free_body", "forces-phi0"),
            ("forces_friction", "shaping", "panel-group_free_body", "forces-general-mechanism"),
            ("equation_of_motion", "linear", "panel-portrait", "polar"),
            ("elastic_four_bar", "dialog", "panel-motor", "elastic-four-bar"),
            ("transfer_functions", "slider_crank", "linkage", "transfer-functions"),
            ("elastic_transmission", "belt", "panel-model", "elastic-transmission-model")]

# Every drawing on the page: its box (the SVG's, within its panel), its labels' boxes, the boxes of its force
# arrows; and every polar plot's radial title and tick labels. Hidden things (display: none, visibility:
# hidden, no size) are left out.
DRAWN_LABELS = """() => {
  const shown = (node) => {
    const r = node.getBoundingClientRect();
    if (!r.width || !r.height) return false;
    for (let n = node; n && n.nodeType === 1; n = n.parentNode) {
      const s = getComputedStyle(n);
      if (s.display === "none" || s.visibility === "hidden" || Number(s.opacity) === 0) return false;
    }
    return true;
  };
  const box = (node) => { const r = node.getBoundingClientRect();
    return { text: node.textContent.trim(), left: r.left, top: r.top, right: r.right, bottom: r.bottom }; };
  const within = (a, b) => ({ text: a.text, left: Math.max(a.left, b.left), top: Math.max(a.top, b.top),
    right: Math.min(a.right, b.right), bottom: Math.min(a.bottom, b.bottom) });
  const drawings = [];
  for (const svg of document.querySelectorAll("body svg")) {
    if (svg.closest(".js-plotly-plot") || svg.parentElement.closest("svg") || !shown(svg)) continue;
    const labels = [...svg.querySelectorAll("text")].filter((t) => t.textContent.trim() && shown(t)).map(box);
    if (!labels.length) continue;
    const holder = svg.closest("figure, section") ?? document.body;
    const arrows = [...svg.querySelectorAll(".force path, .force line")].filter(shown).map(box);
    drawings.push({ where: holder.id || holder.className, frame: within(box(svg), box(holder)), labels, arrows });
  }
  const polars = [...document.querySelectorAll(".js-plotly-plot")].filter((p) => p.querySelector(".polarlayer .polar"))
    .map((plot) => ({ where: plot.closest("figure")?.id ?? "",
      titles: [...plot.querySelectorAll(".g-polartitle text, .annotation-text")].filter(shown).map(box),
      ticks: [...plot.querySelectorAll(".radial-axis text, .angular-axis text")].filter(shown).map(box) }));
  return { drawings, polars };
}"""


def overlap(a: dict, b: dict) -> bool:
    """True if the boxes share more than TOUCH px both across and down."""
    across = min(a["right"], b["right"]) - max(a["left"], b["left"])
    down = min(a["bottom"], b["bottom"]) - max(a["top"], b["top"])
    return across > TOUCH and down > TOUCH


def cut(box: dict, frame: dict) -> bool:
    """True if the box reaches more than TOUCH px beyond the frame."""
    return (box["left"] < frame["left"] - TOUCH or box["top"] < frame["top"] - TOUCH
            or box["right"] > frame["right"] + TOUCH or box["bottom"] > frame["bottom"] + TOUCH)


def label_problems(found: dict) -> list[str]:
    """What a person could not read in the page's drawings and polar plots, said by drawing and label."""
    problems = []
    for drawing in found["drawings"]:
        where, labels = drawing["where"], drawing["labels"]
        problems += [f"{where}: {a['text']!r} covers {b['text']!r}"
                     for i, a in enumerate(labels) for b in labels[i + 1:] if overlap(a, b)]
        problems += [f"{where}: {label['text']!r} cut by the drawing's edge"
                     for label in labels if cut(label, drawing["frame"])]
        problems += [f"{where}: an arrow leaves the drawing" for arrow in drawing["arrows"][:1]
                     if any(cut(arrow, drawing["frame"]) for arrow in drawing["arrows"])]
    for plot in found["polars"]:
        where, titles, ticks = plot["where"], plot["titles"], plot["ticks"]
        problems += [f"{where}: title {a['text']!r} covers tick {b['text']!r}"
                     for a in titles for b in ticks if overlap(a, b)]
        problems += [f"{where}: tick {a['text']!r} covers tick {b['text']!r}"
                     for i, a in enumerate(ticks) for b in ticks[i + 1:] if overlap(a, b)]
    return problems


def settle(page) -> None:
    """Wait until the page has asked for and drawn everything it asks for on its own: the answers arrived and
    every plot they fill drawn (those out of view are drawn when the browser is idle)."""
    page.wait_for_load_state("networkidle")
    page.wait_for_timeout(300)
    page.wait_for_load_state("networkidle")
    page.wait_for_function("""() => [...document.querySelectorAll(".panel-plot, .panel-polar")]
      .filter((figure) => !figure.hidden).every((figure) => figure.querySelector(".main-svg"))""")


def test_overlap_and_cut_say_what_they_mean():
    """Two boxes meeting at an edge, or 1 px into each other, touch; 2 px into each other they overlap."""
    a = {"left": 0, "top": 0, "right": 10, "bottom": 10}
    assert not overlap(a, {"left": 10, "top": 0, "right": 20, "bottom": 10})
    assert not overlap(a, {"left": 9, "top": 0, "right": 20, "bottom": 10})
    assert overlap(a, {"left": 8, "top": 2, "right": 20, "bottom": 10})
    assert not cut(a, {"left": 0.5, "top": -1, "right": 10, "bottom": 11})
    assert cut(a, {"left": 2, "top": 0, "right": 10, "bottom": 10})


def test_the_preview_badge_covers_no_tool_button_while_a_slider_is_dragged(browser_page):
    """A student holds the mouse on a slider of the equation of motion and moves it: the page shows the preview
    (the badge) while the button is held; the badge must leave "clear pinned curves" and its neighbours free."""
    page = browser_page
    page.goto("/scenes/equation-of-motion?lang=ru")
    settle(page)
    families_arrived(page)
    selector = "#controls input[type=range]"
    page.locator(selector).first.scroll_into_view_if_needed()
    box = page.locator(selector).first.bounding_box()
    y = box["y"] + box["height"] / 2
    value, low, high = page.eval_on_selector(selector, "e => [e.value, e.min, e.max].map(Number)")
    x = lambda f: box["x"] + 8 + (box["width"] - 16) * f
    page.mouse.move(x((value - low) / (high - low)), y)
    page.mouse.down()
    start = (value - low) / (high - low)
    for step in range(1, 121):           # held and moved on until the family's preview shows (a guard, not a time)
        page.mouse.move(x(start + (0.2 if start < 0.7 else -0.2) * (1 + step % 2) / 2), y, steps=4)
        if page.locator(".scene-layout.preview").count():
            break
        page.wait_for_timeout(250)
    assert page.locator(".scene-layout.preview").count() == 1, "no preview while the slider was dragged"
    badge = page.locator(".results > .preview-note").bounding_box()
    buttons = page.evaluate("""() => [...document.querySelectorAll('#scene-tools button, #scene-tools select')]
      .filter((b) => b.offsetParent).map((b) => { const r = b.getBoundingClientRect();
        return { text: b.id, left: r.left, top: r.top, right: r.right, bottom: r.bottom }; })""")
    page.screenshot(path=ARTIFACTS / "labels-preview-badge.png")
    page.mouse.up()
    shown = {"text": "badge", "left": badge["x"], "top": badge["y"], "right": badge["x"] + badge["width"],
             "bottom": badge["y"] + badge["height"]}
    assert any(b["text"] == "clear-pinned" for b in buttons)
    assert [b["text"] for b in buttons if overlap(shown, b)] == []
