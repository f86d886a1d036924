"""What an instructor fixes in an assignment: the scene and its variant, each slider's value or the range
its per-student values are drawn from, how far a student may move it, the questions, attempts, deadline."""
from __future__ import annotations

import json
from datetime import datetime, timezone

from pydantic import BaseModel, ConfigDict, Field, field_validator, model_validator

from ..lessons.scenes import AngleGrid

MAX_QUESTIONS = 10
MAX_ATTEMPTS = 10
MAX_MECHANISM_CHARS = 100_000       # an editor's mechanism with its design data is a few kB
DESIGN_DEFAULTS = {"inertias": {"J1": 0.0, "J_rotor": 0.0, "gear_ratio": 1.0},
                   "flywheel": {"omega_mean": 10.0, "delta": 0.05}}     # the course-project page's (design.js)


class SpecError(ValueError):
    """An assignment that cannot be made as specified: the field (dotted path) and the reason."""

    def __init__(self, field: str, reason: str):
        super().__init__(f"{field}: {reason}")
        self.field, self.reason = field, reason


class Span(BaseModel):
    model_config = ConfigDict(extra="forbid")
    min: float = Field(allow_inf_nan=False)
    max: float = Field(allow_inf_nan=False)

    @model_validator(mode="after")
    def ordered(self):
        if self.min > self.max:
            raise ValueError("min is above max")
        return self


class SliderRule(BaseModel):
    """One slider: a fixed ``value``, or per-student values from ``vary`` (every ``step``-th value the
    slider can express in that range); ``free`` lets the student move it within a range to explore
    (the answers are always those of the student's own value), none locks it."""

    model_config = ConfigDict(extra="forbid")
    value: float | None = Field(None, allow_inf_nan=False, description="fixed value (default: the slider's default)")
    vary: Span | None = Field(None, description="per-student values from this range")
    step: float | None = Field(None, gt=0, allow_inf_nan=False, description="spacing of the per-student values "
                                                                            "(default: the slider's step)")
    free: Span | None = Field(None, description="the student may move the slider within this range; none: locked")


class QuestionPick(BaseModel):
    model_config = ConfigDict(extra="forbid")
    id: str = Field(max_length=40)
    tolerance: float | None = Field(None, gt=0, lt=1, description="relative tolerance (default: the question's)")
    angle: AngleGrid | None = Field(None, description="a question at a chosen angle: the angles (degrees) the "
                                                      "student may choose, within the question's own range "
                                                      "(default: the question's)")
    expression: str | None = Field(None, max_length=200, description="a combination question: the quantity as "
                                                                     "an expression over the question's named "
                                                                     "readouts with + − × ÷ and parentheses "
                                                                     "(default: the question's)")


class OwnMechanism(BaseModel):
    """A mechanism of the instructor's (made in the editor) for a variant that takes it from the page address:
    the address's documents, m the linkage and d its masses, loads, inertias and flywheel data."""

    model_config = ConfigDict(extra="forbid")
    m: dict = Field(description="the linkage, as the editor writes it into the address (m)")
    d: dict = Field(description="its masses and loads, inertias and flywheel data (the address's d)")

    @model_validator(mode="after")
    def bounded(self):
        if len(json.dumps([self.m, self.d])) > MAX_MECHANISM_CHARS:
            raise ValueError(f"longer than {MAX_MECHANISM_CHARS} characters of JSON")
        return self

    def documents(self) -> str:
        """The documents {m, d} as JSON text (d completed with the course-project page's defaults where it has no
        inertias or flywheel part), the key of the variant's computations."""
        d = {key: DESIGN_DEFAULTS[key] | self.d.get(key, {}) if key in DESIGN_DEFAULTS else value
             for key, value in (DESIGN_DEFAULTS | self.d).items()}
        return json.dumps({"m": self.m, "d": d}, sort_keys=True, separators=(",", ":"))


class AssignmentSpec(BaseModel):
    """POST /api/v1/assignments: everything the students' link will show and check."""

    model_config = ConfigDict(extra="forbid")
    scene: str = Field(max_length=60, description="scene id, e.g. flywheel")
    variant: str = Field(max_length=60, description="the scene's variant (mechanism set-up)")
    mechanism: OwnMechanism | None = Field(None, description="a variant of one's own mechanism (course project: "
                                                             "variant own): the mechanism made in the editor")
    title: str = Field("", max_length=200)
    lang: str = Field("ru", pattern="^(ru|uk|en)$", description="language of the links")
    sliders: dict[str, SliderRule] = Field(default_factory=dict, max_length=20,
                                           description="by slider id; a slider not named is fixed at its default")
    toggles: dict[str, float | str] = Field(default_factory=dict, max_length=10, description="fixed toggle values")
    questions: list[QuestionPick] = Field(min_length=1, max_length=MAX_QUESTIONS)
    attempts: int = Field(3, ge=1, le=MAX_ATTEMPTS, description="attempts per question")
    reveal_answers: bool = Field(False, description="show the correct value once a question is closed (right, or "
                                                    "no attempt left); off by default: a student could otherwise "
                                                    "spend a made-up name's attempts on a variant like their own")
    deadline: datetime | None = Field(None, description="ISO 8601; without a zone it is UTC")

    @field_validator("deadline")
    @classmethod
    def in_utc(cls, value: datetime | None) -> datetime | None:
        if value is not None and value.tzinfo is None:
            value = value.replace(tzinfo=timezone.utc)
        return value

    @field_validator("questions")
    @classmethod
    def distinct(cls, value: list[QuestionPick]) -> list[QuestionPick]:
        if len({q.id for q in value}) != len(value):
            raise ValueError("a question is picked twice")
        return value
