"""The editor's loads (web/static/js/editor/model/dynamics.js, run in Node) on the shaping machine's preset and its
estimate's load places (server/core/structure/estimate.py): a load the student put on any sliding pair or link, or
a force at a point of a link, is kept while the mechanism still has that pair or link, dropped when it does not;
where every kept load is gone the estimate's load takes their place, where the student kept none there stay none;
"add" offers only the places without a load and adds the load offered there, and a force at a point on any moving
link (as many as wanted), "remove" takes one away."""
from __future__ import annotations

import copy
import json
import math
import shutil
import subprocess
from pathlib import Path

import pytest

from server.core.structure.estimate import estimated_dynamics
from server.core.structure.presets import presets

MODULE = Path(__file__).resolve().parents[1] / "web" / "static" / "js" / "editor" / "model" / "dynamics.js"
SCRIPT = """
const cases = JSON.parse(require("fs").readFileSync(0, "utf8"));
import(process.argv[1]).then((m) => {
  const out = cases.map(({ call, args }) => {
    if (call === "keptOn") return m.keptOn(...args).masses;
    if (call === "freePlaces") return m.freePlaces(...args).map((p) => p.key);
    if (call === "pointPlaces") return m.pointPlaces(...args).map((p) => p.key);
    const [dynamics, ...rest] = args;
    m[call](dynamics, ...rest);
    return dynamics.masses;
  });
  process.stdout.write(JSON.stringify(out));
});
"""
NODE = shutil.which("node") or shutil.which("nodejs")
pytestmark = pytest.mark.skipif(NODE is None, reason="Node is not installed")

SHAPING = presets()["shaping_machine"]
FULL = estimated_dynamics(SHAPING["linkage"])
SHORT_LINKAGE = copy.deepcopy(SHAPING["linkage"])          # the ram's group taken away: pairs s23 only, links 1–3
SHORT_LINKAGE["groups"] = SHORT_LINKAGE["groups"][:1]
SHORT = estimated_dynamics(SHORT_LINKAGE)


def run(*cases: tuple[str, list]) -> list:
    done = subprocess.run([NODE, "-e", SCRIPT, MODULE.as_uri()], text=True, capture_output=True, check=True,
                          timeout=60, input=json.dumps([{"call": call, "args": args} for call, args in cases]))
    return json.loads(done.stdout)


def student(forces: list, moments: list, points: list | None = None) -> dict:
    """The preset's dynamics with the student's loads (and forces at points, where given)."""
    dynamics = copy.deepcopy(SHAPING["dynamics"])
    dynamics["masses"] |= {"forces": forces, "moments": moments, "gravity": 0}
    if points is not None:
        dynamics["masses"]["point_forces"] = points
    return dynamics


def estimate(of: dict) -> dict:
    return {key: of[key] for key in ("masses", "inertias", "motor", "flywheel")}


SLOT = {"joint": "s23", "working": 700.0, "k": 0.2, "sense": 1}
RAM = {"joint": "E/ram", "working": 3000.0, "k": 0.05, "sense": -1}
ROD = {"link": 4, "working": 80.0, "k": 0.5, "sense": -1}
RAM_LINK = {"link": 5, "working": 30.0, "k": 0.1, "sense": 1}
TOOL = {"link": 5, "point": [0.1, -0.05], "name": "K", "magnitude": 3000.0,
        "direction": {"kind": "fixed", "angle": 0.0}, "acts": "working"}
ON_LEVER = {"link": 3, "point": [0.3, 0.0], "magnitude": 200.0, "direction": {"kind": "link", "angle": 1.5},
            "acts": "always"}


def test_loads_stay_on_the_pairs_and_links_the_mechanism_still_has():
    on_full, on_short, all_gone, none_kept = run(
        ("keptOn", [student([SLOT, RAM], [ROD]), estimate(FULL), FULL["load_places"]]),
        ("keptOn", [student([SLOT, RAM], [ROD, RAM_LINK]), estimate(SHORT), SHORT["load_places"]]),
        ("keptOn", [student([RAM], [RAM_LINK]), estimate(SHORT), SHORT["load_places"]]),
        ("keptOn", [student([], []), estimate(FULL), FULL["load_places"]]))
    assert (on_full["forces"], on_full["moments"]) == ([SLOT, RAM], [ROD])     # s23 is none of the estimate's loads
    assert (on_short["forces"], on_short["moments"]) == ([SLOT], [])           # E/ram, links 4 and 5 are gone
    assert (all_gone["forces"], all_gone["moments"]) == (SHORT["masses"]["forces"], SHORT["masses"]["moments"])
    assert SHORT["masses"]["moments"]                                           # (the short one's own: a moment)
    assert (none_kept["forces"], none_kept["moments"]) == ([], [])
    assert on_short["gravity"] == 0                                             # g kept as the student set it
    assert [row["link"] for row in on_short["links"]] == [2, 3]


def test_add_offers_the_free_places_and_adds_their_load_and_remove_takes_one_away():
    places = FULL["load_places"]
    free, added, removed = run(
        ("freePlaces", [student([RAM], [ROD]), places]),
        ("addLoad", [student([RAM], []), places, "moment:3"]),
        ("removeLoad", [student([SLOT, RAM], [ROD]), "forces", 0]))
    assert free == ["force:s23", "moment:1", "moment:2", "moment:3", "moment:5"]
    assert added["moments"] == [next(m for m in places["moments"] if m["link"] == 3)]
    assert added["forces"] == [RAM]
    assert (removed["forces"], removed["moments"]) == ([RAM], [ROD])


def test_forces_at_points_go_with_their_links():
    on_full, on_short, only_gone, without = run(
        ("keptOn", [student([RAM], [], [TOOL, ON_LEVER]), estimate(FULL), FULL["load_places"]]),
        ("keptOn", [student([SLOT], [], [TOOL, ON_LEVER]), estimate(SHORT), SHORT["load_places"]]),
        ("keptOn", [student([], [], [TOOL]), estimate(SHORT), SHORT["load_places"]]),
        ("keptOn", [student([RAM], []), estimate(FULL), FULL["load_places"]]))
    assert on_full["point_forces"] == [TOOL, ON_LEVER] and on_full["forces"] == [RAM]
    assert on_short["point_forces"] == [ON_LEVER] and on_short["forces"] == [SLOT]     # link 5 is gone
    assert only_gone["point_forces"] == [] and only_gone["moments"] == SHORT["masses"]["moments"]
    assert "point_forces" not in without                         # a table without any keeps none


def test_a_force_at_a_point_is_added_on_any_moving_link_and_removed():
    places = FULL["load_places"]
    links, added, again, removed = run(
        ("pointPlaces", [places]),
        ("addLoad", [student([RAM], []), places, "point:5"]),
        ("addLoad", [student([RAM], [], [TOOL]), places, "point:5"]),
        ("removeLoad", [student([RAM], [], [TOOL, ON_LEVER]), "point_forces", 0]))
    assert links == ["point:1", "point:2", "point:3", "point:4", "point:5"]
    new = {"link": 5, "point": [0, 0], "magnitude": 1000, "direction": {"kind": "fixed", "angle": math.pi},
           "acts": "working"}
    assert added["point_forces"] == [new] and added["forces"] == [RAM]
    assert again["point_forces"] == [TOOL, new]                  # a second one on the same link
    assert removed["point_forces"] == [ON_LEVER]
