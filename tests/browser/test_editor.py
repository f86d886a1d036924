"""The mechanism editor (/editor) in Chromium, as a student uses it.

One page load (from the start page's link) builds a shaping machine (crank + RPR + RRP, the coordinates of
content/mechanisms/shaping_machine.json) from nothing with the mouse, and on it: W = 1 and the structural
formula, the animation (the drawing changes between frames), a traced path, the velocity and acceleration
plans (each drawn vector's SVG length times the scale written under the plan equals the value shown in the
table; the plan's value of each point equals the analytic one shown beside it), editing a length redraws, a
refusal's reason beside the group it concerns and undoing its cause, the shared link reloads the same mechanism, and the Russian
page has no English left. A second load at phone size (the mechanism given in the address) fits the screen,
passes axe-core, saves the mechanism as a file and opens another from a file. A third builds a mechanism
driven by a slider (an input slider on a frame guide and an RRR group to a frame joint): W = 1 with the
slider's prismatic pair, the cursor shows s in metres, the special positions are said; then the slider-driven
preset loads; on the crank-slider preset the rod's length is also shown and set as λ = l₂/l₁ and r/l.
"""
from __future__ import annotations

import base64
import json
import re
from pathlib import Path

import pytest

from conftest import PHONE, REPO, drag_slider, interface_texts, screenshot

# Chromium reports every HTTP error answer on the console; the 422 that says why a mechanism is refused is the
# answer the page shows in words (as tests/browser/test_scene.py)
REFUSED = re.compile(r"Failed to load resource: the server responded with a status of 422")
AXE = REPO / "tests" / "browser" / "vendor" / "axe.min.js"
SHAPING = json.loads((REPO / "content" / "mechanisms" / "shaping_machine.json").read_text(encoding="utf-8"))
JAW_CRUSHER = json.loads((REPO / "content" / "mechanisms" / "jaw_crusher.json").read_text(encoding="utf-8"))
NOTATION = {"RRR", "RRP", "RPR", "PRP", "RPP", "II", "sin"}    # the textbook's, the same in every language


def answers(page) -> int:
    return int(page.get_attribute("#editor-drawing", "data-answers") or 0)


def settled(page, before: int) -> None:
    """Wait until the page has shown an answer newer than `before` (a table or a refusal)."""
    page.wait_for_function("""n => { const s = document.querySelector("#editor-drawing");
        return Number(s.dataset.answers ?? 0) > n && s.dataset.state !== "waiting"; }""", arg=before, timeout=30_000)


def click_at(page, x: float, y: float) -> None:
    """A mouse click at the point (x, y) in metres of the drawing (its mapping: data-view = "x₀ y₀ k")."""
    cx, cy = page.evaluate("""([x, y]) => { const svg = document.querySelector("#editor-drawing svg");
        const [x0, y0, k] = svg.dataset.view.split(" ").map(Number);
        const p = svg.createSVGPoint(); p.x = (x - x0) * k; p.y = (y0 - y) * k;
        const q = p.matrixTransform(svg.getScreenCTM()); return [q.x, q.y]; }""", [x, y])
    page.mouse.click(cx, cy)


def act(page, action) -> None:
    """Do something that changes the mechanism and wait for the page to show the server's answer to it."""
    before = answers(page)
    action()
    settled(page, before)


def number(text: str) -> float:
    """A number as the page writes it: decimal comma or point, a true minus, "1,43·10⁻⁹"."""
    text = text.strip().replace("−", "-").replace(",", ".")
    mantissa, _, power = text.partition("·10")
    if power:
        power = power.translate(str.maketrans("⁻⁰¹²³⁴⁵⁶⁷⁸⁹", "-0123456789"))
    return float(mantissa) * 10 ** int(power or 0)


def plans_ready(page) -> None:
    page.wait_for_function("""() => document.querySelector("#editor-plans").dataset.state === "ready"
        && document.querySelectorAll(".plan-svg line").length > 0""", timeout=30_000)


