"""The dynamics scenes in a real browser: every variant's panels (checked on test_notation's walk), the friction drag and self-locking,
the two conventions of M_c0, the phase portrait under a λ drag, the stalling Kloss motor, and the
language switch keeping the settings."""
from __future__ import annotations

from urllib.parse import urlencode

import pytest

from conftest import drag_slider, interface_texts, plot_text, read_scene, screenshot, shown

pytestmark = pytest.mark.browser

SCENES = {scene["id"]: scene for scene in map(read_scene, ["resisting_moment", "reduced_inertia", "equation_of_motion"])}
FRICTION = SCENES["resisting-moment"]
MOTION = SCENES["equation-of-motion"]
GRAPH = "document.querySelector(`#panel-${id} .graph`)"
GRAPH_KINDS = ("plot", "polar")


def open_scene(page, scene: dict, lang: str = "ru", **state) -> None:
    page.goto(f"/scenes/{scene['id']}?{urlencode({'lang': lang, **state})}")
    variant = next((v for v in scene["variants"] if v["id"] == state.get("variant")), scene["variants"][0])
    wait_for_panels(page, scene, variant)


def graph_panels(scene: dict, variant: dict) -> list[str]:
    return [panel for panel in variant["panels"] if scene["panels"][panel]["kind"] in GRAPH_KINDS]


def wait_for_panels(page, scene: dict, variant: dict) -> None:
    """Until every panel of the variant is shown and each graph, scrolled into view, has its curves."""
    for panel in variant["panels"]:
        page.wait_for_selector(f"#panel-{panel}", state="visible")
    for panel in graph_panels(scene, variant):
        page.locator(f"#panel-{panel}").scroll_into_view_if_needed()
        page.wait_for_function(f"id => {GRAPH}?.data?.length > 0", arg=panel)


def trace(page, panel: str, name: str | None = None, key: str = "y") -> str:
    """The values `key` of a panel's trace called name (the first trace if None), as JSON text."""
    return page.evaluate(f"""([id, name, key]) => {{
        const data = {GRAPH}.data;
        return JSON.stringify((data.find(t => t.name === name) ?? data[0])[key]);
    }}""", [panel, name, key])


def wait_for_new_trace(page, panel: str, before: str, name: str | None = None, key: str = "y") -> None:
    page.locator(f"#panel-{panel}").scroll_into_view_if_needed()
    page.wait_for_function(f"""([id, name, key, before]) => {{
        const data = {GRAPH}?.data ?? [];
        const trace = data.find(t => t.name === name) ?? data[0];
        return trace !== undefined && JSON.stringify(trace[key]) !== before;
    }}""", arg=[panel, name, key, before])


def figure_value(page, label: str) -> str:
    """The number shown beside label in the figures panel."""
    return page.locator(".figures-list dt", has_text=label).locator("xpath=following-sibling::dd[1]").inner_text()


def warnings(page) -> str:
    return page.inner_text("#notices")


def prefix(text: str) -> str:
    """The words of an interface text before its first placeholder."""
    return text.split("{")[0]


def assert_variant_shows_all_its_panels(page, scene: dict, variant: dict) -> None:
    """The open page of a dynamics scene in ru at `variant` shows every panel of it, titled as the scene says,
    with the variant's text, no refusal and no NaN (or, for the reader's own mechanism absent from the address,
    the link to the editor). test_notation walks every variant of every scene in ru and calls this on the
    dynamics scenes' pages, so that each page is opened once for both checks."""
    assert page.inner_text("h1") == scene["title"]["ru"]
    assert page.locator("#linkage").count() == 0 and page.locator(".animation").count() == 0
    if variant.get("address"):              # the reader's own mechanism: none in this address, said so
        page.wait_for_selector(".own-mechanism-missing")
        assert page.get_attribute(".own-mechanism-missing a", "href") == "/editor?lang=ru"
        return
    wait_for_panels(page, scene, variant)
    titles = page.locator(".panel:visible h2").all_inner_texts()
    assert titles == [shown(scene["panels"][p]["title"]["ru"]) for p in variant["panels"] if "title" in scene["panels"][p]]
    assert page.inner_text(".variant-text") == shown(variant["text"]["ru"])
    assert page.locator(".refusal, .no-motion").count() == 0
    assert "NaN" not in page.inner_text("body")
    screenshot(page, f"dynamics_{scene['id']}_{variant['id']}")


