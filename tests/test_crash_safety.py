"""A crash in the middle of submissions: nothing acknowledged is lost, nothing is half-written.

1. The server, started as the README starts it, is killed (SIGKILL) during a burst of submissions from
   eight clients; the database is then opened afresh and every submission the server had acknowledged
   (HTTP 200 received) must be there with its answer and attempt number, each student's totals must equal
   their submissions, attempt numbers must run 1, 2, … without gaps, and a restarted server must show the
   same results.
2. A process dies between the two writes of one submission (the attempt row, then the student's totals):
   neither is left behind.
"""
from __future__ import annotations

import os
import signal
import socket
import sqlite3
import subprocess
import sys
import threading
import time
from pathlib import Path

import httpx
import pytest

from server.classroom.assignment_store import DATABASE_FILE

REPO = Path(__file__).resolve().parents[1]
SPEC = {"scene": "transfer-functions", "variant": "slider_crank",
        "sliders": {"lambda": {"vary": {"min": 2.5, "max": 5.0}}},
        "questions": [{"id": "u31_max"}, {"id": "du31_min"}], "attempts": 10}
STUDENTS = [f"student {k}" for k in range(24)]
START_SECONDS = 240         # guards against a hang, not speed limits: a loaded CI machine starts a server slowly


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def start_server(data_dir: Path, port: int) -> subprocess.Popen:
    env = os.environ | {"MDL_DATA_DIR": str(data_dir), "MDL_SUBMISSIONS_PER_MINUTE": "1000000"}
    process = subprocess.Popen([sys.executable, "-m", "server", "--port", str(port)], cwd=REPO, env=env,
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
    deadline = time.monotonic() + START_SECONDS
    while time.monotonic() < deadline:
        try:
            if httpx.get(f"http://127.0.0.1:{port}/api/v1/mechanisms", timeout=1).status_code == 200:
                return process
        except httpx.HTTPError:
            time.sleep(0.1)
    kill_group(process)
    raise RuntimeError("the server did not start")


def kill_group(process: subprocess.Popen) -> None:
    """SIGKILL the server and every process it started (its heavy processes are in its session): a crash of the
    whole service, and nothing left running after the test."""
    try:
        os.killpg(process.pid, signal.SIGKILL)
    except ProcessLookupError:
        pass
    process.wait(timeout=10)


def burst(base: str, assignment: str, secrets: dict, acknowledged: list, stop: threading.Event, seed: int) -> None:
    """Submit wrong answers for the students in turn (each with their personal secret) until the server dies;
    keep what it acknowledged."""
    with httpx.Client(timeout=5) as client:
        k = seed
        while not stop.is_set():
            name, question = STUDENTS[k % len(STUDENTS)], SPEC["questions"][k % 2]["id"]
            answer = 1000.0 + k
            k += 8
            try:
                response = client.post(f"{base}/api/v1/assignments/{assignment}/submissions",
                                       json={"question": question, "answer": answer},
                                       headers={"Authorization": f"Bearer {secrets[name]}"})
            except httpx.HTTPError:
                return                                   # the server is gone
            if response.status_code == 200:
                acknowledged.append((name.lower(), question, answer, response.json()["attempt"]))


def check_database(path: Path, assignment: str, acknowledged: list) -> dict:
    connection = sqlite3.connect(path)
    assert connection.execute("PRAGMA integrity_check").fetchone()[0] == "ok"
    rows = connection.execute("SELECT student_key, question, answer, attempt FROM submissions "
                              "WHERE assignment_id = ?", (assignment,)).fetchall()
    stored = {(key, question, answer): attempt for key, question, answer, attempt in rows}
    for key, question, answer, attempt in acknowledged:
        assert stored.get((key, question, answer)) == attempt, "an acknowledged submission was lost"
    totals = dict(connection.execute("SELECT key, attempts FROM students WHERE assignment_id = ?", (assignment,)))
    for key, attempts in totals.items():
        mine = [a for (k, _, _), a in stored.items() if k == key]
        assert attempts == len(mine), f"{key}: totals {attempts} but {len(mine)} submissions"
        for question in ("u31_max", "du31_min"):
            numbers = sorted(a for (k, q, _), a in stored.items() if k == key and q == question)
            assert numbers == list(range(1, len(numbers) + 1)), f"{key} {question}: attempts {numbers}"
    connection.close()
    return totals


@pytest.mark.parametrize("kill_after", [30, 150])
def test_kill_during_a_burst_of_submissions(tmp_path, kill_after):
    """kill_after: acknowledged submissions before the kill (counted, not timed: a loaded machine is slow)."""
    port = free_port()
    base = f"http://127.0.0.1:{port}"
    server = start_server(tmp_path, port)
    try:
        created = httpx.post(f"{base}/api/v1/assignments", json=SPEC, timeout=30).json()
        secrets = {name: httpx.post(f"{base}/api/v1/assignments/{created['id']}/students", json={"name": name},
                                    timeout=30).json()["secret"] for name in STUDENTS}      # registered first
        acknowledged, stop = [], threading.Event()
        clients = [threading.Thread(target=burst, args=(base, created["id"], secrets, acknowledged, stop, seed))
                   for seed in range(8)]
        for client in clients:
            client.start()
        deadline = time.monotonic() + START_SECONDS
        while len(acknowledged) < kill_after and time.monotonic() < deadline:
            time.sleep(0.005)
        kill_group(server)
        stop.set()
        for client in clients:
            client.join(timeout=10)
    finally:
        kill_group(server)
    assert len(acknowledged) >= kill_after, "the burst did not get going before the kill"
    print(f"{len(acknowledged)} submissions acknowledged before the kill")
    totals = check_database(tmp_path / DATABASE_FILE, created["id"], acknowledged)
    restarted = start_server(tmp_path, port)
    try:
        results = httpx.get(f"{base}/api/v1/assignments/{created['id']}/results/{created['results_token']}").json()
        assert {row["student"].lower(): row["attempts"] for row in results["students"]} == totals
    finally:
        kill_group(restarted)


CRASH_BETWEEN_WRITES = """
import os, sys, time
from pathlib import Path
from server.classroom.store import AssignmentRecord, SQLiteStore, StudentRecord

store = SQLiteStore(Path(sys.argv[1]))
store.create(AssignmentRecord("a1", "hash", time.time(), {}))
store.register("a1", StudentRecord("ivan", "Ivan", 0, {}, time.time()))
store.submit("a1", "ivan", "q", 1.0, False, 3, time.time(), "test")       # one whole submission first


class DiesBeforeTheTotals:
    def __init__(self, connection):
        self.connection = connection

    def execute(self, sql, *args):
        if sql.startswith("UPDATE students"):
            os._exit(3)                                   # the attempt row is written, the totals are not
        return self.connection.execute(sql, *args)


store._local.connection = DiesBeforeTheTotals(store._local.connection)
store.submit("a1", "ivan", "q", 2.0, False, 3, time.time(), "test")
"""


def test_a_death_between_the_two_writes_leaves_neither(tmp_path):
    database = tmp_path / "crash.sqlite3"
    child = subprocess.run([sys.executable, "-c", CRASH_BETWEEN_WRITES, str(database)], cwd=REPO)
    assert child.returncode == 3
    connection = sqlite3.connect(database)
    assert connection.execute("SELECT answer, attempt FROM submissions").fetchall() == [(1.0, 1)]
    assert connection.execute("SELECT attempts FROM students").fetchone()[0] == 1
    assert connection.execute("PRAGMA integrity_check").fetchone()[0] == "ok"
