"""Scores posted to the LMS gradebook (LTI Assignment and Grade Services 2.0), never on a student's request path.

A submission (or an instructor's change) only *queues* the student's score: one row per student in
``lti_passbacks``, due at once. ``post_due`` then posts, off the request, every due score: it reads the
student's standing at that moment (questions right of the number of questions), so a burst of submissions
posts the newest score, and a score queued again while being posted is posted once more. A failure (the
platform down, a refused token) is recorded with the reason and retried later with a growing delay
(RETRY_SECONDS · 2^tries, at most MAX_DELAY_SECONDS), by the next ``post_due`` run of any server (the
app runs one after each LMS student's submission, each instructor launch, and on a timer while scores wait).

Where the score goes: the line item of the student's launch (the ``lineitem`` of the AGS claim), else the one
found or created in the course's ``lineitems`` container for this assignment (tag = the assignment id, kept
in ``lti_line_items``). The service token comes from the platform's token endpoint (client_credentials with a
JWT client assertion signed by the tool's key) through pylti1p3's ServiceConnector.
"""
from __future__ import annotations

import logging
import time
from datetime import datetime, timezone

import requests
from pylti1p3.assignments_grades import AssignmentsGradesService
from pylti1p3.grade import Grade
from pylti1p3.lineitem import LineItem
from pylti1p3.service_connector import ServiceConnector

from .platforms import registration

RETRY_SECONDS = 30
MAX_DELAY_SECONDS = 3600
CLAIM_SECONDS = 120           # a score being posted is not taken by another server for this long
HTTP_TIMEOUT_S = 10
log = logging.getLogger("mdl.lti")


class TimeoutSession(requests.Session):
    """requests without a timeout wait forever; every call of this session gives up after HTTP_TIMEOUT_S."""

    def request(self, method, url, **kwargs):
        kwargs.setdefault("timeout", HTTP_TIMEOUT_S)
        return super().request(method, url, **kwargs)


def standing(store, assignment_id: str, student_key: str) -> tuple[int, int, str]:
    """(questions right, number of questions, AGS activityProgress) of a student now; 0 when they were reset."""
    record = store.assignment(assignment_id)
    questions = len(record.spec["questions"]) if record is not None else 0
    student = store.student(assignment_id, student_key)
    if student is None or not student.attempts:
        return 0, questions, "Initialized"
    return student.solved, questions, "Completed" if student.solved >= questions else "InProgress"


def line_item(store, ags: AssignmentsGradesService, learner, title: str, maximum: int) -> LineItem | None:
    """The line item to post to: the launch's own, or this assignment's in the course (found or made)."""
    if learner.ags.get("lineitem"):
        return None                                   # put_grade posts to the launch's line item
    url = store.lti_line_item(learner.platform_id, learner.context_id, learner.assignment_id)
    if url is None:
        found = ags.find_or_create_lineitem(LineItem().set_tag(learner.assignment_id).set_label(title)
                                            .set_resource_id(learner.assignment_id).set_score_maximum(maximum))
        url = found.get_id()
        store.lti_keep_line_item(learner.platform_id, learner.context_id, learner.assignment_id, url)
    return LineItem().set_id(url)


def post_score(store, assignment_id: str, student_key: str, session: requests.Session | None = None) -> int:
    """Post one student's score to every LMS user linked to them that has a grade service; how many were posted."""
    right, questions, progress = standing(store, assignment_id, student_key)
    record = store.assignment(assignment_id)
    title = (record.spec.get("title") if record else None) or assignment_id
    posted = 0
    for learner in store.lti_learners_of(assignment_id, student_key):
        if not learner.ags or not (learner.ags.get("lineitem") or learner.ags.get("lineitems")):
            continue
        platform = store.lti_platform(learner.platform_id)
        if platform is None:
            continue
        ags = AssignmentsGradesService(ServiceConnector(registration(platform, store), session or TimeoutSession()),
                                       learner.ags)
        grade = (Grade().set_score_given(right).set_score_maximum(max(questions, 1)).set_activity_progress(progress)
                 .set_grading_progress("FullyGraded").set_user_id(learner.sub)
                 .set_timestamp(datetime.now(timezone.utc).isoformat(timespec="milliseconds")))
        ags.put_grade(grade, line_item(store, ags, learner, title, max(questions, 1)))
        posted += 1
    return posted


def reason(error: Exception) -> str:
    """A failure in words for the log and the table: the platform's status and the start of its answer."""
    response = getattr(error, "response", None)
    if response is not None and hasattr(response, "status_code"):
        return f"HTTP {response.status_code} from {response.url.split('?')[0]}: {response.text[:200]}"
    return f"{type(error).__name__}: {str(error)[:300]}"


def post_due(store, now: float | None = None, session: requests.Session | None = None) -> dict:
    """Post every due score (each taken by one server only); counts of posted and failed."""
    now = time.time() if now is None else now
    outcome = {"posted": 0, "failed": 0}
    for pending in store.lti_due_scores(now):
        if not store.lti_claim_score(pending, now + CLAIM_SECONDS):
            continue
        try:
            post_score(store, pending.assignment_id, pending.student_key, session)
        except Exception as error:                    # noqa: BLE001 - a passback never fails anything else
            delay = min(RETRY_SECONDS * 2 ** pending.tries, MAX_DELAY_SECONDS)
            store.lti_score_failed(pending, reason(error), time.time() + delay)
            log.warning("LTI score of a student of assignment %s not posted (try %d, again in %d s): %s",
                        pending.assignment_id, pending.tries + 1, delay, reason(error))
            outcome["failed"] += 1
        else:
            store.lti_score_posted(pending)
            outcome["posted"] += 1
    return outcome