def drawn_plans(page) -> list[dict]:
    """Per plan: the scale written under it, the scale of its SVG, and each vector's drawn length (mm) with the
    value the table shows; each point's value from the plan and the analytic one."""
    return page.evaluate("""() => [...document.querySelectorAll(".plan-block")].map((block) => ({
        written: block.querySelector(".plan-scale").textContent,
        scale: Number(block.querySelector(".plan-svg").dataset.scale),
        vectors: [...block.querySelectorAll(".plan-svg line")].map((l) => ({ name: l.dataset.name,
            mm: Math.hypot(l.x2.baseVal.value - l.x1.baseVal.value, l.y2.baseVal.value - l.y1.baseVal.value),
            shown: block.querySelector(`td[data-vector="${l.dataset.name}"]`).textContent })),
        points: [...block.querySelectorAll("td[data-plan]")].map((td) => ({ plan: td.textContent,
            analytic: block.querySelector(`td[data-analytic="${td.dataset.plan}"]`).textContent })) }))""")


def test_build_a_shaping_machine_with_the_mouse(browser_page):
    page = browser_page
    page.goto("/?lang=en")
    page.click('a[href="/editor?lang=en"] >> nth=0')
    page.wait_for_function("() => document.querySelector('#editor-drawing')?.dataset.answers !== undefined")

    def place(mode, *clicks):
        page.click(f'[data-mode="{mode}"]')
        for item in clicks[:-1]:
            page.click(item) if isinstance(item, str) else click_at(page, *item)
        last = clicks[-1]
        act(page, (lambda: page.click(last)) if isinstance(last, str) else (lambda: click_at(page, *last)))

    place("joint", (0, 0))                                  # O, the crank's pivot
    place("joint", (0, -0.3))                               # O₁, the lever's pivot
    place("guide", (0, 0.25))                               # g1, the ram's guide
    place("crank", '[data-joint="O"]', (0.1, 0))            # crank OA, 0.1 m
    place("RPR", '[data-joint="A"]', '[data-joint="O₁"]')   # block at A in the lever's slot about O₁
    page.click('[data-mode="point"]')
    page.select_option("#editor-point-link", "3")
    act(page, lambda: click_at(page, 0.174, 0.222))         # B on the lever, 0.55 m from O₁
    place("RRP", '[data-joint="B"]', (-0.3, 0.25), (0.32, 0.25))   # rod BC, slider C on g1
    assert page.get_attribute("#editor-drawing", "data-state") == "ready"
    assert page.inner_text("#editor-mobility") == "W = 3·5 − 2·7 − 0 = 1"
    assert page.inner_text("#editor-formula") == "I(0,1) → II₃(2,3) → II₂(4,5)"
    lever = page.locator('[data-group="0"] .point-row input[aria-label="point B: along"]').input_value()
    assert number(lever) == pytest.approx(0.55, abs=0.005)      # the point clicked at 0.55 m along the lever

    frame = page.inner_html("#editor-drawing .links")
    page.click("#editor-play")
    page.wait_for_function("() => document.querySelector('#editor-phi').value !== '0'")
    page.wait_for_function("html => document.querySelector('#editor-drawing .links').innerHTML !== html", arg=frame)
    page.click("#editor-play")
    page.focus("#editor-phi")
    page.keyboard.press("Home")                             # back to φ = 0: B where it was put, clear of the
    page.wait_for_function("() => document.querySelector('#editor-phi').value === '0'")   # guide's angle handle
    plans_ready(page)
    page.click('[data-joint="B"]')                          # in "Look", a click on a joint traces its path
    assert page.locator("#editor-drawing polyline.trace").count() == 1
    shown_phi = page.input_value("#editor-phi")

    for plan in drawn_plans(page):
        # the scale under the plan is the one it is drawn at (3 significant digits written: nice numbers)
        assert number(plan["written"]) == pytest.approx(plan["scale"], rel=1e-12)
        assert len(plan["vectors"]) >= 5
        for v in plan["vectors"]:
            # drawn length × μ against the value shown with 4 significant digits: within its rounding (5e-4)
            assert v["mm"] * plan["scale"] == pytest.approx(number(v["shown"]), rel=6e-4, abs=1e-12), v
        for p in plan["points"]:
            # the plan's sum and the analytic value, 6 significant digits each: equal where shown
            assert number(p["plan"]) == pytest.approx(number(p["analytic"]), rel=2e-6), p

    page.fill("#editor-mu-v", "0.01")                          # the student's own scale μ_v
    page.press("#editor-mu-v", "Enter")
    page.wait_for_function("() => document.querySelector('.plan-svg').dataset.scale === '0.01'")
    velocity = drawn_plans(page)[0]
    assert number(velocity["written"]) == 0.01
    for v in velocity["vectors"]:
        assert v["mm"] * 0.01 == pytest.approx(number(v["shown"]), rel=6e-4, abs=1e-12), v

    typed = page.locator('[data-group="1"] input[type="text"][aria-label="length B C"]')
    before = page.get_attribute('[data-joint="C"]', "cx")
    act(page, lambda: (typed.fill("0.2"), typed.press("Enter")))
    assert page.get_attribute('[data-joint="C"]', "cx") != before, "the slider C did not move with a longer rod"
    assert page.input_value("#editor-phi") == shown_phi
    before = page.get_attribute('[data-joint="C"]', "cx")
    act(page, lambda: drag_slider(page, '[data-group="1"] > label.field input[type="range"]', 0.2))
    assert number(typed.input_value()) < 0.2, "the dragged length is not written in its field"
    assert page.get_attribute('[data-joint="C"]', "cx") != before, "dragging the rod's length did not redraw"

    texts = interface_texts("en")
    act(page, lambda: page.click('[data-element="O₁"] button.remove'))    # the lever's pivot gone: refused
    assert page.get_attribute("#editor-drawing", "data-state") == "refused"
    assert page.inner_text('[data-group="0"] .refusal-reason') == \
        texts["err_unknown_element"].replace("{element}", "O₁")
    act(page, lambda: page.click("#editor-undo"))           # the removal undone
    assert page.get_attribute("#editor-drawing", "data-state") == "ready"

    page.wait_for_function("() => location.search.includes('m=')")
    link, elements = page.url, page.inner_text("#editor-elements")
    page.goto("about:blank")
    page.goto(link)
    page.wait_for_function("() => document.querySelector('#editor-drawing')?.dataset.state === 'ready'")
    assert page.inner_text("#editor-elements") == elements
    assert page.inner_text("#editor-formula") == "I(0,1) → II₃(2,3) → II₂(4,5)"

    with page.expect_navigation():
        page.click('a[data-lang="ru"]')
    page.wait_for_function("() => document.documentElement?.lang === 'ru' "     # (null while the page is replaced)
                           "&& document.querySelector('#editor-drawing')?.dataset.state === 'ready'")
    plans_ready(page)
    assert page.inner_text("#editor-formula") == "I(0,1) → II₃(2,3) → II₂(4,5)"
    text = page.evaluate("""() => {      // the page's visible words, without notation (translate="no") and drawings
        const walker = document.createTreeWalker(document.querySelector("main"), NodeFilter.SHOW_TEXT);
        const words = [];
        for (let node = walker.nextNode(); node; node = walker.nextNode()) {
            const parent = node.parentElement;
            if (parent.closest("[translate='no'], svg, script, .modebar")) continue;
            if (parent.tagName === "OPTION" || parent.checkVisibility()) words.push(node.textContent);
        }
        return words.join(" "); }""")
    english = sorted({w for w in re.findall(r"[A-Za-z]{2,}", text)} - NOTATION)
    assert english == [], f"English words left on the Russian editor: {english}"
    assert re.search(r"\d,\d", text), "no decimal comma on the Russian page"
    screenshot(page, "editor_ru_desktop")
    assert [p for p in page.problems if not REFUSED.search(p)] == []


