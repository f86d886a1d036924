"""Where assignments and submissions live: a small interface, and its SQLite implementation.

SQLite in WAL mode with ``synchronous=FULL``: a submission is acknowledged only after its transaction
has committed, and a transaction either lands whole or not at all, so a server killed in the middle of a
burst loses no acknowledged submission and leaves no half-written row. Several worker processes may
share the file (WAL lets readers run beside the one writer; writers wait up to ``BUSY_TIMEOUT``).
A PostgreSQL backend would implement the same ``AssignmentStore``.
"""
from __future__ import annotations

import json
import sqlite3
import threading
from dataclasses import dataclass
from pathlib import Path
from typing import Protocol

BUSY_TIMEOUT_S = 10.0

SCHEMA = """
CREATE TABLE IF NOT EXISTS assignments (
    id TEXT PRIMARY KEY,
    token_hash TEXT NOT NULL,
    created_at REAL NOT NULL,
    spec TEXT NOT NULL
);
CREATE TABLE IF NOT EXISTS students (
    assignment_id TEXT NOT NULL REFERENCES assignments(id),
    key TEXT NOT NULL,
    name TEXT NOT NULL,
    variant INTEGER NOT NULL,
    parameters TEXT NOT NULL,
    first_seen REAL NOT NULL,
    attempts INTEGER NOT NULL DEFAULT 0,
    solved INTEGER NOT NULL DEFAULT 0,
    last_at REAL,
    PRIMARY KEY (assignment_id, key)
);
CREATE TABLE IF NOT EXISTS submissions (
    id INTEGER PRIMARY KEY,
    assignment_id TEXT NOT NULL,
    student_key TEXT NOT NULL,
    question TEXT NOT NULL,
    answer REAL NOT NULL,
    correct INTEGER NOT NULL CHECK (correct IN (0, 1)),
    correct_value REAL,
    attempt INTEGER NOT NULL CHECK (attempt >= 1),
    at REAL NOT NULL,
    client TEXT NOT NULL,
    UNIQUE (assignment_id, student_key, question, attempt),
    FOREIGN KEY (assignment_id, student_key) REFERENCES students(assignment_id, key)
);
CREATE INDEX IF NOT EXISTS submissions_by_client ON submissions (client, at);
"""
# Columns added after the first release, for files made before them: (table, column, declaration).
ADDED_COLUMNS = (("submissions", "correct_value", "REAL"),)


@dataclass(frozen=True)
class AssignmentRecord:
    id: str
    token_hash: str
    created_at: float
    spec: dict


@dataclass(frozen=True)
class StudentRecord:
    key: str
    name: str
    variant: int
    parameters: dict
    first_seen: float
    attempts: int = 0
    solved: int = 0
    last_at: float | None = None


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
    """No attempt left for the question, or it is already answered right."""

    def __init__(self, reason: str, code: str):
        super().__init__(reason)
        self.reason, self.code = reason, code


class AssignmentStore(Protocol):
    def create(self, record: AssignmentRecord) -> None: ...
    def assignment(self, assignment_id: str) -> AssignmentRecord | None: ...
    def register(self, assignment_id: str, student: StudentRecord) -> StudentRecord: ...
    def student(self, assignment_id: str, key: str) -> StudentRecord | None: ...
    def students(self, assignment_id: str) -> list[StudentRecord]: ...
    def submit(self, assignment_id: str, key: str, question: str, answer: float, correct: bool,
               attempts_allowed: int, at: float, client: str, correct_value: float | None = None) -> Submission: ...
    def submissions(self, assignment_id: str, key: str | None = None) -> list[Submission]: ...
    def recent_by_client(self, client: str, since: float) -> int: ...


