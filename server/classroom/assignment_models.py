"""What the classroom tells of an assignment: its questions (no answers), the state of a student's questions,
the rows of the instructor's results and what a roster upload did. Declared once, here: server/api answers with
these models (server/api/schemas_assignments.py builds its bodies on them)."""
from __future__ import annotations

from pydantic import BaseModel, Field


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
    turning: dict[str, int] | None = Field(None, description=(
        "a course project: of `checked` variant numbers spread over the range, how many `turn` fully; only those "
        "are handed out (a student whose number does not turn gets the next one that does)"))


class QuestionState(QuestionInfo):
    attempts_used: int
    attempts_left: int
    right: bool
    answers: list[float]
    correct_value: float | None = Field(description="given once the question is closed (right, or no attempt left), "
                                                    "if the assignment reveals answers")


class ResultRow(BaseModel):
    id: str = Field(description="the student's handle for the instructor's actions (new link, delete)")
    student: str
    on_roster: bool = Field(description="put on the assignment by the instructor's roster")
    has_link: bool = Field(description="the student has a personal secret (registered, or a link was made)")
    variant: int
    values: dict[str, float | str]
    first_seen: str
    last_submission: str | None
    attempts: int
    score: int = Field(description="questions answered right")
    questions: dict[str, dict] = Field(description="by question: attempts, right, the last answer and the correct "
                                                   "value it was checked against (null before an answer)")


class RosterOutcome(BaseModel):
    added: list[str] = Field(default_factory=list, description="names put on the assignment now")
    already: list[str] = Field(default_factory=list, description="names that were registered before")
    refused: list[dict[str, str]] = Field(default_factory=list, description="lines not taken: line and reason")
    roster_locked: bool = False
