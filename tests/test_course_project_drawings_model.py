"""The course project's drawings on paper (web/static/js/course_project/model/drawing_layout.js and the figures of
view/drawings/*.js, built in Node without a DOM), checked against arithmetic done here:

- a value q at the scale μ is q/μ mm long: a segment between two points of a plane, the crank OA on the plan of
  positions at every position (OA/μ_l from the answer's joints), each plan vector (its value/μ_v, /μ_a), each
  force of the force plans (its magnitude/μ_F), each arm on Zhukovsky's lever (the answer's arm, mm);
- a standard scale is the smallest of 1, 2, 2.5, 4, 5 × 10ᵏ at which an extent fits, and μ_l = 0.002 m/mm is
  the ESKD scale 1:2;
- placed labels never share a point, neither in crowds made here nor on any drawing of the projects
  (POST /api/v1/course-project's answers) of the shaping machine (RPR + RRP), the jaw crusher (RRR + RRR, a
  rocking output) and lever_ram (RPR + PRP, a guide on the lever), and stay inside their drawing;
- the A1 sheet's frame is 20 mm from the left edge and 5 mm from the others, the title block 185 × 55 mm in
  its bottom right corner, tiled exactly by its cells; drawings laid out on a sheet overlap neither each other nor
  the title block and stay inside the frame.
Lengths are compared to 1e-9 mm where the answer sends full doubles (the figures round nothing before the SVG),
to 1e-5 mm where it sends 7 significant digits (the force polygons' ends, the lever's images: ≤ 100 mm)."""
from __future__ import annotations

import itertools
import json
import math
import random
import shutil
import subprocess
from pathlib import Path

import pytest

from server.api.course_project import course_project
from server.api.schemas_project import CourseProjectRequest
from server.api.serialise import respond
from server.core.structure.presets import presets

REPO = Path(__file__).resolve().parents[1]
DRAWINGS = REPO / "web" / "static" / "js" / "course_project"
NODE = shutil.which("node") or shutil.which("nodejs")
pytestmark = pytest.mark.skipif(NODE is None, reason="Node is not installed")
MM = 1e-9                       # mm: the figures keep full doubles
A1 = (841, 594)

# Node: {"calls": [[name, args]]} → the results of drawing_layout's functions; {"answer": path, "lang": l} → every
# figure of the project: its parts, its placed labels' boxes and its extent.
SCRIPT = """
const input = JSON.parse(require("fs").readFileSync(0, "utf8"));
const base = process.argv[1];
(async () => {
  const layout = await import(`${base}/model/drawing_layout.js`);
  if (input.calls) {                    // a placement's at() is a function: its results at the points instead
    const call = ([name, args]) => (name === "paperPlacement"
      ? { ...layout.paperPlacement(...args), at: args[0].map(layout.paperPlacement(...args).at) } : layout[name](...args));
    process.stdout.write(JSON.stringify(input.calls.map(call)));
    return;
  }
  const fs = require("fs");
  const answer = JSON.parse(fs.readFileSync(input.answer, "utf8"));
  const t = JSON.parse(fs.readFileSync(input.texts, "utf8"));
  const view = async (name) => import(`${base}/view/drawings/${name}.js`);
  const [positions, plans, forces, groups, lever, diagrams, witt] = await Promise.all(["plan_of_positions", "plans",
    "force_plans", "groups", "zhukovsky", "diagrams", "wittenbauer"].map(view));
  const figures = {
    plan_of_positions: positions.planOfPositions(answer, t, input.lang, { figure: true }),
    velocity_plan: plans.velocityPlan(answer, t, input.lang, { figure: true }),
    acceleration_plan: plans.accelerationPlan(answer, t, input.lang, { figure: true }),
    force_plans: forces.forcePlans(answer, t, input.lang, { figure: true }),
    groups: groups.groupsWithForces(answer, t, input.lang, { figure: true }),
    zhukovsky: lever.zhukovskyLever(answer, t, input.lang, { figure: true }),
    output_diagrams: diagrams.outputDiagrams(answer, t, input.lang, { figure: true }),
    inertia: diagrams.inertiaDiagram(answer, t, input.lang, { figure: true }),
    moments: diagrams.momentsDiagram(answer, t, input.lang, { figure: true }),
    works: diagrams.worksDiagram(answer, t, input.lang, { figure: true }),
    speed: diagrams.speedDiagram(answer, t, input.lang, { figure: true }),
    wittenbauer: witt.wittenbauerDiagram(answer, t, input.lang, { figure: true }),
    flywheel: witt.flywheelDrawing(answer, t, input.lang, { figure: true }),
  };
  const out = {};
  for (const [name, figure] of Object.entries(figures)) {
    const labels = figure.placeLabels().map((label) => ({ text: label.text, box: label.box }));
    out[name] = { labels, extent: figure.extent(), parts: figure.parts.map(({ type, points, head, attrs }) =>
      ({ type, points, head, attrs })) };
  }
  process.stdout.write(JSON.stringify(out));
})();
"""


