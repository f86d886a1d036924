"""What an LTI launch does in the classroom: an LMS learner becomes (or is again) a student of the assignment
with a personal secret derived for them (the same on every device); an instructor gets a session tied to the assignment (its results without the
token); the course's members (NRPS) fill the roster; a single-use ticket carries a launch from an LMS frame
to a new window; scores are queued for the gradebook and posted off the request path. Glue between the
launch (routers/lti.py), the assignments (assignments.py) and the LTI store (classroom/lti)."""
from __future__ import annotations

import base64
import hashlib
import hmac
import logging
import secrets
import threading
import time
from concurrent.futures import ThreadPoolExecutor

from . import identity
from .lti import grades
from .lti.members import lms_name, student_key, teaches
from .lti.tool_key import tool_key
from .names import normalise
from .store import AssignmentRecord, StoreUnavailable, StudentRecord
from .store.lti_tables import LearnerRecord, PlatformRecord
from .variants import Plan
from .assignment_store import store

TEACHER_COOKIE = "mdl_lti_teacher"
TEACHER_SECONDS = 8 * 3600        # an instructor's session: a working day
TICKET_SECONDS = 300              # "Open in a new window": used once, within five minutes
SWEEP_S = 600                     # expired launch states are removed at most this often per process
RETRY_FLOOR_S = 5.0               # a waiting grade is tried again no sooner than this
AGS_CLAIM = "https://purl.imsglobal.org/spec/lti-ags/claim/endpoint"
CONTEXT_CLAIM = "https://purl.imsglobal.org/spec/lti/claim/context"
log = logging.getLogger("mdl.lti")
_posting = ThreadPoolExecutor(max_workers=1, thread_name_prefix="lti-scores")


def _hash(token: str) -> str:
    return hashlib.sha256(token.encode()).hexdigest()


def context_id(claims: dict) -> str:
    return str((claims.get(CONTEXT_CLAIM) or {}).get("id") or "")


def _linked_student(record: AssignmentRecord, platform: PlatformRecord, sub: str, name: str,
                    resolved: Plan, on_roster: bool) -> StudentRecord:
    """The student this LMS user is in the assignment: the one linked before; else a roster name nobody has
    claimed or linked; else a new record under the user's own key (no name check: the LMS vouches for it)."""
    linked = store().lti_learner(platform.id, sub, record.id)
    if linked is not None:
        student = store().student(record.id, linked.student_key)
        if student is not None:
            return student
    key = student_key(platform.issuer, sub)
    by_name = store().student(record.id, normalise(name)) if name else None
    if (by_name is not None and by_name.secret_hash is None
            and not store().lti_learners_of(record.id, by_name.key)):
        return by_name
    number = resolved.number_for(record.id, key)
    stored, _ = store().register(record.id, StudentRecord(
        key, name or f"LMS {sub[:12]}", number, resolved.values(number), time.time(),
        secret_hash=identity.secret_hash(identity.new_secret()), on_roster=on_roster))
    return stored


def enter_learner(record: AssignmentRecord, resolved: Plan, platform: PlatformRecord, claims: dict) -> StudentRecord:
    """The launching learner as a student of the assignment, linked to their LMS user with their launch's grade
    service (their session's secret is ``new_secret_for``'s)."""
    sub = str(claims["sub"])
    student = _linked_student(record, platform, sub, lms_name(claims), resolved, on_roster=False)
    store().lti_link_learner(LearnerRecord(platform.id, sub, record.id, student.key, context_id(claims),
                                           claims.get(AGS_CLAIM)))
    return student


def fill_roster(record: AssignmentRecord, resolved: Plan, platform: PlatformRecord, context: str,
                members: list[dict]) -> dict:
    """The course's active learners (NRPS members) as students of the assignment, each linked to their LMS
    user; their records get a secret nobody holds, so they enter only through the LMS. Counts."""
    outcome = {"added": 0, "linked": 0, "skipped": 0}
    for member in members:
        sub = str(member.get("user_id") or "")
        if not sub or teaches(member.get("roles")) or member.get("status", "Active") != "Active":
            outcome["skipped"] += 1
            continue
        if store().lti_learner(platform.id, sub, record.id) is not None:
            outcome["linked"] += 1
            continue
        student = _linked_student(record, platform, sub, lms_name(member), resolved, on_roster=True)
        if student.secret_hash is None:
            store().set_secret(record.id, student.key, identity.secret_hash(identity.new_secret()))
        store().lti_link_learner(LearnerRecord(platform.id, sub, record.id, student.key, context, None))
        outcome["added"] += 1
    return outcome


_swept = {"at": 0.0}


