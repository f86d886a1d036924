"""The page and the server build the same request body from a scene: the page's own models
(web/static/js/kinematics/model/scene_model.js, web/static/js/dynamics/model/dynamics_model.js), run in
Chromium as the page loads them, against server/lessons/requests.py (which computes an assignment's answers
and the classroom benchmark's requests), for every scene and variant at its defaults and at changed values.
A course-project scene's page (kind "project", web/static/js/project/project_scene.js) drags no slider: it
builds each variant's body at the defaults only (projectBody), compared with requests.project_body there.

Equal exactly, not within a tolerance: both sides do the same IEEE-754 operations in the same order
(value × to_si × the value at scale, left to right), and JSON carries every double exactly."""
from __future__ import annotations

import json
import random

import pytest

from server.lessons.requests import defaults, scene_request, slider_values
from server.lessons.scenes import scenes

pytestmark = pytest.mark.browser

BUILD_REQUESTS_JS = """async ({ scenes, cases }) => {
  const entry = document.querySelector('script[type="module"][src*="_scene.js"]').src;
  const { SceneModel } = await import(new URL("../kinematics/model/scene_model.js", entry));
  const { DynamicsModel } = await import(new URL("../dynamics/model/dynamics_model.js", entry));
  const { projectBody } = await import(new URL("../project/project_scene.js", entry));
  return cases.map(({ scene, variant, values }) => {
    const data = scenes[scene];
    if (data.kind === "project") {
      const chosen = data.variants.find((v) => v.id === variant);
      return { values: Object.fromEntries(chosen.sliders.map((s) => [s.id, s.default])), body: projectBody(chosen) };
    }
    const model = new (data.kind === "kinematics" ? SceneModel : DynamicsModel)(data, { variant, values });
    return { values: model.values, body: model.request() };
  });
}"""


def cases() -> list[dict]:
    """Per variant: the defaults; every slider at its least value and every toggle at its last option; every
    slider at its greatest and every toggle at its first; two draws of values the sliders can express. A
    course-project scene: the defaults only (its page builds no other body)."""
    rng = random.Random(16)
    out = []
    for scene in scenes().values():
        for variant in scene.variants:
            grids = {s.id: slider_values(s) for s in variant.sliders}
            options = {t.id: t.options for t in variant.toggles}
            if scene.kind == "project":
                out.append({"scene": scene.id, "variant": variant.id, "values": {}})
                continue
            changed = [{**{i: g[0] for i, g in grids.items()}, **{i: o[-1] for i, o in options.items()}},
                       {**{i: g[-1] for i, g in grids.items()}, **{i: o[0] for i, o in options.items()}}]
            changed += [{**{i: rng.choice(g) for i, g in grids.items()}, **{i: rng.choice(o) for i, o in options.items()}}
                        for _ in range(2)]
            out += [{"scene": scene.id, "variant": variant.id, "values": values} for values in [{}, *changed]]
    return out


def test_the_page_and_the_server_build_the_same_request_body_from_every_scene(browser_page):
    page = browser_page
    page.goto("/scenes/transfer-functions?lang=en")
    page.locator(".main-svg").first.wait_for(state="visible")        # the page has drawn: its modules ran
    every = cases()
    pages = page.evaluate(BUILD_REQUESTS_JS, {
        "scenes": {s.id: json.loads(s.model_dump_json()) for s in scenes().values()}, "cases": every})
    differ = []
    for case, built in zip(every, pages, strict=True):
        scene = scenes()[case["scene"]]
        variant = next(v for v in scene.variants if v.id == case["variant"])
        assert built["values"] == defaults(variant) | case["values"], case      # the page took every value
        if built["body"] != scene_request(scene, variant, case["values"]):
            differ.append(case)
    assert differ == []
    assert len(every) == sum(len(s.variants) * (1 if s.kind == "project" else 5) for s in scenes().values())
    assert page.problems == []


BUILD_FAMILY_REQUESTS_JS = """async ({ scenes, cases }) => {
  const entry = document.querySelector('script[type="module"][src*="_scene.js"]').src;
  const { SceneModel } = await import(new URL("../kinematics/model/scene_model.js", entry));
  const { DynamicsModel } = await import(new URL("../dynamics/model/dynamics_model.js", entry));
  const { previewFields } = await import(new URL("../common/model/family_fields.js", entry));
  return cases.map(({ scene, variant, slider }) => {        // family_preview.js: the question of a grab
    const data = scenes[scene];
    const model = new (data.kind === "kinematics" ? SceneModel : DynamicsModel)(data, { variant, values: {} });
    const grabbed = model.variant.sliders.find((s) => s.id === slider);
    const fields = previewFields(model.scene ?? data, model.variant);
    return JSON.stringify({ endpoint: data.endpoint, request: model.request(), vary: model.familyVary(grabbed),
      min: grabbed.min, max: grabbed.max, log: grabbed.log, ...(fields.length ? { fields } : {}), packed: true });
  });
}"""


def _variant_and_slider(case: dict):
    variant = next(v for v in scenes()[case["scene"]].variants if v.id == case["variant"])
    return variant, next(s for s in variant.sliders if s.id == case["slider"])


def test_the_page_and_the_server_build_the_same_family_request_for_every_slider(browser_page):
    """server/lessons/family_requests.py (with which the server computes the families of the scenes' default
    states before a class grabs them) builds the body the page sends on a grab, for every slider of every variant
    at the defaults: the same request, varied paths and factors, range and preview fields; and the response
    cache files both under one key, the page's JSON text (JSON.stringify writes 2, not 2.0) and the twin's."""
    import orjson

    from server.api.routers.family import FamilyRequest
    from server.families.bodies import shared
    from server.lessons.family_requests import family_request
    from server.runtime.response_cache import validated_body

    page = browser_page
    page.goto("/scenes/transfer-functions?lang=en")
    page.locator(".main-svg").first.wait_for(state="visible")
    every = [{"scene": scene.id, "variant": variant.id, "slider": slider.id}
             for scene in scenes().values() if scene.kind != "project"
             for variant in scene.variants if not variant.address for slider in variant.sliders]
    built = page.evaluate(BUILD_FAMILY_REQUESTS_JS, {
        "scenes": {s.id: json.loads(s.model_dump_json()) for s in scenes().values()}, "cases": every})
    differ, keyed_apart = [], []
    for case, text in zip(every, built, strict=True):
        scene = scenes()[case["scene"]]
        variant = next(v for v in scene.variants if v.id == case["variant"])
        slider = next(s for s in variant.sliders if s.id == case["slider"])
        twin = family_request(scene, variant, slider)
        if json.loads(text) != twin:
            differ.append(case)
        key = validated_body(text.encode(), FamilyRequest, shared)
        if key is None or key != validated_body(orjson.dumps(twin), FamilyRequest, shared):
            keyed_apart.append(case)
    assert differ == [] and keyed_apart == []
    assert len(every) > 150 and sum('"fields"' in text for text in built) > 100, (len(every), built[:1])
    assert any('.0,' in orjson.dumps(family_request(scenes()[c["scene"]], *_variant_and_slider(c))).decode()
               and '.0,' not in text for c, text in zip(every, built))     # the spellings differ, the keys do not
    assert page.problems == []
