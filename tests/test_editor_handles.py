"""Dragging a handle of the editor's drawing (web/static/js/editor/model/handles.js, run in Node) changes the
mechanism's data so that the server, computing the changed mechanism on its own (POST /api/v1/kinematics, the
editor's table), puts the dragged joint where the pointer left it at the angle shown: the crank's pin, an RRR's
and an RRP's inner joint (projected on its guide), a point on a link, the input slider's joint; a guide turned by
its angle handle carries its slider along the line to the pointer. Tolerance: the data are written to 0.1 mm, so a
joint lands within 0.1 mm of the pointer for a length or coordinate, a few tenths where two written lengths meet
at an angle (RRR: 5e-5 m each, the angle at C above 30° here)."""
from __future__ import annotations

import copy
import json
import math
import shutil
import subprocess
from pathlib import Path

import pytest
from fastapi.testclient import TestClient

from server.api.app import app
from server.core.structure.presets import presets

EDITOR = Path(__file__).resolve().parents[1] / "web" / "static" / "js" / "editor" / "model"
SCRIPT = """
const cases = JSON.parse(require("fs").readFileSync(0, "utf8"));
const [geometry, handles] = process.argv.slice(1);
Promise.all([import(geometry), import(handles)]).then(([g, h]) => {
  const out = cases.map(({ linkage, table, k, id, to, shown }) => {
    const s = g.stateAt(linkage, table, k);
    const all = h.handles(linkage, s, 0.05);
    const handle = all.find((item) => item.id === id);
    const at = h.moveHandle(linkage, handle, to, s, shown);
    return { linkage, at, ids: all.map((item) => item.id) };
  });
  process.stdout.write(JSON.stringify(out));
});
"""
NODE = shutil.which("node") or shutil.which("nodejs")
pytestmark = pytest.mark.skipif(NODE is None, reason="Node is not installed")
TABLE = ["structure", "joints", "joints_d1", "joints_d2", "angles", "angles_d1", "angles_d2", "slides", "slides_d1",
         "slides_d2"]       # model/table.js TABLE_OUTPUTS
WRITTEN = 1e-4              # m: 0.1 mm, the data's last digit; a rounded value is within half of it


@pytest.fixture(scope="module")
def client() -> TestClient:
    with TestClient(app) as c:
        yield c


SIX_BAR = {"frame": {"joints": {"O": [0, 0], "O1": [0.35, 0]}, "guides": {"g1": {"through": [0.55, 0.1], "angle": 0}}},
           "input": {"kind": "crank", "link": 1, "pivot": "O", "joint": "A", "length": 0.1, "angle0": 0, "sense": 1},
           "groups": [{"kind": "RRR", "links": [2, 3], "outer": ["A", "O1"], "inner": "B", "lengths": [0.25, 0.2236],
                       "branch": 1, "points": {"S2": {"link": 2, "along": 0.1, "across": 0.02}}},
                      {"kind": "RRP", "links": [4, 5], "outer": ["B"], "guide": "g1", "inner": "C", "length": 0.316,
                       "branch": 1}]}


def table(client, linkage) -> dict:
    answer = client.post("/api/v1/kinematics?lang=en", json={"mechanism": "general", "linkage": linkage, "n": 361,
                                                             "outputs": TABLE})
    assert answer.status_code == 200, answer.text
    return answer.json()


def dragged(client, linkage, k, id, to) -> tuple[dict, list, dict]:
    """The handle `id` dragged to `to` at row k: the changed linkage, where the page draws the joint, and the
    server's table of the changed linkage."""
    before = table(client, linkage)
    case = {"linkage": copy.deepcopy(linkage), "table": before, "k": k, "id": id, "to": to, "shown": before["phi"][k]}
    done = subprocess.run([NODE, "-e", SCRIPT, (EDITOR / "geometry.js").as_uri(), (EDITOR / "handles.js").as_uri()],
                          text=True, capture_output=True, check=True, timeout=60, input=json.dumps([case]))
    (out,) = json.loads(done.stdout)
    return out["linkage"], out["at"], table(client, out["linkage"]), out["ids"]


def test_the_handles_are_the_joints_the_data_place_and_the_guides(client):
    _, _, _, ids = dragged(client, SIX_BAR, 0, "frame:O1", [0.35, 0])
    assert ids == ["frame:O", "frame:O1", "crank:A", "RRR:B", "RRP:C", "point:S2", "guide:g1", "guide_angle:g1"]


