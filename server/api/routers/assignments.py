"""/api/v1/assignments: make an assignment, read a student's variant, submit an answer, read the results."""
from __future__ import annotations

import csv
import io
import os
import time

from fastapi import APIRouter, Path, Query, Request, Response
from fastapi.responses import JSONResponse

from ...classroom.spec import AssignmentSpec
from ...classroom.store import AttemptRefused
from ...classroom.variants import MAX_NAME, SpecError
from .. import assignment_answers, assignments
from ..answers import is_right, tolerance
from ..assignment_store import store
from ..schemas import Language
from ..schemas_assignments import (AssignmentCreated, AssignmentInfo, Results, StudentVariant, SubmissionOutcome,
                                   SubmissionRequest)

router = APIRouter(prefix="/assignments", tags=["assignments"])
LANG = Query("en", description="language of the question labels: ru, uk or en")
ID = Path(max_length=40, description="the assignment's id (from the students' link)")
TOKEN = Path(max_length=60, description="the instructor's results token")
SUBMISSIONS_PER_MINUTE = int(os.environ.get("MDL_SUBMISSIONS_PER_MINUTE", "300"))   # per client address


def _number(value: float | None) -> str:
    return "" if value is None else repr(value)


def _refuse(status: int, loc: list, reason: str, code: str):
    return JSONResponse(status_code=status, content={"detail": [{"loc": loc, "msg": reason, "type": code}]})


def spec_error(request: Request, error: SpecError) -> JSONResponse:
    return _refuse(422, ["body", *error.field.split(".")], error.reason, "assignment_error")


@router.post("", status_code=201, response_model=AssignmentCreated, summary="Make an assignment from a scene",
             responses={422: {"description": "the field and the reason"},
                        429: {"description": "too many assignments from this address in the last hour"}})
def create(spec: AssignmentSpec, request: Request) -> AssignmentCreated:
    client = request.client.host if request.client else "unknown"
    assignment_answers.limit_creation(client)                    # 429 past MDL_ASSIGNMENTS_PER_HOUR
    record, resolved, token = assignments.create(spec, client)
    base = str(request.base_url).rstrip("/")
    return AssignmentCreated(id=record.id, student_url=f"{base}/assignments/{record.id}?lang={spec.lang}",
                             results_url=f"{base}/assignments/{record.id}/results/{token}?lang={spec.lang}",
                             results_token=token, variants=resolved.count)


@router.get("/{assignment_id}", response_model=AssignmentInfo, summary="What the assignment asks (no answers)",
            responses={404: {"description": "no such assignment"}})
def describe(assignment_id: str = ID, lang: Language = LANG) -> AssignmentInfo:
    record, resolved = assignments.load(assignment_id)
    return assignments.info(record, resolved, lang)


@router.get("/{assignment_id}/students/{student}", response_model=StudentVariant,
            summary="A student's variant and the state of their questions (answers only once closed)",
            responses={404: {"description": "no such assignment"}})
def student_variant(assignment_id: str = ID, student: str = Path(min_length=1, max_length=MAX_NAME),
                    lang: Language = LANG) -> StudentVariant:
    record, resolved = assignments.load(assignment_id)
    enrolled = assignments.enrol(record, resolved, student)
    return StudentVariant(assignment=assignments.info(record, resolved, lang), student=enrolled.name,
                          variant=enrolled.variant + 1, values=enrolled.parameters,
                          questions=assignments.question_states(record, resolved, enrolled, lang))


@router.post("/{assignment_id}/submissions", response_model=SubmissionOutcome,
             summary="Submit an answer: right or wrong at once, the correct value once the question is closed",
             responses={403: {"description": "the deadline has passed"}, 404: {"description": "no such assignment"},
                        409: {"description": "no attempt left, or already answered right"},
                        422: {"description": "the field and the reason"},
                        429: {"description": "too many submissions from this address"}})
def submit(submission: SubmissionRequest, request: Request, assignment_id: str = ID):
    record, resolved = assignments.load(assignment_id)
    if submission.question not in {p.id for p in resolved.spec.questions}:
        return _refuse(422, ["body", "question"], "not a question of this assignment", "unknown_question")
    if not assignments.is_open(resolved):
        return _refuse(403, ["body"], "the deadline has passed", "deadline_passed")
    client = request.client.host if request.client else "unknown"
    now = time.time()
    if store().recent_by_client(client, now - 60) >= SUBMISSIONS_PER_MINUTE:
        response = _refuse(429, ["body"], "too many submissions from this address; wait a minute", "rate_limited")
        response.headers["Retry-After"] = "60"
        return response
    student = assignments.enrol(record, resolved, submission.student)
    correct = assignment_answers.correct_value(record.id, resolved, student.variant, submission.question)
    right = is_right(submission.answer, correct, tolerance(resolved, submission.question))
    try:
        saved = store().submit(record.id, student.key, submission.question, submission.answer, right,
                               resolved.spec.attempts, now, client, correct)
    except AttemptRefused as refused:
        return _refuse(409, ["body", "question"], refused.reason, refused.code)
    left = 0 if right else resolved.spec.attempts - saved.attempt
    return SubmissionOutcome(question=submission.question, right=right, attempt=saved.attempt, attempts_left=left,
                             closed=right or left == 0,
                             correct_value=correct if resolved.spec.reveal_answers and (right or left == 0) else None)


@router.get("/{assignment_id}/results/{token}", response_model=Results,
            summary="Every student, variant, attempts, score and time (the instructor's token)",
            responses={404: {"description": "no such assignment or wrong token"}})
def results(assignment_id: str = ID, token: str = TOKEN, lang: Language = LANG) -> Results:
    record, resolved = assignments.load(assignment_id)
    assignments.check_token(record, token)
    return Results(assignment=assignments.info(record, resolved, lang),
                   students=assignments.result_rows(record, resolved))


@router.get("/{assignment_id}/results/{token}/csv", summary="The results as CSV (UTF-8 with BOM, for spreadsheets)",
            response_class=Response, responses={200: {"content": {"text/csv": {}}},
                                                404: {"description": "no such assignment or wrong token"}})
def results_csv(assignment_id: str = ID, token: str = TOKEN) -> Response:
    record, resolved = assignments.load(assignment_id)
    assignments.check_token(record, token)
    rows = assignments.result_rows(record, resolved)
    questions = [p.id for p in resolved.spec.questions]
    parameters = list(resolved.values(0))
    out = io.StringIO()
    writer = csv.writer(out)
    writer.writerow(["student", "variant", *parameters,
                     *[f"{q} {part}" for q in questions for part in ("attempts", "right", "answer", "correct")],
                     "score", "attempts", "first_seen", "last_submission"])
    for row in rows:
        writer.writerow([row.student, row.variant, *[row.values.get(p) for p in parameters],
                         *[v for q in questions for v in (row.questions[q]["attempts"], int(row.questions[q]["right"]),
                                                          _number(row.questions[q]["answer"]),
                                                          _number(row.questions[q]["correct"]))],
                         row.score, row.attempts, row.first_seen, row.last_submission or ""])
    name = f"results-{record.id}.csv"
    return Response("\ufeff" + out.getvalue(), media_type="text/csv; charset=utf-8",
                    headers={"Content-Disposition": f'attachment; filename="{name}"'})
