"""The course project's drawings (web/static/js/course_project/view/drawings/) as Chromium draws them, on the
/project page (its origin and styles) for the shaping machine's answer of POST /api/v1/course-project, in Russian
and in English:

- every drawing is an SVG whose user unit is the millimetre: its width and height are written in mm and equal its
  viewBox's (so that it prints at its size);
- the crank OA on the plan of positions measures OA/μ_l mm at every position (OA from the answer's joints);
- no two texts of a drawing cover each other: their getBBox() boxes, the real font's, do not intersect;
- each A1 sheet is 841 × 594 mm, its frame 20 mm from the left edge and 5 mm from the others, the title block
  185 × 55 mm in the frame's bottom right corner holding the student, the group and the sheet's number; a sheet's
  file text parses as SVG;
- no console errors. Screenshots of the drawings and of the first sheet in each language go to test-artifacts/.
"""
from __future__ import annotations

import itertools
import math

import pytest

from conftest import ARTIFACTS, interface_texts
from server.core.structure.presets import presets

SHAPING = presets()["shaping_machine"]
BODY = {"linkage": SHAPING["linkage"], "masses": SHAPING["dynamics"]["masses"],
        "inertias": SHAPING["dynamics"]["inertias"], "omega_mean": SHAPING["dynamics"]["flywheel"]["omega_mean"],
        "delta": SHAPING["dynamics"]["flywheel"]["delta"], "positions": 12, "drawn": [3],
        "title": {"student": "I. Petrenko", "group": "TMM-21", "variant": "7"}}
DRAWINGS = ["plan_of_positions", "velocity_plan", "acceleration_plan", "output_diagrams", "groups", "force_plans",
            "zhukovsky", "inertia", "moments", "works", "speed", "wittenbauer", "flywheel"]
MM = 1e-3                      # mm: SVG lengths are written to 0.001 mm
TOUCH = 1e-3                   # mm²: boxes sharing less than this only touch

# Builds every drawing and the sheets in the page from the answer, appends them to a host at the top of the page
# and measures them: sizes, the crank's lines, each text's box, the sheets' frame and title block.
BUILD = """
async ({ body, t, lang }) => {
  const response = await fetch(`/api/v1/course-project?lang=${lang}`, { method: "POST",
    headers: { "Content-Type": "application/json" }, body: JSON.stringify(body) });
  const answer = await response.json();
  const load = (name) => import(`/static/js/course_project/view/drawings/${name}.js`);
  const [positions, plans, forces, groups, lever, diagrams, witt, sheets] = await Promise.all(["plan_of_positions",
    "plans", "force_plans", "groups", "zhukovsky", "diagrams", "wittenbauer", "sheet"].map(load));
  const drawings = {
    plan_of_positions: positions.planOfPositions(answer, t, lang),
    velocity_plan: plans.velocityPlan(answer, t, lang), acceleration_plan: plans.accelerationPlan(answer, t, lang),
    output_diagrams: diagrams.outputDiagrams(answer, t, lang), groups: groups.groupsWithForces(answer, t, lang),
    force_plans: forces.forcePlans(answer, t, lang), zhukovsky: lever.zhukovskyLever(answer, t, lang),
    inertia: diagrams.inertiaDiagram(answer, t, lang), moments: diagrams.momentsDiagram(answer, t, lang),
    works: diagrams.worksDiagram(answer, t, lang), speed: diagrams.speedDiagram(answer, t, lang),
    wittenbauer: witt.wittenbauerDiagram(answer, t, lang), flywheel: witt.flywheelDrawing(answer, t, lang),
  };
  const host = document.createElement("div");
  host.id = "drawings-under-test";
  host.style.cssText = "background: #fff; padding: 4mm; display: flex; flex-wrap: wrap; gap: 6mm; align-items: flex-start";
  document.body.prepend(host);
  const box = (node) => { const b = node.getBBox(); return { x: b.x, y: b.y, width: b.width, height: b.height }; };
  const measured = {};
  for (const [name, svg] of Object.entries(drawings)) {
    host.append(svg);
    const v = svg.viewBox.baseVal;
    measured[name] = { viewBox: [v.x, v.y, v.width, v.height], width: svg.getAttribute("width"),
      height: svg.getAttribute("height"),
      texts: [...svg.querySelectorAll("text")].map((node) => ({ text: node.textContent, box: box(node) })) };
  }
  const crank = [...drawings.plan_of_positions.querySelectorAll("line[data-role=crank]")].map((line) => ({
    position: Number(line.dataset.position), length: Math.hypot(line.x2.baseVal.value - line.x1.baseVal.value,
      line.y2.baseVal.value - line.y1.baseVal.value) }));
  const made = sheets.projectSheets(answer, t, lang, { date: new Date(2026, 10, 29) });
  const sheet = (svg) => {
    const frame = svg.querySelector("rect.cp-frame");
    const block = svg.querySelector("g.cp-title-block");
    const outline = [...block.querySelectorAll(":scope > rect")].at(-1);
    const parsed = new DOMParser().parseFromString(sheets.sheetFileText(svg), "image/svg+xml");
    return { width: svg.getAttribute("width"), height: svg.getAttribute("height"), viewBox: svg.getAttribute("viewBox"),
      frame: ["x", "y", "width", "height"].map((k) => Number(frame.getAttribute(k))),
      block: block.getAttribute("transform"), outline: ["width", "height"].map((k) => Number(outline.getAttribute(k))),
      cells: Object.fromEntries([...block.querySelectorAll("text[data-cell]")].map((n) => [n.dataset.cell, n.textContent])),
      parsed: parsed.documentElement.localName + " " + parsed.documentElement.namespaceURI
        + (parsed.querySelector("parsererror") ? " error" : "") };
  };
  const first = made[0].svg;
  first.id = "sheet-under-test";
  first.setAttribute("width", 1680);
  first.setAttribute("height", 1187);
  document.body.append(first);
  return { measured, crank, sheets: made.map((s) => ({ kind: s.kind, number: s.number, ...sheet(s.svg) })),
    oa: answer.plan_of_positions.joints, mu: answer.scales.mu_l, count: answer.positions.count };
}
"""


