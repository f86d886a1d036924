"""The course project (/project) in Chromium, as a student hands it in.

On the shaping-machine preset, in English and in Russian: the student types [δ] (a decimal comma in Russian) and
chooses the position of the force analysis; the page's request, posted again through the test's own HTTP client,
answers with the numbers the page shows (the flywheel's I, δ achieved, M_b at the chosen position, to the four
significant digits the page writes). The report printed by Chromium (page.pdf) and read back by pdftotext holds
every section's title and those numbers as the page writes them. A table downloaded as CSV holds the table's
rows as shown (";" and a decimal comma in Russian), an A1 sheet downloaded as SVG is an SVG drawing with the
title block's text. A refusal names the field; the phone-size page does not scroll sideways. The editor's "Course
project" link is disabled with its reason for a four-bar whose crank cannot turn, and opens the project with the
same mechanism and loads for the shaping machine. No console errors.
Screenshots of every section (ru, en) and of the phone page go to test-artifacts/.
"""
from __future__ import annotations

import csv
import io
import json
import re
import shutil
import subprocess

import base64

import httpx
import pytest

from conftest import ARTIFACTS, PHONE, REPO, interface_texts, shown

# Chromium reports every HTTP error answer on the console; a 422 is the answer the page says in words
REFUSED = re.compile(r"Failed to load resource: the server responded with a status of 422")
SECTIONS = ["report-title", "report-structure", "report-kinematics", "report-dynamics", "report-kinetostatics",
            "report-equations"]
TITLES = ["project_report_title", "project_structure", "project_kinematics", "project_dynamics",
          "project_kinetostatics", "project_equations"]
SHOWN_DIGITS = 5e-4          # relative: a number the page writes with 4 significant digits is within half a unit
DELTA = {"en": ("0.05", 0.05), "ru": ("0,05", 0.05)}
SUPERSCRIPT = str.maketrans("⁰¹²³⁴⁵⁶⁷⁸⁹⁻", "0123456789-")
SUBSCRIPT = str.maketrans("₀₁₂₃₄₅₆₇₈₉", "0123456789")


def page_number(text: str) -> float:
    """A number as the page writes it ("1 234,5", "−0,25", "2,081·10⁻⁴", "154,6 кг·м²") read back."""
    match = re.search(r"[−-]?\d+(?:[.,]\d+)?(?:·10[⁻⁰¹²³⁴⁵⁶⁷⁸⁹]+)?", text)
    assert match, text
    mantissa, _, power = match.group(0).replace("−", "-").replace(",", ".").partition("·10")
    return float(mantissa) * 10 ** int(power.translate(SUPERSCRIPT) or 0)


def close(shown_text: str, value: float) -> bool:
    return abs(page_number(shown_text) - value) <= SHOWN_DIGITS * abs(value) + 1e-12


def answers(page) -> int:
    return int(page.get_attribute("#project-status", "data-answers") or 0)


def settled(page, before: int) -> None:
    """Wait until the page has shown an answer newer than `before` (a report or a refusal); a page still loading
    (the editor's link to the project followed) has no status yet."""
    page.wait_for_function("""n => { const s = document.querySelector("#project-status");
        return s !== null && Number(s.dataset.answers ?? 0) > n && s.dataset.state !== "waiting"; }""", arg=before)


def act(page, action) -> dict:
    """Do what a student does, wait for the page's answer, and return the request body the page sent for it."""
    before = answers(page)
    with page.expect_request(lambda r: "/api/v1/course-project" in r.url and r.method == "POST") as sent:
        action()
    settled(page, before)
    return sent.value.post_data_json


def api_answer(app_url: str, lang: str, body: dict) -> dict:
    response = httpx.post(f"{app_url}/api/v1/course-project?lang={lang}", json=body, timeout=120)
    assert response.status_code == 200, response.text
    return response.json()


def fact(page, name: str) -> str:
    return page.inner_text(f"[data-q='{name}']")


def open_shaping_machine(page, lang: str) -> dict:
    page.goto(f"/project?lang={lang}")
    return act(page, lambda: page.select_option("#project-preset", "shaping_machine"))


def type_into(page, selector: str, text: str) -> None:
    field = page.locator(selector)
    field.fill(text)
    field.press("Enter")


