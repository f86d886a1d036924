"""The body of POST /api/v1/family a scene page sends when a student grabs a slider (the contract in the API
docs): the page's own request at the current values, and how the slider's value enters it.

Kinematics scenes set ``params[slider.param] = value × params[slider.scale]``: one path, ``params.<param>``,
with the factor ``params[slider.scale]`` (1 without a scale). Dynamics scenes put ``value × to_si × (value at
slider.scale)`` at ``slider.param`` and every ``slider.also`` path: each of them with that factor
(server/lessons/requests.py, formerly server/api/scene_requests.py). The range is the slider's, in shown
units: ``min``, ``max`` and ``log``.
"""
from __future__ import annotations

from trees import lessons


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
