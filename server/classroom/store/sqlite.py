"""AssignmentStore in one SQLite file: the embedded default.

WAL mode with ``synchronous=FULL``: a transaction either lands whole or not at all and is on disk when
COMMIT returns, so a server killed in the middle of a burst loses no acknowledged submission and leaves no
half-written row (tests/test_crash_safety.py). Every write runs in ``BEGIN IMMEDIATE``, which takes the
file's one write lock before reading, so the attempt count a submission checks cannot change under it:
the attempt limit holds across threads, worker processes and servers sharing the file. Writers wait up to
``BUSY_TIMEOUT_S`` for the lock.

A file that cannot take a write now (a full disk: SQLITE_FULL; a disk I/O error; a lock held past the busy
timeout; a read-only file) raises StoreUnavailable. SQLite has then already rolled the transaction back
itself, so the transaction is rolled back only if it is still open.
"""
from __future__ import annotations

import json
import sqlite3
import threading
import time
from contextlib import contextmanager
from pathlib import Path

from .lti_tables import LtiTables
from .migrations import LATEST, VERSION_TABLE, SchemaTooNew, legacy_version, pending
from .records import (STUDENT_COLUMNS, SUBMISSION_COLUMNS, AssignmentRecord, StoreUnavailable, StudentRecord,
                      Submission, no_such_student, refuse_attempt, student_record, submission_record, unavailable_on)

BUSY_TIMEOUT_S = 10.0
# SQLite's primary result codes of a file that cannot be used now (not of a bug in a statement)
UNAVAILABLE_CODES = {sqlite3.SQLITE_BUSY, sqlite3.SQLITE_LOCKED, sqlite3.SQLITE_NOMEM, sqlite3.SQLITE_READONLY,
                     sqlite3.SQLITE_IOERR, sqlite3.SQLITE_FULL, sqlite3.SQLITE_CANTOPEN, sqlite3.SQLITE_PROTOCOL}


def unavailable(error: BaseException) -> bool:
    """Whether `error` says the file cannot be used now: a full disk, an I/O error, a lock, a read-only file."""
    if not isinstance(error, sqlite3.Error):
        return False
    code = getattr(error, "sqlite_errorcode", None)
    if code is not None:
        return code & 0xFF in UNAVAILABLE_CODES
    return isinstance(error, sqlite3.OperationalError) and any(
        words in str(error) for words in ("disk is full", "disk I/O error", "locked", "readonly", "unable to open"))


