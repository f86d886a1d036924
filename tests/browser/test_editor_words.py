"""The editor's words in Chromium: textbook names, undo and redo, readiness before results, every message filled,
the plans lettered and readable.

On an empty Russian editor a four-bar and then a six-bar are built by clicks: the supports are O and O₁, the crank
OA, the moving joints B, C in order of attachment, the groups II₁(2,3) and II₂(4,5) in the list, the drawings of
the groups apart and the structural formula. A crank length typed so that the four-bar cannot turn: the readiness
line says so in Russian with the exact limits of assembly, checked against the closed form of the flattened
triangle |O₁A| = l_AB + l_BO₁ (|O₁A|² = r² + d² − 2rd cos φ) to the 0.01° written, the dynamics' and the course
project's links disabled with the reason, no "{" in any visible text. Undo and redo by the buttons and by Ctrl+Z,
Ctrl+Shift+Z, Ctrl+Y step back and forth, the address following (each step's m as it was). No English word of the
app's own labels on the Russian page, the presets' guides by their textbook names; on the plans of every preset
every point's image lettered and no two labels' boxes (getBBox) meet. Screenshots in ru, en and at 390 × 844.
Nothing is dragged here (tests of direct manipulation do that).
"""
from __future__ import annotations

import base64
import json
import math
import re
from urllib.parse import parse_qs, urlparse

from conftest import PHONE, REPO, interface_texts, screenshot
from test_editor import act, click_at

REFUSED = re.compile(r"Failed to load resource: the server responded with a status of 422")
PRESETS = sorted(path.stem for path in (REPO / "content" / "mechanisms").glob("*.json"))
TAUGHT = {"slide", "ram", "slot", "left", "right"}          # the presets' guides' own names, English words
# words the textbook writes the same in every language (kinds of groups, keys of the keyboard)
NOTATION = {"rrr", "rrp", "rpr", "prp", "rpp", "ctrl", "shift", "tab", "enter", "esc", "sin"}


def english_labels() -> set[str]:
    """Every English word (3 letters or more) of the app's editor and message texts that the Russian texts do not
    write themselves, and the presets' guides' names."""
    en, ru = interface_texts("en"), interface_texts("ru")
    russian = {w.lower() for text in ru.values() for w in re.findall(r"[A-Za-z]{3,}", text)}
    words = {w.lower() for key, text in en.items() if key.startswith(("editor_", "guide_label_", "warn_", "err_"))
             for w in re.findall(r"[A-Za-z]{3,}", text)}
    return (words - russian - NOTATION) | TAUGHT


VISIBLE_TEXT = """() => {          // every text the page shows, drawings included
    const walker = document.createTreeWalker(document.body, NodeFilter.SHOW_TEXT);
    const texts = [];
    for (let node = walker.nextNode(); node; node = walker.nextNode()) {
        const parent = node.parentElement;
        if (!parent || parent.closest("script, style, template, option")) continue;
        if (parent.checkVisibility()) texts.push(node.textContent);
    }
    return texts.join(" "); }"""

LABELS_APART = """() => [...document.querySelectorAll(".plan-svg")].map((svg) => {
    const boxes = [...svg.querySelectorAll("text")].map((t) => ({ text: t.textContent, box: t.getBBox() }));
    const meet = [];
    boxes.forEach((a, i) => boxes.slice(i + 1).forEach((b) => {
        if (a.box.x < b.box.x + b.box.width && b.box.x < a.box.x + a.box.width
            && a.box.y < b.box.y + b.box.height && b.box.y < a.box.y + a.box.height) meet.push([a.text, b.text]);
    }));
    return { kind: svg.closest("[data-plan-kind]").dataset.planKind, vertices: [...svg.querySelectorAll(".plan-vertex")]
        .map((t) => t.textContent), meet }; })"""


def place(page, mode, *clicks) -> None:
    """A tool, then its clicks: a selector (a joint, a guide) or a point in metres; the last one waits."""
    page.click(f'[data-mode="{mode}"]')
    do = lambda item: page.click(item) if isinstance(item, str) else click_at(page, *item)     # noqa: E731
    for item in clicks[:-1]:
        do(item)
    act(page, lambda: do(clicks[-1]))


def mechanism(page) -> str:
    return parse_qs(urlparse(page.url).query)["m"][0]


def readiness(page, state: str) -> str:
    page.wait_for_function("s => document.querySelector('#editor-readiness').dataset.state === s", arg=state)
    return page.inner_text("#editor-readiness")


def key(page, combination: str) -> None:
    """A keyboard shortcut with the focus out of any field (a field keeps Ctrl+Z for its own text)."""
    page.evaluate("() => document.activeElement?.blur()")
    act(page, lambda: page.keyboard.press(combination))


