"""The family request a scene page sends when a student grabs a slider: the Python twin of the page's
(web/static/js/common/view/family_preview.js, its question; the fields of web/static/js/common/model/
family_fields.js; the slider's paths of the scene models' familyVary), as requests.scene_request is of the
page's own request. The server uses it to compute the families of every scene's default state before a class
asks (runtime/default_answers.py); tests/browser/test_request_body_parity.py runs the page's modules on every
scene and checks that both build the same body.

    {"endpoint", "request": scene_request(…), "vary": [{"path", "factor"}], "min", "max", "log",
     "fields": preview_fields(…) (left out when empty), "packed": true}

with request at each varied path = slider value × factor: kinematics ``params.<param>`` with the factor
``params[slider.scale]`` (1 without a scale); dynamics ``slider.param`` and every ``slider.also`` path with
``to_si × (value at slider.scale)``. The page sends the coarse stage first ("stage": "coarse"), then the body
as it is (the server's default stage, "full").
"""
from __future__ import annotations

from .dotted_paths import path_value
from .requests import scene_request
from .scenes import Scene, Slider, Variant

KINEMATICS_FRAME = ("mechanism", "params", "cycle", "phi", "outputs.special")


def _plot_fields(spec: dict) -> list[str]:
    if spec.get("outputs") is not None:          # an empty list too, as in JavaScript
        return [*KINEMATICS_FRAME, *(f"outputs.{name}" for name in spec["outputs"])]
    fields = [spec.get("x")]
    for series in spec.get("series") or []:
        fields += [series.get("y"), *([series["gaps"]] if series.get("gaps") else [])]
    if spec.get("series_each"):
        fields.append(spec["series_each"].get("path"))
    return fields


# what each panel kind draws in a preview: family_fields.js FIELDS_OF, entry for entry
FIELDS_OF = {
    "linkage": lambda spec: [*KINEMATICS_FRAME, "outputs.joints"],
    "plot": _plot_fields,
    "polar": lambda spec: [path for series in spec.get("series") or [] for path in (series.get("theta"), series.get("r"))],
    "free_body": lambda spec: ["phi", "points", "reactions", "applied", "friction", "friction_circles",
                               "balancing_moment"],
    "group_free_body": lambda spec: ["free_body"],
    "gear_train": lambda spec: ["phi", "points", "inv_AP", "omega_coupler", "epsilon_star", "epsilon_star2", "epsilon"],
    "wittenbauer": lambda spec: ["phi", spec.get("x"), spec.get("y"), spec.get("diagram")],
    "flywheel_drawing": lambda spec: [spec.get("disk")],
}


def preview_fields(scene: Scene, variant: Variant) -> list[str]:
    """The dotted paths the variant's panels draw while a slider is dragged, sorted, once each (the scene read
    as the page gets it: Scene.model_dump)."""
    panels = scene.model_dump(mode="json")["panels"]
    paths = set()
    for panel in variant.panels:
        spec = panels.get(panel)
        if spec and spec.get("kind") in FIELDS_OF:
            paths.update(path for path in FIELDS_OF[spec["kind"]](spec) if isinstance(path, str) and path)
    return sorted(paths)


def family_vary(scene: Scene, slider: Slider, request: dict) -> list[dict]:
    """[{"path", "factor"}]: request at each path = the slider's value × factor (the scene models' familyVary)."""
    if scene.kind == "kinematics":
        factor = request["params"][slider.scale] if slider.scale else 1
        return [{"path": f"params.{slider.param}", "factor": factor}]
    factor = slider.to_si * (path_value(request, slider.scale) if slider.scale else 1)
    return [{"path": path, "factor": factor} for path in (slider.param, *slider.also)]


def family_request(scene: Scene, variant: Variant, slider: Slider, values: dict | None = None) -> dict:
    """The body of POST /api/v1/family the page sends on grabbing `slider`, the controls at `values` (defaults
    where absent), without "stage"."""
    request = scene_request(scene, variant, values)
    fields = preview_fields(scene, variant)
    return {"endpoint": scene.endpoint, "request": request, "vary": family_vary(scene, slider, request),
            "min": slider.min, "max": slider.max, "log": slider.log, **({"fields": fields} if fields else {}),
            "packed": True}
