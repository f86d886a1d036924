"""The shaping machine (a six-bar of content/mechanisms, named by the scenes' variants) in the equation-of-motion,
flywheel and forces scenes in a real browser, one page load each: a dragged slider changes the plots, [δ] the
flywheel, the motor's starting moment the steady cycle's mean speed, f (dry friction in every pair) the flywheel's
balancing moment, the reactions and the free bodies of the Assur groups, which follow the cursor's angle. No
console errors; the ru page shows no English words."""
from __future__ import annotations

import sys
from pathlib import Path

import pytest

from conftest import drag_slider, families_arrived, interface_texts, read_scene, screenshot, shown
from test_dynamics import figure_value, open_scene, trace, wait_for_new_trace

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from test_translations import english_in  # noqa: E402

pytestmark = pytest.mark.browser

MOTION = read_scene("equation_of_motion")
FLYWHEEL = read_scene("flywheel")
FORCES = read_scene("forces_friction")
BODIES = "#panel-group_free_body svg"


def english_words(page) -> list[str]:
    """The English interface texts (content/i18n/en.json, test_translations.english_in) the ru page shows."""
    return english_in(page.inner_text("body"), "ru")


def test_shaping_machine_equation_of_motion(browser_page):
    page = browser_page
    open_scene(page, MOTION, "ru", variant="shaping")
    before = trace(page, "omega_phi")
    drag_slider(page, "#slider-P", 0.8)                     # a larger cutting force: another steady cycle
    wait_for_new_trace(page, "omega_phi", before)
    mean_speed = shown(MOTION["panels"]["figures"]["items"][0]["label"]["ru"])   # ω_ср: the page shows ωср
    slower, before = figure_value(page, mean_speed), trace(page, "omega_phi")
    drag_slider(page, "#slider-M0", 0.9)                    # a stronger motor: a faster steady cycle
    wait_for_new_trace(page, "omega_phi", before)
    page.wait_for_function("""([label, before]) => [...document.querySelectorAll('.figures-list dt')]
        .find(dt => dt.textContent === label)?.nextElementSibling.textContent !== before""", arg=[mean_speed, slower])
    assert number(figure_value(page, mean_speed)) > number(slower)
    faster, before = figure_value(page, mean_speed), trace(page, "omega_phi")
    families_arrived(page)                                  # two heavy families in flight: a third is told 429
    drag_slider(page, "#slider-f", 0.9)                     # dry friction in every pair: the pairs' work slows it
    wait_for_new_trace(page, "omega_phi", before)
    page.wait_for_function("""([label, before]) => [...document.querySelectorAll('.figures-list dt')]
        .find(dt => dt.textContent === label)?.nextElementSibling.textContent !== before""", arg=[mean_speed, faster])
    assert number(figure_value(page, mean_speed)) < number(faster)
    items = MOTION["panels"]["figures"]["items"]
    efficiency, driving, useful = (shown(next(i for i in items if i["path"] == path)["label"]["ru"])
                                   for path in ("efficiency", "works.driving", "works.useful"))
    eta = number(figure_value(page, efficiency))                 # the pairs' work: η = A_useful/A_driving < 1
    assert 0 < eta < 1
    assert eta == pytest.approx(number(figure_value(page, useful)) / number(figure_value(page, driving)), rel=2e-3)
    assert english_words(page) == []
    assert "NaN" not in page.inner_html("#panels")
    screenshot(page, "general_motion_shaping_ru")
    assert page.problems == []


def test_shaping_machine_flywheel(browser_page):
    page = browser_page
    open_scene(page, FLYWHEEL, "ru", variant="shaping")
    label = FLYWHEEL["panels"]["figures"]["items"][0]["label"]["ru"]
    before = figure_value(page, label)
    drag_slider(page, "#slider-delta", 0.2)                 # a smaller [δ]: a larger flywheel
    page.wait_for_function("""([label, before]) => [...document.querySelectorAll('.figures-list dt')]
        .find(dt => dt.textContent === label)?.nextElementSibling.textContent !== before""", arg=[label, before])
    assert number(figure_value(page, label)) > number(before)
    balancing = shown(FLYWHEEL["panels"]["figures"]["items"][-1]["label"]["ru"])
    before = figure_value(page, balancing)
    drag_slider(page, "#slider-f", 0.9)                     # dry friction in every pair: a larger M_с to balance
    page.wait_for_function("""([label, before]) => [...document.querySelectorAll('.figures-list dt')]
        .find(dt => dt.textContent === label)?.nextElementSibling.textContent !== before""", arg=[balancing, before])
    assert abs(number(figure_value(page, balancing))) > abs(number(before))     # the pairs' work added
    assert english_words(page) == []
    assert "NaN" not in page.inner_html("#panels")
    screenshot(page, "general_flywheel_shaping_ru")
    assert page.problems == []


def test_shaping_machine_forces_and_free_bodies(browser_page):
    page = browser_page
    t = interface_texts("ru")
    open_scene(page, FORCES, "ru", variant="shaping")
    page.wait_for_selector(f"{BODIES} .free-body-cell")
    cells = page.locator(f"{BODIES} .free-body-cell")
    assert cells.count() == 3                                # RRP (4, 5), RPR (2, 3), the crank
    assert page.locator(f"{BODIES} .friction-circle").count() > 0
    assert page.locator(f"{BODIES} .reaction").count() >= 6
    readings = page.inner_html("#panel-group_free_body .free-body-readings")     # real subscripts: R<sub>34</sub>
    assert "R<sub>34</sub>" in readings and "R<sub>01</sub>" in readings
    assert shown_symbol(t["symbol_balancing_moment"]) in page.inner_text("#panel-group_free_body .free-body-readings")
    reactions = page.evaluate("() => document.querySelector('#panel-reactions_by_pair .graph').data.map(d => d.name)")
    assert len(reactions) == 7                               # every pair of the six-bar

    drawn = page.inner_html(BODIES)
    before = trace(page, "reactions_by_pair")
    drag_slider(page, "#slider-f", 0.9)
    wait_for_new_trace(page, "reactions_by_pair", before)
    page.wait_for_function("([sel, before]) => document.querySelector(sel).innerHTML !== before", arg=[BODIES, drawn])

    angle = page.inner_text(".group-free-body-angle")
    page.eval_on_selector("#crank-angle", "(e, v) => { e.value = v; e.dispatchEvent(new Event('input')); }", 200)
    page.wait_for_function("before => document.querySelector('.group-free-body-angle').textContent !== before",
                           arg=angle)
    assert "200,0" in page.inner_text(".group-free-body-angle")     # the bodies at the cursor's angle, decimal comma
    assert english_words(page) == []
    assert "NaN" not in page.inner_html("#panels")
    screenshot(page, "general_forces_shaping_ru")
    page.set_viewport_size({"width": 390, "height": 844})
    page.wait_for_function(f"() => document.querySelector('{BODIES}').viewBox.baseVal.width < 600")   # one below the other
    page.locator("#panel-group_free_body").scroll_into_view_if_needed()
    screenshot(page, "general_forces_shaping_ru_phone")
    assert page.problems == []


def number(shown: str) -> float:
    """The number a figure shows ("0,873", "−1,2 Н·м": decimal comma, the minus sign)."""
    return float(shown.split()[0].replace(",", ".").replace("\u2212", "-"))


def shown_symbol(text: str) -> str:
    """M_ур as the page's innerText reads it (the subscript a <sub> or tspan: the markup's underscore gone)."""
    return text.replace("_", "")
