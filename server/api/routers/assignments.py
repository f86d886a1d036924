"""/api/v1/assignments: make an assignment; register a student (who gets a personal secret); read one's own
variant and submit answers with that secret; the instructor's results, roster and personal links.

A student's requests carry their secret: the ``mdl_student`` cookie (the pages), or ``Authorization: Bearer
<secret>`` (API clients; the secret comes back from the registration). Without one: 401 ``no_secret``; with a
secret that belongs to nobody (reset or deleted by the instructor): 403 ``unknown_secret``.
"""
from __future__ import annotations

import os
import time

from fastapi import APIRouter, Depends, Path, Query, Request, Response
from fastapi.responses import JSONResponse

from ...classroom.names import NameRefused, normalise
from ...classroom.spec import AssignmentSpec
from ...classroom.store import AttemptRefused, StudentRecord
from ...classroom.variants import SpecError
from ...classroom import assignment_answers, assignments, lti_classroom
from ...classroom.answers import is_right, tolerance
from ...classroom.assignment_store import store
from ..errors import NAME_STATUS
from ..csv_export import links_csv, results_csv as results_csv_file
from ..schemas import Language
from ..schemas_assignments import (AssignmentCreated, AssignmentInfo, PersonalLink, Registration, Results,
                                   ResultsLink, RosterLock, RosterOutcome, RosterUpload, StudentRegistration,
                                   StudentVariant, SubmissionOutcome, SubmissionRequest)
from ..student_secret import from_another_site, hand_over, keep_private, sent_secret

router = APIRouter(prefix="/assignments", tags=["assignments"])
LANG = Query("en", description="language of the question labels: ru, uk or en")
ID = Path(max_length=40, description="the assignment's id (from the students' link)")
TOKEN = Path(max_length=60, description="the instructor's results token")
STUDENT = Path(max_length=16, description="the student's handle (`id` in the results)")
SECRET = Depends(sent_secret)
SUBMISSIONS_PER_MINUTE = int(os.environ.get("MDL_SUBMISSIONS_PER_MINUTE", "300"))   # per client address
NO_SECRET = {401: {"description": "no personal secret (`no_secret`)"},
             403: {"description": "a secret of nobody (`unknown_secret`), or a name not the student's"}}


def _refuse(status: int, loc: list, reason: str, code: str, **about):
    return JSONResponse(status_code=status, content={"detail": [{"loc": loc, "msg": reason, "type": code, **about}]})


def spec_error(request: Request, error: SpecError) -> JSONResponse:
    return _refuse(422, ["body", *error.field.split(".")], error.reason, "assignment_error")


def name_refused(refused: NameRefused) -> JSONResponse:
    response = _refuse(NAME_STATUS[refused.code], ["body", "name"], refused.reason, refused.code,
                       **refused.about)
    if refused.code == "too_many_registrations":
        response.headers["Retry-After"] = str(assignments.REGISTRATION_WINDOW_S)
    return response


def the_student(secret: str | None, record) -> StudentRecord | JSONResponse:
    """The student whose secret the request carries, or the refusal to send."""
    if not secret:
        return _refuse(401, ["header", "authorization"], "no personal secret: open the assignment's link and type "
                                                         "your name, or open your personal link", "no_secret")
    student = assignments.identify(record, secret)
    if student is None:
        return _refuse(403, ["header", "authorization"], "this personal secret belongs to nobody here (the "
                                                         "instructor may have made a new link): open your "
                                                         "newest personal link, or ask the instructor",
                       "unknown_secret")
    return student


@router.post("", status_code=201, response_model=AssignmentCreated, summary="Make an assignment from a scene",
             responses={422: {"description": "the field and the reason"},
                        429: {"description": "too many assignments from this address in the last hour"}})
def create(spec: AssignmentSpec, request: Request) -> AssignmentCreated:
    client = request.client.host if request.client else "unknown"
    assignment_answers.limit_creation(client)                    # 429 past MDL_ASSIGNMENTS_PER_HOUR
    record, resolved, token = assignments.create(spec, client)
    base = str(request.base_url).rstrip("/")
    return AssignmentCreated(id=record.id, student_url=f"{base}/assignments/{record.id}?lang={spec.lang}",
                             results_url=assignments.results_url(base, record, token, spec.lang),
                             results_token=token, variants=resolved.count)


@router.get("/{assignment_id}", response_model=AssignmentInfo, summary="What the assignment asks (no answers)",
            responses={404: {"description": "no such assignment"}})
def describe(assignment_id: str = ID, lang: Language = LANG) -> AssignmentInfo:
    record, resolved = assignments.load(assignment_id)
    return assignments.info(record, resolved, lang)