def node(payload: dict):
    done = subprocess.run([NODE, "-e", SCRIPT, DRAWINGS.as_uri()], input=json.dumps(payload), text=True,
                          capture_output=True, timeout=120)
    assert done.returncode == 0, done.stderr[-2000:]
    return json.loads(done.stdout)


def layout(*calls):
    return node({"calls": [[name, list(args)] for name, *args in calls]})


def overlap(a: dict, b: dict) -> float:
    w = min(a["x"] + a["width"], b["x"] + b["width"]) - max(a["x"], b["x"])
    h = min(a["y"] + a["height"], b["y"] + b["height"]) - max(a["y"], b["y"])
    return w * h if w > 0 and h > 0 else 0.0


def inside(box: dict, outer: dict, tolerance: float = 1e-9) -> bool:
    return (box["x"] >= outer["x"] - tolerance and box["y"] >= outer["y"] - tolerance
            and box["x"] + box["width"] <= outer["x"] + outer["width"] + tolerance
            and box["y"] + box["height"] <= outer["y"] + outer["height"] + tolerance)


def test_a_value_is_drawn_its_value_over_the_scale_long():
    mu_l, margin, points = 0.0025, 12, [[0.1, -0.2], [0.35, 0.4], [-0.05, 0.1]]
    placement, = layout(("paperPlacement", points, mu_l, margin))
    on_paper = placement["at"]
    for (i, p), (j, q) in itertools.combinations(enumerate(points), 2):
        assert abs(math.dist(on_paper[i], on_paper[j]) - math.dist(p, q) / mu_l) <= MM
    assert all(a[1] - b[1] == pytest.approx(-(p[1] - q[1]) / mu_l, abs=MM)          # y up in metres, down on paper
               for (a, p), (b, q) in itertools.combinations(zip(on_paper, points), 2))
    assert placement["width"] == pytest.approx((0.35 + 0.05) / mu_l + 2 * margin, abs=MM)
    assert placement["height"] == pytest.approx((0.4 + 0.2) / mu_l + 2 * margin, abs=MM)


@pytest.mark.parametrize("extent, millimetres", [(0.23, 100), (0.55, 250), (1234.0, 60), (3e-4, 40), (7.5, 30),
                                                 (0.4, 160), (471.25, 120)])
def test_a_standard_scale_is_the_smallest_standard_value_at_which_the_extent_fits(extent, millimetres):
    mu, = layout(("standardScale", extent, millimetres))
    power = 10 ** math.floor(math.log10(mu) + 1e-12)
    assert round(mu / power, 9) in (1, 2, 2.5, 4, 5)
    assert extent / mu <= millimetres * (1 + 1e-12)
    ladder = sorted(m * 10 ** k for m in (1, 2, 2.5, 4, 5) for k in range(-8, 8))
    smaller = max(value for value in ladder if value < mu * (1 - 1e-12))
    assert extent / smaller > millimetres


def test_eskd_scales_of_a_length_drawing():
    assert layout(("eskdScale", 0.002), ("eskdScale", 0.0025), ("eskdScale", 0.0005), ("eskdScale", 0.01),
                  ("eskdScale", 0.001)) == ["1:2", "1:2.5", "2:1", "1:10", "1:1"]


def test_round_ticks_are_multiples_of_a_standard_step_at_least_the_spacing_apart():
    cases = [(-0.37, 0.02, 0.01), (0, 412, 10), (9.85, 10.15, 0.01), (-471, 1.6, 4)]
    for (low, high, mu), result in zip(cases, layout(*[("roundTicks", *case, 10) for case in cases])):
        step, ticks = result["step"], result["ticks"]
        assert step / mu >= 10 * (1 - 1e-12)
        assert all(abs(v / step - round(v / step)) < 1e-9 for v in ticks)
        assert ticks and low - 1e-9 <= ticks[0] < low + step and high - step < ticks[-1] <= high + 1e-9


