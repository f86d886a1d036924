"""The editor's readiness line (web/static/js/editor/view/readiness.js) in Node, on the server's own answers.

A four-bar whose crank is too long for its coupler and rocker: the server's special positions (exact limits of
assembly) give the stretch where its group assembles, running on through 0° from the second limit to the first,
equal to the closed form of the flattened triangle |O₁A| = l_AB + l_BO₁ to 1e-12 rad (the server's bisection and
arccos, both to round-off); the sentence in Russian names the group II₁(2,3) and writes both limits to 0.01°. The
same four-bar with a short crank turns fully and is ready. An input slider's travel is not periodic: a group that
closes only inside it assembles between its two limits, one that stops closing at the travel's start assembles from
its limit to the travel's end.
"""
from __future__ import annotations

import copy
import json
import math
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from server.core.mechanisms.general import GeneralMechanism, compute_general
from server.core.structure.presets import presets
from server.lessons.scenes import interface_texts

VIEW = Path(__file__).resolve().parents[1] / "web" / "static" / "js" / "editor" / "view" / "readiness.js"
NODE = shutil.which("node") or shutil.which("nodejs")
pytestmark = pytest.mark.skipif(NODE is None, reason="Node is not installed")
SCRIPT = """
const data = JSON.parse(require("fs").readFileSync(0, "utf8"));
import(process.argv[1]).then((m) => {
  const out = data.cases.map(({ linkage, table, special }) => {
    const ready = m.readiness({ linkage, table, refusal: null, special });
    return { ready, said: m.readinessText(ready, "", data.t, "ru") };
  });
  out.push(data.travel.map(([limits, range]) => m.assemblyRanges(limits, range, false)));
  process.stdout.write(JSON.stringify(out));
});
"""


def answer(linkage) -> dict:
    """What the editor's two questions for a linkage answer: the table over the turn (joints null where a group
    does not close) and the special positions."""
    result = compute_general(linkage, ["structure", "joints"], n=361)
    joints = {name: [[None, None] if np.isnan(x) else [x, y] for x, y in rows.tolist()]
              for name, rows in result.outputs["joints"].items()}
    special = [sp.as_dict() for sp in GeneralMechanism(linkage).special_positions({})]
    return {"linkage": linkage, "table": {"outputs": {"structure": result.outputs["structure"], "joints": joints}},
            "special": special}


def test_readiness_of_a_four_bar_that_cannot_turn_and_of_one_that_can():
    long_crank = copy.deepcopy(presets()["four_bar"]["linkage"])       # O at 0, O₁ at 0.4 m, coupler 0.35, rocker 0.3
    long_crank["input"]["length"] = 0.3
    cases = [answer(long_crank), answer(presets()["four_bar"]["linkage"])]
    travel = [([{"phi": 0.12, "assembles_after": True}, {"phi": 0.17, "assembles_after": False}], [0.1, 0.2]),
              ([{"phi": 0.15, "assembles_after": True}], [0.1, 0.2]),
              ([{"phi": 0.15, "assembles_after": False}], [0.1, 0.2])]
    data = {"cases": cases, "t": interface_texts("ru"), "travel": travel}
    done = subprocess.run([NODE, "-e", SCRIPT, VIEW.as_uri()], text=True, capture_output=True, check=True, timeout=60,
                          input=json.dumps(data))
    (cannot, can, ranges) = json.loads(done.stdout)
    stretched = math.acos((0.3**2 + 0.4**2 - (0.35 + 0.3) ** 2) / (2 * 0.3 * 0.4))
    assert cannot["ready"]["state"] == "partial" and cannot["ready"]["turns"] is False
    (group,) = cannot["ready"]["groups"]
    (start, end), = group["ranges"]
    assert group["name"] == "II₁(2,3)"
    assert abs(start - (2 * math.pi - stretched)) <= 1e-12 and abs(end - stretched) <= 1e-12
    degrees = lambda value: f"{math.degrees(value):.2f}°".replace(".", ",")      # noqa: E731
    assert cannot["said"]["turn"] == (f"Кривошип не проворачивается полностью. Группа II₁(2,3) собирается только при "
                                      f"φ от {degrees(2 * math.pi - stretched)} через 0° до {degrees(stretched)}.")
    assert cannot["said"]["mobility"] == "W = 1."
    assert can["ready"]["state"] == "ready" and can["ready"]["turns"] is True and can["ready"]["groups"] == []
    assert can["said"]["turn"] == "Кривошип проворачивается полностью."
    assert ranges == [[[0.12, 0.17]], [[0.15, 0.2]], [[0.1, 0.15]]]
