"""The request a scene page sends for given slider and toggle values: the Python twin of the browser's
scene models (web/static/js/kinematics/model/scene_model.js, dynamics_model.js), used to compute an assignment's answers
on the server and by the classroom load test to send what the pages send.

Kinematics scenes: ``params = fixed``, each toggle sets ``params[toggle.param]``, each slider sets
``params[slider.param] = value × params[slider.scale]`` (λ = l₂/l₁ sets l₂ in metres).
Dynamics scenes: the variant's ``request`` with the mechanism; toggles at their dotted paths; each slider
puts ``value × to_si × (value at slider.scale)`` at ``slider.param`` and at every ``slider.also`` path.
Course-project scenes: the same request, without the mechanism's name and the outputs (one whole answer).
"""
from __future__ import annotations

import copy
import json
import math
from functools import lru_cache

from .dotted_paths import path_value, set_path
from .scene_files import addressed
from .scenes import Scene, Slider, Variant, scenes

TURN = 2 * math.pi
POINTS_PER_TURN = 360          # the kinematics page's grid: 1° of crank angle
LOG_POSITIONS = 1000           # web/static/js/common/model/slider_scale.js
LOG_DIGITS = 3


def slider_values(slider: Slider) -> list[float]:
    """Every value the slider can express: min + k·step, or the log slider's 1001 rounded positions."""
    if slider.log:
        low, high = math.log10(slider.min), math.log10(slider.max)
        values = (float(f"{10 ** (low + (high - low) * p / LOG_POSITIONS):.{LOG_DIGITS}g}")
                  for p in range(LOG_POSITIONS + 1))
        return sorted({min(slider.max, max(slider.min, v)) for v in values})
    count = int(math.floor((slider.max - slider.min) / slider.step + 1e-9))
    return [round(slider.min + k * slider.step, 12) for k in range(count + 1)]


def defaults(variant: Variant) -> dict[str, float | str]:
    return {c.id: c.default for c in [*variant.sliders, *variant.toggles]}


def kinematics_params(variant: Variant, values: dict) -> dict:
    params = dict(variant.fixed)
    for toggle in variant.toggles:
        params[toggle.param] = values[toggle.id]
    for slider in variant.sliders:
        params[slider.param] = values[slider.id] * (params[slider.scale] if slider.scale else 1)
    return params


def dynamics_body(variant: Variant, values: dict) -> dict:
    body = copy.deepcopy(variant.request) | {"mechanism": variant.mechanism}
    for toggle in variant.toggles:
        set_path(body, toggle.param, values[toggle.id])
    for slider in variant.sliders:
        scale = path_value(body, slider.scale) if slider.scale else 1
        for path in (slider.param, *slider.also):
            set_path(body, path, values[slider.id] * slider.to_si * scale)
    return body


def project_body(variant: Variant, values: dict) -> dict:
    """A course-project scene's request (POST /api/v1/course-project): the variant's request with the sliders
    set as in a dynamics scene; the whole project is one answer, so there is no mechanism name and no outputs."""
    body = dynamics_body(variant, values)
    body.pop("mechanism")
    return body


def address_variant(variant: Variant, documents: dict) -> Variant:
    """The variant as a page whose address holds the documents {"m": linkage, "d": dynamics} shows it (a variant
    without ``address`` is itself); KeyError names a path the documents lack."""
    if variant.address is None:
        return variant
    return Variant.model_validate(addressed(variant.model_dump(), documents))


@lru_cache(maxsize=64)
def scene_variant(scene_id: str, variant_id: str, documents: str = "") -> Variant:
    """A scene's variant by id; one that takes its mechanism from the address resolved with `documents` (the JSON
    text of {"m", "d"}: an assignment of an instructor's own mechanism), else as the scene file resolves it."""
    variant = next(v for v in scenes()[scene_id].variants if v.id == variant_id)
    return address_variant(variant, json.loads(documents)) if documents and variant.address else variant


def page_outputs(scene: Scene, variant: Variant) -> list[str]:
    """What the page asks for: the scene's outputs and those of the variant's panels (kinematics), or
    what the variant's panels need (dynamics)."""
    if scene.kind == "kinematics":
        names = list(scene.outputs)
        for panel in variant.panels:
            names += scene.panels[panel].get("outputs", [])
    else:
        names = [need for panel in variant.panels for need in scene.panels.get(panel, {}).get("needs", [])]
    return list(dict.fromkeys(names))


def scene_request(scene: Scene, variant: Variant, values: dict | None = None,
                  outputs: list[str] | None = None, points_per_turn: int = POINTS_PER_TURN) -> dict:
    """The body the page posts to /api/v1/<scene.endpoint> (values default to the sliders' defaults)."""
    values = defaults(variant) | (values or {})
    outputs = page_outputs(scene, variant) if outputs is None else outputs
    if scene.kind == "kinematics":
        return {"mechanism": variant.mechanism, "params": kinematics_params(variant, values),
                "n": points_per_turn + 1, "outputs": outputs}
    if scene.kind == "project":
        return project_body(variant, values)
    return dynamics_body(variant, values) | {"outputs": outputs}
