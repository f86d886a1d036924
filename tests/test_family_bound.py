"""The family's bound against the endpoints' exact answers on every scene (server/api/family.py): for
every slider of every variant, at the defaults and with the other sliders at random values, the family the page
asks for (its drawn ``fields``, packed) is interpolated by the contract's rule (linear or cubic by interval)
at random values between members, and every drawn quantity is within TOLERANCE of its span of the endpoint's
exact answer there, plus the 5 digits sent (SENT × |value|) and what packing may move a value (PACK_QUANTUM / 2
of the span). Checked where the family claims the bound: families whose interpolation_error is within the
tolerance (plus packing's), in every interval wider than a slider resolves. A family above it says where in
numerics.message (a jump, a corner, the cap) and claims nothing: there the estimates of single intervals are
not a bound either (on the elastic transmission's speed and the angular acceleration's amplitude, intervals
estimated within the tolerance are off by 1–2 %, linear and cubic alike). Families run in this process with
the time budgets lifted, so nothing depends on the machine's speed.
"""
from __future__ import annotations

import json
import random
import shutil
import subprocess
from functools import cache
from pathlib import Path

import numpy as np
import pytest

from server.api import family
from server.api.endpoints import compute_answer
from server.lessons.requests import path_value, scene_request, slider_values
from server.lessons.scenes import scenes
from test_family import SENT, TOLERANCE
from test_family_engine import client  # noqa: F401  the fixture: in-process, no time budgets
from test_family_fields import whole_members

ROOT = Path(__file__).resolve().parents[1]
FIELDS_SCRIPT = """
const scenes = JSON.parse(require("fs").readFileSync(0, "utf8"));
import(process.argv[1]).then(({ previewFields }) => {
  const out = {};
  for (const scene of scenes) for (const variant of scene.variants) out[`${scene.id}/${variant.id}`] = previewFields(scene, variant);
  process.stdout.write(JSON.stringify(out));
});
"""
CHECKS = 2              # random values per family


@cache
def page_fields() -> dict[str, list[str]]:
    """"scene/variant" → the fields the page asks for (web/static/js/common/model/family_fields.js run in Node), or {} (the
    whole answers) where Node is not installed."""
    node = shutil.which("node") or shutil.which("nodejs")
    if node is None:
        return {}
    module = ROOT / "web" / "static" / "js" / "common" / "model" / "family_fields.js"
    listed = [json.loads(scene.model_dump_json()) for scene in scenes().values()]
    done = subprocess.run([node, "-e", FIELDS_SCRIPT, module.as_uri()], input=json.dumps(listed), text=True,
                          capture_output=True, check=True, timeout=120)
    return json.loads(done.stdout)


def page_body(scene, variant, slider, values: dict | None) -> dict:
    """The family request the page sends on a grab (bench/family_request.py does the same)."""
    request = scene_request(scene, variant, values)
    if scene.kind == "kinematics":
        factor = request["params"][slider.scale] if slider.scale else 1.0
        vary = [{"path": f"params.{slider.param}", "factor": float(factor)}]
    else:
        scale = path_value(request, slider.scale) if slider.scale else 1.0
        vary = [{"path": path, "factor": float(slider.to_si * scale)} for path in (slider.param, *slider.also)]
    fields = page_fields().get(f"{scene.id}/{variant.id}")
    return {"endpoint": scene.endpoint, "request": request, "vary": vary, "min": slider.min, "max": slider.max,
            "log": slider.log} | ({"fields": fields, "packed": True} if fields else {})


def check(client, body: dict, rng: random.Random) -> int:
    """Compare the interpolated family with the exact answer at CHECKS random values; the values checked."""
    response = client.post("/api/v1/family", json=body)
    assert response.status_code == 200, response.text[:500]
    answer = response.json()
    values, log = answer["values"], body["log"]
    members = whole_members(answer)
    width = family.spans(members)
    finest = (family.coordinate(values[-1], log) - family.coordinate(values[0], log)) * family.FINEST_FRACTION
    trie = family.field_trie(body["fields"]) if "fields" in body else None
    vary = [family.Vary(v["path"], v["factor"]) for v in body["vary"]]
    if answer["interpolation_error"] is None or answer["interpolation_error"] > TOLERANCE + family.PACK_QUANTUM / 2:
        return 0                    # no claim: the message says where and why
    intervals = [k for k in range(len(values) - 1) if members[k] is not None and members[k + 1] is not None
                 and family.coordinate(values[k + 1], log) - family.coordinate(values[k], log) > finest * 1.01]
    for k in rng.sample(intervals, min(CHECKS, len(intervals))):
        a, b = family.coordinate(values[k], log), family.coordinate(values[k + 1], log)
        value = family.from_coordinate(a + rng.uniform(0.05, 0.95) * (b - a), log)
        payload = compute_answer(body["endpoint"], family.member_body(body["request"], vary, value)).payload
        exact = family.as_tree(payload if trie is None else family.pruned(payload, trie), sent=False)
        preview = family.interpolate_family(values, members, value, log, answer["orders"])
        for path, leaf in family.checked_leaves(exact):
            guess = family._leaf(preview, path)
            ends = [family._leaf(members[k], path), family._leaf(members[k + 1], path)]
            shapes = {np.shape(x) for x in (guess, leaf, *ends)}
            if guess is None or any(end is None for end in ends) or len(shapes) > 1:
                continue            # the nearer member's leaf (the contract): another grid, or one end lacks it
            bound = (TOLERANCE + family.PACK_QUANTUM / 2) * width[path] + SENT * np.abs(leaf)
            off = np.abs(np.asarray(guess, float) - leaf)
            assert np.all(~(off > bound)), (body["endpoint"], value, answer["orders"][k], family.quantity(path),
                                            float(np.nanmax(off) / width[path]))
    return min(CHECKS, len(intervals))


def random_values(variant, rng: random.Random) -> dict:
    """Every slider of the variant at a random value it can take."""
    return {slider.id: rng.choice(slider_values(slider)) for slider in variant.sliders}




@pytest.mark.parametrize("scene_id", list(scenes()))
def test_every_slider_family_of_the_scene_is_within_the_bound_of_the_exact_answers(client, scene_id):
    scene = scenes()[scene_id]
    rng = random.Random(scene_id)
    checked = 0
    for variant in scene.variants:
        for values in (None, random_values(variant, rng)):
            for slider in variant.sliders:
                checked += check(client, page_body(scene, variant, slider, values), rng)
    assert checked > 0              # every scene has families within the tolerance
