""""Take the results away" and "Explore", in a real browser: each plot's export (PNG, SVG, CSV
equal to the plotted data), hover readouts in notation with units and the decimal comma, pinned ghost curves,
reset, the crank turned by hand (pointer and keys) with the plots' cursors following, stale results dimmed
while a computation is held back, the link that is the whole state (opened in a new page: the same request
body and the same plots), and the printed report. Two scenes, few page loads: the kinematics scene (its
linkage drawing) and the flywheel (its indicator diagram and the [δ] presets)."""
from __future__ import annotations

import csv
import io
import json
import math
import re
import xml.etree.ElementTree as ET

import pytest

from conftest import ARTIFACTS, interface_texts, read_scene, screenshot

pytestmark = pytest.mark.browser

KINEMATICS = read_scene("transfer_functions")
FLYWHEEL = read_scene("flywheel")
T = interface_texts("ru")
GRAPH = "document.querySelector(`#panel-${id} .graph`)"


def wait_for_plot(page, panel: str) -> None:
    page.wait_for_function(f"id => {GRAPH}?.data?.length > 0", arg=panel)


def traces(page, panel: str) -> list[dict]:
    """The panel's Plotly traces as drawn: x, y, whether a ghost."""
    return page.evaluate(f"""id => {GRAPH}.data.map(t => ({{x: t.x, y: t.y, ghost: Boolean(t.meta?.ghost),
        skip: t.hoverinfo === "skip"}}))""", panel)


def number(text: str) -> float | None:
    return None if text == "" else float(text.replace(",", "."))


def download(page, selector: str) -> bytes:
    with page.expect_download() as info:
        page.click(selector)
    return info.value.path().read_bytes()