@pytest.mark.parametrize("lang", ["en", "ru"])
def test_a_student_sets_delta_and_the_position_and_prints_the_report(browser_page, app_url, lang, tmp_path):
    page, t = browser_page, interface_texts(lang)
    open_shaping_machine(page, lang)
    typed, delta = DELTA[lang]
    body = act(page, lambda: type_into(page, "[data-path='flywheel.delta']", typed))
    assert body["delta"] == delta
    answer = api_answer(app_url, lang, body)
    dynamics = answer["dynamics"]
    assert close(fact(page, "flywheel-inertia"), dynamics["flywheel"]["flywheel_inertia"])
    assert close(fact(page, "delta-achieved"), dynamics["delta_achieved"])
    assert fact(page, "chosen") == str(answer["kinetostatics"]["number"])

    body = act(page, lambda: page.select_option("#project-chosen", "3"))
    assert body["chosen"] == 3 and body["delta"] == delta
    answer = api_answer(app_url, lang, body)
    kinetostatics = answer["kinetostatics"]
    assert kinetostatics["number"] == 3 and fact(page, "chosen") == "3"
    assert close(fact(page, "Mb"), kinetostatics["balancing_moment"])
    assert close(fact(page, "Mb-lever"), kinetostatics["zhukovsky"]["moment"])
    row = page.locator("#table-balancing tr.chosen td")
    assert row.first.inner_text() == "3"
    assert close(row.nth(4).inner_text(), answer["table"][2]["M_b_groups"])
    assert "p=" in page.url and "d=" in page.url          # the link holds the project: a reload shows the same one
    shown_before = fact(page, "flywheel-inertia"), fact(page, "Mb")
    page.reload()
    settled(page, 0)                                     # the reloaded page's first answer
    assert page.input_value("#project-chosen") == "3" and page.input_value("[data-path='flywheel.delta']") == typed
    assert (fact(page, "flywheel-inertia"), fact(page, "Mb")) == shown_before

    with page.expect_download() as got:                 # the language's separators: "," and "." in en, ";" and ","
        page.click("button[data-table='table-positions']")
    lines = got.value.path().read_bytes().decode("utf-8").lstrip("\ufeff").split("\r\n")
    first = lines[1].split(";" if lang == "ru" else ",")
    assert first[0] == "1" and first[1] == page.locator("#table-positions tbody tr td").nth(1).inner_text()
    assert ("." in first[1]) == (lang == "en") and ("," in first[1]) == (lang == "ru")

    for section in SECTIONS:
        page.locator(f"#{section}").screenshot(path=ARTIFACTS / f"course_project_{section}_{lang}.png")

    pdf = ARTIFACTS / f"course_project_{lang}.pdf"
    page.pdf(path=str(pdf), format="A4")                  # Chromium prints with the page's print rules
    assert shutil.which("pdftotext"), "pdftotext (Debian's poppler-utils) is missing: tests/run.sh installs it"
    text = subprocess.run(["pdftotext", "-layout", str(pdf), "-"], capture_output=True, text=True, check=True).stdout
    flat = " ".join(text.split())
    for key in TITLES:
        assert shown(t[key]) in flat, key
    for name in ("flywheel-inertia", "Mb", "delta-achieved"):
        assert fact(page, name) in flat, name
    assert t["project_input"] not in flat and t["project_print"] not in flat      # the controls are left out
    assert page.problems == []