def sweep_expired() -> None:
    """Remove expired launch states, tickets and sessions from the database, at most every SWEEP_S per process
    (called on each login: the table grows only with launches). Never raises."""
    now = time.time()
    if now - _swept["at"] < SWEEP_S:
        return
    _swept["at"] = now
    try:
        store().lti_forget_expired(now)
    except StoreUnavailable as error:                    # the database is down: one line, the next sweep retries
        log.warning("removing expired LTI launch states waits for the database: %s", error)
    except Exception:                                    # noqa: BLE001 - the next sweep tries again
        log.exception("removing expired LTI launch states failed")


# an instructor's session, and the tickets that carry a launch to a new window
def new_teacher_session(assignment_id: str, platform_id: str, context: str) -> str:
    token = secrets.token_urlsafe(24)
    store().lti_put(f"teacher:{_hash(token)}", {"assignment": assignment_id, "platform": platform_id,
                                                "context": context}, time.time() + TEACHER_SECONDS)
    return token


def teacher_session(token: str | None, assignment_id: str) -> dict | None:
    """The instructor session this cookie names, if it is for this assignment and not expired."""
    if not token or len(token) > 64:
        return None
    session = store().lti_get(f"teacher:{_hash(token)}", time.time())
    return session if session is not None and session.get("assignment") == assignment_id else None


def new_ticket(about: dict) -> str:
    ticket = secrets.token_urlsafe(24)
    store().lti_put(f"ticket:{_hash(ticket)}", about, time.time() + TICKET_SECONDS)
    return ticket


def take_ticket(ticket: str) -> dict | None:
    """What the ticket was made for, once: a second use, or after TICKET_SECONDS, gives None."""
    if not ticket or len(ticket) > 64:
        return None
    return store().lti_take(f"ticket:{_hash(ticket)}", time.time())


# scores for the gradebook
def queue_score(assignment_id: str, key: str) -> bool:
    """Queue the student's score if they came from an LMS; whether it was queued."""
    if not store().lti_learners_of(assignment_id, key):
        return False
    store().lti_queue_score(assignment_id, key, time.time())
    return True


def post_scores_later() -> None:
    """Post every due score in this process's one background thread (never on a request's path)."""
    _posting.submit(_post_due)


def _post_due() -> None:
    try:
        grades.post_due(store())
        waiting = store().lti_pending_scores()
    except StoreUnavailable as error:                    # the database is down: one line, no traceback
        log.warning("posting LTI scores waits for the database: %s", error)
        waiting = []
    except Exception:                                    # noqa: BLE001 - logged; the rows stay due
        log.exception("posting LTI scores failed")
        waiting = []
    if waiting:                                          # a retry later, even if no student submits again
        _retry_at(min(p.retry_at for p in waiting))


_retry = {"timer": None}
_retry_lock = threading.Lock()


def _retry_at(at: float) -> None:
    """One timer per process wakes the posting thread when the earliest waiting score is due (no sooner than
    RETRY_FLOOR_S, no later than an hour; another server may post it first: the row is then gone or taken)."""
    with _retry_lock:
        if _retry["timer"] is not None and _retry["timer"].is_alive():
            return
        delay = min(max(at - time.time(), RETRY_FLOOR_S), grades.MAX_DELAY_SECONDS)
        _retry["timer"] = threading.Timer(delay, post_scores_later)
        _retry["timer"].daemon = True
        _retry["timer"].start()


def submitted(assignment_id: str, key: str) -> None:
    """After a submission: queue the student's score for the LMS and post it later. Never raises."""
    try:
        if queue_score(assignment_id, key):
            post_scores_later()
    except StoreUnavailable as error:                    # the database is down: one line, no traceback
        log.warning("queueing an LTI score waits for the database: %s", error)
    except Exception:                                    # noqa: BLE001 - a submission never fails for this
        log.exception("queueing an LTI score failed")


def score_changed(assignment_id: str, key: str) -> None:
    """The instructor changed a student's standing (a reset): post their score again, later. Never raises."""
    submitted(assignment_id, key)


def post_due_now() -> dict:
    """Post the due scores on this request (the administrator's retry): counts of posted and failed."""
    return grades.post_due(store())


def new_secret_for(assignment_id: str, key: str) -> str | None:
    """The personal secret of a student who enters through the LMS (None if they were removed meanwhile).

    It is derived (HMAC-SHA-256 under a key derived from the tool's private key, which only the database holds)
    from the assignment and the student, so every launch, on any device, hands over the same secret and the
    sessions of a student's other devices keep working; a secret the instructor gave them instead is replaced."""
    student = store().student(assignment_id, key)
    if student is None:
        return None
    mac = hmac.new(_secrets_key(), f"{assignment_id}\n{key}".encode(), hashlib.sha256).digest()
    secret = base64.urlsafe_b64encode(mac[:identity.SECRET_BYTES]).decode()
    if student.secret_hash != identity.secret_hash(secret):
        if not store().set_secret(assignment_id, key, identity.secret_hash(secret)):
            return None
    return secret


def _secrets_key() -> bytes:
    return hashlib.sha256(b"mdl-lti-student-secrets\n" + tool_key(store()).private_pem.encode()).digest()