def test_a_shared_mechanism_on_a_phone(phone, tmp_path):
    encoded = base64.urlsafe_b64encode(json.dumps(SHAPING["linkage"]).encode()).decode().rstrip("=")
    phone.goto(f"/editor?lang=ru&m={encoded}")
    phone.wait_for_function("() => document.querySelector('#editor-drawing')?.dataset.state === 'ready'")
    plans_ready(phone)
    assert phone.inner_text("#editor-formula") == "I(0,1) → II₃(2,3) → II₂(4,5)"
    width = phone.evaluate("() => document.documentElement.scrollWidth")
    assert width <= PHONE["width"], f"the editor is {width} px wide on a 390 px screen"
    phone.add_script_tag(path=str(AXE))
    violations = phone.evaluate("""() => axe.run(document, { resultTypes: ["violations"] }).then((r) =>
        r.violations.filter((v) => ["serious", "critical"].includes(v.impact))
          .map((v) => `${v.id} (${v.impact}): ${v.nodes.map((n) => n.target.join(" ")).slice(0, 3).join(", ")}`))""")
    assert violations == [], f"axe-core finds {violations}"
    screenshot(phone, "editor_ru_phone")

    with phone.expect_download() as download:                # saved as a file: the same mechanism
        phone.click("#editor-export")
    saved = json.loads(Path(download.value.path()).read_text(encoding="utf-8"))
    assert saved["mechanism"] == "general"
    assert saved["linkage"]["groups"] == SHAPING["linkage"]["groups"]
    crusher = tmp_path / "jaw_crusher.json"                  # a file opened: another mechanism
    crusher.write_text(json.dumps(JAW_CRUSHER["linkage"]), encoding="utf-8")
    before = answers(phone)
    phone.set_input_files("#editor-import", str(crusher))
    settled(phone, before)
    assert phone.inner_text("#editor-formula") == "I(0,1) → II₁(2,3) → II₁(4,5)"
    assert phone.problems == []