def four_bar_limits(r: float, d: float, coupler: float, rocker: float) -> tuple[float, float]:
    """The crank angles (degrees) where |O₁A| = l_AB + l_BO₁: O at the origin, O₁ at (d, 0), the crank along +x at φ = 0."""
    stretched = math.degrees(math.acos((r**2 + d**2 - (coupler + rocker) ** 2) / (2 * r * d)))
    return stretched, 360 - stretched


def test_names_undo_readiness_and_words_in_russian(browser_page):
    page, ru = browser_page, interface_texts("ru")
    page.goto("/editor?lang=ru")
    page.wait_for_function("() => document.querySelector('#editor-readiness')?.dataset.state === 'empty'")
    assert page.inner_text("#editor-readiness") == ru["editor_next_frame"].replace("{tool}", ru["editor_mode_joint"])

    place(page, "joint", (0, 0))                                     # O
    place(page, "joint", (0.4, 0))                                   # O₁
    place(page, "crank", '[data-joint="O"]', (0.1, 0))              # OA, 0.1 m
    place(page, "RRR", '[data-joint="A"]', '[data-joint="O₁"]', (0.3, 0.25))     # B: AB 0.32 m, BO₁ 0.269 m
    for name in ("O", "O₁", "A", "B"):
        assert page.locator(f'#editor-drawing [data-joint="{name}"]').count() == 1, name
    assert page.inner_text('[data-element="crank"] strong').endswith("OA")
    assert page.inner_text("#editor-formula") == "I(0,1) → II₁(2,3)"
    assert readiness(page, "ready").startswith("W = 1. " + ru["editor_ready_full_turn"])
    four_bar = mechanism(page)

    crank = page.locator('[data-element="crank"] input[type="text"][aria-label="длина O A"]')
    act(page, lambda: (crank.fill("0,2"), crank.press("Enter")))     # the crank too long: the group opens out
    said = readiness(page, "partial")
    page.wait_for_function("() => document.querySelector('#editor-readiness').innerText.includes('через 0°')")
    said = page.inner_text("#editor-readiness")
    first, second = four_bar_limits(0.2, 0.4, 0.32, 0.269)
    degrees = lambda value: f"{value:.2f}°".replace(".", ",")        # noqa: E731
    assert said == (f"W = 1. {ru['editor_ready_no_full_turn']} Группа II₁(2,3) собирается только при φ от "
                    f"{degrees(second)} через 0° до {degrees(first)}. {ru['editor_next_turn']}"), said
    limits = page.locator("#editor-special li[data-kind='limit_of_assembly']")
    assert [limits.nth(k).inner_text() for k in range(limits.count())] == [
        f"φ = {degrees(first)}: группа II₁(2,3) RRR: предел сборки", f"φ = {degrees(second)}: группа II₁(2,3) RRR: предел сборки"]
    open_links = page.locator("#editor-open-dynamics")
    assert open_links.locator("a").count() == 0 and open_links.locator("[aria-disabled='true']").count() >= 4
    assert page.inner_text("#editor-open-dynamics-reason") == ru["editor_project_needs_turn"]
    assert page.get_attribute("#editor-course-project", "aria-disabled") == "true"
    assert page.get_attribute("#editor-course-project", "href") is None
    text = page.evaluate(VISIBLE_TEXT)
    assert "{" not in text and "null" not in text and "joints_d1" not in text, text
    screenshot(page, "editor_words_cannot_turn_ru")
    cannot_turn = mechanism(page)

    key(page, "Control+z")                                            # the typed length undone …
    assert readiness(page, "ready").startswith("W = 1. " + ru["editor_ready_full_turn"])
    assert mechanism(page) == four_bar
    key(page, "Control+Shift+z")                                      # … and redone …
    readiness(page, "partial")
    assert mechanism(page) == cannot_turn
    act(page, lambda: page.click("#editor-undo"))                     # … and undone by the button
    readiness(page, "ready")
    assert mechanism(page) == four_bar and not page.is_disabled("#editor-redo")

    place(page, "guide", (0, 0.45))                                  # g1 along x through y = 0.45 m
    place(page, "RRP", '[data-joint="B"]', (-0.3, 0.45), (0.6, 0.45))            # C on g1: BC 0.361 m
    assert page.locator('#editor-drawing [data-joint="C"]').count() == 1
    assert page.is_disabled("#editor-redo")                           # a new step: nothing left to redo
    assert page.inner_text("#editor-formula") == "I(0,1) → II₁(2,3) → II₂(4,5)"
    assert [page.inner_text(f'[data-group="{k}"] > strong').split(" ")[0] for k in (0, 1)] == ["II₁(2,3)", "II₂(4,5)"]
    assert page.eval_on_selector_all(".structure-groups li", "items => items.map((li) => li.dataset.groupName)") == \
        ["II₁(2,3)", "II₂(4,5)"]
    assert page.eval_on_selector_all("#editor-apart figcaption", "c => c.map((e) => e.textContent)") == \
        ["I(0,1)", "II₁(2,3) RRR", "II₂(4,5) RRP"]
    six_bar = mechanism(page)
    act(page, lambda: page.click("#editor-undo"))                     # the group off …
    assert page.inner_text("#editor-formula") == "I(0,1) → II₁(2,3)" and mechanism(page) != six_bar
    act(page, lambda: page.click("#editor-redo"))                     # … and on again
    assert page.inner_text("#editor-formula") == "I(0,1) → II₁(2,3) → II₂(4,5)" and mechanism(page) == six_bar
    key(page, "Control+z")
    key(page, "Control+y")
    assert mechanism(page) == six_bar
    page.wait_for_function("() => document.querySelector('#editor-plans').dataset.state === 'ready'")
    plans = page.evaluate(LABELS_APART)
    assert [p["kind"] for p in plans] == ["velocity", "acceleration"]
    for plan, pole in zip(plans, ("p", "π")):
        assert plan["meet"] == [], plan
        lettered = {name for label in plan["vertices"] for name in label.split(", ")}
        assert {pole, "a", "b", "c"} <= lettered, plan["vertices"]
    screenshot(page, "editor_words_six_bar_ru")
    english = english_labels()
    words = {w.lower() for w in re.findall(r"[A-Za-z]{3,}", page.evaluate(VISIBLE_TEXT))}
    assert words & english == set(), sorted(words & english)
    assert [p for p in page.problems if not REFUSED.search(p)] == []