@unavailable_on(unavailable)
class SQLiteStore(LtiTables):
    """AssignmentStore in one SQLite file; one connection per thread. StoreUnavailable (naming the file and
    the reason) when the file or its directory cannot be opened, migrated or written."""

    def __init__(self, path: Path):
        self.path = Path(path)
        self.where = str(self.path)
        self._local = threading.local()
        try:
            self.path.parent.mkdir(parents=True, exist_ok=True)
            self._open()
        except (OSError, sqlite3.Error) as error:
            raise StoreUnavailable(f"cannot open the database {self.path} for writing: {error}") from error
        except SchemaTooNew as error:
            raise StoreUnavailable(f"cannot use the database {self.path}: {error}") from error

    def _open(self) -> None:
        """Migrate, trying again for up to BUSY_TIMEOUT_S while the file is locked: the workers of a server started
        on a new file open it at once, and switching a new file to WAL can be refused at once ("database is
        locked", without the busy handler) while another connection is doing the same."""
        deadline = time.monotonic() + BUSY_TIMEOUT_S
        while True:
            try:
                self._migrate()
                return
            except sqlite3.OperationalError as error:
                if "locked" not in str(error) or time.monotonic() > deadline:
                    raise
                connection = getattr(self._local, "connection", None)
                if connection is not None:
                    connection.close()
                    self._local.connection = None
                time.sleep(0.05)

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

    @contextmanager
    def _transaction(self):
        """One write transaction holding the file's write lock from its start; committed on leaving."""
        connection = self._connection()
        connection.execute("BEGIN IMMEDIATE")
        try:
            yield connection
            connection.execute("COMMIT")
        except BaseException:
            if connection.in_transaction:      # SQLite ends the transaction itself on SQLITE_FULL or IOERR
                try:
                    connection.execute("ROLLBACK")
                except sqlite3.Error:          # a connection in doubt is closed: the next call opens a new one
                    connection.close()
                    self._local.connection = None
            raise

    def _migrate(self) -> None:
        with self._transaction() as connection:
            tables = {row[0] for row in connection.execute("SELECT name FROM sqlite_master WHERE type = 'table'")}
            connection.execute(VERSION_TABLE["sqlite"])
            if "schema_version" not in tables:
                columns = {row[1] for row in connection.execute("PRAGMA table_info(submissions)")}
                for number in range(1, legacy_version(tables, columns) + 1):
                    connection.execute("INSERT INTO schema_version VALUES (?, ?, ?)",
                                       (number, "found in a file made before versioning", time.time()))
            current = connection.execute("SELECT COALESCE(MAX(version), 0) FROM schema_version").fetchone()[0]
            for migration in pending(current):
                for statement in migration.statements("sqlite"):
                    connection.execute(statement)
                connection.execute("INSERT INTO schema_version VALUES (?, ?, ?)",
                                   (migration.number, migration.what, time.time()))

    def schema_version(self) -> int:
        return self._connection().execute("SELECT MAX(version) FROM schema_version").fetchone()[0]

    def applied_versions(self) -> list[int]:
        return [row[0] for row in self._connection().execute("SELECT version FROM schema_version ORDER BY 1")]

    def check(self) -> None:
        """StoreUnavailable unless the file takes a write now (a write transaction, rolled back)."""
        try:
            with self._transaction() as connection:
                connection.execute("UPDATE schema_version SET what = what WHERE version = ?", (LATEST,))
        except sqlite3.Error as error:
            raise StoreUnavailable(f"cannot write the database {self.path}: {error}") from error

    def create(self, record: AssignmentRecord) -> None:
        with self._transaction() as connection:
            connection.execute(
                "INSERT INTO assignments (id, token_hash, created_at, spec, roster_locked, client) "
                "VALUES (?, ?, ?, ?, ?, ?)", (record.id, record.token_hash, record.created_at,
                                              json.dumps(record.spec), int(record.roster_locked), record.client))

    def assignment(self, assignment_id: str) -> AssignmentRecord | None:
        row = self._connection().execute(
            "SELECT id, token_hash, created_at, spec, roster_locked, client FROM assignments WHERE id = ?",
            (assignment_id,)).fetchone()
        return None if row is None else AssignmentRecord(row[0], row[1], row[2], json.loads(row[3]), bool(row[4]),
                                                         row[5])

    def set_roster_locked(self, assignment_id: str, locked: bool) -> None:
        with self._transaction() as connection:
            connection.execute("UPDATE assignments SET roster_locked = ? WHERE id = ?", (int(locked), assignment_id))

    def recent_assignments_by_client(self, client: str, since: float) -> int:
        return self._connection().execute("SELECT COUNT(*) FROM assignments WHERE client = ? AND created_at >= ?",
                                          (client, since)).fetchone()[0]

    def replace_token(self, assignment_id: str, old_hash: str, new_hash: str) -> bool:
        """Put a new results token's hash in place of ``old_hash``; False if the assignment has another one (a
        replacement at the same moment won)."""
        with self._transaction() as connection:
            return connection.execute("UPDATE assignments SET token_hash = ? WHERE id = ? AND token_hash = ?",
                                      (new_hash, assignment_id, old_hash)).rowcount == 1

    def recent_registrations_by_client(self, client: str, since: float) -> int:
        return self._connection().execute("SELECT COUNT(*) FROM students WHERE client = ? AND first_seen >= ?",
                                          (client, since)).fetchone()[0]

    def register(self, assignment_id: str, student: StudentRecord, client: str = "") -> tuple[StudentRecord, bool]:
        """The student as stored, and whether this call created them: a second registration under the same
        key changes nothing. ``client``: the address that registered them ("" for the instructor's roster)."""
        with self._transaction() as connection:
            created = connection.execute(
                "INSERT INTO students (assignment_id, key, name, variant, parameters, first_seen, secret_hash, "
                "on_roster, client) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?) ON CONFLICT (assignment_id, key) DO NOTHING",
                (assignment_id, student.key, student.name, student.variant, json.dumps(student.parameters),
                 student.first_seen, student.secret_hash, int(student.on_roster), client)).rowcount == 1
            row = connection.execute(f"SELECT {STUDENT_COLUMNS} FROM students WHERE assignment_id = ? AND key = ?",
                                     (assignment_id, student.key)).fetchone()
        return student_record(row), created

    def _students(self, where: str, args: tuple) -> list[StudentRecord]:
        rows = self._connection().execute(f"SELECT {STUDENT_COLUMNS} FROM students {where}", args).fetchall()
        return [student_record(row) for row in rows]

    def student(self, assignment_id: str, key: str) -> StudentRecord | None:
        rows = self._students("WHERE assignment_id = ? AND key = ?", (assignment_id, key))
        return rows[0] if rows else None

    def student_by_secret(self, assignment_id: str, secret_hash: str) -> StudentRecord | None:
        rows = self._students("WHERE assignment_id = ? AND secret_hash = ?", (assignment_id, secret_hash))
        return rows[0] if rows else None

    def students(self, assignment_id: str) -> list[StudentRecord]:
        return self._students("WHERE assignment_id = ? ORDER BY first_seen, key", (assignment_id,))

    def set_secret(self, assignment_id: str, key: str, secret_hash: str | None) -> bool:
        with self._transaction() as connection:
            return connection.execute("UPDATE students SET secret_hash = ? WHERE assignment_id = ? AND key = ?",
                                      (secret_hash, assignment_id, key)).rowcount == 1

    def claim_secret(self, assignment_id: str, key: str, secret_hash: str) -> bool:
        """Give the student this secret only if they have none (one conditional UPDATE: of two claims at once,
        exactly one succeeds)."""
        with self._transaction() as connection:
            return connection.execute("UPDATE students SET secret_hash = ? WHERE assignment_id = ? AND key = ? "
                                      "AND secret_hash IS NULL", (secret_hash, assignment_id, key)).rowcount == 1

    def delete_student(self, assignment_id: str, key: str) -> bool:
        """The student and every submission of theirs, in one transaction."""
        with self._transaction() as connection:
            connection.execute("DELETE FROM submissions WHERE assignment_id = ? AND student_key = ?",
                               (assignment_id, key))
            return connection.execute("DELETE FROM students WHERE assignment_id = ? AND key = ?",
                                      (assignment_id, key)).rowcount == 1

    def submit(self, assignment_id: str, key: str, question: str, answer: float, correct: bool,
               attempts_allowed: int, at: float, client: str, correct_value: float | None = None) -> Submission:
        """Record one attempt (with the value it was checked against) and the student's totals in one
        transaction; AttemptRefused if none is left or the student is not registered."""
        with self._transaction() as connection:
            if connection.execute("SELECT 1 FROM students WHERE assignment_id = ? AND key = ?",
                                  (assignment_id, key)).fetchone() is None:
                raise no_such_student()
            used, solved = connection.execute(
                "SELECT COUNT(*), COALESCE(MAX(correct), 0) FROM submissions "
                "WHERE assignment_id = ? AND student_key = ? AND question = ?",
                (assignment_id, key, question)).fetchone()
            refuse_attempt(used, bool(solved), attempts_allowed)
            connection.execute(
                "INSERT INTO submissions (assignment_id, student_key, question, answer, correct, correct_value, "
                "attempt, at, client) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?)",
                (assignment_id, key, question, answer, int(correct), correct_value, used + 1, at, client))
            connection.execute(
                "UPDATE students SET attempts = attempts + 1, solved = solved + ?, last_at = ? "
                "WHERE assignment_id = ? AND key = ?", (int(correct), at, assignment_id, key))
        return Submission(key, question, answer, correct, used + 1, at, correct_value)

    def submissions(self, assignment_id: str, key: str | None = None) -> list[Submission]:
        query = (f"SELECT {SUBMISSION_COLUMNS} FROM submissions WHERE assignment_id = ?"
                 + (" AND student_key = ?" if key is not None else "") + " ORDER BY id")
        args = (assignment_id,) if key is None else (assignment_id, key)
        return [submission_record(row) for row in self._connection().execute(query, args).fetchall()]

    def recent_by_client(self, client: str, since: float) -> int:
        return self._connection().execute("SELECT COUNT(*) FROM submissions WHERE client = ? AND at >= ?",
                                          (client, since)).fetchone()[0]

    def variant_answers(self, assignment_id: str, variant: int) -> dict | None:
        row = self._connection().execute(
            "SELECT answers FROM variant_answers WHERE assignment_id = ? AND variant = ?",
            (assignment_id, variant)).fetchone()
        return None if row is None else json.loads(row[0])

    def put_variant_answers(self, assignment_id: str, variant: int, answers: dict) -> None:
        """Store (or replace) a variant's answers: question id → correct value or the error text."""
        with self._transaction() as connection:
            connection.execute(
                "INSERT INTO variant_answers (assignment_id, variant, answers) VALUES (?, ?, ?) "
                "ON CONFLICT (assignment_id, variant) DO UPDATE SET answers = excluded.answers",
                (assignment_id, variant, json.dumps(answers)))