@router.post("/{assignment_id}/students", status_code=201, response_model=Registration,
             summary="Register a student by name: their variant, and a personal secret (cookie and link)",
             responses={200: {"description": "the request already carries this student's secret"},
                        403: {"description": "the name (or one it looks like) is on the instructor's roster: "
                                             "only its personal link enters it (`roster_name_needs_link`); "
                                             "registration is locked to the roster (`roster_locked`); or the "
                                             "request came from another site"},
                        404: {"description": "no such assignment"},
                        409: {"description": "the name is taken (`name_taken`) or looks like a registered one "
                                             "(`name_confusable`, with `resembles`)"},
                        422: {"description": "no name, too long, or a word in two alphabets"},
                        429: {"description": "this address registered MDL_REGISTRATIONS_PER_HOUR students in the "
                                             "last hour (`too_many_registrations`, with Retry-After)"}})
def register(registration: StudentRegistration, request: Request, response: Response, assignment_id: str = ID,
             sent: str | None = SECRET):
    record, resolved = assignments.load(assignment_id)
    if from_another_site(request):
        return _refuse(403, ["header", "origin"], "registration from another site's page", "cross_site")
    client = request.client.host if request.client else "unknown"
    try:
        student, secret = assignments.register(record, resolved, registration.name,
                                               assignments.identify(record, sent), client)
    except NameRefused as refused:
        return name_refused(refused)
    keep_private(response)
    if secret is None:
        response.status_code = 200
    else:
        hand_over(response, request, record.id, secret)
    return Registration(student=student.name, variant=student.variant + 1, secret=secret,
                        personal_url=None if secret is None else assignments.personal_url(
                            str(request.base_url).rstrip("/"), record, resolved, secret))


@router.get("/{assignment_id}/me", response_model=StudentVariant,
            summary="The student's own variant and the state of their questions (answers only once closed)",
            responses={**NO_SECRET, 404: {"description": "no such assignment"}})
def student_variant(response: Response, assignment_id: str = ID, lang: Language = LANG,
                    secret: str | None = SECRET):
    record, resolved = assignments.load(assignment_id)
    student = the_student(secret, record)
    if isinstance(student, JSONResponse):
        return student
    keep_private(response)
    return StudentVariant(assignment=assignments.info(record, resolved, lang), student=student.name,
                          variant=student.variant + 1, values=student.parameters,
                          questions=assignments.question_states(record, resolved, student, lang))


@router.post("/{assignment_id}/submissions", response_model=SubmissionOutcome,
             summary="Submit an answer: right or wrong at once, the correct value once the question is closed",
             responses={401: NO_SECRET[401], 403: {"description": "the deadline has passed, or the secret is nobody's"},
                        404: {"description": "no such assignment"},
                        409: {"description": "no attempt left, or already answered right"},
                        422: {"description": "the field and the reason"},
                        429: {"description": "too many submissions from this address"}})
def submit(submission: SubmissionRequest, request: Request, assignment_id: str = ID, secret: str | None = SECRET):
    record, resolved = assignments.load(assignment_id)
    if submission.question not in {p.id for p in resolved.spec.questions}:
        return _refuse(422, ["body", "question"], "not a question of this assignment", "unknown_question")
    if not assignments.is_open(resolved):
        return _refuse(403, ["body"], "the deadline has passed", "deadline_passed")
    student = the_student(secret, record)
    if isinstance(student, JSONResponse):
        return student
    if submission.student is not None and normalise(submission.student) != normalise(student.name):
        return _refuse(403, ["body", "student"], "this is not the name of the student whose secret came with the "
                                                 "request", "not_your_name")
    client = request.client.host if request.client else "unknown"
    now = time.time()
    if store().recent_by_client(client, now - 60) >= SUBMISSIONS_PER_MINUTE:
        response = _refuse(429, ["body"], "too many submissions from this address; wait a minute", "rate_limited")
        response.headers["Retry-After"] = "60"
        return response
    correct = assignment_answers.correct_value(record.id, resolved, student.variant, submission.question,
                                               submission.angle)
    right = is_right(submission.answer, correct, tolerance(resolved, submission.question))
    try:
        saved = store().submit(record.id, student.key, submission.question, submission.answer, right,
                               resolved.spec.attempts, now, client, correct)
    except AttemptRefused as refused:
        return _refuse(403 if refused.code == "no_such_student" else 409, ["body", "question"], refused.reason,
                       refused.code)
    lti_classroom.submitted(record.id, student.key)      # an LMS student's score to their gradebook, later
    left = 0 if right else resolved.spec.attempts - saved.attempt
    return SubmissionOutcome(question=submission.question, right=right, attempt=saved.attempt, attempts_left=left,
                             closed=right or left == 0,
                             correct_value=correct if resolved.spec.reveal_answers and (right or left == 0) else None)


@router.get("/{assignment_id}/results/{token}", response_model=Results,
            summary="Every student, variant, attempts, score and time (the instructor's token)",
            responses={404: {"description": "no such assignment or wrong token"}})
def results(response: Response, assignment_id: str = ID, token: str = TOKEN, lang: Language = LANG) -> Results:
    record, resolved = assignments.load(assignment_id)
    assignments.check_token(record, token)
    keep_private(response)
    return Results(assignment=assignments.info(record, resolved, lang),
                   students=assignments.result_rows(record, resolved))


