"""A database that cannot be written now: the store raises StoreUnavailable, and the API answers 503.

1. SQLite on a full file (``PRAGMA max_page_count``, which SQLite enforces as it would a full disk: SQLITE_FULL,
   "database or disk is full"): the store raises StoreUnavailable naming the file and the reason, rolls the
   transaction back cleanly (no "cannot rollback - no transaction is active" in its place), keeps nothing of
   it, and takes writes again once there is room.
2. The API on a really full disk (a 2 MB tmpfs mounted for the test, filled to the last byte; root only):
   a submission gets 503 with Retry-After, a JSON reason and the security headers, the log holds one line
   naming the reason and no traceback; once there is room the same student submits again and the attempt
   counts from 1 (the refused one was not stored).
3. The other failures of a store (a PostgreSQL server down, refusing connections, shut down by its
   administrator) are StoreUnavailable too, and the same 503.
"""
from __future__ import annotations

import logging
import os
import sqlite3
import subprocess
import uuid
from pathlib import Path

import psycopg
import pytest
from fastapi.testclient import TestClient

from server.classroom import assignment_store
from server.api.app import app
from server.api.security import SECURITY_HEADERS
from server.classroom.store import AssignmentRecord, SQLiteStore, StoreUnavailable, StudentRecord
from server.classroom.store.postgres import unavailable as postgres_unavailable

API = "/api/v1/assignments"
CRANK = {"scene": "transfer-functions", "variant": "slider_crank",
         "sliders": {"lambda": {"vary": {"min": 2.5, "max": 5.0}}},
         "questions": [{"id": "u31_max"}, {"id": "du31_min"}], "attempts": 3}


def record(number: int, spec_bytes: int = 100) -> AssignmentRecord:
    return AssignmentRecord(f"a{number}", "hash", 1.0, {"padding": "x" * spec_bytes})


def test_a_full_sqlite_file_is_store_unavailable_and_rolled_back_cleanly(tmp_path):
    store = SQLiteStore(tmp_path / "classroom.sqlite3")
    store.create(record(0))
    store.register("a0", StudentRecord("ivan", "Ivan", 0, {}, 1.0))
    connection = store._connection()         # this thread's connection: the one the next calls use
    pages = connection.execute("PRAGMA page_count").fetchone()[0]
    connection.execute(f"PRAGMA max_page_count = {pages}")      # the file may not grow: a full disk to SQLite
    with pytest.raises(StoreUnavailable, match=f"cannot use the database {tmp_path / 'classroom.sqlite3'}: "
                                               "database or disk is full"):
        store.create(record(1, spec_bytes=200_000))
    assert not connection.in_transaction
    assert store.assignment("a1") is None                      # nothing of it was kept
    assert store.assignment("a0") is not None                  # and the store still reads
    with pytest.raises(StoreUnavailable, match="disk is full"):
        store.create(record(2, spec_bytes=200_000))            # and refuses again the same way
    connection.execute(f"PRAGMA max_page_count = {10 * pages + 1000}")
    store.create(record(3, spec_bytes=200_000))                # room again: the same store writes
    assert store.assignment("a3").spec["padding"] == "x" * 200_000
    assert store.submit("a0", "ivan", "q", 1.0, False, 3, 2.0, "c").attempt == 1


def test_a_bug_in_a_statement_is_not_called_unavailable(tmp_path):
    """Only the errors of a database that cannot be used now become StoreUnavailable; a bug stays a bug."""
    store = SQLiteStore(tmp_path / "classroom.sqlite3")
    store.create(record(0))
    with pytest.raises(sqlite3.IntegrityError):
        store.create(record(0))                                # the same id twice


@pytest.mark.parametrize("error", [psycopg.OperationalError("connection refused"),
                                   psycopg.errors.AdminShutdown("terminating connection due to administrator "
                                                                "command"),
                                   psycopg.errors.CannotConnectNow("the database system is starting up")])
def test_a_postgresql_server_down_is_store_unavailable(error):
    assert postgres_unavailable(error)


def test_a_postgresql_bug_is_not_called_unavailable():
    assert not postgres_unavailable(psycopg.errors.UniqueViolation("duplicate key"))
    assert not postgres_unavailable(ValueError("not a database error"))


# --- the API on a really full disk --------------------------------------------------------------------------

@pytest.fixture()
def tiny_disk(tmp_path):
    """A 2 MB tmpfs mounted for the test (root only), unmounted afterwards."""
    if os.geteuid() != 0:
        pytest.skip("mounting a tmpfs needs root; the store's part is checked with max_page_count above")
    mount_point = tmp_path / "tiny"
    mount_point.mkdir()
    mounted = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=2m", "tmpfs", str(mount_point)],
                             capture_output=True, text=True)
    if mounted.returncode != 0:
        pytest.skip(f"cannot mount a tmpfs here: {mounted.stderr.strip()}")
    try:
        yield mount_point
    finally:
        subprocess.run(["umount", "-l", str(mount_point)], check=True)


def fill(directory: Path) -> Path:
    """Write zeros into a file of `directory` until its filesystem has no byte left."""
    filler = directory / f"filler-{uuid.uuid4().hex}"
    with open(filler, "wb", buffering=0) as out:
        for size in (65536, 4096, 512, 1):
            try:
                while True:
                    out.write(b"\0" * size)
            except OSError:
                continue
    return filler


@pytest.fixture()
def client_on(tiny_disk, monkeypatch):
    monkeypatch.setenv("MDL_DATA_DIR", str(tiny_disk))
    monkeypatch.delenv("MDL_DATABASE_URL", raising=False)
    assignment_store.store.cache_clear()
    yield TestClient(app, raise_server_exceptions=False)
    assignment_store.store.cache_clear()


def test_a_full_disk_answers_503_with_retry_after_and_the_reason_logged_once(client_on, tiny_disk, caplog):
    client = client_on
    created = client.post(API, json=CRANK).json()
    registered = client.post(f"{API}/{created['id']}/students", json={"name": "Ivan Petrov"})
    headers = {"Authorization": f"Bearer {registered.json()['secret']}"}
    submissions = f"{API}/{created['id']}/submissions"
    assert client.post(submissions, json={"question": "u31_max", "answer": 1000.0}, headers=headers).status_code == 200
    with sqlite3.connect(tiny_disk / assignment_store.DATABASE_FILE) as connection:
        connection.execute("PRAGMA wal_checkpoint(TRUNCATE)")   # the next commit must grow the WAL file
    filler = fill(tiny_disk)
    caplog.clear()
    with caplog.at_level(logging.WARNING, logger="uvicorn.error"):
        refused = client.post(submissions, json={"question": "du31_min", "answer": 1000.0}, headers=headers)
    assert refused.status_code == 503, refused.text
    assert int(refused.headers["retry-after"]) > 0
    for name, value in SECURITY_HEADERS.items():
        assert refused.headers[name] == value
    assert refused.json()["detail"][0]["type"] == "store_unavailable"
    assert "try again" in refused.json()["detail"][0]["msg"]
    lines = [r for r in caplog.records if r.name == "uvicorn.error"]
    assert len(lines) == 1, [r.getMessage() for r in lines]
    assert "disk is full" in lines[0].getMessage() and "/submissions" in lines[0].getMessage()
    assert lines[0].exc_info is None and lines[0].levelno == logging.WARNING
    filler.unlink()                                 # room again: the same server, the same student
    accepted = client.post(submissions, json={"question": "du31_min", "answer": 1000.0}, headers=headers)
    assert accepted.status_code == 200, accepted.text
    assert accepted.json()["attempt"] == 1          # the refused answer was not stored
