"""The editor's view of the plane (web/static/js/editor/model/viewport.js, run in Node): world ↔ drawing, zoom about
a point, pan, pinch, fit, the grid's step and snapping, each checked by arithmetic done here: the mapping
X = (x − x₀)k, Y = (y₀ − y)k inverted, the world point under the pointer (between the fingers) kept where it is,
the step the smallest round length at least the units asked for, a snapped point the nearest grid node."""
from __future__ import annotations

import json
import math
import shutil
import subprocess
from pathlib import Path

import pytest

MODULE = Path(__file__).resolve().parents[1] / "web" / "static" / "js" / "editor" / "model" / "viewport.js"
SCRIPT = """
const cases = JSON.parse(require("fs").readFileSync(0, "utf8"));
import(process.argv[1]).then((m) => {
  const out = cases.map(({ call, args }) => m[call](...args));
  process.stdout.write(JSON.stringify(out.map((value) => (Object.is(value, -0) ? "-0" : value))));   // JSON drops −0
});
"""
NODE = shutil.which("node") or shutil.which("nodejs")
pytestmark = pytest.mark.skipif(NODE is None, reason="Node is not installed")
TIGHT = 1e-12          # relative: a few roundings of doubles in metres or drawing units


def run(*cases: tuple[str, list]) -> list:
    done = subprocess.run([NODE, "-e", SCRIPT, MODULE.as_uri()], text=True, capture_output=True, check=True,
                          timeout=60, input=json.dumps([{"call": call, "args": args} for call, args in cases]))
    return json.loads(done.stdout)


VIEW = {"x0": -0.37, "y0": 0.42, "k": 713.0}


def screen(view, p):
    """X = (x − x₀)k, Y = (y₀ − y)k, written out here."""
    return [(p[0] - view["x0"]) * view["k"], (view["y0"] - p[1]) * view["k"]]


def world(view, q):
    return [view["x0"] + q[0] / view["k"], view["y0"] - q[1] / view["k"]]


def test_world_and_drawing_points_map_both_ways():
    p = [0.123, -0.456]
    on_screen, back = run(("toScreen", [VIEW, p]), ("toWorld", [VIEW, screen(VIEW, p)]))
    assert on_screen == pytest.approx(screen(VIEW, p), rel=TIGHT)
    assert back == pytest.approx(p, rel=TIGHT)


def test_zoom_keeps_the_world_point_under_the_pointer_and_pan_moves_it_with_the_pointer():
    pointer = [611.0, 97.0]
    zoomed, panned, limited = run(("zoomAbout", [VIEW, pointer, 1.7]), ("panBy", [VIEW, [40.0, -25.0]]),
                                  ("zoomAbout", [VIEW, pointer, 1e9]))
    assert zoomed["k"] == pytest.approx(VIEW["k"] * 1.7, rel=TIGHT)
    assert world(zoomed, pointer) == pytest.approx(world(VIEW, pointer), rel=TIGHT)
    # the world point that was at the pointer is now 40 units right and 25 up of it
    assert screen(panned, world(VIEW, pointer)) == pytest.approx([pointer[0] + 40, pointer[1] - 25], rel=TIGHT)
    assert limited["k"] == 200000          # K_RANGE: no view narrower than 4 mm
    assert world(limited, pointer) == pytest.approx(world(VIEW, pointer), rel=TIGHT)


def test_a_pinch_scales_by_the_fingers_distance_and_keeps_their_midpoint_on_its_world_point():
    before = [[300.0, 300.0], [400.0, 360.0]]
    after = [[250.0, 310.0], [470.0, 400.0]]
    (view,) = run(("pinch", [VIEW, before, after]))
    ratio = math.dist(*after) / math.dist(*before)
    assert view["k"] == pytest.approx(VIEW["k"] * ratio, rel=TIGHT)
    mid_before = [(before[0][i] + before[1][i]) / 2 for i in range(2)]
    mid_after = [(after[0][i] + after[1][i]) / 2 for i in range(2)]
    assert screen(view, world(VIEW, mid_before)) == pytest.approx(mid_after, rel=TIGHT)


def test_fit_puts_every_point_inside_the_drawing_centred():
    points = [[-0.36, -0.23], [0.26, 0.23], [0.0, 0.1]]
    (view,) = run(("fitView", [points, VIEW]))
    drawn = [screen(view, p) for p in points]
    assert all(0 <= x <= 800 and 0 <= y <= 600 for x, y in drawn)
    assert (min(x for x, _ in drawn) + max(x for x, _ in drawn)) / 2 == pytest.approx(400, rel=TIGHT)
    assert (min(y for _, y in drawn) + max(y for _, y in drawn)) / 2 == pytest.approx(300, rel=TIGHT)


@pytest.mark.parametrize("k, units", [(600.0, 12.0), (713.0, 12.0), (37.0, 6.0), (12345.0, 25.9), (180000.0, 12.0)])
def test_the_grid_step_is_the_smallest_round_length_as_long_as_asked(k, units):
    step, major = run(("gridStep", [{"x0": 0, "y0": 0, "k": k}, units]), ("majorStep", [0.02]))
    rounds = sorted(m * 10.0 ** e for m in (1, 2, 5) for e in range(-6, 3))
    expected = next(r for r in rounds if r * k >= units * (1 - 1e-12))
    assert step == pytest.approx(expected, rel=TIGHT)
    assert major == pytest.approx(0.1, rel=TIGHT)


def test_a_snapped_point_is_the_nearest_grid_node_written_without_noise():
    snapped, tiny, negative = run(("snapPoint", [[0.1234, -0.0751], 0.01]), ("snapValue", [0.30000000000000004, 0.1]),
                                  ("snapValue", [-0.004, 0.01]))
    assert snapped == [0.12, -0.08]         # nearest multiples of 10 mm, exactly as written
    assert tiny == 0.3
    assert negative == 0                    # not "-0": no "−0" on the page