def test_kinematics_scene_exports_hovers_pins_turns_and_marks_stale(browser_page):
    page = browser_page
    page.goto(f"/scenes/{KINEMATICS['id']}?lang=ru&variant=slider_crank")
    wait_for_plot(page, "u31")
    tools = "#panel-u31 .plot-tools"

    # Export: the buttons on the plot, with words in Russian, reachable from the keyboard (buttons)
    labels = page.eval_on_selector_all(f"{tools} button", "bs => bs.map(b => b.getAttribute('aria-label'))")
    assert labels == [T["plot_zoom_reset"], f"{T['plot_pan']}: {T['plot_pan_title']}", T["export_png"], T["export_svg"], T["export_csv"]]
    png = download(page, f"{tools} button:has-text('PNG')")
    assert png.startswith(b"\x89PNG\r\n\x1a\n") and len(png) > 5000
    svg = download(page, f"{tools} button:has-text('SVG')")
    root = ET.fromstring(svg.decode("utf-8"))
    assert root.tag == "{http://www.w3.org/2000/svg}svg"
    assert "u" in "".join(root.itertext()) and "Первая передаточная функция" in "".join(root.itertext())

    # CSV: UTF-8 with BOM, decimal comma and ";" in ru, headers in notation with units, rows = the plotted data
    raw = download(page, f"{tools} button:has-text('CSV')")
    assert raw.startswith("\ufeff".encode("utf-8"))
    rows = list(csv.reader(io.StringIO(raw.decode("utf-8-sig")), delimiter=";"))
    assert rows[0] == ["Угол кривошипа φ, °", "u₃₁, м"]
    plotted = traces(page, "u31")[0]
    assert len(rows) - 1 == len(plotted["x"]) == 361
    assert [number(r[0]) for r in rows[1:]] == [float(f"{x:.6g}") for x in plotted["x"]]   # φ to 6 digits
    assert [number(r[1]) for r in rows[1:]] == plotted["y"]
    assert any("," in r[1] for r in rows[1:]) and not any("." in r[1] for r in rows[1:])

    # Hover: one box titled with φ and its unit, the value in notation (u with subscript 31), unit, decimal comma
    box = page.locator("#panel-u31 .graph .nsewdrag").first.bounding_box()
    page.mouse.move(box["x"] + box["width"] * 0.3, box["y"] + box["height"] * 0.5)
    page.wait_for_function("() => document.querySelector('#panel-u31 .hoverlayer')?.textContent.includes('φ =')")
    hover = page.eval_on_selector("#panel-u31 .hoverlayer", "e => e.textContent")
    hover_svg = page.inner_html("#panel-u31 .hoverlayer")
    assert re.match(r"^φ = \d+,\d°", hover) and " м" in hover, hover
    assert "u₃₁ = " in hover
    value = hover.split("u₃₁ = ")[1].split(" м")[0]
    assert "," in value and "." not in value, hover
    page.mouse.move(5, 5)

    # Zoom: a box dragged on the plot zooms in (Plotly's own); the toolbar's ⟲ puts the axes back
    x_range = f"id => {GRAPH}._fullLayout.xaxis.range"
    page.mouse.move(box["x"] + box["width"] * 0.2, box["y"] + box["height"] * 0.2)
    page.mouse.down()
    page.mouse.move(box["x"] + box["width"] * 0.5, box["y"] + box["height"] * 0.8, steps=5)
    page.mouse.up()
    page.wait_for_function(f"id => {{ const r = ({x_range})(id); return r[1] - r[0] < 200; }}", arg="u31")
    page.click(f"{tools} button:has-text('⟲')")
    page.wait_for_function(f"id => {{ const r = ({x_range})(id); return r[0] === 0 && r[1] === 360; }}", arg="u31")

    # Compare runs: pin, change λ, both drawn; clear: the ghosts gone. Nothing is asked for the ghosts.
    # the page at rest first (under load a redraw could still come between reading the curve and pinning it)
    page.wait_for_function("() => !document.querySelector('.scene-layout.preview, .stage.busy')")
    page.wait_for_load_state("networkidle")
    asked = []
    page.on("request", lambda request: "/api/" in request.url and asked.append(request.url))
    before = traces(page, "u31")[0]["y"]
    page.click("#pin-curves")
    page.wait_for_function(f"id => {GRAPH}.data.some(t => t.meta?.ghost)", arg="u31")
    assert asked == []
    assert [t["y"] for t in traces(page, "u31") if t["ghost"]] == [before]     # the ghost is the curve pinned
    page.focus("#slider-lambda")
    for _ in range(5):
        page.keyboard.press("ArrowRight")
    page.wait_for_function("() => new URLSearchParams(location.search).get('lambda') === '3.05'")
    # compared value by value in the page (Python's and JavaScript's JSON write 1e-07 differently)
    page.wait_for_function(f"([id, before]) => {{ const own = {GRAPH}.data.filter(t => !t.meta?.ghost);"
                           " return own.length && own[0].y.some((y, i) => y !== before[i])"
                           " && !document.querySelector('.scene-layout.preview, .stage.busy'); }",
                           arg=["u31", before])
    drawn = traces(page, "u31")
    ghosts = [t for t in drawn if t["ghost"]]
    assert [g["y"] for g in ghosts] == [before] and any(not t["ghost"] and t["y"] != before for t in drawn)
    assert page.eval_on_selector("#panel-u31 .legend", "e => e.textContent").count(T["pinned"]) == 1
    screenshot(page, "explore_pinned_ru")
    page.click("#clear-pinned")
    page.wait_for_function(f"id => !{GRAPH}.data.some(t => t.meta?.ghost)", arg="u31")

    # Turn the crank: drag about its pivot; the angle follows, and the plots' cursors with it
    page.locator("#linkage svg").scroll_into_view_if_needed()
    circle = page.locator("#linkage .crank-circle").bounding_box()
    cx, cy = circle["x"] + circle["width"] / 2, circle["y"] + circle["height"] / 2
    radius = circle["width"] / 2
    cursor = "document.querySelector('#panel-u31 .cursor').style.transform"
    cursor_before = page.evaluate(cursor)
    phi_before = page.inner_text(".phi-readout")
    page.mouse.move(cx + radius, cy)
    page.mouse.down()
    page.mouse.move(cx, cy + radius, steps=6)              # a quarter turn on the screen
    page.mouse.move(cx, cy - radius, steps=12)             # on, the short way, through the right
    page.mouse.up()
    phi_dragged = page.inner_text(".phi-readout")
    assert phi_dragged != phi_before
    degrees_now = number(phi_dragged.removeprefix("φ = ").removesuffix("°"))
    pin = page.evaluate("""() => { const pins = document.querySelectorAll('#linkage .moving circle');
        return [...pins].map(p => p.getBoundingClientRect()).map(r => [r.x + r.width / 2, r.y + r.height / 2]); }""")
    assert any(math.dist(p, (cx, cy - radius)) < 6 for p in pin), "the crank pin is where the pointer let go"
    assert 0 <= degrees_now < 360
    assert page.evaluate(cursor) != cursor_before
    page.focus("#linkage svg")
    page.keyboard.press("ArrowRight")
    phi_key = number(page.get_attribute("#linkage svg", "aria-valuenow"))
    assert phi_key == round(degrees_now + 1) % 360 or abs(phi_key - (degrees_now + 1)) <= 1

    # Immediate feedback: a computation held back beyond 300 ms dims the old curves and shows progress
    held = []
    page.route("**/api/v1/kinematics*", lambda route: held.append(route))
    old = json.dumps(traces(page, "u31")[0]["y"])
    page.check("#overlay")                        # the overlay values of λ: asked at once (no family)
    page.wait_for_function("() => document.querySelector('#plots').classList.contains('stale')")
    assert page.is_visible(".progress") and page.inner_text(".progress") == T["recomputing"]
    page.wait_for_function("() => getComputedStyle(document.querySelector('#panel-u31 .graph')).opacity === '0.4'")
    assert json.dumps(traces(page, "u31")[0]["y"]) == old            # the old curves stay, marked
    screenshot(page, "explore_stale_ru")
    for route in held:
        route.continue_()
    page.unroute("**/api/v1/kinematics*")
    page.wait_for_function("() => !document.querySelector('#plots').classList.contains('stale')")
    page.wait_for_function(f"id => {GRAPH}.data.length > 1", arg="u31")     # the overlays drawn
    assert not page.is_visible(".progress")

    # Reset: the variant's defaults again (the address says so), the mechanism kept
    page.click("#reset-scene")
    lam = next(s for s in next(v for v in KINEMATICS["variants"] if v["id"] == "slider_crank")["sliders"]
               if s["id"] == "lambda")
    page.wait_for_function("d => new URLSearchParams(location.search).get('lambda') === String(d)", arg=lam["default"])
    assert page.input_value("#variant") == "slider_crank"
    assert page.problems == []


