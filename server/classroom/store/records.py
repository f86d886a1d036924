"""What the store keeps (assignments, students, submissions) and the interface every backend implements.

Every method of ``AssignmentStore`` is one transaction: it lands whole or not at all, and it returns only after
it has committed, so whatever a caller acknowledges survives a crash. Both backends (``sqlite.SQLiteStore``,
``postgres.PostgresStore``) give the same guarantees, checked by one test suite (tests/test_store.py).
"""
from __future__ import annotations

import functools
import inspect
import json
from dataclasses import dataclass
from typing import Callable, Protocol


@dataclass(frozen=True)
class AssignmentRecord:
    id: str
    token_hash: str
    created_at: float
    spec: dict
    roster_locked: bool = False     # only students on the roster may register
    client: str = ""                # the address that made it (the creation rate limit)


@dataclass(frozen=True)
class StudentRecord:
    key: str                        # the normalised name (computed by the caller, not the store)
    name: str
    variant: int
    parameters: dict
    first_seen: float
    attempts: int = 0
    solved: int = 0
    last_at: float | None = None
    secret_hash: str | None = None  # sha256 hex of the student's personal secret
    on_roster: bool = False


@dataclass(frozen=True)
class Submission:
    student_key: str
    question: str
    answer: float
    correct: bool
    attempt: int
    at: float
    correct_value: float | None = None      # the value the answer was checked against (None in older files)


class AttemptRefused(Exception):
    """No attempt left for the question, it is already answered right, or the student is gone."""

    def __init__(self, reason: str, code: str):
        super().__init__(reason)
        self.reason, self.code = reason, code


class StoreUnavailable(Exception):
    """The database cannot be used now (a read-only or full disk, a file locked too long, an unreachable or
    restarting server): the message names where and why. Nothing of the transaction landed; the API answers
    503 with Retry-After."""


def unavailable_on(is_unavailable: Callable[[BaseException], bool]):
    """Class decorator for a backend: each public method turns the errors of a database that cannot be used
    now (``is_unavailable``) into StoreUnavailable naming the database (``self.where``) and the reason; other
    errors (a bug) pass unchanged."""
    def guard(method):
        @functools.wraps(method)
        def guarded(self, *args, **kwargs):
            try:
                return method(self, *args, **kwargs)
            except StoreUnavailable:
                raise
            except Exception as error:
                if not is_unavailable(error):
                    raise
                reason = str(error).strip().splitlines()[0] if str(error).strip() else type(error).__name__
                raise StoreUnavailable(f"cannot use the database {self.where}: {reason}") from error
        return guarded

    def decorate(cls):
        for name in dir(cls):                       # the class's own methods and those it inherits (LtiTables)
            member = inspect.getattr_static(cls, name)   # a plain function: a method (not a static one)
            if inspect.isfunction(member) and not name.startswith("_") and name != "close":
                setattr(cls, name, guard(member))
        return cls
    return decorate


class AssignmentStore(Protocol):
    def check(self) -> None: ...        # StoreUnavailable unless a write would succeed now
    def create(self, record: AssignmentRecord) -> None: ...
    def assignment(self, assignment_id: str) -> AssignmentRecord | None: ...
    def set_roster_locked(self, assignment_id: str, locked: bool) -> None: ...
    def recent_assignments_by_client(self, client: str, since: float) -> int: ...
    def register(self, assignment_id: str, student: StudentRecord,
                 client: str = "") -> tuple[StudentRecord, bool]: ...
    def recent_registrations_by_client(self, client: str, since: float) -> int: ...
    def replace_token(self, assignment_id: str, old_hash: str, new_hash: str) -> bool: ...
    def student(self, assignment_id: str, key: str) -> StudentRecord | None: ...
    def student_by_secret(self, assignment_id: str, secret_hash: str) -> StudentRecord | None: ...
    def students(self, assignment_id: str) -> list[StudentRecord]: ...
    def set_secret(self, assignment_id: str, key: str, secret_hash: str | None) -> bool: ...
    def claim_secret(self, assignment_id: str, key: str, secret_hash: str) -> bool: ...
    def delete_student(self, assignment_id: str, key: str) -> bool: ...
    def submit(self, assignment_id: str, key: str, question: str, answer: float, correct: bool,
               attempts_allowed: int, at: float, client: str, correct_value: float | None = None) -> Submission: ...
    def submissions(self, assignment_id: str, key: str | None = None) -> list[Submission]: ...
    def recent_by_client(self, client: str, since: float) -> int: ...
    def variant_answers(self, assignment_id: str, variant: int) -> dict | None: ...
    def put_variant_answers(self, assignment_id: str, variant: int, answers: dict) -> None: ...


def refuse_attempt(used: int, solved: bool, attempts_allowed: int) -> None:
    """The one rule of attempts, shared by the backends: a question answered right is closed, and at most
    ``attempts_allowed`` answers are recorded per question."""
    if solved:
        raise AttemptRefused("this question is already answered right", "already_right")
    if used >= attempts_allowed:
        raise AttemptRefused(f"all {attempts_allowed} attempts are used", "no_attempts_left")


def no_such_student() -> AttemptRefused:
    """A submission for a student who is not (or no longer) registered: nothing is recorded."""
    return AttemptRefused("no such student (deleted by the instructor?)", "no_such_student")


# The columns both backends select, in the order the records take them.
STUDENT_COLUMNS = "key, name, variant, parameters, first_seen, attempts, solved, last_at, secret_hash, on_roster"
SUBMISSION_COLUMNS = "student_key, question, answer, correct, attempt, at, correct_value"


def student_record(row) -> StudentRecord:
    return StudentRecord(row[0], row[1], row[2], json.loads(row[3]), row[4], row[5], row[6], row[7], row[8],
                         bool(row[9]))


def submission_record(row) -> Submission:
    return Submission(row[0], row[1], row[2], bool(row[3]), row[4], row[5], row[6])
