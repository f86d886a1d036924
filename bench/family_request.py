"""The body of POST /api/v1/family a scene page sends when a student grabs a slider (the contract in the API
docs): the page's own request at the current values, and how the slider's value enters it.

Kinematics scenes set ``params[slider.param] = value × params[slider.scale]``: one path, ``params.<param>``,
with the factor ``params[slider.scale]`` (1 without a scale). Dynamics scenes put ``value × to_si × (value at
slider.scale)`` at ``slider.param`` and every ``slider.also`` path: each of them with that factor
(server/lessons/requests.py, formerly server/api/scene_requests.py). The range is the slider's, in shown
units: ``min``, ``max`` and ``log``.

The page also names the leaves its panels draw in a preview (``fields``, web/static/js/common/model/family_fields.js) and
asks for the family packed; ``preview_fields`` runs that module in Node on the scenes as the page gets them
(Scene.model_dump_json()), so a benchmark sends what the page sends.
"""
from __future__ import annotations

import argparse
import json
import shutil
import subprocess
from functools import cache
from pathlib import Path

from trees import ROOT, lessons

FIELDS_PLACES = ("", "common/model")     # where a tree keeps web/static/js/…/family_fields.js (before and after
                                         # the modules were sorted into folders)
FIELDS_SCRIPT = """
const scenes = JSON.parse(require("fs").readFileSync(0, "utf8"));
import(process.argv[1]).then(({ previewFields }) => {
  const out = {};
  for (const scene of scenes) for (const variant of scene.variants) out[`${scene.id}/${variant.id}`] = previewFields(scene, variant);
  process.stdout.write(JSON.stringify(out));
});
"""


def vary(scene, variant, slider, request: dict) -> list[dict]:
    """[{"path", "factor"}] such that request at path = slider value × factor, for every path the slider sets."""
    path_value = lessons()[4]
    if scene.kind == "kinematics":
        factor = request["params"][slider.scale] if slider.scale else 1.0
        return [{"path": f"params.{slider.param}", "factor": float(factor)}]
    factor = slider.to_si * (path_value(request, slider.scale) if slider.scale else 1.0)
    return [{"path": path, "factor": float(factor)} for path in (slider.param, *slider.also)]


def family_body(scene, variant, slider, values: dict | None = None) -> dict:
    """The family request for one slider of one variant, the other controls at `values` (defaults if absent)."""
    scene_request = lessons()[1]
    request = scene_request(scene, variant, values)
    return {"endpoint": scene.endpoint, "request": request, "vary": vary(scene, variant, slider, request),
            "min": slider.min, "max": slider.max, "log": slider.log}


@cache
def all_preview_fields(tree: Path = ROOT) -> dict[str, list[str]]:
    """"scene/variant" → the fields the page of that tree sends (family_fields.js, where that tree keeps it, run in Node)."""
    module = next((tree / "web" / "static" / "js" / place / "family_fields.js" for place in FIELDS_PLACES
                   if (tree / "web" / "static" / "js" / place / "family_fields.js").exists()), None)
    if module is None:
        return {}
    node = shutil.which("node") or shutil.which("nodejs")
    if node is None:
        raise SystemExit("Node.js is needed to run the page's family_fields.js (apt-get install nodejs)")
    scenes = [json.loads(scene.model_dump_json()) for scene in lessons()[0]().values()]
    done = subprocess.run([node, "-e", FIELDS_SCRIPT, module.as_uri()], input=json.dumps(scenes), text=True,
                          capture_output=True, check=True)
    return json.loads(done.stdout)


def page_family_body(scene, variant, slider, tree: Path = ROOT, values: dict | None = None) -> dict:
    """The family request the page of ``tree`` sends on a grab (without "stage"), the other controls at
    ``values`` (defaults if absent). A page with family_fields.js asks for the family packed, and names the
    fields when the variant's panels draw any in a preview (a variant of tables alone names none: whole answers)."""
    body = family_body(scene, variant, slider, values)
    previews = all_preview_fields(tree)
    key = f"{scene.id}/{variant.id}"
    if key not in previews:
        return body
    return body | ({"fields": previews[key]} if previews[key] else {}) | {"packed": True}


if __name__ == "__main__":
    epilog = ("A module: the body of POST /api/v1/family a scene page sends, for the bench scripts"
              "; nothing to run by itself.")
    argparse.ArgumentParser(description=__doc__.split("\n\n")[0], epilog=epilog).parse_args()