def test_crowded_labels_are_placed_apart_and_off_the_marks():
    rng = random.Random(7)
    marks = [{"x": 48, "y": 48, "width": 4, "height": 4}]
    segments = [[[0, 50], [100, 50]], [[50, 0], [50, 100]]]
    crowds = [[{"text": f"R_{rng.randint(1, 99)}", "at": [50 + rng.uniform(-3, 3), 50 + rng.uniform(-3, 3)],
                "fontSize": rng.choice([2.5, 3.5]), "anchor": rng.choice(["start", "middle", "end"])}
               for _ in range(20 + 15 * crowd)] for crowd in range(3)]
    for placed in layout(*[("placeLabels", labels, {"marks": marks, "segments": segments}) for labels in crowds]):
        boxes = [label["box"] for label in placed]
        assert all(overlap(a, b) == 0 for a, b in itertools.combinations(boxes, 2))
        assert all(overlap(box, marks[0]) == 0 for box in boxes)


def test_a_label_that_has_room_stays_where_its_drawing_put_it():
    label = {"text": "A", "at": [10, 10], "fontSize": 3.5, "anchor": "start"}
    placed, = layout(("placeLabels", [label], {}))
    assert placed[0]["moved"] == 0 and placed[0]["x"] == 10 and placed[0]["y"] == 10


def test_the_a1_frame_and_the_title_block():
    sheet, cells = layout(("sheetFrame",), ("titleBlockCells",))
    assert (sheet["width"], sheet["height"]) == A1
    assert sheet["frame"] == {"x": 20, "y": 5, "width": 841 - 25, "height": 594 - 10}
    block = sheet["titleBlock"]
    assert (block["width"], block["height"]) == (185, 55)
    assert block["x"] + 185 == 841 - 5 and block["y"] + 55 == 594 - 5          # in the frame's bottom right corner
    whole = {"x": 0, "y": 0, "width": 185, "height": 55}
    assert all(inside(cell, whole) for cell in cells)
    assert all(overlap(a, b) == 0 for a, b in itertools.combinations(cells, 2))
    assert sum(c["width"] * c["height"] for c in cells) == pytest.approx(185 * 55, abs=1e-9)   # tiled exactly
    assert {c["name"] for c in cells} >= {"student", "group", "variant", "sheet_name", "scale", "maker", "date",
                                          "sheet_number", "sheet_count"}


def test_drawings_laid_out_on_a_sheet_keep_to_the_frame_and_off_the_title_block():
    rng = random.Random(3)
    cases = [[{"width": rng.uniform(40, 300), "height": rng.uniform(30, 260)} for _ in range(rng.randint(3, 9))]
             for _ in range(6)]
    sheet, *results = layout(("sheetFrame",), *[("layOutSheet", sizes) for sizes in cases])
    frame, block = sheet["frame"], sheet["titleBlock"]
    for sizes, result in zip(cases, results):
        boxes = [{**spot, **size} for spot, size in zip(result["placed"], sizes) if spot]
        assert len(boxes) + len(result["overflow"]) == len(sizes)
        assert all(inside(box, frame) for box in boxes)
        assert all(overlap(box, block) == 0 for box in boxes)
        assert all(overlap(a, b) == 0 for a, b in itertools.combinations(boxes, 2))


def test_a_drawing_larger_than_any_sheet_still_gets_a_sheet_of_its_own():
    result, = layout(("layOutSheet", [{"width": 900, "height": 100}, {"width": 50, "height": 50}]))
    assert result["placed"][0]["oversize"] and result["overflow"] == []


CASES = [("shaping_machine", "ru"), ("shaping_machine", "en"), ("jaw_crusher", "ru"), ("lever_ram", "en")]
ANSWERS = {}                   # preset → (path, answer): one project per preset for the module


def body(preset: str) -> dict:
    """The preset's project: its linkage and dynamics, 12 positions, the plans drawn at position 3."""
    p = presets()[preset]
    d = p["dynamics"]
    return {"linkage": p["linkage"], "masses": d["masses"], "inertias": d["inertias"],
            "omega_mean": d["flywheel"]["omega_mean"], "delta": d["flywheel"]["delta"], "positions": 12,
            "drawn": [3], "title": {"student": "I. Petrenko", "group": "TMM-21", "variant": "7"}}


