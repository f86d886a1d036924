"""A student's own six-bar carried from the editor to the course project they hand in, in Chromium.

The six-bar (a crank-rocker whose rocker drives a slider on a frame guide through a connecting rod: crank, RRR,
then RRP; no preset) opens in the editor from its link, as the editor keeps a mechanism it built. There the
student takes away the estimated load on the slider and puts a force at the tool's point K of the slider instead,
on the working stroke; the editor's "Course project" link opens the project with both. On the project page the
force gets its load diagram over the stroke (zero at the stroke's ends, full from 10 to 90 %), [δ] is typed and
the position of the force analysis chosen. The page's request, posted again through the test's HTTP client, gives
the numbers the page shows; the printed report (page.pdf, read by pdftotext) holds every section and those
numbers; every A1 sheet downloads as an SVG drawing with the title block, a table of each kind as CSV with the rows the
page shows. No console errors; screenshots in ru and en (test-artifacts/course_project_own_*).
"""
from __future__ import annotations

import base64
import csv
import io
import json
import shutil
import subprocess
import xml.etree.ElementTree as ElementTree

import pytest

from conftest import ARTIFACTS, interface_texts, shown
from test_project_report import SECTIONS, TITLES, act, api_answer, close, fact, settled, type_into

pytestmark = pytest.mark.browser

SIX = {"frame": {"joints": {"O": [0, 0], "C": [0.3, 0.05]}, "guides": {"g": {"through": [0, 0.3], "angle": 0}}},
       "input": {"link": 1, "pivot": "O", "joint": "A", "length": 0.1},
       "groups": [{"kind": "RRR", "links": [2, 3], "outer": ["A", "C"], "inner": "B", "lengths": [0.3, 0.2],
                   "branch": 1},
                  {"kind": "RRP", "links": [4, 5], "outer": ["B"], "guide": "g", "inner": "D", "length": 0.3,
                   "branch": 1, "points": {"K": {"link": 5, "along": 0.05, "across": -0.03}}}]}
ROW = "masses.point_forces.0"
DIAGRAM = [[0.05, 0.0], [0.1, 1.0], [0.9, 1.0], [0.95, 0.0]]
TABLES = ("table-positions", "table-points-5", "table-flywheel", "table-inertia", "table-group-1", "table-lever",
          "table-balancing")
TYPED = {"en": ("0.05 0; 0.1 1; 0.9 1; 0.95 0", "0.04", 0.04), "ru": ("0,05 0; 0,1 1; 0,9 1; 0,95 0", "0,04", 0.04)}


def address(data: dict) -> str:
    return base64.urlsafe_b64encode(json.dumps(data).encode()).decode().rstrip("=")


def edited(page, path: str, text: str) -> None:
    """Type into the editor's loads table and leave the cell (the table takes a cell's text on leaving it)."""
    cell = f'#editor-dynamics input[data-path="{path}"]'
    page.fill(cell, text)
    page.press(cell, "Tab")


def put_the_tool_force(page, lang: str) -> None:
    """In the editor: the estimated slider load taken away, a force at K on the slider (link 5) put instead."""
    page.goto(f"/editor?lang={lang}&m={address(SIX)}")
    page.wait_for_function("() => document.querySelector('#editor-open-dynamics a[data-scene]') !== null",
                           timeout=60_000)
    page.click('#editor-dynamics button[data-remove="forces.0"]')
    page.select_option("#editor-load-place", "point:5")
    page.click("#editor-load-add")
    page.wait_for_selector("#editor-masses-points")
    page.fill(f'input[data-path="{ROW}.name"]', "K")
    page.press(f'input[data-path="{ROW}.name"]', "Tab")
    decimal = "," if lang == "ru" else "."
    edited(page, f"{ROW}.point.0", f"0{decimal}05")
    edited(page, f"{ROW}.point.1", f"−0{decimal}03")
    edited(page, f"{ROW}.magnitude", "2000")
    page.wait_for_function("""() => { const link = document.querySelector('#editor-course-project');
        const d = link && link.href && new URL(link.href).searchParams.get('d');
        const masses = d && JSON.parse(atob(d.replace(/-/g, '+').replace(/_/g, '/'))).masses;
        return masses && masses.forces.length === 0 && masses.point_forces?.[0]?.magnitude === 2000
            && masses.point_forces[0].name === 'K'; }""", timeout=30_000)


