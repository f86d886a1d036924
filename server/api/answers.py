"""An assignment's correct answers, computed on the server from the student's variant, and what the
student's page may show without giving them away."""
from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

from ..classroom.variants import Plan, SpecError
from ..core.numerics import parabola_extremum
from .endpoints import compute
from ..lessons.scenes import Question, Scene, Slider, Toggle, scenes
from ..lessons.requests import path_value, scene_request

ANSWER_POINTS_PER_TURN = 3600    # kinematics answers: 0.1° grid, extremum refined by a parabola (error ~h³)


def question(scene: Scene, question_id: str) -> Question:
    return next(q for q in scene.questions if q.id == question_id)


def _extremum(values: list, largest: bool) -> float:
    """Largest (smallest) value of a sampled function, refined by the parabola through the best node and
    its neighbours: the error falls from O(h²) of the nodes to O(h³). A function over one cycle (first
    and last nodes equal) wraps around; a time history's end node is taken as it is."""
    y = np.asarray([np.nan if v is None else v for v in values], float)
    if not np.all(np.isfinite(y)):
        raise SpecError("questions", "the quantity is undefined somewhere on the cycle (a singular position)")
    periodic = y.size > 2 and np.isclose(y[0], y[-1], rtol=1e-9, atol=1e-12)
    return parabola_extremum(y, 1 if largest else -1, periodic)


@lru_cache(maxsize=4096)
def _answer(scene_id: str, variant_id: str, values: tuple, question_id: str) -> float:
    scene = scenes()[scene_id]
    variant = next(v for v in scene.variants if v.id == variant_id)
    asked = question(scene, question_id)
    points = ANSWER_POINTS_PER_TURN if scene.kind == "kinematics" else None
    body = scene_request(scene, variant, dict(values), outputs=list(asked.outputs),
                         **({"points_per_turn": points} if points else {}))
    found = path_value(compute(scene.endpoint, body), asked.path)
    value = found if asked.reduce == "value" else _extremum(found, asked.reduce == "max")
    if not isinstance(value, (int, float)) or not math.isfinite(value):
        raise SpecError("questions", f"'{question_id}' has no value for these parameters")
    return float(value)


def correct_answer(plan: Plan, values: dict, question_id: str) -> float:
    return _answer(plan.scene.id, plan.variant.id, tuple(sorted(values.items())), question_id)


def tolerance(plan: Plan, question_id: str) -> float:
    pick = next(q for q in plan.spec.questions if q.id == question_id)
    return pick.tolerance if pick.tolerance is not None else question(plan.scene, question_id).tolerance


def is_right(answer: float, correct: float, relative: float) -> bool:
    """|answer − correct| ≤ tolerance × |correct| (an exact zero needs an exact zero)."""
    return abs(answer - correct) <= relative * abs(correct)


def hidden_outputs(plan: Plan) -> set[str]:
    return {name for pick in plan.spec.questions for name in question(plan.scene, pick.id).hides}


def student_scene(plan: Plan, values: dict) -> Scene:
    """The scene as the student sees it: only the assignment's variant, its sliders at the student's values
    (locked, or movable within the instructor's range), its toggles fixed, no presets or questions, and
    without every output and panel that would show an answer."""
    scene, variant, hidden = plan.scene, plan.variant, hidden_outputs(plan)
    limits = plan.limits()

    def slider(s: Slider) -> Slider:
        value = values[s.id]
        span = limits[s.id]
        if span is None:
            return s.model_copy(update={"default": value, "locked": True})
        return s.model_copy(update={"default": value, "min": min(span[0], value), "max": max(span[1], value)})

    def toggle(t: Toggle) -> Toggle:
        i = t.options.index(values[t.id])
        return t.model_copy(update={"options": [t.options[i]], "option_labels": [t.option_labels[i]],
                                    "default": t.options[i]})

    def shows_answer(panel_id: str) -> bool:
        panel = scene.panels.get(panel_id, {})
        return bool(hidden & set(panel.get("outputs", []) + panel.get("needs", [])))

    panels = [p for p in variant.panels if not shows_answer(p)]
    student_variant = variant.model_copy(update={
        "sliders": [slider(s) for s in variant.sliders], "toggles": [toggle(t) for t in variant.toggles],
        "panels": panels, "overlay": None, "overlay_values": []})
    return scene.model_copy(update={
        "variants": [student_variant], "presets": [], "questions": [],
        "outputs": [o for o in scene.outputs if o not in hidden],
        "panels": {k: v for k, v in scene.panels.items() if k in panels}})
