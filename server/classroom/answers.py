"""An assignment's correct answers, computed on the server from the student's variant, and what the
student's page may show without giving them away.

The answers are the computing endpoints' answers to the requests the student's page would send
(server/lessons/requests.py). The endpoints, their request models and the serialiser live in server/api; the API
gives the classroom the one function it computes with (``use_endpoints``, when the app is made), and
assignment_answers hands the same function to the heavy process that computes a variant's answers.
"""
from __future__ import annotations

import math
import re
from collections.abc import Callable
from functools import lru_cache

import numpy as np

from ..lessons.expression import ExpressionError, evaluate, parse
from .variants import Plan, SpecError
from .visibility import shows_any
from ..core.answer import Answer
from ..core.numerics import parabola_extremum
from ..lessons.scenes import AngleGrid, Question, Readout, Scene, Slider, Toggle, scenes
from ..lessons.dotted_paths import path_value
from ..lessons.requests import scene_request, scene_variant

ANSWER_POINTS_PER_TURN = 3600    # kinematics answers: 0.1° grid, extremum refined by a parabola (error ~h³)
POSITION_INDEX = re.compile(r"\{([A-Za-z0-9_.]+)\}")     # "kinematics.{positions.chosen}.points.E.v.value"


# What the classroom computes with: POST /api/v1/<endpoint> in-process, the body validated as the route validates
# it (pydantic's ValidationError; the core's GeometryError where the route answers 422), the answer's payload as a
# client parses it (full precision, null for every non-finite number) and whether a bound cut it short.
Endpoints = Callable[[str, dict], Answer]


class AnswerCutShort(Exception):
    """The endpoint's answer was cut short by a work or time bound: not an answer to grade against (computing
    it again, at a quieter moment, may finish it)."""


class NoEndpoints(RuntimeError):
    """The classroom was asked for an answer before it was given the endpoints to compute it with."""


def _no_endpoints(endpoint: str, body: dict) -> Answer:
    raise NoEndpoints(f"no endpoints to compute the {endpoint} answer with: server/api gives them to the classroom "
                      f"(answers.use_endpoints) when it makes the app")


compute_answer: Endpoints = _no_endpoints


def use_endpoints(endpoints: Endpoints) -> None:
    """Compute every answer from now on with `endpoints` (the API's, given when the app is made; a heavy process
    is handed the same function with the work it runs)."""
    global compute_answer
    compute_answer = endpoints


def compute(endpoint: str, body: dict) -> dict:
    """The endpoint's whole answer as a client parses it (full precision, null for non-finite numbers);
    AnswerCutShort when a bound cut it short."""
    answer = compute_answer(endpoint, body)
    if answer.partial:
        raise AnswerCutShort(f"the {endpoint} answer was cut short by its work bound")
    return answer.payload


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


@lru_cache(maxsize=2)
def _project(scene_id: str, variant_id: str, documents: str, values: tuple) -> dict:
    """A course-project scene's whole answer for the variant's values: computed once for all its questions
    (a few hundred ms; every question reads its own path of it)."""
    scene = scenes()[scene_id]
    variant = scene_variant(scene_id, variant_id, documents)
    return compute(scene.endpoint, scene_request(scene, variant, dict(values)))


def project_path(answer: dict, path: str) -> str:
    """A path with ``{dotted path}`` segments, each the position number found there in the answer, as the index
    of that position's row ("kinematics.{positions.chosen}" is the row of the chosen position)."""
    return POSITION_INDEX.sub(lambda found: str(int(path_value(answer, found.group(1))) - 1), path)


