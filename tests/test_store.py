"""The assignment store: one suite run against every backend (SQLite in a temporary file; PostgreSQL on a real
server that tests/postgres.py starts, a fresh database per test).

Each backend is checked against the interface's promises (server/classroom/store/records.py), not against
the other backend: records come back as stored, a second registration changes nothing, a deleted student
takes their submissions along, the attempt limit holds when separate store instances (separate
connections, as separate servers have) submit for one student at once, and the schema migrates forward
from main's file and applies each numbered migration exactly once.
"""
from __future__ import annotations

import sqlite3
import subprocess
import sys
import threading
from pathlib import Path

import psycopg
import pytest

from server.classroom.store import (AssignmentRecord, AttemptRefused, SQLiteStore, StoreUnavailable, StudentRecord,
                                    Submission)
from server.classroom.store.migrations import LATEST, MIGRATIONS
from server.classroom.store.postgres import PostgresStore

from postgres import fresh_database, postgres_url  # noqa: F401 (the session's PostgreSQL server)

BACKENDS = ["sqlite", "postgresql"]
REPO = Path(__file__).resolve().parents[1]

# main's schema before versioning (server/classroom/storage.py at d0a7cb5), verbatim
MAIN_SCHEMA = """
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


def open_at(location: str):
    """A new store instance on the database at ``location`` (a PostgreSQL URL or a SQLite file's path)."""
    return PostgresStore(location, pool_size=2) if location.startswith("postgresql://") else SQLiteStore(location)


@pytest.fixture(params=BACKENDS)
def database(request, tmp_path) -> str:
    """One fresh database: a SQLite file's path, or a new database on the session's PostgreSQL."""
    if request.param == "sqlite":
        return str(tmp_path / "classroom.sqlite3")
    return fresh_database(request.getfixturevalue("postgres_url"))


@pytest.fixture()
def open_store(database):
    """A function opening a new store instance (its own connections) on the test's database."""
    opened = []

    def open_one():
        opened.append(open_at(database))
        return opened[-1]

    yield open_one
    for store in opened:
        if isinstance(store, PostgresStore):
            store.close()


@pytest.fixture()
def store(open_store):
    store = open_store()
    store.create(AssignmentRecord("a1", "hash", 100.0, {"title": "Lab 5", "sliders": {"b": 1, "a": 2}},
                                  client="10.0.0.1"))
    return store


def ivan(**fields) -> StudentRecord:
    return StudentRecord("ivan", "Ivan", 3, {"delta": 0.025, "omega_mean": 50.0}, 101.0, **fields)


def test_an_assignment_comes_back_as_stored(store, open_store):
    assert store.assignment("a1") == AssignmentRecord("a1", "hash", 100.0, {"title": "Lab 5", "sliders": {"b": 1, "a": 2}},
                                                      roster_locked=False, client="10.0.0.1")
    assert list(open_store().assignment("a1").spec["sliders"]) == ["b", "a"]      # key order kept
    assert store.assignment("nope") is None
    with pytest.raises((sqlite3.IntegrityError, psycopg.IntegrityError)):
        store.create(AssignmentRecord("a1", "other", 0.0, {}))                      # ids are unique
    assert store.assignment("a1").token_hash == "hash"


def test_the_roster_lock(store):
    store.set_roster_locked("a1", True)
    assert store.assignment("a1").roster_locked is True
    store.set_roster_locked("a1", False)
    assert store.assignment("a1").roster_locked is False


def test_a_second_registration_changes_nothing(store):
    first, created = store.register("a1", ivan(secret_hash="s1", on_roster=True))
    assert created and first == ivan(secret_hash="s1", on_roster=True)
    again, created = store.register("a1", StudentRecord("ivan", "IVAN", 7, {"delta": 0.04}, 200.0, secret_hash="s2"))
    assert not created and again == first
    assert store.students("a1") == [first]


def test_students_come_in_the_order_they_came(store):
    store.register("a1", StudentRecord("zoya", "Zoya", 0, {}, 50.0))
    store.register("a1", ivan())
    store.register("a1", StudentRecord("anna", "Anna", 1, {}, 101.0))
    assert [s.key for s in store.students("a1")] == ["zoya", "anna", "ivan"]
    assert store.students("nope") == []


def test_a_student_is_found_by_their_secret_and_the_secret_can_be_reset(store):
    store.create(AssignmentRecord("a2", "hash", 100.0, {}))
    store.register("a1", ivan(secret_hash="old"))
    assert store.student_by_secret("a1", "old").key == "ivan"
    assert store.student_by_secret("a2", "old") is None                    # a secret opens one assignment only
    assert store.set_secret("a1", "ivan", "new") is True
    assert store.student_by_secret("a1", "old") is None
    assert store.student_by_secret("a1", "new") == ivan(secret_hash="new")
    assert store.set_secret("a1", "nobody", "x") is False
    assert store.set_secret("a1", "ivan", None) is True and store.student("a1", "ivan").secret_hash is None


def test_of_claims_on_a_student_without_a_secret_exactly_one_wins(store, open_store):
    """A name on the roster (no secret yet) claimed by eight students at once, each through a store instance of
    its own (as eight servers would): exactly one claim succeeds and the student holds that claim's secret."""
    store.register("a1", ivan(secret_hash=None))
    instances = [open_store() for _ in range(8)]
    start = threading.Barrier(len(instances))
    won = []

    def claim(k, instance):
        start.wait()
        if instance.claim_secret("a1", "ivan", f"secret-{k}"):
            won.append(k)

    threads = [threading.Thread(target=claim, args=(k, instance)) for k, instance in enumerate(instances)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join(timeout=120)
    assert len(won) == 1 and store.student("a1", "ivan").secret_hash == f"secret-{won[0]}"
    assert store.claim_secret("a1", "ivan", "late") is False                # a secret is never claimed over
    assert store.claim_secret("a1", "nobody", "x") is False


def test_deleting_a_student_takes_their_submissions(store):
    store.register("a1", ivan())
    store.register("a1", StudentRecord("anna", "Anna", 1, {}, 102.0))
    store.submit("a1", "ivan", "q", 1.0, False, 3, 110.0, "c")
    store.submit("a1", "anna", "q", 2.0, True, 3, 111.0, "c")
    assert store.delete_student("a1", "ivan") is True
    assert store.student("a1", "ivan") is None
    assert [s.student_key for s in store.submissions("a1")] == ["anna"]
    assert store.delete_student("a1", "ivan") is False
    with pytest.raises(AttemptRefused) as refused:
        store.submit("a1", "ivan", "q", 1.0, False, 3, 112.0, "c")
    assert refused.value.code == "no_such_student" and store.submissions("a1", "ivan") == []
    again, created = store.register("a1", ivan())
    assert created and again.attempts == 0                                 # a fresh start


def test_submissions_count_attempts_and_close_a_question(store, open_store):
    store.register("a1", ivan())
    first = store.submit("a1", "ivan", "q", 1.5, False, 2, 110.0, "c", 2.5)
    assert first == Submission("ivan", "q", 1.5, False, 1, 110.0, 2.5)
    assert store.submit("a1", "ivan", "q", 1.6, False, 2, 111.0, "c", 2.5).attempt == 2
    with pytest.raises(AttemptRefused) as refused:
        store.submit("a1", "ivan", "q", 2.5, True, 2, 112.0, "c", 2.5)
    assert refused.value.code == "no_attempts_left"
    assert store.submit("a1", "ivan", "r", 7.0, True, 2, 113.0, "c", 7.0).correct
    with pytest.raises(AttemptRefused) as refused:
        store.submit("a1", "ivan", "r", 7.0, True, 2, 114.0, "c", 7.0)
    assert refused.value.code == "already_right"
    assert [(s.question, s.attempt, s.correct) for s in store.submissions("a1", "ivan")] == [
        ("q", 1, False), ("q", 2, False), ("r", 1, True)]
    totals = open_store().student("a1", "ivan")                 # committed before submit returned
    assert (totals.attempts, totals.solved, totals.last_at) == (3, 1, 113.0)


def test_rate_limits_are_counted_in_the_database(store, open_store):
    store.register("a1", ivan())
    for at in (100.0, 130.0, 160.0):
        store.submit("a1", "ivan", "q", 1.0, False, 5, at, "10.0.0.9")
    other = open_store()                                                   # another server sees the same counts
    assert [other.recent_by_client("10.0.0.9", since) for since in (0.0, 130.0, 161.0)] == [3, 2, 0]
    assert other.recent_by_client("10.0.0.1", 0.0) == 0
    store.create(AssignmentRecord("a2", "hash", 140.0, {}, client="10.0.0.1"))
    store.create(AssignmentRecord("a3", "hash", 150.0, {}, client="10.0.0.2"))
    assert [other.recent_assignments_by_client("10.0.0.1", since) for since in (0.0, 120.0, 141.0)] == [2, 1, 0]


def test_registrations_are_counted_per_address_in_the_database(store, open_store):
    """The registration rate limit counts the students each address registered (the roster's carry no address)."""
    for k, at in enumerate((100.0, 130.0, 160.0)):
        store.register("a1", StudentRecord(f"s{k}", f"S{k}", 0, {}, at), client="10.0.0.9")
    store.register("a1", StudentRecord("r", "R", 0, {}, 150.0, on_roster=True))
    store.register("a1", StudentRecord("s0", "S0", 0, {}, 170.0), client="10.0.0.9")      # not created: not counted
    other = open_store()
    assert [other.recent_registrations_by_client("10.0.0.9", since) for since in (0.0, 130.0, 161.0)] == [3, 2, 0]
    assert other.recent_registrations_by_client("10.0.0.1", 0.0) == 0


def test_the_results_token_is_replaced_once_and_the_old_one_ends(store, open_store):
    assert store.replace_token("a1", "hash", "new-hash")
    assert open_store().assignment("a1").token_hash == "new-hash"          # committed, seen by another server
    assert not store.replace_token("a1", "hash", "third")                # a replacement of the old one: refused
    assert not store.replace_token("nope", "new-hash", "x")
    assert store.assignment("a1").token_hash == "new-hash"


def test_variant_answers_are_a_cache_shared_by_every_server(store, open_store):
    assert store.variant_answers("a1", 0) is None
    answers = {"flywheel_inertia": 0.1 + 0.2, "delta": 1e-300, "u31_max": "no answer: the mechanism does not turn"}
    store.put_variant_answers("a1", 0, answers)
    assert open_store().variant_answers("a1", 0) == answers                  # floats exact, texts kept
    assert store.variant_answers("a1", 1) is None
    store.put_variant_answers("a1", 0, {"flywheel_inertia": 2.0})
    assert store.variant_answers("a1", 0) == {"flywheel_inertia": 2.0}


def test_the_attempt_limit_holds_across_store_instances(store, open_store):
    """Twelve submitters, each with a store instance of its own (as twelve servers would have), submit a wrong
    answer for one student at once: exactly `attempts` land, numbered 1..attempts, and the totals agree."""
    store.register("a1", ivan())
    instances = [open_store() for _ in range(12)]
    start = threading.Barrier(len(instances))
    outcomes = []

    def one(instance):
        start.wait()
        try:
            outcomes.append(instance.submit("a1", "ivan", "q", 1.0, False, 3, 120.0, "c").attempt)
        except AttemptRefused as refused:
            outcomes.append(refused.code)
        except Exception as error:                      # a unique-constraint clash, a deadlock: shown, not lost
            outcomes.append(repr(error))

    threads = [threading.Thread(target=one, args=(instance,)) for instance in instances]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join(timeout=120)
    assert sorted(outcomes, key=str) == [1, 2, 3] + ["no_attempts_left"] * 9
    assert [s.attempt for s in store.submissions("a1")] == [1, 2, 3]
    assert store.student("a1", "ivan").attempts == 3


SUBMITTER = """
import sys
from server.classroom.store import AttemptRefused, SQLiteStore
location = sys.argv[1]
if location.startswith("postgresql://"):
    from server.classroom.store.postgres import PostgresStore
    store = PostgresStore(location, pool_size=1)
else:
    store = SQLiteStore(location)
print("ready", flush=True)
sys.stdin.readline()                                   # all start together
try:
    print(store.submit("a1", "ivan", "q", 1.0, False, 3, 120.0, "c").attempt)
except AttemptRefused as refused:
    print(refused.code)
"""


def test_the_attempt_limit_holds_across_processes(store, database):
    """Eight processes (eight servers), each with its own store, submit for one student at the same moment:
    exactly `attempts` are accepted."""
    store.register("a1", ivan())
    children = [subprocess.Popen([sys.executable, "-c", SUBMITTER, database], cwd=REPO, stdin=subprocess.PIPE,
                                 stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True) for _ in range(8)]
    try:
        for child in children:
            assert child.stdout.readline().strip() == "ready", child.stderr.read()
        for child in children:
            child.stdin.write("go\n")
            child.stdin.flush()
        outcomes = [child.communicate(timeout=120) for child in children]
    finally:
        for child in children:
            child.kill()
    assert sorted((out.strip() for out, _ in outcomes), key=str) == ["1", "2", "3"] + ["no_attempts_left"] * 5, \
        [err for _, err in outcomes]
    assert [s.attempt for s in store.submissions("a1")] == [1, 2, 3]


DIES_BETWEEN_THE_WRITES = """
import os, sys
import psycopg
from server.classroom.store.postgres import PostgresStore

store = PostgresStore(sys.argv[1], pool_size=1)
execute = psycopg.Connection.execute


def dies_before_the_totals(connection, query, *args, **kwargs):
    if str(query).startswith("UPDATE students"):
        os._exit(3)                                   # the attempt row is written, the totals are not
    return execute(connection, query, *args, **kwargs)


psycopg.Connection.execute = dies_before_the_totals
store.submit("a1", "ivan", "q", 2.0, False, 3, 121.0, "c")
"""


def test_a_death_between_the_two_writes_leaves_neither_on_postgresql(postgres_url):
    """A server process dying inside a submission on PostgreSQL (SQLite: tests/test_crash_safety.py) leaves
    neither the attempt row nor the totals: the transaction was never committed."""
    database = fresh_database(postgres_url)
    store = PostgresStore(database, pool_size=1)
    store.create(AssignmentRecord("a1", "hash", 100.0, {}))
    store.register("a1", ivan())
    store.submit("a1", "ivan", "q", 1.0, False, 3, 120.0, "c")
    child = subprocess.run([sys.executable, "-c", DIES_BETWEEN_THE_WRITES, database], cwd=REPO, timeout=120)
    assert child.returncode == 3
    assert [(s.answer, s.attempt) for s in store.submissions("a1")] == [(1.0, 1)]
    assert store.student("a1", "ivan").attempts == 1
    assert store.submit("a1", "ivan", "q", 3.0, False, 3, 122.0, "c").attempt == 2       # the row lock is free
    store.close()


def test_migrations_apply_once_and_opening_again_changes_nothing(open_store):
    """Every numbered migration is applied exactly once, whether stores open one after another or four at once."""
    stores = []
    threads = [threading.Thread(target=lambda: stores.append(open_store())) for _ in range(4)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join(timeout=120)
    assert len(stores) == 4
    again = open_store()
    assert again.schema_version() == LATEST == len(MIGRATIONS)
    assert again.applied_versions() == list(range(1, LATEST + 1))


def test_a_database_from_a_newer_server_is_refused(open_store, database):
    """A server that does not know the schema's latest migration must not write to it: it refuses to start."""
    open_store()
    if database.startswith("postgresql://"):
        with psycopg.connect(database, autocommit=True) as connection:
            connection.execute("INSERT INTO schema_version VALUES (%s, 'from the future', 0)", (LATEST + 1,))
    else:
        with sqlite3.connect(database) as connection:
            connection.execute("INSERT INTO schema_version VALUES (?, 'from the future', 0)", (LATEST + 1,))
    with pytest.raises(StoreUnavailable, match=f"schema is at version {LATEST + 1}, newer than this server's "
                                               f"{LATEST}: update this server"):
        open_store()


# --- SQLite: files made before the schema was versioned ---------------------------------------------------

def main_file(path, schema: str) -> None:
    """A database as main made it: one assignment, one student, one submission."""
    old = sqlite3.connect(path)
    old.executescript(schema)
    old.execute("INSERT INTO assignments VALUES ('a1', 'h', 0, '{\"title\": \"Lab 5\"}')")
    old.execute("INSERT INTO students (assignment_id, key, name, variant, parameters, first_seen, attempts) "
                "VALUES ('a1', 'ivan', 'Ivan', 0, '{}', 0, 1)")
    old.execute("INSERT INTO submissions (assignment_id, student_key, question, answer, correct, attempt, at, client) "
                "VALUES ('a1', 'ivan', 'q', 1.5, 0, 1, 0, 'c')")
    old.commit()
    old.close()


@pytest.mark.parametrize("schema", [MAIN_SCHEMA, MAIN_SCHEMA.replace("    correct_value REAL,\n", "")],
                         ids=["main", "before correct values"])
def test_a_file_made_by_main_migrates_forward(tmp_path, schema):
    """main's file (and the one before submissions kept their correct value) opens, keeps its rows and gains
    every later field; a second opening applies nothing again."""
    path = tmp_path / "old.sqlite3"
    main_file(path, schema)
    store = SQLiteStore(path)
    assert store.assignment("a1") == AssignmentRecord("a1", "h", 0, {"title": "Lab 5"}, False, "")
    assert store.student("a1", "ivan") == StudentRecord("ivan", "Ivan", 0, {}, 0, 1, 0, None, None, False)
    store.submit("a1", "ivan", "q", 2.5, True, 3, 1.0, "c", 2.51)
    assert [(s.answer, s.attempt, s.correct_value) for s in store.submissions("a1")] == [(1.5, 1, None),
                                                                                        (2.5, 2, 2.51)]
    assert store.set_secret("a1", "ivan", "s") and store.student_by_secret("a1", "s").key == "ivan"
    store.put_variant_answers("a1", 0, {"q": 2.51})
    reopened = SQLiteStore(path)
    assert reopened.schema_version() == LATEST and reopened.applied_versions() == list(range(1, LATEST + 1))
    assert reopened.submissions("a1")[1].correct_value == 2.51 and reopened.variant_answers("a1", 0) == {"q": 2.51}
    assert sqlite3.connect(path).execute("PRAGMA integrity_check").fetchone()[0] == "ok"



OPEN_AND_CHECK = """
import sys
from pathlib import Path
from server.classroom.store import SQLiteStore
store = SQLiteStore(Path(sys.argv[1]))
store.check()
print(store.schema_version())
"""


def test_the_workers_of_a_server_started_on_a_new_file_all_open_it(tmp_path):
    """Several processes open one new file at once (the workers of `python3 -m server --workers N` on a fresh
    data folder): each migrates or finds it migrated and can write; none fails with "database is locked"
    (switching a new file to WAL can be refused at once while another connection does the same:
    SQLiteStore._open tries again)."""
    repo = Path(__file__).resolve().parents[1]
    for round_ in range(3):
        path = tmp_path / f"round{round_}" / "classroom.sqlite3"
        processes = [subprocess.Popen([sys.executable, "-c", OPEN_AND_CHECK, str(path)], cwd=repo,
                                      stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True) for _ in range(6)]
        outcomes = [process.communicate(timeout=120) for process in processes]
        assert [process.returncode for process in processes] == [0] * 6, [err[-500:] for _, err in outcomes]
        assert {out.strip() for out, _ in outcomes} == {str(SQLiteStore(path).schema_version())}