def test_friction_drag_changes_the_moment_and_its_mean(browser_page):
    page = browser_page
    open_scene(page, FRICTION, "ru", variant="sine")
    label = shown(FRICTION["panels"]["figures"]["items"][0]["label"]["ru"])
    before_plot, before_mean = trace(page, "moment"), figure_value(page, label)
    assert before_mean.startswith("0,748")          # (3.12): 0,748 P_c l₁ at f = 0,15
    drag_slider(page, "#slider-f", 0.5)
    wait_for_new_trace(page, "moment", before_plot)
    f = float(page.input_value("#slider-f"))
    assert 0.5 < f < 0.7
    assert page.inner_text(".slider .readout >> nth=0") == f"f (коэффициент трения) = {f:.2f}".replace(".", ",")
    page.wait_for_function("before => document.querySelector('.figures-list dd').textContent !== before", arg=before_mean)
    assert float(figure_value(page, label).replace(",", ".")) > 0.75
    assert "converges" in page.get_attribute(".series-summary", "class")
    page.wait_for_url(f"**f={f}**")
    screenshot(page, "dynamics_friction_dragged")
    assert page.problems == []


def test_sine_mechanism_self_locks_from_f_one(browser_page):
    page = browser_page
    t = interface_texts("en")
    open_scene(page, FRICTION, "en", variant="sine")
    before = trace(page, "moment")
    page.focus("#slider-f")
    page.keyboard.press("End")                       # f = 1.2 ≥ 1
    wait_for_new_trace(page, "moment", before)
    page.wait_for_selector("#notices .warnings")
    assert prefix(t["warn_iteration_diverges"]) in warnings(page)
    assert "diverges" in page.get_attribute(".series-summary", "class")
    assert t["series_diverges"] in page.inner_text(".series-summary")
    consistent = shown(FRICTION["panels"]["figures"]["items"][1]["label"]["en"])
    assert figure_value(page, consistent) == "—"    # the exact sum of the series does not exist
    assert "NaN" not in page.inner_text("body")
    screenshot(page, "dynamics_sine_self_locking")
    assert page.problems == []


def test_printed_and_consistent_formulas_give_different_mean_moments(browser_page):
    page = browser_page
    open_scene(page, FRICTION, "en", variant="slider_crank")
    mean = plot_text(FRICTION["panels"]["moment"]["series"][2]["label"]["en"])
    names = lambda: page.evaluate(f"id => {GRAPH}.data.map(trace => trace.name)", "moment")
    printed = next(name for name in names() if name.startswith(mean))
    assert printed.startswith(f"{mean} = 0.395")     # (3.30) as printed, f = 0.2, λ = 3, k_p = 0.2
    page.check("input[name='toggle-convention'][value='consistent']")
    page.wait_for_function(f"([id, printed]) => !{GRAPH}.data.some(trace => trace.name === printed)",
                           arg=["moment", printed])
    assert any(name.startswith(f"{mean} = 0.404") for name in names())      # friction always resists
    page.wait_for_url("**convention=consistent**")
    assert prefix(interface_texts("en")["warn_textbook_series"]) not in warnings(page)
    assert page.problems == []