def shared(a: dict, b: dict) -> float:
    w = min(a["x"] + a["width"], b["x"] + b["width"]) - max(a["x"], b["x"])
    h = min(a["y"] + a["height"], b["y"] + b["height"]) - max(a["y"], b["y"])
    return w * h if w > 0 and h > 0 else 0.0


@pytest.mark.parametrize("lang", ["ru", "en"])
def test_drawings_are_to_scale_in_millimetres_with_their_texts_apart(browser_page, lang):
    page = browser_page
    page.goto(f"/project?lang={lang}")
    result = page.evaluate(BUILD, {"body": BODY, "t": interface_texts(lang), "lang": lang})
    page.locator("#drawings-under-test").screenshot(path=ARTIFACTS / f"course_project_drawings_{lang}.png")
    page.locator("#sheet-under-test").screenshot(path=ARTIFACTS / f"course_project_sheet_1_{lang}.png")

    measured = result["measured"]
    assert sorted(measured) == sorted(DRAWINGS)
    for name, drawing in measured.items():
        _, _, width, height = drawing["viewBox"]
        assert drawing["width"].endswith("mm") and drawing["height"].endswith("mm"), name
        assert abs(float(drawing["width"][:-2]) - width) <= MM and abs(float(drawing["height"][:-2]) - height) <= MM
        assert len(drawing["texts"]) >= 3, name               # a heading, a scale, labels
        clashes = [(a["text"], b["text"]) for a, b in itertools.combinations(drawing["texts"], 2)
                   if shared(a["box"], b["box"]) > TOUCH]
        assert not clashes, (name, clashes)

    joints, mu = result["oa"], result["mu"]
    assert sorted(line["position"] for line in result["crank"]) == list(range(1, result["count"] + 1))
    for line in result["crank"]:
        i = line["position"] - 1
        assert abs(line["length"] - math.dist(joints["O"][i], joints["A"][i]) / mu) <= 2 * MM

    t = interface_texts(lang)
    assert [s["kind"] for s in result["sheets"]][:1] == ["kinematics"] and len(result["sheets"]) >= 3
    for sheet in result["sheets"]:
        assert (sheet["width"], sheet["height"], sheet["viewBox"]) in {("841mm", "594mm", "0 0 841 594"),
                                                                        ("1680", "1187", "0 0 841 594")}
        assert sheet["frame"] == [20, 5, 816, 584]
        assert sheet["block"] == "translate(651 534)" and sheet["outline"] == [185, 55]
        cells = sheet["cells"]
        assert cells["student"] == "I. Petrenko" and cells["group"] == "TMM-21" and cells["variant"] == "7"
        assert cells["sheet_number"] == t["project_dwg_tb_sheet_number"].replace("{n}", str(sheet["number"]))
        assert cells["maker"] == t["app_title"]
        assert sheet["parsed"] == "svg http://www.w3.org/2000/svg"
    assert not page.problems, page.problems
