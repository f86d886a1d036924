"""Request and response bodies of /api/v1/assignments."""
from __future__ import annotations

from pydantic import BaseModel, ConfigDict, Field

from ..classroom.names import MAX_NAME


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


class Results(BaseModel):
    assignment: AssignmentInfo
    students: list[ResultRow]


class RosterUpload(BaseModel):
    model_config = ConfigDict(extra="forbid")
    names: str = Field(max_length=200_000, description="one name per line, or a table (tab, semicolon, or comma "
                                                       "with a header) whose column name / student / ФИО / ПІБ "
                                                       "holds the names")
    lock: bool | None = Field(None, description="also lock (true) or open (false) registration to the roster")


class RosterOutcome(BaseModel):
    added: list[str] = Field(default_factory=list, description="names put on the assignment now")
    already: list[str] = Field(default_factory=list, description="names that were registered before")
    refused: list[dict[str, str]] = Field(default_factory=list, description="lines not taken: line and reason")
    roster_locked: bool = False


class RosterLock(BaseModel):
    model_config = ConfigDict(extra="forbid")
    locked: bool = Field(description="true: only names already registered (the roster among them) may register")


class PersonalLink(BaseModel):
    student: str
    personal_url: str = Field(description="the student's new personal link; the old one no longer works")


class ResultsLink(BaseModel):
    results_token: str = Field(description="the instructor's new results token; the old one no longer works")
    results_url: str = Field(description="the new private results page")