class SQLiteStore:
    """AssignmentStore in one SQLite file; one connection per thread."""

    def __init__(self, path: Path):
        self.path = Path(path)
        self.path.parent.mkdir(parents=True, exist_ok=True)
        self._local = threading.local()
        connection = self._connection()
        connection.executescript(SCHEMA)
        for table, column, declaration in ADDED_COLUMNS:
            if column not in {row[1] for row in connection.execute(f"PRAGMA table_info({table})")}:
                connection.execute(f"ALTER TABLE {table} ADD COLUMN {column} {declaration}")

    def _connection(self) -> sqlite3.Connection:
        connection = getattr(self._local, "connection", None)
        if connection is None:
            connection = sqlite3.connect(self.path, timeout=BUSY_TIMEOUT_S, isolation_level=None,
                                         check_same_thread=False)
            connection.execute("PRAGMA journal_mode=WAL")
            connection.execute("PRAGMA synchronous=FULL")
            connection.execute("PRAGMA foreign_keys=ON")
            self._local.connection = connection
        return connection

    def create(self, record: AssignmentRecord) -> None:
        self._connection().execute("INSERT INTO assignments VALUES (?, ?, ?, ?)",
                                   (record.id, record.token_hash, record.created_at, json.dumps(record.spec)))

    def assignment(self, assignment_id: str) -> AssignmentRecord | None:
        row = self._connection().execute("SELECT id, token_hash, created_at, spec FROM assignments WHERE id = ?",
                                         (assignment_id,)).fetchone()
        return None if row is None else AssignmentRecord(row[0], row[1], row[2], json.loads(row[3]))

    def register(self, assignment_id: str, student: StudentRecord) -> StudentRecord:
        """The student as first seen: a second registration under the same key changes nothing."""
        self._connection().execute(
            "INSERT OR IGNORE INTO students (assignment_id, key, name, variant, parameters, first_seen) "
            "VALUES (?, ?, ?, ?, ?, ?)", (assignment_id, student.key, student.name, student.variant,
                                          json.dumps(student.parameters), student.first_seen))
        return self.student(assignment_id, student.key)

    def student(self, assignment_id: str, key: str) -> StudentRecord | None:
        rows = self._students("WHERE assignment_id = ? AND key = ?", (assignment_id, key))
        return rows[0] if rows else None

    def students(self, assignment_id: str) -> list[StudentRecord]:
        return self._students("WHERE assignment_id = ? ORDER BY first_seen, key", (assignment_id,))

    def _students(self, where: str, args: tuple) -> list[StudentRecord]:
        rows = self._connection().execute(
            "SELECT key, name, variant, parameters, first_seen, attempts, solved, last_at FROM students " + where,
            args).fetchall()
        return [StudentRecord(r[0], r[1], r[2], json.loads(r[3]), r[4], r[5], r[6], r[7]) for r in rows]

    def submit(self, assignment_id: str, key: str, question: str, answer: float, correct: bool,
               attempts_allowed: int, at: float, client: str, correct_value: float | None = None) -> Submission:
        """Record one attempt (with the value it was checked against) and the student's totals in one
        transaction; AttemptRefused if none is left."""
        connection = self._connection()
        connection.execute("BEGIN IMMEDIATE")
        try:
            used, solved = connection.execute(
                "SELECT COUNT(*), COALESCE(MAX(correct), 0) FROM submissions "
                "WHERE assignment_id = ? AND student_key = ? AND question = ?",
                (assignment_id, key, question)).fetchone()
            if solved:
                raise AttemptRefused("this question is already answered right", "already_right")
            if used >= attempts_allowed:
                raise AttemptRefused(f"all {attempts_allowed} attempts are used", "no_attempts_left")
            connection.execute(
                "INSERT INTO submissions (assignment_id, student_key, question, answer, correct, correct_value, "
                "attempt, at, client) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?)",
                (assignment_id, key, question, answer, int(correct), correct_value, used + 1, at, client))
            connection.execute(
                "UPDATE students SET attempts = attempts + 1, solved = solved + ?, last_at = ? "
                "WHERE assignment_id = ? AND key = ?", (int(correct), at, assignment_id, key))
            connection.execute("COMMIT")
        except BaseException:
            connection.execute("ROLLBACK")
            raise
        return Submission(key, question, answer, correct, used + 1, at, correct_value)

    def submissions(self, assignment_id: str, key: str | None = None) -> list[Submission]:
        query = ("SELECT student_key, question, answer, correct, attempt, at, correct_value FROM submissions "
                 "WHERE assignment_id = ?" + (" AND student_key = ?" if key is not None else "") + " ORDER BY id")
        args = (assignment_id,) if key is None else (assignment_id, key)
        return [Submission(r[0], r[1], r[2], bool(r[3]), r[4], r[5], r[6])
                for r in self._connection().execute(query, args).fetchall()]

    def recent_by_client(self, client: str, since: float) -> int:
        return self._connection().execute("SELECT COUNT(*) FROM submissions WHERE client = ? AND at >= ?",
                                          (client, since)).fetchone()[0]