@lru_cache(maxsize=4096)
def _readout(scene_id: str, variant_id: str, documents: str, values: tuple, readout: Readout,
             angles: tuple | None = None):
    """One readout for the variant's values (``documents``: the JSON of an own mechanism's {m, d}, else ""): a
    number, or (``angles`` in degrees given) its values there."""
    scene = scenes()[scene_id]
    variant = scene_variant(scene_id, variant_id, documents)
    if scene.kind == "project":
        answer = _project(scene_id, variant_id, documents, values)
        found = path_value(answer, project_path(answer, readout.path))
        return found if readout.reduce == "value" else _extremum(found, readout.reduce == "max")
    points = ANSWER_POINTS_PER_TURN if scene.kind == "kinematics" else None
    body = scene_request(scene, variant, dict(values), outputs=list(readout.outputs),
                         **({"points_per_turn": points} if points else {}))
    if angles is not None:                  # the kinematics endpoint evaluates at exactly these angles
        body.pop("n")
        body["phi"] = [math.radians(a) for a in angles]
        return path_value(compute(scene.endpoint, body), readout.path)
    found = path_value(compute(scene.endpoint, body), readout.path)
    return found if readout.reduce == "value" else _extremum(found, readout.reduce == "max")


def _finite(value, question_id: str) -> float:
    if not isinstance(value, (int, float)) or not math.isfinite(value):
        raise SpecError("questions", f"'{question_id}' has no value for these parameters")
    return float(value)


def angle_grid(plan: Plan, question_id: str) -> AngleGrid | None:
    """The angles a student may choose for an at_angle question: the instructor's, else the question's."""
    pick = next((q for q in plan.spec.questions if q.id == question_id), None)
    return pick.angle if pick is not None and pick.angle is not None else question(plan.scene, question_id).angle


def expression_text(plan: Plan, question_id: str) -> str:
    pick = next((q for q in plan.spec.questions if q.id == question_id), None)
    own = question(plan.scene, question_id).expression
    return pick.expression if pick is not None and pick.expression is not None else own


def _grid_angles(grid: AngleGrid) -> tuple[float, ...]:
    count = round((grid.max - grid.min) / grid.step)
    return tuple(round(grid.min + k * grid.step, 9) for k in range(count + 1))


def variant_answer(plan: Plan, values: dict, question_id: str) -> float | dict[str, float]:
    """What one variant's answer is, as a per-variant cache may keep it (JSON): the number, or for an at_angle
    question the value at every angle offered, keyed by repr(angle in degrees). SpecError when it has none."""
    asked, key = question(plan.scene, question_id), tuple(sorted(values.items()))
    at = (plan.scene.id, plan.variant.id, "" if plan.spec.mechanism is None else plan.spec.mechanism.documents(), key)
    if asked.kind == "at_angle":
        angles = _grid_angles(angle_grid(plan, question_id))
        found = _readout(*at, asked.readout_list()[0], angles)
        return {repr(a): _finite(value, f"{question_id} at φ = {a:g}°") for a, value in zip(angles, found)}
    if asked.kind == "combination":
        readouts = {name: _finite(_readout(*at, readout), question_id) for name, readout in asked.readouts.items()}
        try:
            return evaluate(parse(expression_text(plan, question_id), set(readouts)), readouts)
        except ExpressionError as error:
            raise SpecError("questions", f"'{question_id}' has no value for these parameters: {error}") from None
    return _finite(_readout(*at, asked.readout_list()[0]), question_id)


def answer_from(plan: Plan, question_id: str, kept: float | dict[str, float], angle: float | None = None) -> float:
    """The correct value from what variant_answer gave: for an at_angle question the value at the student's
    `angle` (degrees), which must be on the question's grid (SpecError on the field ``angle`` otherwise)."""
    if not isinstance(kept, dict):
        return float(kept)
    grid = angle_grid(plan, question_id)
    if angle is None:
        raise SpecError("angle", "this question needs the crank angle φ you chose, in degrees")
    if not grid.holds(angle):
        raise SpecError("angle", f"choose φ from {grid.min:g}° to {grid.max:g}° in steps of {grid.step:g}°")
    return float(kept[repr(round(grid.min + round((angle - grid.min) / grid.step) * grid.step, 9))])


