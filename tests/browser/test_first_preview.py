"""The first preview after an exact answer only moves the curves: while the reader holds a slider whose family has
arrived, the exact answer's plots are drawn with axes that hold every member of the family, so that the first key
(or a drag's first move) after it draws its preview in the drawn axes, without Plotly laying a plot out anew
(Plotly.react, Plotly.newPlot) and with the same plot elements on the page.

On the transfer-functions scene (kinematics, λ), the equation-of-motion scene (a dynamics scene, λ) and the induction
motor's (its operating point a marker among nulls: moved as the curves are); each with a key pressed and released once first, so that the exact answer the keys rest on is drawn while the family is held.
"""
from __future__ import annotations

import pytest

from conftest import families_arrived

pytestmark = pytest.mark.browser

# Plotly's calls that lay out anew a plot in (or within 100 px of) the window, as a preview draws them, from now on (a
# plot further down may still be drawn with the exact answer in an idle moment); and each plot's main SVG element.
WATCH_PLOTLY = """() => {
  window.__laidOut = [];
  const near = (graph) => { const r = graph.getBoundingClientRect(); return r.bottom > -100 && r.top < innerHeight + 100; };
  for (const name of ["react", "newPlot"]) {
    const call = Plotly[name];
    Plotly[name] = (graph, ...rest) => {
      if (near(graph)) window.__laidOut.push(`${name} ${graph.closest(".panel")?.id}`);
      return call(graph, ...rest);
    };
  }
  window.__mainSvgs = [...document.querySelectorAll(".panel:not([hidden]) .graph")].map((g) => g.querySelector(".main-svg"));
}"""
SAME_SVGS = """() => [...document.querySelectorAll(".panel:not([hidden]) .graph")]
  .every((g, i) => g.querySelector(".main-svg") === window.__mainSvgs[i])"""


def marks(page, name: str) -> int:
    return page.evaluate("name => performance.getEntriesByName(name).length", name)


def curves(page) -> list[str]:
    return page.eval_on_selector_all(".panel:not([hidden]) .scatterlayer path.js-line",
                                     "paths => paths.map((p) => p.getAttribute('d'))")


def press_and_wait_for_exact(page, key: str) -> None:
    """One press (down and up): a preview, then the exact answer once the keys rest; returns once it is drawn."""
    drawn = marks(page, "exact-drawn")
    page.keyboard.press(key)
    page.wait_for_function("n => performance.getEntriesByName('exact-drawn').length > n", arg=drawn)
    page.wait_for_function("() => !document.querySelector('.scene-layout.preview')")
    page.wait_for_load_state("networkidle")


def first_preview_lays_nothing_out(page, url: str, slider: str) -> None:
    page.goto(url)
    page.wait_for_function("() => performance.getEntriesByName('exact-drawn').length > 0")
    page.wait_for_load_state("networkidle")
    page.locator(slider).scroll_into_view_if_needed()
    page.focus(slider)                                              # a grab: the family is asked for
    page.wait_for_function("() => performance.getEntriesByName('family-arrived').length > 0")
    families_arrived(page)
    press_and_wait_for_exact(page, "ArrowRight")                    # the exact answer the next key starts from
    page.evaluate("() => new Promise((resolve) => requestAnimationFrame(() => setTimeout(resolve, 0)))")

    page.evaluate(WATCH_PLOTLY)
    exact = curves(page)
    previews = marks(page, "plots-drawn")
    page.keyboard.down("ArrowRight")                                # the first key after the exact answer
    page.wait_for_function("n => performance.getEntriesByName('plots-drawn').length > n", arg=previews)
    assert page.is_visible(".preview-note")
    assert curves(page) != exact                                    # the preview is drawn
    assert page.evaluate("() => window.__laidOut") == []            # by moving the curves only
    assert page.evaluate(SAME_SVGS)
    page.keyboard.up("ArrowRight")
    page.wait_for_function("() => !document.querySelector('.scene-layout.preview')")
    page.wait_for_load_state("networkidle")
    assert page.problems == []


def test_transfer_functions_first_key_after_the_exact_answer_moves_the_curves_only(browser_page):
    first_preview_lays_nothing_out(browser_page, "/scenes/transfer-functions?lang=en&variant=slider_crank", "#slider-lambda")


def test_equation_of_motion_first_key_after_the_exact_answer_moves_the_curves_only(browser_page):
    first_preview_lays_nothing_out(browser_page, "/scenes/equation-of-motion?lang=en&variant=linear", "#slider-lambda")


def test_induction_motor_first_key_after_the_exact_answer_moves_the_curves_and_the_operating_point_only(browser_page):
    first_preview_lays_nothing_out(browser_page, "/scenes/induction-motor?lang=en&variant=kloss", "#slider-load")