def test_a_table_downloads_as_csv_and_a_sheet_as_svg(browser_page, app_url):
    page = browser_page
    open_shaping_machine(page, "ru")
    act(page, lambda: type_into(page, "#project-student", "И. Петренко"))
    assert fact(page, "student") == "И. Петренко"
    with page.expect_download() as got:
        page.click("button[data-table='table-balancing']")
    text = got.value.path().read_bytes().decode("utf-8")
    assert text.startswith("\ufeff") and text.endswith("\r\n")
    rows = list(csv.reader(io.StringIO(text.lstrip("\ufeff")), delimiter=";"))
    plain = lambda header: " ".join(header.translate(SUBSCRIPT).split())
    headers = [plain(cell.inner_text()) for cell in page.locator("#table-balancing thead th").all()]
    assert [plain(h) for h in rows[0]] == headers and text.split("\r\n")[0].lstrip("\ufeff").startswith('"№";')
    body = page.locator("#table-balancing tbody tr").all()
    assert len(rows) - 1 == len(body) == 12
    for csv_row, tr in zip(rows[1:], body):
        cells = [td.inner_text() for td in tr.locator("td").all()]
        assert len(csv_row) == len(cells)
        for written, on_page in zip(csv_row, cells):
            if on_page == "—":
                assert written == ""
                continue
            assert "." not in written                    # a decimal comma in Russian
            value = page_number(on_page)
            assert abs(float(written.replace(",", ".")) - value) <= 1e-9 * max(1.0, abs(value))

    sheets = page.locator("button.sheet-download")
    assert sheets.count() >= 1
    with page.expect_download() as got:
        sheets.first.click()
    svg = got.value.path().read_text(encoding="utf-8")
    assert svg.startswith("<?xml") and "<svg" in svg and "И. Петренко" in svg
    assert page.problems == []


def test_a_refusal_names_the_field_and_a_phone_shows_the_report(chromium, app_url):
    context = chromium.new_context(base_url=app_url, viewport=PHONE, device_scale_factor=1)
    page = context.new_page()
    problems = []
    page.on("console", lambda m: m.type == "error" and not REFUSED.search(m.text) and problems.append(m.text))
    page.on("pageerror", lambda error: problems.append(str(error)))
    t = interface_texts("uk")
    open_shaping_machine(page, "uk")
    assert page.evaluate("document.documentElement.scrollWidth") <= PHONE["width"]
    page.screenshot(path=ARTIFACTS / "course_project_phone_uk.png", full_page=False)
    page.locator("#report-dynamics").screenshot(path=ARTIFACTS / "course_project_phone_dynamics_uk.png")
    act(page, lambda: page.click("[data-remove='forces.0']"))       # the only useful load taken away
    sentence = page.inner_text("#project-refusal-sentence")
    assert shown(t["project_stroke_loads"]) in sentence and shown(t["err_project_needs_load"]) in sentence
    assert page.get_attribute("#project-report", "class").split().count("stale") == 1
    assert problems == []
    context.close()


def test_the_editor_opens_the_project_and_says_why_it_cannot(browser_page):
    page, t = browser_page, interface_texts("en")
    preset = json.loads((REPO / "content" / "mechanisms" / "shaping_machine.json").read_text(encoding="utf-8"))
    address = lambda data: base64.urlsafe_b64encode(json.dumps(data).encode()).decode().rstrip("=")
    four_bar = {"frame": {"joints": {"A": [0, 0], "D": [0.2, 0]}}, "input": {"link": 1, "pivot": "A", "joint": "B",
                "length": 0.15}, "groups": [{"kind": "RRR", "links": [2, 3], "outer": ["B", "D"], "inner": "C",
                                             "lengths": [0.1, 0.12], "branch": 1}]}     # B cannot pass φ = 90°…270°
    page.goto(f"/editor?lang=en&m={address(four_bar)}")
    page.wait_for_function("() => document.querySelector('#editor-course-project-reason').textContent !== ''")
    assert page.get_attribute("#editor-course-project", "aria-disabled") == "true"
    assert page.get_attribute("#editor-course-project", "href") is None
    assert page.inner_text("#editor-course-project-reason") == t["editor_project_needs_turn"]
    page.wait_for_function("() => document.querySelector('#editor-masses-status').textContent !== ''")
    assert page.text_content("#editor-masses-status") == t["editor_project_needs_turn"]   # no estimate asked
    assert page.problems == []                           # (the server refuses one for this crank: 422)
    page.goto(f"/editor?lang=en&m={address(preset['linkage'])}&d={address(preset['dynamics'])}")
    page.wait_for_function("() => document.querySelector('#editor-course-project').getAttribute('aria-disabled') === 'false'")
    with page.expect_navigation():
        page.click("#editor-course-project")
    page.wait_for_function("() => document.querySelector('#project-status')?.dataset.state === 'ready'")  # (null while parsed)
    assert page.inner_text("[data-q='output']") == t["project_output_slide"].replace("{name}", "E/ram")
    assert float(page.input_value("[data-path='masses.forces.0.working']")) == preset["dynamics"]["masses"]["forces"][0]["working"]
    assert page.problems == []
