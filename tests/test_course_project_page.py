"""The course project's page (/project): served in every language with that language's interface texts, its
sections' headings and the presets driven by a crank (title and source in the page's language, the linkage and
the dynamics as the API takes them); linked from the start page and from the editor. Its model run in Node: a
table's CSV holds the answer's values rounded here the way the page rounds them (4 significant digits, angles to
0.1°; ";" and a decimal comma in ru, "," and a point in en; text cells quoted); the settings read from an address
are checked; the request built from the editor's design data is the one the API takes (posted: 200); a refusal
names its field in the student's words."""
from __future__ import annotations

import csv
import html
import io
import json
import math
import shutil
import subprocess
from decimal import ROUND_HALF_UP, Decimal
from pathlib import Path

import pytest

from server.core.structure.presets import presets
from server.lessons.scenes import interface_texts
from test_editor_page import client, embedded  # noqa: F401  (the module's client fixture)

REPO = Path(__file__).resolve().parents[1]
SECTIONS = ["project_report_title", "project_structure", "project_kinematics", "project_dynamics",
            "project_kinetostatics", "project_equations", "project_sheets"]




@pytest.mark.parametrize("lang", ["ru", "uk", "en"])
def test_the_project_page_carries_its_texts_sections_and_presets(client, lang):
    answer = client.get(f"/project?lang={lang}")
    assert answer.status_code == 200
    page = answer.text
    texts = embedded(page, "interface-texts")
    assert texts == interface_texts(lang)
    assert f'<html lang="{lang}">' in page and f"<h1>{html.escape(texts['project_title'])}</h1>" in page
    for key in SECTIONS:                               # every section's heading, in the page's language
        assert html.escape(texts[key]) in page, key
    shown = embedded(page, "project-presets")
    cranked = [name for name, p in presets().items() if p["linkage"]["input"].get("kind", "crank") == "crank"]
    assert [p["name"] for p in shown] == cranked and "shaping_machine" in cranked
    for item in shown:
        preset = presets()[item["name"]]
        assert item["title"] == preset["title"][lang] and item["source"] == preset["source"][lang]
        assert item["linkage"] == preset["linkage"] and item["dynamics"] == preset.get("dynamics")
    assert '/js/course_project/main.js"' in page and "/css/course_project.css" in page


def test_an_unknown_language_falls_back_and_the_page_still_renders(client):
    answer = client.get("/project?lang=xx")
    assert answer.status_code == 200 and 'id="project-report"' in answer.text


def test_the_start_page_and_the_editor_link_to_the_project(client):
    assert 'href="/project?lang=uk"' in client.get("/?lang=uk").text
    editor = client.get("/editor?lang=ru").text
    assert 'id="editor-course-project"' in editor and html.escape(interface_texts("ru")["editor_course_project"]) in editor


# ---- the page's model (web/static/js/course_project/model/, no DOM) run in Node ----

NODE = shutil.which("node") or shutil.which("nodejs")
MODEL = REPO / "web" / "static" / "js" / "course_project" / "model"
SCRIPT = """
const input = JSON.parse(require("fs").readFileSync(0, "utf8"));
(async () => {
  const m = async (name) => import(`${process.argv[1]}/${name}.js`);
  const [address, design, request, refusal, tables, csv] = await Promise.all(
    ["address", "design", "request", "refusal", "report_tables", "csv"].map(m));
  const out = {};
  if (input.answer) {
    for (const name of ["positionsTable", "balancingTable", "flywheelTable"]) {
      const table = tables[name](name === "flywheelTable" ? input.answer.dynamics.flywheel : input.answer, input.t);
      out[name] = { kinds: table.columns.map((c) => c.kind), csv: csv.tableCsv(table, input.lang) };
    }
  }
  if (input.settings) out.settings = address.settingsOf(input.settings);
  if (input.project) {
    const dynamics = design.completed(input.project.dynamics);
    out.request = request.projectRequest({ ...input.project, dynamics, settings: address.settingsOf(input.project.settings) });
  }
  if (input.refusal) out.sentence = refusal.refusalSentence(input.refusal.error, "REASON", input.refusal.request, input.t);
  process.stdout.write(JSON.stringify(out));
})().catch((error) => { console.error(error); process.exit(1); });
"""
needs_node = pytest.mark.skipif(NODE is None, reason="Node is not installed")
SHAPING = presets()["shaping_machine"]


def model(payload: dict) -> dict:
    done = subprocess.run([NODE, "-e", SCRIPT, MODEL.as_uri()], input=json.dumps(payload), text=True,
                          capture_output=True, timeout=120)
    assert done.returncode == 0, done.stderr[-2000:]
    return json.loads(done.stdout)


def rounded(value: float, kind: str) -> float:
    """The number a cell shows, rounded here in decimal as JavaScript's toPrecision(4) and toFixed(1) round (the
    exact binary value, a tie away from zero): 4 significant digits, an angle in degrees to 0.1°."""
    exact = Decimal(math.degrees(value)) if kind == "angle" else Decimal(value)
    if kind == "angle":
        return float(exact.quantize(Decimal("0.1"), rounding=ROUND_HALF_UP))
    if exact == 0:
        return 0.0
    step = Decimal(1).scaleb(exact.adjusted() - 3)
    return float(exact.quantize(step, rounding=ROUND_HALF_UP))


