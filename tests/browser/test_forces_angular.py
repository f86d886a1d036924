"""The force, wear and angular-acceleration scenes in a real browser: the free-body diagrams follow the
crank angle and the friction coefficient, self-locking is told in words without NaN, the efficiency-chain
calculator, the wear polar plot, and the instantaneous gear train with its straight-line limit at φ = 90°."""
from __future__ import annotations

import pytest

from conftest import drag_slider, interface_texts, read_scene, screenshot
from test_crank_drag import assert_turned, before_turning, turn_crank
from test_dynamics import figure_value, open_scene, prefix, trace, wait_for_new_trace, warnings

pytestmark = pytest.mark.browser

FORCES = read_scene("forces_friction")
WEAR = read_scene("wear")
ANGULAR = read_scene("angular_acceleration")
ARROWS = "#panel-free_body svg .forces"


def scrub(page, degrees: float) -> None:
    """Put the crank at degrees with the animation's scrub slider, as a reader's drag does."""
    page.eval_on_selector("#crank-angle", "(e, v) => { e.value = v; e.dispatchEvent(new Event('input')); }", degrees)


def shows_no_nan(page) -> bool:
    return "NaN" not in page.inner_text("body") and "NaN" not in page.inner_html("#panels")


def test_friction_changes_the_reactions_and_the_free_body_follows_the_crank(browser_page):
    page = browser_page
    open_scene(page, FORCES, "en")
    efficiency = FORCES["panels"]["figures"]["items"][0]["label"]["en"]
    before_plot, before_eta = trace(page, "reactions"), figure_value(page, efficiency)
    assert page.locator("#panel-free_body .friction-circles circle").count() == 5        # O; A on crank and rod; B on rod and slider
    drag_slider(page, "#slider-f", 0.6)
    wait_for_new_trace(page, "reactions", before_plot)
    assert float(page.input_value("#slider-f")) > 0.3
    page.wait_for_function("""([label, before]) => [...document.querySelectorAll('.figures-list dt')]
        .find(dt => dt.textContent === label).nextElementSibling.textContent !== before""", arg=[efficiency, before_eta])
    assert float(figure_value(page, efficiency)) < float(before_eta)          # more friction, less efficiency

    page.locator("#panel-free_body").scroll_into_view_if_needed()
    arrows = page.inner_html(ARROWS)
    cursor = page.get_attribute("#panel-reactions .cursor", "style")
    scrub(page, 90)
    assert page.inner_text(".phi-readout") == "φ = 90.0°"
    assert page.inner_html(ARROWS) != arrows
    assert figure_value(page, interface_texts("en")["crank_angle"]) == "90.0°"
    scrubbed = page.inner_html(ARROWS)
    page.click(".play")
    page.wait_for_function("() => Number(document.querySelector('#crank-angle').value) > 120")
    page.click(".play")
    assert page.inner_html(ARROWS) != scrubbed
    assert page.get_attribute("#panel-reactions .cursor", "style") != cursor
    assert "R₁₂ = " in page.inner_text("#panel-reactions .cursor-readout")
    assert shows_no_nan(page)
    screenshot(page, "forces_free_body_animated")
    assert page.problems == []


def test_self_locking_is_told_in_words_and_the_drawing_has_no_reactions_there(browser_page):
    page = browser_page
    t = interface_texts("ru")
    open_scene(page, FORCES, "ru", variant="central", **{"lambda": "1.05", "f": "0.6"})
    page.wait_for_selector("#notices .warnings")
    assert prefix(t["warn_kinetostatics_self_locking"]) in warnings(page)
    efficiency = FORCES["panels"]["figures"]["items"][0]["label"]["ru"]
    assert figure_value(page, efficiency) == "—"
    page.locator("#panel-free_body").scroll_into_view_if_needed()
    scrub(page, 90)                                   # inside the first range where the slider locks
    page.wait_for_selector(".self-locking-note", state="visible")
    assert page.inner_text(".self-locking-note") == t["self_locking_at_angle"]
    assert page.locator(f"{ARROWS} .reaction:visible").count() == 0
    assert shows_no_nan(page)
    screenshot(page, "forces_self_locking")
    scrub(page, 180)                                  # between the two ranges the reactions exist again
    page.wait_for_selector(".self-locking-note", state="hidden")
    assert page.locator(f"{ARROWS} .reaction:visible").count() >= 4
    assert shows_no_nan(page)
    assert page.problems == []


