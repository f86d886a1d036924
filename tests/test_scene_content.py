"""Every scene in content/ is complete in three languages, and its default set-up computes without warnings of failure."""
import copy
import json
import math
import re
from pathlib import Path

import pytest
from fastapi.testclient import TestClient

from server.api.app import app
from server.lessons.requests import path_value as get_path, set_path
from server.lessons.scenes import LANGUAGES, interface_texts, scenes

client = TestClient(app)
DYNAMIC = [(s.id, v.id) for s in scenes().values() if s.kind == "dynamics" for v in s.variants]


def _has(data: dict, path: str) -> bool:
    try:
        get_path(data, path)
    except KeyError:
        return False
    return True


def default_body(scene, variant) -> dict:
    """What the page sends before the student touches anything (mirrors web/static/js)."""
    body = copy.deepcopy(variant.request) | {"mechanism": variant.mechanism}
    for toggle in variant.toggles:
        set_path(body, toggle.param, toggle.default)
    for slider in variant.sliders:
        value = slider.default * slider.to_si * (get_path(body, slider.scale) if slider.scale else 1.0)
        for path in [slider.param, *slider.also]:
            set_path(body, path, value)
    needs = sorted({need for name in variant.panels for need in scene.panels[name].get("needs", [])})
    return body | {"outputs": needs}


def strict_json(text: str):
    return json.loads(text, parse_constant=lambda name: pytest.fail(f"{name} in the response"))


@pytest.mark.parametrize("scene_id, variant_id", DYNAMIC)
def test_dynamics_scene_defaults_compute(scene_id, variant_id):
    scene = scenes()[scene_id]
    variant = next(v for v in scene.variants if v.id == variant_id)
    response = client.post(f"/api/v1/{scene.endpoint}", json=default_body(scene, variant))
    assert response.status_code == 200, response.text
    data = strict_json(response.text)
    if scene.endpoint == "motion":
        assert data["numerics"]["message"] == "" and data["delta"] > 0     # a steady cycle was found
        assert data["numerics"]["error_estimate"] <= data["numerics"]["rtol"]


@pytest.mark.parametrize("scene_id, variant_id", DYNAMIC)
def test_every_panel_path_of_a_scene_exists_in_its_answer(scene_id, variant_id):
    scene = scenes()[scene_id]
    variant = next(v for v in scene.variants if v.id == variant_id)
    data = client.post(f"/api/v1/{scene.endpoint}", json=default_body(scene, variant)).json()
    for name in variant.panels:
        panel = scene.panels[name]
        paths = [s[key] for s in panel.get("series", []) for key in ("y", "theta", "r") if key in s]
        paths += [item["path"] for item in panel.get("items", [])]
        paths += [panel[key] for key in ("x", "y", "path", "diagram") if key in panel]
        if panel["kind"] == "numerics":       # shows whichever of its paths the variant computes
            assert any(_has(data, path) for path in panel["paths"])
            if len(panel["paths"]) > 1:       # a column per computation, headed by its name in three languages
                assert len(panel["columns"]) == len(panel["paths"]), name
                assert all(column.get(lang) for column in panel["columns"] for lang in LANGUAGES), name
        for path in paths:
            if path.startswith("inertia.parts.link2_rotation") and variant.mechanism == "sine":
                continue          # the sine mechanism's block does not rotate
            get_path(data, path)


def test_every_scene_and_variant_speaks_three_languages():
    for scene in scenes().values():
        texts = [scene.title, scene.summary, scene.text, scene.source]
        texts += [panel.get("title") for panel in scene.panels.values() if panel.get("title")]
        for variant in scene.variants:
            texts += [variant.label, variant.text] + [s.label for s in variant.sliders] + [t.label for t in variant.toggles]
        for text in texts:
            assert all(text.get(lang) for lang in LANGUAGES), text


def test_interface_texts_have_the_same_keys_in_every_language():
    keys = {lang: set(interface_texts(lang)) for lang in LANGUAGES}
    assert keys["ru"] == keys["uk"] == keys["en"]


def test_slider_defaults_lie_in_their_ranges():
    for scene in scenes().values():
        for variant in scene.variants:
            for slider in variant.sliders:
                assert slider.min <= slider.default <= slider.max and math.isfinite(slider.step)


SOURCES = json.loads((Path(__file__).resolve().parents[1] / "content" / "sources.json").read_text(encoding="utf-8"))
REFERENCE = re.compile(r"\(L?\d+(?:\.\d+)?\*?\)|§ ?\d|(?:Figs?\.|рис\.|Tables?|табл\.) ?\d")


def test_every_scene_cites_its_sources_equations_in_each_language():
    """Each part of a scene's `source` (split at ';') that names a source (a key of content/sources.json or its
    ru/uk form) also gives an equation, section, figure or table number of it: "Eremyants (2.42*)",
    "Lecture 10 §10.9", "Table 4.3".  Exact text check: nothing to tolerate."""
    missing = []
    for scene in scenes().values():
        for lang in LANGUAGES:
            names = [name for record in SOURCES.values() for name in record["names"][lang]]
            parts = [part for part in scene.source[lang].split(";") if any(name in part for name in names)]
            missing += [f"{scene.id} [{lang}]: {part.strip()}" for part in parts if not REFERENCE.search(part)]
            if not parts:
                missing.append(f"{scene.id} [{lang}]: names no source")
    assert missing == []