def project_request() -> dict:
    return {"linkage": SHAPING["linkage"], "masses": SHAPING["dynamics"]["masses"], "inertias": SHAPING["dynamics"]["inertias"],
            "omega_mean": 10.0, "delta": 0.03, "positions": 12, "chosen": 4, "title": {"student": "S; \"quoted\""}}


@needs_node
@pytest.mark.parametrize("lang, delimiter, comma", [("ru", ";", ","), ("en", ",", ".")])
def test_a_tables_csv_holds_the_answers_rows_rounded_as_the_page_shows_them(client, lang, delimiter, comma):
    answer = client.post(f"/api/v1/course-project?lang={lang}", json=project_request())
    assert answer.status_code == 200, answer.text
    data = answer.json()
    out = model({"answer": data, "t": interface_texts(lang), "lang": lang})
    rows_of = {"positionsTable": [[r["number"], r["phi"], None, r["omega1"], r["epsilon1"]] for r in data["kinematics"]],
               "balancingTable": [[r["number"], r["phi"], r["omega1"], r["epsilon1"], r["M_b_groups"], r["M_b_lever"],
                                   r["M_b_reduced"], r["difference_percent"], r["useful_load"]] for r in data["table"]],
               "flywheelTable": [[None, m["inertia"], m["additional"], m["energy_swing"], m["delta_achieved"]]
                                 for m in data["dynamics"]["flywheel"]["methods"]]}
    for name, expected in rows_of.items():
        text, kinds = out[name]["csv"], out[name]["kinds"]
        assert text.startswith("\ufeff") and text.endswith("\r\n") and "\n" not in text.replace("\r\n", "")
        lines = list(csv.reader(io.StringIO(text[1:], newline=""), delimiter=delimiter))
        quoted = delimiter.join('"' + cell.replace('"', '""') + '"' for cell in lines[0])
        assert text[1:].split("\r\n")[0] == quoted                                       # text cells quoted
        assert len(lines) - 1 == len(expected)
        for written, values in zip(lines[1:], expected):
            for cell, value, kind in zip(written, values, kinds):
                if kind == "text":
                    continue
                assert "." not in cell if comma == "," else "," not in cell
                assert float(cell.replace(",", ".")) == (value if kind == "int" else rounded(value, kind)), (name, cell, value)


@needs_node
def test_the_settings_in_the_address_are_checked_and_the_request_is_the_apis(client):
    settings = model({"settings": {"positions": 9, "chosen": 30, "drawn": [3, 3, 99, 1], "start": "x",
                                   "title": {"student": "x" * 100, "group": 5}}})["settings"]
    assert settings == {"positions": 12, "start": None, "output": None, "chosen": None, "drawn": [1, 3],
                        "title": {"student": "x" * 80, "group": "", "variant": ""}}
    project = {"linkage": SHAPING["linkage"], "dynamics": SHAPING["dynamics"],
               "settings": {"positions": 24, "start": 0.5, "chosen": 20, "drawn": [2, 20], "output": "E/ram",
                            "title": {"student": "I. Petrenko", "group": "TMM-21", "variant": "7"}}}
    body = model({"project": project})["request"]
    dynamics = SHAPING["dynamics"]
    assert body == {"linkage": SHAPING["linkage"], "masses": {**dynamics["masses"], "friction": 0, "pair_radius": 0},
                    "inertias": dynamics["inertias"], "omega_mean": dynamics["flywheel"]["omega_mean"],
                    "delta": dynamics["flywheel"]["delta"], "positions": 24, "start": 0.5, "output": "E/ram",
                    "chosen": 20, "drawn": [2, 20], "title": project["settings"]["title"]}
    answer = client.post("/api/v1/course-project?lang=en", json=body)          # the API takes what the page sends
    assert answer.status_code == 200, answer.text
    assert answer.json()["kinetostatics"]["number"] == 20 and answer.json()["positions"]["drawn"] == [2, 20]


@needs_node
def test_a_refusal_is_a_sentence_naming_the_field_in_the_students_words():
    t = interface_texts("en")
    request = {"masses": {"links": [{"link": 3, "mass": 1}], "point_forces": [{"link": 5}]}}
    said = lambda loc: model({"refusal": {"error": {"code": "x", "loc": loc}, "request": request}, "t": t})["sentence"]
    assert said(["body", "masses", "links", 0, "mass"]) == f"{t['editor_link']} 3 (mass): REASON"
    assert said(["body", "masses", "point_forces", 0, "point"]).startswith(
        t["project_point_force_name"].replace("{k}", "1").replace("{link}", "5"))
    assert said(["body", "delta"]) == f"{t['project_delta']}: REASON"
    assert said(["body", "masses", "forces"]) == f"{t['project_stroke_loads']}: REASON"
    assert said(["body", "linkage", "groups", "0"]) == "REASON"              # the mechanism: the server's sentence alone