def test_efficiency_chain_calculator(browser_page):
    """On a Russian page the fields are read with a decimal comma whatever the browser's locale, and what could
    mean two numbers is refused in words."""
    page = browser_page
    t = interface_texts("ru")
    open_scene(page, FORCES, "ru")
    page.locator("#panel-chain").scroll_into_view_if_needed()
    page.wait_for_function("() => document.querySelector('.chain-series').textContent === '0,72'")
    assert page.inner_text(".chain-parallel") == "0,85"          # (0.9·100 + 0.8·100) / 200
    assert page.input_value(".chain-table tr:nth-child(1) .chain-efficiency") == "0,9"
    page.click(".chain-add")
    page.wait_for_function("() => document.querySelector('.chain-series').textContent === '0,576'")
    page.fill(".chain-table tr:nth-child(3) .chain-efficiency", "1,5")
    assert page.get_attribute(".chain-table tr:nth-child(3) .chain-efficiency", "aria-invalid") == "true"
    assert page.inner_text(".chain-series") == "—"
    page.fill(".chain-table tr:nth-child(3) .chain-efficiency", "0,5")            # 0.9·0.8·0.5
    page.wait_for_function("() => document.querySelector('.chain-series').textContent === '0,36'")
    page.fill(".chain-table tr:nth-child(3) .chain-efficiency", "0,5.1")
    assert page.inner_text(".chain-message") == t["number_ambiguous"].replace("{text}", "0,5.1")
    page.click(".chain-table tr:nth-child(3) .chain-remove")
    page.wait_for_function("() => document.querySelector('.chain-series').textContent === '0,72'")
    page.fill(".chain-table tr:nth-child(2) .chain-work", "300")
    page.wait_for_function("() => document.querySelector('.chain-parallel').textContent === '0,825'")
    screenshot(page, "forces_efficiency_chain")
    assert page.problems == []


def test_wear_scene_draws_its_polar_plot_in_degrees_and_micrometres(browser_page):
    page = browser_page
    open_scene(page, WEAR, "ru")
    polar = page.evaluate("""() => document.querySelector('#panel-joint .graph').data
        .map(trace => [trace.type, Math.max(...trace.theta), Math.max(...trace.r)])""")
    assert [kind for kind, _, _ in polar] == ["scatterpolar"] * 2
    # β in degrees (to 1e-4°: the answer's angles come at plot precision, 7 significant digits of 2π), wear in µm
    assert all(abs(theta - 360) < 1e-4 and 1 < r < 1000 for _, theta, r in polar)
    piston = WEAR["panels"]["figures"]["items"][0]["label"]["ru"]
    assert figure_value(page, piston).endswith(interface_texts("ru")["units_um"])
    assert page.locator(".animation").count() == 0
    assert shows_no_nan(page)
    screenshot(page, "wear_polar")
    assert page.problems == []


def gear_train(page) -> dict:
    """The attributes of the circles, the straight-line limit and P in the gear-train drawing."""
    return page.evaluate("""() => {
        const svg = document.querySelector('#panel-gear_train svg');
        const attrs = (node) => Object.fromEntries([...node.attributes].map(a => [a.name, a.value]));
        return {
            wheel: attrs(svg.querySelector('circle.coupler-wheel')),
            line: attrs(svg.querySelector('line.coupler-wheel')),
            crank: attrs(svg.querySelector('circle.crank-wheel')),
            centre: attrs(svg.querySelector('.instant-centre circle')),
            mark: attrs(svg.querySelector('g.instant-centre')),
            html: svg.innerHTML,
        };
    }""")


def reading(page, name: str) -> str:
    return page.locator(".gear-train-readings dt", has_text=name).first.locator("xpath=following-sibling::dd[1]").inner_text()


def test_gear_train_follows_the_crank_and_turns_into_parallel_lines_at_90_degrees(browser_page):
    page = browser_page
    open_scene(page, ANGULAR, "en", variant="crank_slider")
    scrub(page, 30)
    at30 = gear_train(page)
    assert reading(page, "AP") == "2.24 m"                 # λ = 0.5, OA = 1: AP = √5 at 30°
    scrub(page, 60)
    at60 = gear_train(page)
    assert at60["wheel"]["cx"] != at30["wheel"]["cx"] and at60["centre"]["cy"] != at30["centre"]["cy"]
    assert at60["crank"] == at30["crank"]
    assert page.is_hidden(".instant-centre-note")
    scrub(page, 90)
    limit = gear_train(page)
    assert "display: none" in limit["wheel"].get("style", "") and "display: none" in limit["mark"].get("style", "")
    assert "display: none" not in limit["line"].get("style", "")
    # through A, perpendicular to OA: level to 0.01 px (the crank angle comes at plot precision, 7 significant
    # digits, which tilts a line a few thousand px long by at most 5e-7 rad)
    assert abs(float(limit["line"]["y1"]) - float(limit["line"]["y2"])) < 1e-2
    page.wait_for_selector(".instant-centre-note", state="visible")
    assert reading(page, "AP") == "∞"
    assert "NaN" not in limit["html"] and shows_no_nan(page)
    screenshot(page, "angular_parallel_limit")
    scrub(page, 100)
    assert page.is_hidden(".instant-centre-note")

    page.select_option("#variant", "trammel")
    page.wait_for_function("() => document.querySelector('#panel-gear_train svg .bar') !== null")
    scrub(page, 50)
    page.wait_for_function("() => document.querySelectorAll('.gear-train-readings dd')[6]?.textContent === '1 m'")
    assert reading(page, "AP") == reading(page, "OA") == "1 m"                    # P: the rectangle's fourth corner
    assert reading(page, "ε**") == "0 rad/s²"
    # the trammel's crank OA turns by hand (the view built anew for this variant); the plots' cursors follow
    state = before_turning(page, "#panel-gear_train svg")
    state["pivot"], state["end"] = turn_crank(page, "#panel-gear_train svg")
    phi = assert_turned(page, "#panel-gear_train svg", "components", state)
    assert reading(page, "φ") == f"{phi:.1f}°"
    assert shows_no_nan(page)
    screenshot(page, "angular_trammel")
    assert page.problems == []
