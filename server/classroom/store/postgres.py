"""AssignmentStore on PostgreSQL (psycopg 3, a connection pool): several app servers behind one database.

Every method is one transaction on a connection of the pool, committed when its ``with`` block ends and
before the method returns, so a submission is acknowledged only after it has committed. A submission first
locks its student's row (``SELECT … FOR UPDATE``): submissions for one student, from any server, take turns,
and each counts the attempts the ones before it committed (READ COMMITTED takes a fresh snapshot per
statement), so the attempt limit holds; the UNIQUE (student, question, attempt) constraint backs it. The rate
limits are counts of rows, so every server sees the same ones. Migrations run under an advisory lock, so
servers starting together apply each one once.

A server that cannot be reached (down, restarting, refusing connections, shut down by its administrator, or
killed with a transaction in flight) raises StoreUnavailable: the API answers 503 with Retry-After, and the
transaction was rolled back, or it committed without the answer coming back (then the caller was not told
it landed; a submission sent again counts the attempt already there). The pool waits at most
``POOL_WAIT_S`` for a connection, checks each one before lending it, and gives up reconnecting after
``RECONNECT_S``, so that the next request starts afresh: a server started again is used again without
restarting the app.
"""
from __future__ import annotations

import json
import os
import time

import psycopg
from psycopg.conninfo import conninfo_to_dict
from psycopg_pool import ConnectionPool, PoolTimeout

from .lti_tables import LtiTables
from .migrations import LATEST, VERSION_TABLE, SchemaTooNew, pending
from .records import (STUDENT_COLUMNS, SUBMISSION_COLUMNS, AssignmentRecord, StoreUnavailable, StudentRecord,
                      Submission, no_such_student, refuse_attempt, student_record, submission_record, unavailable_on)

POOL_SIZE = int(os.environ.get("MDL_DATABASE_POOL", "8"))      # connections per worker process
CONNECT_TIMEOUT_S = 10
POOL_WAIT_S = 5.0          # a request waits this long for a connection, then StoreUnavailable (503)
RECONNECT_S = 10.0         # the pool's reconnection backoff gives up after this; the next request tries again
MIGRATION_LOCK = 0x6D646C                                      # pg_advisory_xact_lock key ("mdl")


def where(url: str) -> str:
    """The server and database a URL names, without its password (for messages)."""
    try:
        parts = conninfo_to_dict(url)
    except psycopg.ProgrammingError:
        return "PostgreSQL (an unreadable MDL_DATABASE_URL)"
    return (f"PostgreSQL {parts.get('user', '')}@{parts.get('host', '')}:{parts.get('port', 5432)}"
            f"/{parts.get('dbname', '')}")


def unavailable(error: BaseException) -> bool:
    """Whether `error` says the server cannot be used now (psycopg's OperationalError: connection refused or
    lost, admin shutdown, starting up, a pool timeout; or a read-only server), rather than a bug."""
    return isinstance(error, (psycopg.OperationalError, psycopg.errors.ReadOnlySqlTransaction))