@router.get("/{assignment_id}/results/{token}/csv", summary="The results as CSV (UTF-8 with BOM, for spreadsheets)",
            response_class=Response, responses={200: {"content": {"text/csv": {}}},
                                                404: {"description": "no such assignment or wrong token"}})
def results_csv(assignment_id: str = ID, token: str = TOKEN) -> Response:
    record, resolved = assignments.load(assignment_id)
    assignments.check_token(record, token)
    return keep_private(results_csv_file(resolved, assignments.result_rows(record, resolved),
                                         f"results-{record.id}.csv"))


@router.post("/{assignment_id}/results/{token}/roster", response_model=RosterOutcome,
             summary="Put a roster's names on the assignment (each gets a variant; no link yet), optionally locking "
                     "registration to them",
             responses={404: {"description": "no such assignment or wrong token"}})
def upload_roster(upload: RosterUpload, assignment_id: str = ID, token: str = TOKEN) -> RosterOutcome:
    record, resolved = assignments.load(assignment_id)
    assignments.check_token(record, token)
    outcome = assignments.add_roster(record, resolved, upload.names)
    if upload.lock is not None:
        store().set_roster_locked(record.id, upload.lock)
    outcome.roster_locked = upload.lock if upload.lock is not None else record.roster_locked
    return outcome


@router.put("/{assignment_id}/results/{token}/roster-lock", response_model=RosterLock,
            summary="Lock registration to the names already there (the roster), or open it again",
            responses={404: {"description": "no such assignment or wrong token"}})
def lock_roster(lock: RosterLock, assignment_id: str = ID, token: str = TOKEN) -> RosterLock:
    record, _ = assignments.load(assignment_id)
    assignments.check_token(record, token)
    store().set_roster_locked(record.id, lock.locked)
    return lock


@router.post("/{assignment_id}/results/{token}/links", summary="One personal link per student as CSV, for an LMS "
             "or e-mail: every link is new (older links and cookies stop working); `only_new` gives links only to "
             "students who have none yet", response_class=Response,
             responses={200: {"content": {"text/csv": {}}}, 404: {"description": "no such assignment or wrong token"}})
def personal_links(request: Request, assignment_id: str = ID, token: str = TOKEN,
                   only_new: bool = Query(False, description="only students without a link (keeps the others)")):
    record, resolved = assignments.load(assignment_id)
    assignments.check_token(record, token)
    base = str(request.base_url).rstrip("/")
    rows = []
    for student in store().students(record.id):
        if only_new and student.secret_hash is not None:
            continue
        secret = assignments.new_link(record, student)
        rows.append([student.name, student.variant + 1, assignments.personal_url(base, record, resolved, secret)])
    return keep_private(links_csv(resolved, rows, f"links-{record.id}.csv"))


@router.post("/{assignment_id}/results/{token}/students/{student_id}/link", response_model=PersonalLink,
             summary="A new personal link for one student (the old one and its cookies stop working)",
             responses={404: {"description": "no such assignment or student, or wrong token"}})
def new_link(request: Request, response: Response, assignment_id: str = ID, token: str = TOKEN,
             student_id: str = STUDENT):
    record, resolved = assignments.load(assignment_id)
    assignments.check_token(record, token)
    student = assignments.find_student(record, student_id)
    secret = assignments.new_link(record, student)
    keep_private(response)
    return PersonalLink(student=student.name, personal_url=assignments.personal_url(
        str(request.base_url).rstrip("/"), record, resolved, secret))


@router.delete("/{assignment_id}/results/{token}/students/{student_id}", status_code=204,
               summary="Delete a student and their submissions", response_class=Response,
               responses={404: {"description": "no such assignment or student, or wrong token"}})
def delete_student(assignment_id: str = ID, token: str = TOKEN, student_id: str = STUDENT) -> Response:
    record, _ = assignments.load(assignment_id)
    assignments.check_token(record, token)
    student = assignments.find_student(record, student_id)
    store().delete_student(record.id, student.key)
    lti_classroom.score_changed(record.id, student.key)      # an LMS student's grade goes back to 0
    return Response(status_code=204)


@router.post("/{assignment_id}/results/{token}/token", response_model=ResultsLink,
             summary="Replace the results token (a results link that leaked): the new token and results link; the "
                     "old ones stop working at once",
             responses={404: {"description": "no such assignment or wrong token"}})
def new_results_token(request: Request, response: Response, assignment_id: str = ID, token: str = TOKEN,
                      lang: Language | None = Query(None, description="the new link's language (the assignment's "
                                                                      "unless given)")) -> ResultsLink:
    record, resolved = assignments.load(assignment_id)
    new = assignments.replace_token(record, token)
    keep_private(response)
    return ResultsLink(results_token=new, results_url=assignments.results_url(
        str(request.base_url).rstrip("/"), record, new, lang or resolved.spec.lang))
