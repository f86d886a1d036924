"""Request and response bodies of /api/v1/assignments."""
from __future__ import annotations

from pydantic import BaseModel, ConfigDict, Field

from ..classroom.variants import MAX_NAME


class AssignmentCreated(BaseModel):
    id: str
    student_url: str = Field(description="the link for the students")
    results_url: str = Field(description="the instructor's private link (keep it: the token is not stored)")
    results_token: str
    variants: int = Field(description="how many different variants the ranges give")


class QuestionInfo(BaseModel):
    id: str
    label: str
    unit: str
    tolerance: float = Field(description="relative")
    kind: str = Field("readout", description="readout, at_angle (submit the angle too), combination, prediction")
    angle: dict | None = Field(None, description="at_angle: the angles offered, degrees {min, max, step}")
    locks: list[str] = Field(default_factory=list, description="prediction: the panels that open once it is closed")


class AssignmentInfo(BaseModel):
    id: str
    title: str
    scene: str
    scene_title: str
    variant: str
    questions: list[QuestionInfo]
    attempts: int
    deadline: str | None = Field(description="ISO 8601, UTC")
    open: bool = Field(description="submissions are accepted (the deadline has not passed)")
    variants: int


class QuestionState(QuestionInfo):
    attempts_used: int
    attempts_left: int
    right: bool
    answers: list[float]
    correct_value: float | None = Field(description="given once the question is closed (right, or no attempt left), "
                                                    "if the assignment reveals answers")


class StudentVariant(BaseModel):
    assignment: AssignmentInfo
    student: str
    variant: int = Field(description="the student's variant number, 1 … variants")
    values: dict[str, float | str] = Field(description="the student's slider and toggle values, in the sliders' units")
    questions: list[QuestionState]


class SubmissionRequest(BaseModel):
    model_config = ConfigDict(extra="forbid")
    student: str = Field(min_length=1, max_length=MAX_NAME, description="name or number, as typed")
    question: str = Field(max_length=40)
    answer: float = Field(allow_inf_nan=False)
    angle: float | None = Field(None, allow_inf_nan=False, description="at_angle questions: the crank angle φ "
                                                                       "the student chose, degrees")


class SubmissionOutcome(BaseModel):
    question: str
    right: bool
    attempt: int
    attempts_left: int
    closed: bool
    correct_value: float | None = Field(description="only once the question is closed, if the assignment reveals "
                                                    "answers")


class ResultRow(BaseModel):
    student: str
    variant: int
    values: dict[str, float | str]
    first_seen: str
    last_submission: str | None
    attempts: int
    score: int = Field(description="questions answered right")
    questions: dict[str, dict] = Field(description="by question: attempts, right, the last answer and the correct "
                                                   "value it was checked against (null before an answer)")


class Results(BaseModel):
    assignment: AssignmentInfo
    students: list[ResultRow]
