"""A database the server cannot write stops it at start-up with a message naming the file
and the reason (it used to start and answer 500 on the first submission).

The machine runs the tests as root, for whom file modes do not stop writes: a read-only file or directory is
made with ``chattr +i`` (immutable, honoured even for root), or with chmod when the tests run as another user.
"""
from __future__ import annotations

import os
import subprocess
import sys
from contextlib import contextmanager
from pathlib import Path

import pytest
from fastapi.testclient import TestClient

from server.classroom import assignment_store
from server.api.app import app
from server.classroom.store import AssignmentRecord, SQLiteStore, StoreUnavailable
from server.classroom.store.postgres import PostgresStore

from postgres import free_port, fresh_database, postgres_url  # noqa: F401 (the session's PostgreSQL server)

REPO = Path(__file__).resolve().parents[1]
FLYWHEEL = {"scene": "flywheel", "variant": "rig", "sliders": {"delta": {"value": 0.02}, "omega_mean": {"value": 50}},
            "questions": [{"id": "flywheel_inertia"}]}


@contextmanager
def read_only(*paths: Path):
    """The paths refuse every write while inside, root included."""
    if os.geteuid() == 0:
        made = subprocess.run(["chattr", "+i", *map(str, paths)], capture_output=True, text=True)
        if made.returncode != 0:
            pytest.skip(f"chattr +i is not available here: {made.stderr.strip()}")
        try:
            yield
        finally:
            subprocess.run(["chattr", "-i", *map(str, paths)], check=True)
    else:
        modes = [path.stat().st_mode for path in paths]
        for path in paths:
            path.chmod(0o555 if path.is_dir() else 0o444)
        try:
            yield
        finally:
            for path, mode in zip(paths, modes):
                path.chmod(mode)


@pytest.fixture()
def data_dir(tmp_path, monkeypatch):
    monkeypatch.setenv("MDL_DATA_DIR", str(tmp_path))
    monkeypatch.delenv("MDL_DATABASE_URL", raising=False)
    assignment_store.store.cache_clear()
    yield tmp_path
    assignment_store.store.cache_clear()


def existing_database(directory: Path) -> Path:
    """A database file as a server that ran before left it: migrated, one assignment in it."""
    path = directory / assignment_store.DATABASE_FILE
    SQLiteStore(path).create(AssignmentRecord("a1", "hash", 0.0, {}))
    return path


def test_a_read_only_database_file_answered_500_on_the_first_write(data_dir):
    """The failure as it was: the store opens a read-only file without a word, the first write fails."""
    path = existing_database(data_dir)
    with read_only(path):
        opened = SQLiteStore(path)
        with pytest.raises(Exception, match="readonly"):
            opened.set_roster_locked("a1", True)


def test_a_read_only_database_file_stops_the_start(data_dir):
    path = existing_database(data_dir)
    with read_only(path):
        assignment_store.store.cache_clear()
        with pytest.raises(StoreUnavailable, match=f"cannot write the database {path}: .*readonly"):
            with TestClient(app):
                pass


def test_a_read_only_data_directory_stops_the_start(data_dir):
    with read_only(data_dir):
        with pytest.raises(StoreUnavailable, match=f"{data_dir / assignment_store.DATABASE_FILE}.*unable to open"):
            with TestClient(app):
                pass


def test_a_file_where_the_data_directory_should_be_stops_the_start(tmp_path, monkeypatch):
    blocker = tmp_path / "data"
    blocker.write_text("")
    monkeypatch.setenv("MDL_DATA_DIR", str(blocker))
    assignment_store.store.cache_clear()
    try:
        with pytest.raises(StoreUnavailable, match=f"cannot open the database {blocker}"):
            with TestClient(app):
                pass
    finally:
        assignment_store.store.cache_clear()


def test_the_server_refuses_to_start_and_says_why(data_dir):
    """`python3 -m server` on a read-only data directory exits at once (not serving) with the path and the reason."""
    with read_only(data_dir):
        try:
            started = subprocess.run([sys.executable, "-m", "server", "--port", "0"], cwd=REPO, capture_output=True,
                                     text=True, timeout=120)        # a guard: a server that starts serves on
        except subprocess.TimeoutExpired:
            pytest.fail("the server started on a read-only data directory")
    assert started.returncode != 0
    assert f"the server cannot start: cannot open the database {data_dir / assignment_store.DATABASE_FILE}" \
           f" for writing: unable to open database file" in started.stderr


def test_a_writable_database_starts(data_dir):
    with TestClient(app) as client:
        assert client.post("/api/v1/assignments", json=FLYWHEEL).status_code == 201


# --- PostgreSQL (MDL_DATABASE_URL) ------------------------------------------------------------------------

@pytest.fixture()
def database_url(monkeypatch):
    """Point the app at a URL (set by the test) and forget the store before and after."""
    def use(url: str) -> str:
        monkeypatch.setenv("MDL_DATABASE_URL", url)
        assignment_store.store.cache_clear()
        return url
    yield use
    assignment_store.store.cache_clear()


def test_an_unreachable_postgresql_stops_the_start_without_showing_the_password(database_url):
    port = free_port()                                  # nothing listens there
    database_url(f"postgresql://mdl:hunter2@127.0.0.1:{port}/classroom")
    with pytest.raises(StoreUnavailable, match=f"cannot use the database PostgreSQL mdl@127.0.0.1:{port}/classroom: "
                                               f".*(refused|failed)") as refused:
        with TestClient(app):
            pass
    assert "hunter2" not in str(refused.value)


def test_a_database_url_of_another_kind_stops_the_start(database_url):
    database_url("mysql://root@localhost/mdl")
    with pytest.raises(StoreUnavailable, match="MDL_DATABASE_URL must start with postgresql://"):
        with TestClient(app):
            pass


def test_a_read_only_postgresql_stops_the_start(database_url, postgres_url):
    import psycopg

    url = database_url(fresh_database(postgres_url))
    PostgresStore(url).close()                           # migrated while it could write
    with psycopg.connect(postgres_url, autocommit=True) as admin:
        admin.execute(f'ALTER DATABASE "{url.rsplit("/", 1)[1]}" SET default_transaction_read_only = on')
    with pytest.raises(StoreUnavailable, match="cannot write the database PostgreSQL .*read-only transaction"):
        with TestClient(app):
            pass


def test_the_api_runs_on_postgresql(database_url, postgres_url):
    """MDL_DATABASE_URL switches the whole API: an assignment made, answered and read back from the database."""
    import psycopg

    url = database_url(fresh_database(postgres_url))
    with TestClient(app) as client:
        created = client.post("/api/v1/assignments", json=FLYWHEEL).json()
        client.post(f"/api/v1/assignments/{created['id']}/students", json={"name": "Ivan Petrov"})  # the cookie
        outcome = client.post(f"/api/v1/assignments/{created['id']}/submissions",
                              json={"question": "flywheel_inertia", "answer": 1.0})
        assert outcome.status_code == 200 and outcome.json()["attempt"] == 1
    with psycopg.connect(url) as connection:
        assert connection.execute("SELECT student_key, answer, attempt FROM submissions").fetchall() == [
            ("ivan petrov", 1.0, 1)]
    assignment_store.store().close()