@unavailable_on(unavailable)
class PostgresStore(LtiTables):
    """AssignmentStore on the PostgreSQL at ``url``. StoreUnavailable (naming the server and the reason) when it
    cannot be reached, migrated or written."""

    def __init__(self, url: str, pool_size: int = POOL_SIZE):
        self.url, self.where = url, where(url)
        try:
            with psycopg.connect(url, connect_timeout=CONNECT_TIMEOUT_S) as connection:
                self._migrate(connection)
        except (psycopg.Error, SchemaTooNew) as error:
            raise StoreUnavailable(f"cannot use the database {self.where}: {error}".strip()) from error
        self._pool = ConnectionPool(url, min_size=1, max_size=pool_size, name="mdl", open=True,
                                    check=ConnectionPool.check_connection,     # a connection the server dropped
                                    kwargs={"connect_timeout": CONNECT_TIMEOUT_S},  # is replaced, not used
                                    timeout=POOL_WAIT_S, reconnect_timeout=RECONNECT_S)

    def close(self) -> None:
        self._pool.close()

    @staticmethod
    def _migrate(connection: psycopg.Connection) -> None:
        """Apply the pending migrations in one transaction, holding the advisory lock."""
        with connection.transaction():
            connection.execute("SELECT pg_advisory_xact_lock(%s)", (MIGRATION_LOCK,))
            if connection.execute("SELECT to_regclass('schema_version')").fetchone()[0] is None:
                connection.execute(VERSION_TABLE["postgres"])     # (skipped when there: a read-only server opens)
            current = connection.execute("SELECT COALESCE(MAX(version), 0) FROM schema_version").fetchone()[0]
            for migration in pending(current):
                for statement in migration.statements("postgres"):
                    connection.execute(statement)
                connection.execute("INSERT INTO schema_version VALUES (%s, %s, %s)",
                                   (migration.number, migration.what, time.time()))

    def schema_version(self) -> int:
        return self._one("SELECT MAX(version) FROM schema_version")[0]

    def applied_versions(self) -> list[int]:
        with self._pool.connection() as connection:
            return [row[0] for row in connection.execute("SELECT version FROM schema_version ORDER BY 1")]

    def check(self) -> None:
        """StoreUnavailable unless the database takes a write now (a read-only server or transaction refuses)."""
        try:
            with self._pool.connection(timeout=CONNECT_TIMEOUT_S) as connection:
                connection.execute("UPDATE schema_version SET what = what WHERE version = %s", (LATEST,))
        except (psycopg.Error, PoolTimeout) as error:
            raise StoreUnavailable(f"cannot write the database {self.where}: {error}") from error

    def _one(self, query: str, args: tuple = ()):
        with self._pool.connection() as connection:
            return connection.execute(query, args).fetchone()

    def create(self, record: AssignmentRecord) -> None:
        with self._pool.connection() as connection:
            connection.execute(
                "INSERT INTO assignments (id, token_hash, created_at, spec, roster_locked, client) "
                "VALUES (%s, %s, %s, %s, %s, %s)", (record.id, record.token_hash, record.created_at,
                                                    json.dumps(record.spec), record.roster_locked, record.client))

    def assignment(self, assignment_id: str) -> AssignmentRecord | None:
        row = self._one("SELECT id, token_hash, created_at, spec, roster_locked, client FROM assignments "
                        "WHERE id = %s", (assignment_id,))
        return None if row is None else AssignmentRecord(row[0], row[1], row[2], json.loads(row[3]), row[4], row[5])

    def set_roster_locked(self, assignment_id: str, locked: bool) -> None:
        with self._pool.connection() as connection:
            connection.execute("UPDATE assignments SET roster_locked = %s WHERE id = %s", (locked, assignment_id))

    def recent_assignments_by_client(self, client: str, since: float) -> int:
        return self._one("SELECT COUNT(*) FROM assignments WHERE client = %s AND created_at >= %s",
                         (client, since))[0]

    def replace_token(self, assignment_id: str, old_hash: str, new_hash: str) -> bool:
        """Put a new results token's hash in place of ``old_hash``; False if the assignment has another one (a
        replacement at the same moment won)."""
        with self._pool.connection() as connection:
            return connection.execute("UPDATE assignments SET token_hash = %s WHERE id = %s AND token_hash = %s",
                                      (new_hash, assignment_id, old_hash)).rowcount == 1

    def recent_registrations_by_client(self, client: str, since: float) -> int:
        return self._one("SELECT COUNT(*) FROM students WHERE client = %s AND first_seen >= %s", (client, since))[0]

    def register(self, assignment_id: str, student: StudentRecord, client: str = "") -> tuple[StudentRecord, bool]:
        """The student as stored, and whether this call created them: a second registration under the same
        key (even at the same moment, from another server) changes nothing. ``client``: the address that
        registered them ("" for the instructor's roster)."""
        with self._pool.connection() as connection:
            row = connection.execute(
                "INSERT INTO students (assignment_id, key, name, variant, parameters, first_seen, secret_hash, "
                "on_roster, client) VALUES (%s, %s, %s, %s, %s, %s, %s, %s, %s) "
                f"ON CONFLICT (assignment_id, key) DO NOTHING RETURNING {STUDENT_COLUMNS}",
                (assignment_id, student.key, student.name, student.variant, json.dumps(student.parameters),
                 student.first_seen, student.secret_hash, student.on_roster, client)).fetchone()
            created = row is not None
            if not created:
                row = connection.execute(f"SELECT {STUDENT_COLUMNS} FROM students WHERE assignment_id = %s "
                                         "AND key = %s", (assignment_id, student.key)).fetchone()
        return student_record(row), created

    def _students(self, condition: str, args: tuple) -> list[StudentRecord]:
        with self._pool.connection() as connection:
            rows = connection.execute(f"SELECT {STUDENT_COLUMNS} FROM students {condition}", args).fetchall()
        return [student_record(row) for row in rows]

    def student(self, assignment_id: str, key: str) -> StudentRecord | None:
        rows = self._students("WHERE assignment_id = %s AND key = %s", (assignment_id, key))
        return rows[0] if rows else None

    def student_by_secret(self, assignment_id: str, secret_hash: str) -> StudentRecord | None:
        rows = self._students("WHERE assignment_id = %s AND secret_hash = %s", (assignment_id, secret_hash))
        return rows[0] if rows else None

    def students(self, assignment_id: str) -> list[StudentRecord]:
        return self._students("WHERE assignment_id = %s ORDER BY first_seen, key", (assignment_id,))

    def set_secret(self, assignment_id: str, key: str, secret_hash: str | None) -> bool:
        with self._pool.connection() as connection:
            return connection.execute("UPDATE students SET secret_hash = %s WHERE assignment_id = %s AND key = %s",
                                      (secret_hash, assignment_id, key)).rowcount == 1

    def claim_secret(self, assignment_id: str, key: str, secret_hash: str) -> bool:
        """Give the student this secret only if they have none (one conditional UPDATE: of two claims at once,
        exactly one succeeds)."""
        with self._pool.connection() as connection:
            return connection.execute("UPDATE students SET secret_hash = %s WHERE assignment_id = %s AND key = %s "
                                      "AND secret_hash IS NULL", (secret_hash, assignment_id, key)).rowcount == 1

    def delete_student(self, assignment_id: str, key: str) -> bool:
        """The student and every submission of theirs, in one transaction; the student's row is locked first,
        as a submission locks it, so a submission in flight lands before the deletion or not at all."""
        with self._pool.connection() as connection:
            if connection.execute("SELECT 1 FROM students WHERE assignment_id = %s AND key = %s FOR UPDATE",
                                  (assignment_id, key)).fetchone() is None:
                return False
            connection.execute("DELETE FROM submissions WHERE assignment_id = %s AND student_key = %s",
                               (assignment_id, key))
            connection.execute("DELETE FROM students WHERE assignment_id = %s AND key = %s", (assignment_id, key))
        return True

    def submit(self, assignment_id: str, key: str, question: str, answer: float, correct: bool,
               attempts_allowed: int, at: float, client: str, correct_value: float | None = None) -> Submission:
        """Record one attempt and the student's totals in one transaction, holding the student's row;
        AttemptRefused if none is left or the student is not registered."""
        with self._pool.connection() as connection:
            if connection.execute("SELECT 1 FROM students WHERE assignment_id = %s AND key = %s FOR UPDATE",
                                  (assignment_id, key)).fetchone() is None:
                raise no_such_student()
            used, solved = connection.execute(
                "SELECT COUNT(*), COALESCE(BOOL_OR(correct), FALSE) FROM submissions "
                "WHERE assignment_id = %s AND student_key = %s AND question = %s",
                (assignment_id, key, question)).fetchone()
            refuse_attempt(used, solved, attempts_allowed)
            connection.execute(
                "INSERT INTO submissions (assignment_id, student_key, question, answer, correct, correct_value, "
                "attempt, at, client) VALUES (%s, %s, %s, %s, %s, %s, %s, %s, %s)",
                (assignment_id, key, question, answer, correct, correct_value, used + 1, at, client))
            connection.execute(
                "UPDATE students SET attempts = attempts + 1, solved = solved + %s, last_at = %s "
                "WHERE assignment_id = %s AND key = %s", (int(correct), at, assignment_id, key))
        return Submission(key, question, answer, correct, used + 1, at, correct_value)

    def submissions(self, assignment_id: str, key: str | None = None) -> list[Submission]:
        query = (f"SELECT {SUBMISSION_COLUMNS} FROM submissions WHERE assignment_id = %s"
                 + (" AND student_key = %s" if key is not None else "") + " ORDER BY id")
        with self._pool.connection() as connection:
            rows = connection.execute(query, (assignment_id,) if key is None else (assignment_id, key)).fetchall()
        return [submission_record(row) for row in rows]

    def recent_by_client(self, client: str, since: float) -> int:
        return self._one("SELECT COUNT(*) FROM submissions WHERE client = %s AND at >= %s", (client, since))[0]

    def variant_answers(self, assignment_id: str, variant: int) -> dict | None:
        row = self._one("SELECT answers FROM variant_answers WHERE assignment_id = %s AND variant = %s",
                        (assignment_id, variant))
        return None if row is None else json.loads(row[0])

    def put_variant_answers(self, assignment_id: str, variant: int, answers: dict) -> None:
        """Store (or replace) a variant's answers: question id → correct value or the error text."""
        with self._pool.connection() as connection:
            connection.execute(
                "INSERT INTO variant_answers (assignment_id, variant, answers) VALUES (%s, %s, %s) "
                "ON CONFLICT (assignment_id, variant) DO UPDATE SET answers = excluded.answers",
                (assignment_id, variant, json.dumps(answers)))