def project(preset: str, folder: Path) -> tuple[Path, dict]:
    """The endpoint's answer as the page gets it: its body function and serialisation, run in this process (the
    heavy process pool's start-up is none of this test's business)."""
    if preset not in ANSWERS:
        response = respond(course_project(CourseProjectRequest(**body(preset)), "ru"))
        path = folder / f"{preset}.json"
        path.write_bytes(response.body)
        ANSWERS[preset] = path, json.loads(response.body)
    return ANSWERS[preset]


@pytest.fixture(scope="module", params=CASES, ids=[f"{preset}-{lang}" for preset, lang in CASES])
def case(request, tmp_path_factory):
    """(answer, figures): a preset's answer and every drawing of it built in Node in one language."""
    preset, lang = request.param
    path, answer = project(preset, tmp_path_factory.getbasetemp())
    return answer, node({"answer": str(path), "texts": str(REPO / "content" / "i18n" / f"{lang}.json"), "lang": lang})


def drawn(parts: list, key: str, value=None) -> list:
    return [p for p in parts if key in (p["attrs"] or {}) and (value is None or str(p["attrs"][key]) == str(value))]


def arrow_length(part: dict) -> float:
    return math.dist(part["points"][0], part["head"][0])


def test_no_two_labels_of_any_drawing_share_a_point_and_all_stay_inside_it(case):
    _, figures = case
    assert len(figures) == 13
    for name, figure in figures.items():
        boxes = [label["box"] for label in figure["labels"]]
        clashes = [(a["text"], b["text"]) for a, b in itertools.combinations(figure["labels"], 2)
                   if overlap(a["box"], b["box"]) > 0]
        assert not clashes, (name, clashes)
        assert all(inside(box, figure["extent"]) for box in boxes), name


def test_the_crank_measures_oa_over_mu_l_at_every_position(case):
    data, figures = case
    joints, mu = data["plan_of_positions"]["joints"], data["scales"]["mu_l"]
    crank = drawn(figures["plan_of_positions"]["parts"], "data-role", "crank")
    assert len(crank) == data["positions"]["count"]
    for part in crank:
        i = int(part["attrs"]["data-position"]) - 1
        assert abs(math.dist(*part["points"]) - math.dist(joints["O"][i], joints["A"][i]) / mu) <= MM


def test_plan_vectors_measure_their_values_over_mu_v_and_mu_a(case):
    data, figures = case
    row = data["kinematics"][data["positions"]["drawn"][0] - 1]
    for plan, which, mu in (("velocity_plan", "velocity", data["scales"]["mu_v"]),
                            ("acceleration_plan", "acceleration", data["scales"]["mu_a"])):
        values = {v["name"]: v["value"] for equation in row[which] for v in equation["vectors"]}
        arrows = drawn(figures[plan]["parts"], "data-vector")
        assert {a["attrs"]["data-vector"] for a in arrows if a["attrs"]["data-kind"] != "point"} == \
            {name for name, value in values.items() if value / mu >= 0.05}
        for a in arrows:
            if a["attrs"]["data-kind"] != "point":
                assert abs(arrow_length(a) - values[a["attrs"]["data-vector"]] / mu) <= MM


def test_force_polygons_measure_each_force_over_mu_f(case):
    data, figures = case
    mu = data["scales"]["mu_F"]
    forces = {(str(p["group"]), v["name"]): v["magnitude"] for p in data["kinetostatics"]["force_plans"]
              for v in p["vectors"]}
    arrows = drawn(figures["force_plans"]["parts"], "data-force")
    assert len(arrows) == sum(1 for value in forces.values() if value / mu >= 0.05)
    for a in arrows:
        key = (str(a["attrs"]["data-group"]), a["attrs"]["data-force"])
        assert abs(arrow_length(a) - forces[key] / mu) <= 1e-5    # the polygon's ends are sent to 7 digits


def test_each_arm_on_zhukovskys_lever_is_the_answers_arm(case):
    data, figures = case
    lever = data["kinetostatics"]["zhukovsky"]
    arms = {row["name"]: abs(row["arm"]) for row in lever["lever"] if "arm" in row}
    arms["balancing"] = abs(lever["balancing_force"]["arm"])
    lines = drawn(figures["zhukovsky"]["parts"], "data-arm")
    assert lines and {line["attrs"]["data-arm"] for line in lines} == {name for name, arm in arms.items() if arm >= 0.5}
    for line in lines:
        assert abs(math.dist(*line["points"]) - arms[line["attrs"]["data-arm"]]) <= 1e-5   # images sent to 7 digits
