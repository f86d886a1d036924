"""The editor's model in Node: the edit history (web/static/js/editor/model/history.js) and the textbook's names
of what the student places (web/static/js/editor/model/linkage.js).

- Undo and redo: each recorded step undone gives back the mechanism before it, redo the one after it, in order;
  a new step after an undo forgets what could be redone; a hundred steps are kept.
- Names: a six-bar placed as a student places it (two frame joints, the crank, an RRR group, a frame guide, an RRP
  group) is named as the textbook names it: the supports O and O₁, the crank OA, the moving joints B, C in order of
  attachment, links 1 (the crank) to 5; its groups' names are the terms of the structural formula the server's
  structural analysis writes for the same linkage (server/core/structure/analysis.py, an independent writer).
- A joint renamed is renamed wherever the mechanism refers to it (the server's analysis accepts the result); a name
  another element has is refused.
"""
from __future__ import annotations

import json
import shutil
import subprocess
from pathlib import Path

import pytest

from server.core.structure.analysis import analyse
from server.core.structure.spec import parse
from server.lessons.scenes import interface_texts

MODEL = Path(__file__).resolve().parents[1] / "web" / "static" / "js" / "editor" / "model"
NODE = shutil.which("node") or shutil.which("nodejs")
pytestmark = pytest.mark.skipif(NODE is None, reason="Node is not installed")


def node(script: str, data=None):
    """Run `script` (an async function body with `history` and `linkage` the two modules and `data` the input)."""
    program = f"""
const data = JSON.parse(require("fs").readFileSync(0, "utf8"));
Promise.all([import(process.argv[1]), import(process.argv[2])]).then(async ([history, linkage]) => {{
  const out = await (async () => {{ {script} }})();
  process.stdout.write(JSON.stringify(out));
}});
"""
    done = subprocess.run([NODE, "-e", program, (MODEL / "history.js").as_uri(), (MODEL / "linkage.js").as_uri()],
                          text=True, capture_output=True, check=True, timeout=60, input=json.dumps(data))
    return json.loads(done.stdout)


def test_undo_and_redo_walk_the_steps_back_and_forth():
    out = node("""
      const h = new history.EditHistory();
      const seen = [h.canUndo, h.canRedo];
      h.record("m0"); h.record("m1"); h.record("m2");          // three steps: m0 → m1 → m2 → m3 shown
      const back = [h.undo("m3"), h.undo("m2"), h.canRedo];     // m2, m1
      const forth = [h.redo("m1"), h.canRedo, h.redo("m2"), h.redo("m3")];   // m2, true, m3, null
      h.undo("m3");                                              // back to m2 …
      h.record("m2");                                            // … and a new step from it: m3 cannot come back
      const after = [h.canRedo, h.undo("m4"), h.undo("m2"), h.undo("m1"), h.undo("m0")];
      const deep = new history.EditHistory();
      for (let k = 0; k < 150; k += 1) deep.record(`s${k}`);
      let count = 0, last = null;
      for (let s = deep.undo("now"); s !== null; s = deep.undo(s)) { count += 1; last = s; }
      return { seen, back, forth, after, count, last };
    """)
    assert out["seen"] == [False, False]
    assert out["back"] == ["m2", "m1", True]
    assert out["forth"] == ["m2", True, "m3", None]
    assert out["after"] == [False, "m2", "m1", "m0", None]
    assert out["count"] == 100 and out["last"] == "s50"      # the last hundred steps


SIX_BAR = """
  const m = linkage.emptyLinkage();
  const o = linkage.addFrameJoint(m, [0, 0]);
  const o1 = linkage.addFrameJoint(m, [0.4, 0]);
  linkage.setCrank(m, o, [0.1, 0]);
  const at = { [o]: [0, 0], [o1]: [0.4, 0], A: [0.1, 0], B: [0.3, 0.25] };
  linkage.addGroup(m, "RRR", [m.input.joint, o1], [0.3, 0.25], (n) => at[n]);
  const g = linkage.addFrameGuide(m, [0, 0.4]);
  linkage.addGroup(m, "RRP", [m.groups[0].inner, g], [0.6, 0.4], (n) => at[n], () => ({ point: [0, 0.4], angle: 0 }));
"""


def test_a_six_bar_is_named_as_the_textbook_names_it():
    out = node(SIX_BAR + """
      return { m, frame: Object.keys(m.frame.joints), crank: `${m.input.pivot}${m.input.joint}`,
        inner: m.groups.map((g) => g.inner), links: linkage.links(m).map(([l]) => l), names: linkage.groupNames(m) };
    """)
    assert out["frame"] == ["O", "O₁"] and out["crank"] == "OA" and out["inner"] == ["B", "C"]
    assert out["links"] == [1, 2, 3, 4, 5]
    formula = analyse(parse(out["m"]))["formula"]
    assert formula == " → ".join(["I(0,1)", *out["names"]]) == "I(0,1) → II₁(2,3) → II₂(4,5)"


def test_a_renamed_joint_is_renamed_everywhere():
    out = node(SIX_BAR + """
      const taken = linkage.renameJoint(m, "O₁", "C");          // C is the slider's joint already
      const empty = linkage.renameJoint(m, "O₁", "  ");
      const renamed = [linkage.renameJoint(m, "O₁", "D"), linkage.renameJoint(m, "B", "K")];
      return { taken, empty, renamed, m, label: linkage.guideLabel("ram", data.ru), own: linkage.guideLabel("g1", data.ru) };
    """, {"ru": interface_texts("ru")})
    assert out["taken"] is False and out["empty"] is False and out["renamed"] == [True, True]
    m = out["m"]
    assert list(m["frame"]["joints"]) == ["O", "D"]
    assert m["groups"][0]["outer"] == ["A", "D"] and m["groups"][0]["inner"] == "K" and m["groups"][1]["outer"] == ["K"]
    assert analyse(parse(m))["W"] == 1
    assert out["label"] == "x–x" and out["own"] == "g1"
