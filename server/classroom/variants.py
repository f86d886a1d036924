"""Per-student variants: the values of an assignment's sliders for one student.

The variant number is derived from the assignment and the student's name alone,
``number = SHA-256(assignment id, normalised name) mod (number of variants)``, so the same student always
gets the same variant, on any server, without storing anything first (a course project's variant whose crank
cannot turn fully is never handed out: the next number that turns is, turning.py). The number is read as a
mixed-radix numeral: one digit per varied slider, each digit an index into that slider's values.
"""
from __future__ import annotations

import hashlib
import math

import numpy as np
from dataclasses import dataclass, field

from ..lessons.scenes import Question, Scene, Variant
from ..lessons.requests import scene_variant, slider_values
from . import turning
from ..lessons.expression import ExpressionError, parse
from .spec import AssignmentSpec, QuestionPick, SpecError

MAX_CHOICES = 10_000      # values of one varied slider


@dataclass
class Plan:
    """An assignment resolved against its scene: fixed values, and the values each varied slider takes."""

    scene: Scene
    variant: Variant
    spec: AssignmentSpec
    fixed: dict[str, float | str] = field(default_factory=dict)
    varied: dict[str, list[float]] = field(default_factory=dict)

    @property
    def count(self) -> int:
        return math.prod(len(values) for values in self.varied.values())

    def number_for(self, assignment_id: str, key: str) -> int:
        digest = hashlib.sha256(f"{assignment_id}\n{key}".encode()).digest()
        return turning.handed_out(self, int.from_bytes(digest, "big") % self.count)

    def values(self, number: int) -> dict[str, float | str]:
        values = dict(self.fixed)
        for slider_id, choices in self.varied.items():
            number, digit = divmod(number, len(choices))
            values[slider_id] = choices[digit]
        return values

    def limits(self) -> dict[str, tuple[float, float] | None]:
        """How far the student may move each slider (None: locked)."""
        rules = self.spec.sliders
        return {s.id: (rules[s.id].free.min, rules[s.id].free.max) if s.id in rules and rules[s.id].free else None
                for s in self.variant.sliders}


def plan(spec: AssignmentSpec, scenes: dict[str, Scene]) -> Plan:
    """Check spec against its scene and resolve it; SpecError names the first field that is wrong."""
    scene = scenes.get(spec.scene)
    if scene is None:
        raise SpecError("scene", f"no scene '{spec.scene}'")
    variant = next((v for v in scene.variants if v.id == spec.variant), None)
    if variant is None:
        raise SpecError("variant", f"scene '{scene.id}' has no variant '{spec.variant}'")
    if variant.address is not None:
        if spec.mechanism is None:
            raise SpecError("variant", f"variant '{variant.id}' computes the reader's own mechanism from the page "
                                       "address; an assignment needs a mechanism of the scene, or that mechanism "
                                       "sent as mechanism {m, d}")
        try:
            variant = scene_variant(scene.id, variant.id, spec.mechanism.documents())
        except KeyError as missing:
            raise SpecError("mechanism", f"the mechanism has no {missing.args[0]!r}") from None
        except ValueError as error:
            raise SpecError("mechanism", f"its sliders cannot be made from it: {error}") from None
    elif spec.mechanism is not None:
        raise SpecError("mechanism", f"variant '{variant.id}' has a mechanism of its own; send none")
    sliders = {s.id: s for s in variant.sliders}
    for name in spec.sliders:
        if name not in sliders:
            raise SpecError(f"sliders.{name}", f"variant '{variant.id}' has no slider '{name}'")
    result = Plan(scene, variant, spec)
    for slider in variant.sliders:
        rule = spec.sliders.get(slider.id)
        grid = slider_values(slider)
        where = f"sliders.{slider.id}"
        if rule is not None and rule.vary is not None:
            if rule.vary.min < slider.min - 1e-12 or rule.vary.max > slider.max + 1e-12:
                raise SpecError(f"{where}.vary", f"the range must lie within {slider.min:g} … {slider.max:g}")
            choices = [g for g in grid if rule.vary.min - 1e-12 <= g <= rule.vary.max + 1e-12]
            if rule.step is not None and choices:           # the slider's values nearest min, min + step, …
                targets = np.arange(rule.vary.min, rule.vary.max + rule.step * 1e-9, rule.step)[:MAX_CHOICES]
                choices = sorted({min(choices, key=lambda g: abs(g - target)) for target in targets})
            if not choices:
                raise SpecError(f"{where}.vary", "the range holds no value the slider can take")
            result.varied[slider.id] = choices
        else:
            value = slider.default if rule is None or rule.value is None else rule.value
            if not slider.min <= value <= slider.max:
                raise SpecError(f"{where}.value", f"{value:g} is outside {slider.min:g} … {slider.max:g}")
            result.fixed[slider.id] = value
        if rule is not None and rule.free is not None and (
                rule.free.min < slider.min - 1e-12 or rule.free.max > slider.max + 1e-12):
            raise SpecError(f"{where}.free", f"the range must lie within {slider.min:g} … {slider.max:g}")
    toggles = {t.id: t for t in variant.toggles}
    for name, value in spec.toggles.items():
        if name not in toggles:
            raise SpecError(f"toggles.{name}", f"variant '{variant.id}' has no toggle '{name}'")
        if value not in toggles[name].options:
            raise SpecError(f"toggles.{name}", f"one of {toggles[name].options}")
    for toggle in variant.toggles:
        result.fixed[toggle.id] = spec.toggles.get(toggle.id, toggle.default)
    asked = {q.id: q for q in scene.questions if not q.variants or variant.id in q.variants}
    for i, pick in enumerate(spec.questions):
        if pick.id not in asked:
            raise SpecError(f"questions.{i}.id", f"not a question of variant '{variant.id}' "
                                                 f"(one of {sorted(asked) or 'none'})")
        _check_pick(asked[pick.id], pick, f"questions.{i}")
    return result


def _check_pick(question: Question, pick: QuestionPick, where: str) -> None:
    """An instructor's angle grid lies within the question's; an expression reads only its readouts."""
    if pick.angle is not None:
        own = question.angle
        if own is None:
            raise SpecError(f"{where}.angle", f"'{question.id}' does not ask for an angle of the student's choice")
        if pick.angle.min < own.min - 1e-9 or pick.angle.max > own.max + 1e-9:
            raise SpecError(f"{where}.angle", f"the angles must lie within {own.min:g}° … {own.max:g}°")
    if pick.expression is not None:
        if question.kind != "combination":
            raise SpecError(f"{where}.expression", f"'{question.id}' is not computed from readouts")
        try:
            parse(pick.expression, set(question.readouts))
        except ExpressionError as error:
            raise SpecError(f"{where}.expression", str(error)) from None