@pytest.mark.parametrize("lang", ["en", "ru"])
def test_an_own_six_bar_with_a_tool_force_goes_from_the_editor_to_the_printed_project(browser_page, app_url, lang):
    page, t = browser_page, interface_texts(lang)
    put_the_tool_force(page, lang)
    before = 0
    page.click("#editor-course-project")
    settled(page, before)
    assert page.get_attribute("#project-status", "data-state") == "ready", page.inner_text("#project-status")
    diagram_text, delta_text, delta = TYPED[lang]
    act(page, lambda: page.select_option(f"select[data-path='{ROW}.diagram.over']", "stroke"))
    body = act(page, lambda: type_into(page, f"input[data-path='{ROW}.diagram.points']", diagram_text))
    force = body["masses"]["point_forces"][0]
    assert body["masses"]["forces"] == [] and force["diagram"] == {"over": "stroke", "points": DIAGRAM}
    assert force["link"] == 5 and force["point"] == [0.05, -0.03] and force["acts"] == "working"
    act(page, lambda: type_into(page, "#project-student", "Student Own"))
    act(page, lambda: type_into(page, "[data-path='flywheel.delta']", delta_text))
    body = act(page, lambda: page.select_option("#project-chosen", "5"))
    assert body["delta"] == delta and body["chosen"] == 5 and body["linkage"]["frame"] == SIX["frame"]
    answer = api_answer(app_url, lang, body)
    assert "force K" in answer["dynamics"]["M_c_parts"]
    assert close(fact(page, "flywheel-inertia"), answer["dynamics"]["flywheel"]["flywheel_inertia"])
    assert close(fact(page, "delta-achieved"), answer["dynamics"]["delta_achieved"])
    assert fact(page, "chosen") == "5" == str(answer["kinetostatics"]["number"])
    assert close(fact(page, "Mb"), answer["kinetostatics"]["balancing_moment"])
    assert close(fact(page, "Mb-lever"), answer["kinetostatics"]["zhukovsky"]["moment"])
    for section in SECTIONS:
        page.locator(f"#{section}").screenshot(path=ARTIFACTS / f"course_project_own_{section}_{lang}.png")

    sheets = page.locator("button.sheet-download")
    assert sheets.count() >= 3                                   # kinematics, kinetostatics, dynamics
    for k in range(sheets.count()):
        with page.expect_download() as got:
            sheets.nth(k).click()
        svg = ElementTree.fromstring(got.value.path().read_bytes())
        assert svg.tag.endswith("svg") and svg.get("width") == "841mm" and svg.get("height") == "594mm"
        assert "Student Own" in "".join(svg.itertext())
    separator = ";" if lang == "ru" else ","
    for name in TABLES:            # one table of each kind (Chromium lets a page start ten downloads in a row)
        with page.expect_download() as got:
            page.click(f"button[data-table='{name}']")
        rows = list(csv.reader(io.StringIO(got.value.path().read_bytes().decode("utf-8").lstrip("\ufeff")),
                               delimiter=separator))
        assert len(rows) - 1 == page.locator(f"#{name} tbody tr").count() > 0, name

    pdf = ARTIFACTS / f"course_project_own_{lang}.pdf"
    page.pdf(path=str(pdf), format="A4")
    assert shutil.which("pdftotext"), "pdftotext (Debian's poppler-utils) is missing: tests/run.sh installs it"
    flat = " ".join(subprocess.run(["pdftotext", "-layout", str(pdf), "-"], capture_output=True, text=True,
                                   check=True).stdout.split())
    for key in TITLES:
        assert shown(t[key]) in flat, key
    for name in ("flywheel-inertia", "Mb", "Mb-lever", "delta-achieved"):
        assert fact(page, name) in flat, name
    assert page.problems == []
