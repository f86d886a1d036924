"""The schema as numbered migrations, one list for both backends.

Each migration is applied once, in order, inside the transaction that records its number in the table
``schema_version``; a backend holds a lock while it migrates (SQLite ``BEGIN IMMEDIATE``, PostgreSQL an
advisory lock), so servers starting together apply each one exactly once. A SQLite file made before the
schema was versioned (main before the numbered migrations) has no ``schema_version``: ``legacy_version`` tells which
migrations its tables already contain, and the rest are applied on opening.
"""
from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Migration:
    number: int
    what: str
    sqlite: str
    postgres: str

    def statements(self, dialect: str) -> list[str]:
        return [part.strip() for part in getattr(self, dialect).split(";") if part.strip()]


MIGRATIONS = (
    Migration(1, "assignments, students and their submissions", """
        CREATE TABLE assignments (
            id TEXT PRIMARY KEY,
            token_hash TEXT NOT NULL,
            created_at REAL NOT NULL,
            spec TEXT NOT NULL);
        CREATE TABLE students (
            assignment_id TEXT NOT NULL REFERENCES assignments(id),
            key TEXT NOT NULL,
            name TEXT NOT NULL,
            variant INTEGER NOT NULL,
            parameters TEXT NOT NULL,
            first_seen REAL NOT NULL,
            attempts INTEGER NOT NULL DEFAULT 0,
            solved INTEGER NOT NULL DEFAULT 0,
            last_at REAL,
            PRIMARY KEY (assignment_id, key));
        CREATE TABLE submissions (
            id INTEGER PRIMARY KEY,
            assignment_id TEXT NOT NULL,
            student_key TEXT NOT NULL,
            question TEXT NOT NULL,
            answer REAL NOT NULL,
            correct INTEGER NOT NULL CHECK (correct IN (0, 1)),
            attempt INTEGER NOT NULL CHECK (attempt >= 1),
            at REAL NOT NULL,
            client TEXT NOT NULL,
            UNIQUE (assignment_id, student_key, question, attempt),
            FOREIGN KEY (assignment_id, student_key) REFERENCES students(assignment_id, key));
        CREATE INDEX submissions_by_client ON submissions (client, at)
    """, """
        CREATE TABLE assignments (
            id TEXT PRIMARY KEY,
            token_hash TEXT NOT NULL,
            created_at DOUBLE PRECISION NOT NULL,
            spec TEXT NOT NULL);
        CREATE TABLE students (
            assignment_id TEXT NOT NULL REFERENCES assignments(id),
            key TEXT NOT NULL,
            name TEXT NOT NULL,
            variant INTEGER NOT NULL,
            parameters TEXT NOT NULL,
            first_seen DOUBLE PRECISION NOT NULL,
            attempts INTEGER NOT NULL DEFAULT 0,
            solved INTEGER NOT NULL DEFAULT 0,
            last_at DOUBLE PRECISION,
            PRIMARY KEY (assignment_id, key));
        CREATE TABLE submissions (
            id BIGINT GENERATED ALWAYS AS IDENTITY PRIMARY KEY,
            assignment_id TEXT NOT NULL,
            student_key TEXT NOT NULL,
            question TEXT NOT NULL,
            answer DOUBLE PRECISION NOT NULL,
            correct BOOLEAN NOT NULL,
            attempt INTEGER NOT NULL CHECK (attempt >= 1),
            at DOUBLE PRECISION NOT NULL,
            client TEXT NOT NULL,
            UNIQUE (assignment_id, student_key, question, attempt),
            FOREIGN KEY (assignment_id, student_key) REFERENCES students(assignment_id, key));
        CREATE INDEX submissions_by_client ON submissions (client, at)
    """),
    Migration(2, "each submission keeps the value it was checked against",
              "ALTER TABLE submissions ADD COLUMN correct_value REAL",
              "ALTER TABLE submissions ADD COLUMN correct_value DOUBLE PRECISION"),
    Migration(3, "identity: who made an assignment, its roster lock, students' secrets and the roster", """
        ALTER TABLE assignments ADD COLUMN roster_locked INTEGER NOT NULL DEFAULT 0;
        ALTER TABLE assignments ADD COLUMN client TEXT NOT NULL DEFAULT '';
        CREATE INDEX assignments_by_client ON assignments (client, created_at);
        ALTER TABLE students ADD COLUMN secret_hash TEXT;
        ALTER TABLE students ADD COLUMN on_roster INTEGER NOT NULL DEFAULT 0;
        CREATE UNIQUE INDEX students_by_secret ON students (assignment_id, secret_hash)
    """, """
        ALTER TABLE assignments ADD COLUMN roster_locked BOOLEAN NOT NULL DEFAULT FALSE;
        ALTER TABLE assignments ADD COLUMN client TEXT NOT NULL DEFAULT '';
        CREATE INDEX assignments_by_client ON assignments (client, created_at);
        ALTER TABLE students ADD COLUMN secret_hash TEXT;
        ALTER TABLE students ADD COLUMN on_roster BOOLEAN NOT NULL DEFAULT FALSE;
        CREATE UNIQUE INDEX students_by_secret ON students (assignment_id, secret_hash)
    """),
    Migration(4, "each variant's answers, computed once and shared by every server", """
        CREATE TABLE variant_answers (
            assignment_id TEXT NOT NULL REFERENCES assignments(id),
            variant INTEGER NOT NULL,
            answers TEXT NOT NULL,
            PRIMARY KEY (assignment_id, variant))
    """, """
        CREATE TABLE variant_answers (
            assignment_id TEXT NOT NULL REFERENCES assignments(id),
            variant INTEGER NOT NULL,
            answers TEXT NOT NULL,
            PRIMARY KEY (assignment_id, variant))
    """),
    Migration(5, "each student keeps the address that registered them (the registration rate limit)", """
        ALTER TABLE students ADD COLUMN client TEXT NOT NULL DEFAULT '';
        CREATE INDEX students_by_client ON students (client, first_seen)
    """, """
        ALTER TABLE students ADD COLUMN client TEXT NOT NULL DEFAULT '';
        CREATE INDEX students_by_client ON students (client, first_seen)
    """),
    Migration(6, "LTI 1.3: platforms, the tool's key pair, launch state, LMS users as students, placements, line "
                 "items and scores still to post", """
        CREATE TABLE lti_platforms (
            id TEXT PRIMARY KEY,
            issuer TEXT NOT NULL,
            client_id TEXT NOT NULL,
            name TEXT NOT NULL,
            auth_login_url TEXT NOT NULL,
            auth_token_url TEXT NOT NULL,
            key_set_url TEXT NOT NULL,
            deployment_ids TEXT NOT NULL,
            created_at REAL NOT NULL,
            UNIQUE (issuer, client_id));
        CREATE TABLE lti_tool_keys (
            slot INTEGER PRIMARY KEY,
            kid TEXT NOT NULL,
            private_pem TEXT NOT NULL,
            created_at REAL NOT NULL);
        CREATE TABLE lti_launch_state (
            key TEXT PRIMARY KEY,
            value TEXT NOT NULL,
            expires_at REAL NOT NULL);
        CREATE INDEX lti_launch_state_by_expiry ON lti_launch_state (expires_at);
        CREATE TABLE lti_learners (
            platform_id TEXT NOT NULL REFERENCES lti_platforms(id),
            sub TEXT NOT NULL,
            assignment_id TEXT NOT NULL REFERENCES assignments(id),
            student_key TEXT NOT NULL,
            context_id TEXT NOT NULL,
            ags TEXT,
            PRIMARY KEY (platform_id, sub, assignment_id));
        CREATE INDEX lti_learners_by_student ON lti_learners (assignment_id, student_key);
        CREATE TABLE lti_placements (
            platform_id TEXT NOT NULL REFERENCES lti_platforms(id),
            context_id TEXT NOT NULL,
            assignment_id TEXT NOT NULL REFERENCES assignments(id),
            title TEXT NOT NULL,
            placed_at REAL NOT NULL,
            PRIMARY KEY (platform_id, context_id, assignment_id));
        CREATE TABLE lti_line_items (
            platform_id TEXT NOT NULL REFERENCES lti_platforms(id),
            context_id TEXT NOT NULL,
            assignment_id TEXT NOT NULL REFERENCES assignments(id),
            url TEXT NOT NULL,
            PRIMARY KEY (platform_id, context_id, assignment_id));
        CREATE TABLE lti_passbacks (
            assignment_id TEXT NOT NULL REFERENCES assignments(id),
            student_key TEXT NOT NULL,
            queued_at REAL NOT NULL,
            tries INTEGER NOT NULL,
            retry_at REAL NOT NULL,
            last_error TEXT,
            PRIMARY KEY (assignment_id, student_key));
        CREATE INDEX lti_passbacks_by_retry ON lti_passbacks (retry_at)
    """, """
        CREATE TABLE lti_platforms (
            id TEXT PRIMARY KEY,
            issuer TEXT NOT NULL,
            client_id TEXT NOT NULL,
            name TEXT NOT NULL,
            auth_login_url TEXT NOT NULL,
            auth_token_url TEXT NOT NULL,
            key_set_url TEXT NOT NULL,
            deployment_ids TEXT NOT NULL,
            created_at DOUBLE PRECISION NOT NULL,
            UNIQUE (issuer, client_id));
        CREATE TABLE lti_tool_keys (
            slot INTEGER PRIMARY KEY,
            kid TEXT NOT NULL,
            private_pem TEXT NOT NULL,
            created_at DOUBLE PRECISION NOT NULL);
        CREATE TABLE lti_launch_state (
            key TEXT PRIMARY KEY,
            value TEXT NOT NULL,
            expires_at DOUBLE PRECISION NOT NULL);
        CREATE INDEX lti_launch_state_by_expiry ON lti_launch_state (expires_at);
        CREATE TABLE lti_learners (
            platform_id TEXT NOT NULL REFERENCES lti_platforms(id),
            sub TEXT NOT NULL,
            assignment_id TEXT NOT NULL REFERENCES assignments(id),
            student_key TEXT NOT NULL,
            context_id TEXT NOT NULL,
            ags TEXT,
            PRIMARY KEY (platform_id, sub, assignment_id));
        CREATE INDEX lti_learners_by_student ON lti_learners (assignment_id, student_key);
        CREATE TABLE lti_placements (
            platform_id TEXT NOT NULL REFERENCES lti_platforms(id),
            context_id TEXT NOT NULL,
            assignment_id TEXT NOT NULL REFERENCES assignments(id),
            title TEXT NOT NULL,
            placed_at DOUBLE PRECISION NOT NULL,
            PRIMARY KEY (platform_id, context_id, assignment_id));
        CREATE TABLE lti_line_items (
            platform_id TEXT NOT NULL REFERENCES lti_platforms(id),
            context_id TEXT NOT NULL,
            assignment_id TEXT NOT NULL REFERENCES assignments(id),
            url TEXT NOT NULL,
            PRIMARY KEY (platform_id, context_id, assignment_id));
        CREATE TABLE lti_passbacks (
            assignment_id TEXT NOT NULL REFERENCES assignments(id),
            student_key TEXT NOT NULL,
            queued_at DOUBLE PRECISION NOT NULL,
            tries INTEGER NOT NULL,
            retry_at DOUBLE PRECISION NOT NULL,
            last_error TEXT,
            PRIMARY KEY (assignment_id, student_key));
        CREATE INDEX lti_passbacks_by_retry ON lti_passbacks (retry_at)
    """),
)
LATEST = MIGRATIONS[-1].number
VERSION_TABLE = {
    "sqlite": "CREATE TABLE IF NOT EXISTS schema_version "
              "(version INTEGER PRIMARY KEY, what TEXT NOT NULL, applied_at REAL NOT NULL)",
    "postgres": "CREATE TABLE IF NOT EXISTS schema_version "
                "(version INTEGER PRIMARY KEY, what TEXT NOT NULL, applied_at DOUBLE PRECISION NOT NULL)",
}


class SchemaTooNew(Exception):
    """The database was migrated by a newer server than this one."""


def pending(current: int) -> list[Migration]:
    """The migrations a database at version ``current`` still needs, in order; SchemaTooNew when it is past
    the last one this code knows (a server older than the others must not write a schema it does not know)."""
    if current > LATEST:
        raise SchemaTooNew(f"the database's schema is at version {current}, newer than this server's {LATEST}: "
                           f"update this server")
    return [migration for migration in MIGRATIONS if migration.number > current]


def legacy_version(tables: set[str], submission_columns: set[str]) -> int:
    """The version of a database made before ``schema_version`` existed, from what its tables hold:
    0 for an empty one, 1 for the first release, 2 once submissions kept their correct value."""
    if "assignments" not in tables:
        return 0
    return 2 if "correct_value" in submission_columns else 1