class Bodies(list):
    """The flywheel request bodies a page sent, in order, and how many of them were answered."""
    answered = 0


def flywheel_bodies(page) -> Bodies:
    bodies = Bodies()

    def flywheel(request) -> bool:
        return request.url.split("?")[0].endswith("/api/v1/flywheel")

    def finished(request) -> None:
        bodies.answered += flywheel(request)

    page.on("request", lambda request: flywheel(request) and bodies.append(json.loads(request.post_data)))
    page.on("requestfinished", finished)
    page.on("requestfailed", finished)
    return bodies


def settled(page, bodies: Bodies) -> None:
    """Every flywheel request sent is answered, none follows for 300 ms, and every graph of the page has drawn the
    last answer (whatever the machine's speed: the page may send its request a moment after the change that asked
    for it)."""
    for _ in range(2400):                              # a guard against a hang (2 minutes), not a time limit
        page.wait_for_timeout(50)
        if bodies.answered == len(bodies) > 0:
            page.wait_for_timeout(300)
            if bodies.answered == len(bodies):
                break
    page.wait_for_function("() => !document.querySelector('.results').classList.contains('busy')")
    # every graph shown holds the last answer: one out of view is drawn in an idle period, which a busy machine
    # puts off (dynamics_view.js: the panels' data-answers, each graph's data-answer)
    page.wait_for_function("""() => [...document.querySelectorAll('#panels > figure:not([hidden])')]
        .filter((figure) => figure.querySelector(':scope > .graph-frame'))
        .every((figure) => figure.dataset.answer === document.querySelector('#panels').dataset.answers)""")


