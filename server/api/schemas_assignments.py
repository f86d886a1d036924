"""Request and response bodies of /api/v1/assignments; what the classroom itself tells of an assignment (its
questions, a student's state, the results' rows, a roster's outcome) is declared in
server/classroom/assignment_models.py and answered as it is."""
from __future__ import annotations

from pydantic import BaseModel, ConfigDict, Field

from ..classroom.assignment_models import (AssignmentInfo, QuestionInfo, QuestionState,  # noqa: F401 (answered)
                                           ResultRow, RosterOutcome)
from ..classroom.names import MAX_NAME


class AssignmentCreated(BaseModel):
    id: str
    student_url: str = Field(description="the link for the students")
    results_url: str = Field(description="the instructor's private link (keep it: the token is not stored)")
    results_token: str
    variants: int = Field(description="how many different variants the ranges give")


class StudentVariant(BaseModel):
    assignment: AssignmentInfo
    student: str
    variant: int = Field(description="the student's variant number, 1 … variants")
    values: dict[str, float | str] = Field(description="the student's slider and toggle values, in the sliders' units")
    questions: list[QuestionState]


class StudentRegistration(BaseModel):
    model_config = ConfigDict(extra="forbid")
    name: str = Field(min_length=1, max_length=MAX_NAME, description="name or number, as the student types it")


class Registration(BaseModel):
    student: str = Field(description="the name as registered (cleaned: spaces collapsed, invisible characters "
                                     "removed)")
    variant: int = Field(description="the student's variant number, 1 … variants")
    secret: str | None = Field(description="the personal secret (null when the request already carried it): send "
                                           "it as `Authorization: Bearer <secret>`, or keep the cookie")
    personal_url: str | None = Field(description="the personal link: opening it on any device sets the cookie "
                                                 "(shown once: keep it)")


class SubmissionRequest(BaseModel):
    model_config = ConfigDict(extra="forbid")
    student: str | None = Field(None, min_length=1, max_length=MAX_NAME,
                                description="optional: the student's name; the secret identifies the student, and "
                                            "a name that is not theirs is refused (403)")
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


class Results(BaseModel):
    assignment: AssignmentInfo
    students: list[ResultRow]


class RosterUpload(BaseModel):
    model_config = ConfigDict(extra="forbid")
    names: str = Field(max_length=200_000, description="one name per line, or a table (tab, semicolon, or comma "
                                                       "with a header) whose column name / student / ФИО / ПІБ "
                                                       "holds the names")
    lock: bool | None = Field(None, description="also lock (true) or open (false) registration to the roster")


class RosterLock(BaseModel):
    model_config = ConfigDict(extra="forbid")
    locked: bool = Field(description="true: only names already registered (the roster among them) may register")


class PersonalLink(BaseModel):
    student: str
    personal_url: str = Field(description="the student's new personal link; the old one no longer works")


class ResultsLink(BaseModel):
    results_token: str = Field(description="the instructor's new results token; the old one no longer works")
    results_url: str = Field(description="the new private results page")