def correct_answer(plan: Plan, values: dict, question_id: str, angle: float | None = None) -> float:
    """The exact answer for the variant's values (an at_angle question: at the student's `angle`)."""
    return answer_from(plan, question_id, variant_answer(plan, values, question_id), angle)


def check_answerable(plan: Plan, values: dict, question_id: str) -> None:
    """SpecError unless the question has an answer for these values (an at_angle one at every angle offered)."""
    variant_answer(plan, values, question_id)


def check(plan: Plan, values: dict, question_id: str, answer: float, angle: float | None = None
          ) -> tuple[float, bool]:
    """The correct value the answer is checked against, and whether it is right."""
    correct = correct_answer(plan, values, question_id, angle)
    return correct, is_right(answer, correct, tolerance(plan, question_id))


def tolerance(plan: Plan, question_id: str) -> float:
    pick = next(q for q in plan.spec.questions if q.id == question_id)
    return pick.tolerance if pick.tolerance is not None else question(plan.scene, question_id).tolerance


def is_right(answer: float, correct: float, relative: float) -> bool:
    """|answer − correct| ≤ tolerance × |correct| (an exact zero needs an exact zero)."""
    return abs(answer - correct) <= relative * abs(correct)


def hidden_outputs(plan: Plan, unlocked: frozenset[str] = frozenset()) -> set[str]:
    """Outputs the student's page must not ask for: those of every question, except a prediction's once it
    is closed (``unlocked``)."""
    return {name for pick in plan.spec.questions if pick.id not in unlocked
            for name in question(plan.scene, pick.id).hides}


def locked_panels(plan: Plan, question_id: str) -> list[str]:
    """The variant's panels a prediction keeps locked on the student's page until it is closed."""
    asked = question(plan.scene, question_id)
    if asked.kind != "prediction":
        return []
    return [p for p in plan.variant.panels if shows_any(plan.scene.panels.get(p, {}), set(asked.hides))]


def question_kind(plan: Plan, question_id: str) -> dict:
    """What the student's page needs to ask a question: its kind, the angles offered, the panels it locks."""
    grid = angle_grid(plan, question_id)
    return {"kind": question(plan.scene, question_id).kind,
            "angle": None if grid is None else grid.model_dump(),
            "locks": locked_panels(plan, question_id)}


def unlocked_predictions(plan: Plan, submissions: list) -> frozenset[str]:
    """Predictions a student has closed (right, or no attempt left): their panels open on the student's page.
    `submissions` are the student's own (the store's records with ``question`` and ``correct``)."""
    closed = set()
    for pick in plan.spec.questions:
        if question(plan.scene, pick.id).kind != "prediction":
            continue
        mine = [s for s in submissions if s.question == pick.id]
        if any(s.correct for s in mine) or len(mine) >= plan.spec.attempts:
            closed.add(pick.id)
    return frozenset(closed)


def student_scene(plan: Plan, values: dict, unlocked: frozenset[str] = frozenset()) -> Scene:
    """The scene as the student sees it: only the assignment's variant, its sliders at the student's values
    (locked, or movable within the instructor's range), its toggles fixed, no presets or questions, and
    without every output and panel that would show an answer (a prediction's open once it is `unlocked`)."""
    scene, variant, hidden = plan.scene, plan.variant, hidden_outputs(plan, unlocked)
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

    panels = [p for p in variant.panels if not shows_any(scene.panels.get(p, {}), hidden)]
    student_variant = variant.model_copy(update={
        "sliders": [slider(s) for s in variant.sliders], "toggles": [toggle(t) for t in variant.toggles],
        "panels": panels, "overlay": None, "overlay_values": []})
    return scene.model_copy(update={
        "variants": [student_variant], "presets": [], "questions": [],
        "outputs": [o for o in scene.outputs if o not in hidden],
        "panels": {k: v for k, v in scene.panels.items() if k in panels}})
