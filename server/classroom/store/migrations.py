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