def test_lambda_drag_reshapes_the_phase_portrait_and_delta(browser_page):
    page = browser_page
    open_scene(page, MOTION, "en", variant="linear")
    steady = MOTION["panels"]["portrait"]["series"][1]["label"]["en"]
    delta = MOTION["panels"]["figures"]["items"][2]["label"]["en"]
    before_portrait, before_delta = trace(page, "portrait", steady, "r"), figure_value(page, delta)
    assert page.evaluate(f"id => {GRAPH}.data.map(trace => trace.type)", "portrait") == ["scatterpolar"] * 2
    drag_slider(page, "#slider-lambda", 0.05)
    wait_for_new_trace(page, "portrait", before_portrait, steady, "r")
    lam = float(page.input_value("#slider-lambda"))
    assert lam < 1.8
    assert f"r/l = {1 / lam:.3g}" in page.inner_text(".slider .readout >> nth=0")
    page.wait_for_function(f"""([label, before]) => [...document.querySelectorAll('.figures-list dt')]
        .find(dt => dt.textContent === label).nextElementSibling.textContent !== before""", arg=[delta, before_delta])
    assert float(figure_value(page, delta)) > float(before_delta)      # a shorter rod: larger J(φ) swing, larger δ
    assert page.locator("#panel-numerics .numerics-runtime_ms td").count() == 2       # steady cycle and start-up
    screenshot(page, "dynamics_phase_portrait_short_rod")
    assert page.problems == []


def test_kloss_motor_stall_is_told_in_words_instead_of_plots(browser_page):
    """Twice: the second time the server has the answers and M_к's family at hand, so that the keys are
    previewed from the family (members that stall among them) before the exact answers come."""
    page = browser_page
    t = interface_texts("en")
    for _ in range(2):
        open_scene(page, MOTION, "en", variant="kloss")
        page.focus("#slider-load")
        page.keyboard.press("End")                       # P_c = 6000 N
        page.wait_for_function("() => new URLSearchParams(location.search).get('load') === '6000'"
                               " && !document.querySelector('.scene-layout.preview, .stage.busy')")
        arrived = page.evaluate("() => performance.getEntriesByName('family-arrived').length")
        page.focus("#slider-M_max")                      # the grab: M_к's family
        page.wait_for_function("n => performance.getEntriesByName('family-arrived').length > n", arg=arrived,
                               timeout=120_000)
        for _ in range(3):
            page.keyboard.press("PageDown")              # M_к 70 → 28 N·m, below what the load needs
        assert float(page.input_value("#slider-M_max")) < 35
        page.wait_for_selector("#notices .no-motion")
        page.wait_for_function("() => !document.querySelector('.scene-layout.preview, .stage.busy')")
        page.wait_for_timeout(1000)                      # an animation frame and an idle period: panels drawn late
        assert page.inner_text("#notices .no-motion h2") == t["no_motion"]
        assert prefix(t["warn_stall_mean"]) in warnings(page) or prefix(t["warn_stall_in_cycle"]) in warnings(page)
        for panel in ("omega_phi", "epsilon", "time", "figures"):
            assert page.locator(f"#panel-{panel}").is_hidden()
        assert page.locator("#panel-numerics").is_visible()
        assert "NaN" not in page.inner_text("body")
        assert page.problems == []
    screenshot(page, "dynamics_kloss_stall")


def test_language_switch_keeps_the_settings_and_translates_the_warnings(browser_page):
    page = browser_page
    open_scene(page, FRICTION, "ru", variant="sine")
    page.check("input[name='toggle-convention'][value='consistent']")
    page.focus("#slider-f")
    page.keyboard.press("End")
    page.wait_for_selector("#notices .warnings")
    assert prefix(interface_texts("ru")["warn_iteration_diverges"]) in warnings(page)
    with page.expect_navigation():                       # the old page holds the same plots
        page.click("a[data-lang='uk']")
    page.wait_for_selector("#panel-iteration", state="visible")
    t = interface_texts("uk")
    assert page.inner_text("h1") == FRICTION["title"]["uk"]
    assert page.input_value("#slider-f") == "1.2"
    assert page.is_checked("input[name='toggle-convention'][value='consistent']")
    assert page.inner_text(".field span") == t["variant"]
    page.wait_for_selector("#notices .warnings")
    assert prefix(t["warn_iteration_diverges"]) in warnings(page)
    assert page.inner_text("#notices h2") == t["no_motion"]      # self-locking at every angle: no M_c(φ) to plot
    assert page.locator("#panel-moment").is_hidden()
    screenshot(page, "dynamics_friction_uk")
    assert page.problems == []