def test_a_slider_driven_mechanism(browser_page):
    page = browser_page
    page.goto("/editor?lang=en")
    page.wait_for_function("() => document.querySelector('#editor-drawing')?.dataset.answers !== undefined")

    def place(mode, *clicks):
        page.click(f'[data-mode="{mode}"]')
        for item in clicks[:-1]:
            click_at(page, *item)
        act(page, lambda: click_at(page, *clicks[-1]))

    place("joint", (0, 0))                                  # O, the crank's pivot
    place("guide", (0.2, 0))                                # g1 through (0.2, 0), along x
    place("slider", (0.45, 0), (0.3, 0))                    # the input slider on g1, its joint at s = 0.1 m
    place("RRR", (0.3, 0), (0, 0), (0, 0.1))                # rod to the crank pin, crank about O
    assert page.get_attribute("#editor-drawing", "data-state") == "ready"
    assert page.inner_text("#editor-mobility") == "W = 3·3 − 2·4 − 0 = 1"
    assert page.inner_text("#editor-formula") == "I(0,1) → II₁(2,3)"
    assert page.inner_text("#editor-phi-value").startswith("s = 0.1")      # the travel 0.1…0.2 m
    assert page.inner_text("#editor-phi-label") == interface_texts("en")["editor_travel_s"]
    plans_ready(page)
    assert page.inner_text("#editor-plans .hint").startswith("s = 0.1")    # the plans at s, with v₁ and a₁
    page.wait_for_function("() => document.querySelectorAll('#editor-special li').length > 0")
    assert "link 3 reverses" not in page.inner_text("#editor-special")      # the crank turns one way
    frame = page.inner_html("#editor-drawing .links")
    page.fill("#editor-phi", "200")
    page.dispatch_event("#editor-phi", "input")
    page.wait_for_function("html => document.querySelector('#editor-drawing .links').innerHTML !== html", arg=frame)
    screenshot(page, "editor_slider_input")
    # played, the slider runs its travel out and back: near the end of its travel it turns back, no jump to the start
    page.fill("#editor-phi", "350")
    page.dispatch_event("#editor-phi", "input")
    page.click("#editor-play")
    shown = page.evaluate("""() => new Promise((done) => {
        const seen = [], start = performance.now();
        const look = () => {
          seen.push(Number(document.querySelector('#editor-phi').value));
          if (seen.at(-1) < 340 || performance.now() - start > 20000) done(seen); else requestAnimationFrame(look);
        };
        look(); })""")
    page.click("#editor-play")
    assert shown[-1] < 340 and min(shown) > 200, shown          # a jump to the start would show rows near 0

    before = answers(page)
    page.select_option("#editor-preset", "slider_driven_crank")
    settled(page, before)
    assert page.inner_text("#editor-formula") == "I(0,1) → II₁(2,3)"
    assert page.get_attribute("#editor-drawing", "data-state") == "ready"

    before = answers(page)                 # a crank again: the rod's length also as λ = l₂/l₁ and r/l
    page.select_option("#editor-preset", "slider_crank")
    settled(page, before)
    assert page.inner_text("#editor-phi-label") == "Crank angle φ"
    ratio = page.locator('[data-group="0"] input[type="text"][aria-label="λ: length A B over length O A"]')
    inverse = page.locator('[data-group="0"] input[type="text"][aria-label="r/l: length O A over length A B"]')
    assert number(ratio.input_value()) == pytest.approx(3.0) and number(inverse.input_value()) == pytest.approx(1 / 3, abs=5e-4)
    act(page, lambda: (ratio.fill("4"), ratio.press("Enter")))
    rod = page.locator('[data-group="0"] input[type="text"][aria-label="length A B"]')
    assert number(rod.input_value()) == pytest.approx(0.4) and number(inverse.input_value()) == pytest.approx(0.25)
    assert [p for p in page.problems if not REFUSED.search(p)] == []
