"""The page address keeps a dynamics scene's edited lists (web/static/js/common/model/url_state.js, read by
web/static/js/dynamics/model/dynamics_model.js, run in Node): a free law's table (the equation of motion's
variant 'free_law', motor.table_phi and motor.table_moment) of any length the server accepts, 2 to 361 points,
comes back from the address as it was written; a malformed one (lengths apart, too few or too many points, angles
not increasing or beyond the turn, a moment beyond ±10⁷ N·m, not a number) gives the scene's own points, both
lists; the indicator diagram's points keep the variant's own length."""
from __future__ import annotations

import json
import math
import shutil
import subprocess
from pathlib import Path

import pytest

from server.lessons.scenes import scenes

JS = Path(__file__).resolve().parents[1] / "web" / "static" / "js"
SCRIPT = """
globalThis.location = { search: "" };
const { scenes, cases } = JSON.parse(require("fs").readFileSync(0, "utf8"));
Promise.all([import(process.argv[1]), import(process.argv[2])]).then(([{ DynamicsModel }, { readState, stateQuery }]) => {
  const out = cases.map(({ scene, variant, query, edits }) => {
    let model = new DynamicsModel(scenes[scene], readState(`?variant=${variant}&${query ?? ""}`));
    for (const [path, values] of Object.entries(edits ?? {})) model.edit(path, values);
    if (edits) model = new DynamicsModel(scenes[scene], readState(`?${stateQuery(model, "ru")}`));   // a reload
    return model.request().motor;
  });
  process.stdout.write(JSON.stringify(out));
});
"""
NODE = shutil.which("node") or shutil.which("nodejs")
pytestmark = pytest.mark.skipif(NODE is None, reason="Node is not installed")

SCENES = {name: json.loads(scenes()[name].model_dump_json()) for name in ("equation-of-motion", "flywheel")}
FREE_LAW = next(v for v in SCENES["equation-of-motion"]["variants"] if v["id"] == "free_law")["request"]["motor"]
OWN = (FREE_LAW["table_phi"], FREE_LAW["table_moment"])
RIG = next(v for v in SCENES["flywheel"]["variants"] if v["id"] == "rig")["request"]["motor"]


def motors(*cases: dict) -> list[dict]:
    done = subprocess.run([NODE, "-e", SCRIPT, (JS / "dynamics" / "model" / "dynamics_model.js").as_uri(),
                           (JS / "common" / "model" / "url_state.js").as_uri()], text=True, capture_output=True,
                          check=True, timeout=60, input=json.dumps({"scenes": SCENES, "cases": list(cases)}))
    return json.loads(done.stdout)


def free_law(query: str | None = None, **edits) -> tuple[list, list]:
    [motor] = motors({"scene": "equation-of-motion", "variant": "free_law", "query": query, "edits": edits or None})
    return motor["table_phi"], motor["table_moment"]


def degrees(*angles: float) -> list[float]:
    return [math.radians(a) for a in angles]


def query(phi, moment=None) -> str:
    text = "edit.motor.table_phi=" + ",".join(map(str, phi))
    return text if moment is None else f"{text}&edit.motor.table_moment=" + ",".join(map(str, moment))


def test_the_scene_gives_its_own_points():
    assert free_law() == OWN and len(OWN[0]) == 12


@pytest.mark.parametrize("points", [2, 11, 13, 360, 361])
def test_a_table_of_any_allowed_length_comes_back_from_the_address_as_written(points):
    phi = [2 * math.pi * j / 361 for j in range(points)]
    moment = [round(10 * math.sin(j) - 0.5, 6) for j in range(points)]
    edits = {"motor.table_phi": phi, "motor.table_moment": moment}
    assert free_law(**edits) == (phi, moment)


def test_a_point_added_in_the_editor_survives_a_reload():
    phi = OWN[0] + [math.radians(345)]
    moment = OWN[1] + [10.0]
    assert free_law(**{"motor.table_phi": phi, "motor.table_moment": moment}) == (phi, moment)


def test_angles_alone_of_the_scenes_length_go_with_the_scenes_moments():
    phi = degrees(*range(5, 360, 30))
    assert free_law(query(phi)) == (phi, OWN[1])


@pytest.mark.parametrize("malformed", [
    query(degrees(0, 90, 180), [1, 2]),                              # lengths apart
    query(degrees(0, 90, 180, 270) + [0.1]),                         # angles alone, not the scene's length
    query([0.0], [1.0]),                                             # one point
    query([j * 0.017 for j in range(362)], [1.0] * 362),             # too many points
    query(degrees(0, 180, 90), [1, 2, 3]),                           # angles not increasing
    query([0.0, 1.0, 1.0 + 1e-8], [1, 2, 3]),                        # nearer than 10⁻⁶ rad
    query([0.0, 1.0, 7.0], [1, 2, 3]),                               # beyond the turn
    query(degrees(*range(0, 330, 30)) + [7.0]),                      # the scene's length, the last beyond the turn
    query([-0.1, 1.0, 2.0], [1, 2, 3]),                              # before it
    query([0.0, 1.0, 2.0], [1, 2e7, 3]),                             # a moment too large
    "edit.motor.table_phi=0,x,2&edit.motor.table_moment=1,2,3",     # not a number
    "edit.motor.table_phi=&edit.motor.table_moment=",                # empty
    "edit.motor.table_phi=0,1,2&edit.motor.table_moment=1,Infinity,3",
])
def test_a_malformed_table_gives_the_scenes_points(malformed):
    assert free_law(malformed) == OWN


def test_the_indicator_diagram_keeps_its_own_length():
    ordinates = [round(1 - j / 20, 6) for j in range(11)]
    kept, dropped = motors(
        {"scene": "flywheel", "variant": "rig", "edits": {"motor.expansion": ordinates}},
        {"scene": "flywheel", "variant": "rig", "query": "edit.motor.expansion=" + ",".join(["0.5"] * 12)})
    assert kept["expansion"] == ordinates and dropped["expansion"] == RIG["expansion"]