def test_presets_plans_lettered_apart_and_in_russian(browser_page):
    page = browser_page
    page.goto("/editor?lang=ru")
    page.wait_for_function("() => document.querySelector('#editor-drawing')?.dataset.answers !== undefined")
    english = english_labels()
    for name in PRESETS:
        act(page, lambda: page.select_option("#editor-preset", name))
        page.wait_for_function("() => document.querySelector('#editor-plans').dataset.state === 'ready'"
                               " && document.querySelectorAll('.plan-vertex').length > 0")
        for plan in page.evaluate(LABELS_APART):
            assert plan["meet"] == [], (name, plan)
        guides = page.eval_on_selector_all("#editor-drawing .guide-label", "g => g.map((e) => e.textContent)")
        assert not set(guides) & (TAUGHT | {"x"}), (name, guides)
        words = {w.lower() for w in re.findall(r"[A-Za-z]{3,}", page.evaluate(VISIBLE_TEXT))}
        assert words & english == set(), (name, sorted(words & english))
        assert "{" not in page.evaluate(VISIBLE_TEXT), name
        if name == "shaping_machine":
            screenshot(page, "editor_words_shaping_machine_ru")
    assert [p for p in page.problems if not REFUSED.search(p)] == []


def test_english_and_phone(browser_page, phone):
    linkage = {"frame": {"joints": {"O": [0, 0], "O₁": [0.4, 0]}, "guides": {"g1": {"through": [0, 0.45], "angle": 0}}},
               "input": {"kind": "crank", "link": 1, "pivot": "O", "joint": "A", "length": 0.2, "angle0": 0, "sense": 1},
               "groups": [{"kind": "RRR", "links": [2, 3], "outer": ["A", "O₁"], "inner": "B", "lengths": [0.32, 0.269],
                           "branch": 1},
                          {"kind": "RRP", "links": [4, 5], "outer": ["B"], "guide": "g1", "inner": "C", "length": 0.361,
                           "branch": 1}]}
    encoded = base64.urlsafe_b64encode(json.dumps(linkage, ensure_ascii=False).encode()).decode().rstrip("=")
    en = interface_texts("en")
    page = browser_page
    page.goto(f"/editor?lang=en&m={encoded}")
    said = readiness(page, "partial")
    assert said.startswith(f"W = 1. {en['editor_ready_no_full_turn']}") and said.endswith(en["editor_next_turn"])
    assert "{" not in page.evaluate(VISIBLE_TEXT)
    page.wait_for_function("() => document.querySelector('#editor-readiness').innerText.includes('through 0°')")
    screenshot(page, "editor_words_cannot_turn_en")
    phone.goto(f"/editor?lang=ru&m={encoded}")
    readiness(phone, "partial")
    box = phone.locator("#editor-readiness").bounding_box()
    assert box["width"] <= PHONE["width"] and phone.evaluate("() => document.documentElement.scrollWidth") <= PHONE["width"]
    for _ in range(5):                                                 # past the header's links (home, languages)
        phone.keyboard.press("Tab")
        if phone.evaluate("() => document.activeElement.closest('main') !== null"):
            break
    # the page's first stop: the skip link to the drawing (the next one to the tools)
    assert phone.evaluate("() => document.activeElement.getAttribute('href')") == "#editor-drawing"
    phone.keyboard.press("Enter")
    assert phone.evaluate("() => document.activeElement.id") == "editor-drawing"
    screenshot(phone, "editor_words_phone_ru")
    assert [p for p in page.problems + phone.problems if not REFUSED.search(p)] == []