@pytest.mark.parametrize("id, to, k, tolerance", [
    ("crank:A", [0.06, 0.09], 40, WRITTEN),          # |OA| and θ₀ written: the pin within 0.1 mm
    ("RRR:B", [0.22, 0.23], 40, 3 * WRITTEN),         # two written lengths meeting at C
    ("point:S2", [0.2, 0.15], 40, WRITTEN),
    ("frame:O1", [0.37, 0.02], 40, WRITTEN),
])
def test_a_dragged_joint_is_where_the_server_puts_it(client, id, to, k, tolerance):
    linkage, at, after, _ = dragged(client, SIX_BAR, k, id, to)
    name = id.split(":")[1]
    assert at == pytest.approx(to, abs=tolerance)
    assert after["outputs"]["joints"][name][k] == pytest.approx(to, abs=tolerance)


def test_an_rrp_joint_dragged_off_its_guide_lands_on_the_guide_below_the_pointer(client):
    linkage, at, after, _ = dragged(client, SIX_BAR, 90, "RRP:C", [0.5, 0.17])
    assert at == pytest.approx([0.5, 0.1], abs=1e-12)            # the guide y = 0.1 along x
    assert after["outputs"]["joints"]["C"][90] == pytest.approx([0.5, 0.1], abs=WRITTEN)
    b = table(client, SIX_BAR)["outputs"]["joints"]["B"][90]
    assert linkage["groups"][1]["length"] == pytest.approx(math.dist(b, [0.5, 0.1]), abs=WRITTEN / 2)


def test_the_crank_keeps_turning_from_where_it_was_left(client):
    """θ₀ is read back so that the pin is at the pointer at the shown φ; at φ + 90° it has turned 90° on."""
    linkage, _, after, _ = dragged(client, SIX_BAR, 40, "crank:A", [0.0, 0.1])
    assert after["outputs"]["joints"]["A"][130] == pytest.approx([-0.1, 0.0], abs=WRITTEN)


def test_the_input_slider_follows_its_guide_and_keeps_its_stroke(client):
    linkage = presets()["slider_driven_crank"]["linkage"]
    moved, at, after, _ = dragged(client, linkage, 100, "input_slider:B", [0.31, 0.04])
    assert at == pytest.approx([0.31, 0.0], abs=WRITTEN)
    assert after["outputs"]["joints"]["B"][100] == pytest.approx([0.31, 0.0], abs=WRITTEN)
    travel = linkage["input"]["travel"]
    assert moved["input"]["travel"][1] - moved["input"]["travel"][0] == pytest.approx(travel[1] - travel[0], abs=WRITTEN)


def test_a_guide_turned_by_its_angle_handle_carries_its_slider_on_the_new_line(client):
    linkage = presets()["slider_crank"]["linkage"]
    through = linkage["frame"]["guides"]["x"]["through"]
    moved, _, after, _ = dragged(client, linkage, 60, "guide_angle:x", [0.1, 0.03])
    direction = math.atan2(0.03 - through[1], 0.1 - through[0])
    assert moved["frame"]["guides"]["x"]["angle"] == pytest.approx(direction, abs=1e-6)
    b = after["outputs"]["joints"]["B"][60]
    line = moved["frame"]["guides"]["x"]["angle"]
    # B on the line through the guide's point at that angle: its distance from the line is zero, to the 7
    # significant digits the API writes positions with (5e-8 m at 0.4 m)
    assert (b[0] - through[0]) * math.sin(line) - (b[1] - through[1]) * math.cos(line) == pytest.approx(0, abs=1e-7)


def test_a_guide_on_a_link_turned_to_the_pointer_measures_its_angle_from_the_link(client):
    """The lever-and-ram's slot on the lever: turned to the pointer at φ = 30°, the ram's block E sits where the
    slot's new line through the lever's pivot C meets the ram's guide."""
    linkage = presets()["lever_ram"]["linkage"]
    c = linkage["frame"]["joints"]["C"]
    to = [0.02, -0.1]
    _, _, after, _ = dragged(client, linkage, 30, "guide_angle:slot", to)
    e = after["outputs"]["joints"]["E"][30]
    assert math.atan2(e[1] - c[1], e[0] - c[0]) == pytest.approx(math.atan2(to[1] - c[1], to[0] - c[0]), abs=1e-6)