def test_flywheel_link_is_the_whole_state_and_the_report_prints(browser_page):
    page = browser_page
    bodies = flywheel_bodies(page)
    page.goto(f"/scenes/{FLYWHEEL['id']}?lang=ru")
    wait_for_plot(page, "speed")

    # Change everything: a toggle, a slider, the [δ] preset, an indicator-diagram point
    page.check("#toggle-strokes input[value='4']")
    page.focus("#slider-omega_mean")
    page.keyboard.press("ArrowRight")
    page.select_option("#preset", "1")
    page.click(".indicator-table summary")
    point = page.locator(".indicator-table tbody tr").nth(3).locator("input").first
    point.fill("0.5")
    point.dispatch_event("change")
    page.wait_for_function("() => new URLSearchParams(location.search).has('edit.motor.expansion')")
    settled(page, bodies)
    expected = bodies[-1]
    assert expected["motor"]["strokes"] == 4 and expected["motor"]["expansion"][3] == 0.5
    speed = json.dumps(traces(page, "speed")[0]["y"])

    # Hover in notation: A with the subscript д as Plotly's subscript, the unit, the decimal comma
    page.locator("#panel-work").scroll_into_view_if_needed()
    box = page.locator("#panel-work .nsewdrag").first.bounding_box()
    page.mouse.move(box["x"] + box["width"] * 0.4, box["y"] + box["height"] * 0.5)
    page.wait_for_function("() => document.querySelector('#panel-work .hoverlayer')?.textContent.includes('φ =')")
    hover = page.eval_on_selector("#panel-work .hoverlayer", "e => e.textContent").replace("\u200b", "")
    subscripts = page.eval_on_selector_all("#panel-work .hoverlayer tspan[style*='baseline-shift'], "
                                           "#panel-work .hoverlayer tspan[dy]", "ts => ts.map(t => t.textContent)")
    assert re.match(r"^φ = \d+,\d°", hover), hover
    assert "Aд = " in hover and " Дж" in hover and "д" in subscripts, (hover, subscripts)
    value = hover.split("Aд = ")[1].split(" Дж")[0]
    assert "," in value and "." not in value, hover
    page.mouse.move(5, 5)

    page.context.grant_permissions(["clipboard-read", "clipboard-write"])
    page.click("#copy-link")
    page.wait_for_function("() => document.querySelector('#share-status').textContent !== ''")
    link = page.input_value("#share-link")
    assert page.is_visible("#share-link")
    assert page.inner_text("#share-status") in (T["link_copied"], T["link_copy_by_hand"])

    # The link in a new page: the same request body, the same plots, the preset and the edit shown
    other = page.context.new_page()
    other_bodies = flywheel_bodies(other)
    other.goto(link)
    wait_for_plot(other, "speed")
    settled(other, other_bodies)
    assert other_bodies[0] == expected
    assert json.dumps(traces(other, "speed")[0]["y"]) == speed
    assert other.input_value("#preset") == "1"
    assert other.locator(".indicator-table tbody tr").nth(3).locator("input").first.input_value() == "0.5"
    other.close()

    # The printed report: set-up, plots, numbers, numerics, sources; the page's controls left out
    page.evaluate("() => { window.printed = 0; window.print = () => { window.printed += 1; }; }")
    page.click("#print-report")
    page.wait_for_function("() => window.printed === 1")
    page.emulate_media(media="print")
    for part in ["h1", ".intro .source", "#controls .readout", "#variant", "#panel-speed .graph svg",
                 "#panel-figures", "#panel-numerics", "#panel-comparison"]:
        assert page.locator(part).first.is_visible(), part
    for chrome in [".scene-tools", "#panel-speed .plot-tools", "#slider-delta", ".breadcrumb"]:
        assert not page.locator(chrome).first.is_visible(), chrome
    ARTIFACTS.mkdir(exist_ok=True)
    pdf = page.pdf(path=str(ARTIFACTS / "explore_report_ru.pdf"), format="A4")
    assert pdf.startswith(b"%PDF") and len(pdf) > 50_000
    page.emulate_media(media="screen")
    page.set_viewport_size({"width": 390, "height": 844})
    screenshot(page, "explore_flywheel_ru_390")
    assert page.problems == []
