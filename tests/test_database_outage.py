"""PostgreSQL killed in the middle of a class's submissions, and started again: the app servers ride it out.

Two app servers on one PostgreSQL (a cluster of this test's own), behind the shipped nginx site, as in
tests/test_deployment.py. A class submits wrong answers, every (student, question) in a thread of its own;
after KILL_AFTER acknowledged answers the postmaster is killed (SIGKILL: a crash, its backends end with it),
the class keeps submitting, and once the servers have refused DOWN_ANSWERS answers the same data directory is
started again on the same port. Counted in answers, not seconds (waits are guards against a hang):
- while the database is down every answer is 503 with Retry-After (the reason as JSON), never a 500, never
  a gateway timeout: each request returns;
- after the restart both servers acknowledge answers again, without being restarted (the pool reconnects);
- every answer acknowledged (HTTP 200), before, during or after, is stored exactly once, with the attempt
  number it was acknowledged with, and each question's attempts run 1, 2, … without a gap;
- no postgres process of the cluster is left behind (nginx and the app servers are stopped by their helpers).
"""
from __future__ import annotations

import itertools
import os
import signal
import subprocess
import threading
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import httpx
import psycopg
import pytest

from leftover_processes import wait_gone
from postgres import _owner, _run_as, _wait_ready, postgres_bin, start_postgres
from test_deployment import API, QUESTIONS, SPEC, Student, deployment_on, stored_submissions

ATTEMPTS = 10                  # per question: 20 answers per student, under the servers' 30 per minute per address
CLASS_SIZE = 12
KILL_AFTER = 30                # acknowledged answers before the kill
DOWN_ANSWERS = 24              # answers refused while the database is down before it is started again
AFTER_RESTART = 30             # acknowledged answers after the restart before the class stops
GUARD_S = 300                  # against a hang only


def cluster_processes(postmaster: int) -> set[int]:
    """The postmaster and its children (the backends and background processes)."""
    children = set()
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                stat = (entry / "stat").read_text()
            except OSError:
                continue
            if int(stat.rsplit(")", 1)[1].split()[1]) == postmaster:
                children.add(int(entry.name))
    return children | {postmaster}


class Cluster:
    """A PostgreSQL cluster of the test's own that can be killed and started again on its data directory."""

    def __init__(self, tmp: Path):
        self.url, self._stop = start_postgres(tmp)
        with psycopg.connect(self.url, autocommit=True) as admin:
            self.data = Path(admin.execute("SHOW data_directory").fetchone()[0])
        self.port = int(self.url.rsplit(":", 1)[1].split("/")[0])
        self.restarted: subprocess.Popen | None = None
        self.seen: set[int] = set()

    def postmaster(self) -> int:
        return int((self.data / "postmaster.pid").read_text().splitlines()[0])

    def kill(self) -> None:
        """SIGKILL the postmaster; wait until it and every process it had started have ended."""
        pid = self.postmaster()
        processes = cluster_processes(pid)
        self.seen |= processes
        os.kill(pid, signal.SIGKILL)
        try:
            os.waitpid(pid, 0)      # reaped (start_postgres's child): a zombie's pid would look alive to postgres
        except ChildProcessError:
            pass
        wait_gone(processes, "the killed cluster")

    def start_again(self) -> None:
        """`postgres` on the same data directory and port (it recovers from the crash first)."""
        root = self.data.parent
        deadline = time.monotonic() + GUARD_S
        while True:
            with open(root / "server.log", "a") as log:
                server = _run_as(_owner(), [str(postgres_bin() / "postgres"), "-D", str(self.data), "-p",
                                            str(self.port), "-k", str(root), "-c", "listen_addresses=127.0.0.1",
                                            "-c", "max_connections=300"], root, stdout=log, stderr=subprocess.STDOUT)
            if _wait_ready(server, self.url):
                self.restarted = server
                return
            server.wait()
            assert time.monotonic() < deadline, "PostgreSQL did not start again: " + \
                (root / "server.log").read_text(errors="replace")[-2000:]
            time.sleep(0.5)

    def stop(self) -> None:
        """Stop the restarted server (immediate shutdown) and remove the cluster; nothing of it left running."""
        if self.restarted is not None:
            self.seen |= cluster_processes(self.restarted.pid)
            if self.restarted.poll() is None:
                self.restarted.send_signal(signal.SIGQUIT)
            self.restarted.wait(timeout=GUARD_S)
        self._stop()
        wait_gone(self.seen, "the cluster after the test")


@pytest.fixture()
def cluster(tmp_path):
    running = Cluster(tmp_path)
    try:
        yield running
    finally:
        running.stop()


class Class:
    """What the class saw, by phase ("up", "down", "again"): acknowledgements and refusals."""

    def __init__(self):
        self.phase = "up"
        self.stop = threading.Event()
        self.acknowledged: list[tuple[str, str, float, int, str]] = []   # key, question, answer, attempt, phase
        self.refused: dict[str, int] = {"up": 0, "down": 0, "again": 0}  # 503 store_unavailable
        self.wrong: list[str] = []                                       # anything else than 200, 503, 409
        self.values = itertools.count(1)
        self.lock = threading.Lock()

    def count(self, phase: str) -> int:
        return sum(1 for a in self.acknowledged if a[4] == phase)

    def submit_until_stopped(self, student: Student, question: str) -> None:
        while not self.stop.is_set():
            with self.lock:
                value, phase = 1000.0 + next(self.values), self.phase
            try:
                response = student.submit(question, value)
            except httpx.TransportError as error:     # a request that did not return: the point of the test
                self.wrong.append(f"{phase}: no answer ({error!r})")
                return
            if response.status_code == 200:
                with self.lock:
                    self.acknowledged.append((student.key, question, value, response.json()["attempt"], phase))
            elif response.status_code == 409:         # no attempt left
                return
            elif response.status_code == 503 and response.headers.get("retry-after") and \
                    response.json()["detail"][0]["type"] == "store_unavailable":
                with self.lock:
                    self.refused[phase] += 1
                time.sleep(0.1)
            elif response.status_code == 503 and response.headers.get("retry-after") and \
                    response.json()["detail"][0]["type"] in ("answers_busy", "answers_not_ready"):
                time.sleep(0.5)                       # the variant's answers being computed: no attempt used
            else:
                self.wrong.append(f"{phase}: {response.status_code} {response.headers.get('retry-after')} "
                                  f"{response.text[:300]}")
                return


def wait_for(condition, what: str, jobs) -> None:
    deadline = time.monotonic() + GUARD_S
    while not condition():
        assert time.monotonic() < deadline, f"{what} not reached within {GUARD_S} s"
        assert not all(job.done() for job in jobs), f"the class stopped before {what}"
        time.sleep(0.05)


def test_postgresql_killed_during_a_burst_and_started_again(cluster, tmp_path):
    spec = {**SPEC, "attempts": ATTEMPTS}
    (tmp_path / "deployment").mkdir()
    with deployment_on(tmp_path / "deployment", {"MDL_DATABASE_URL": cluster.url}) as deployment:
        proxy = deployment.proxy
        created = httpx.post(f"{proxy.url}{API}/assignments", json=spec, timeout=60).json()
        students = [Student(proxy.url, created["id"], f"Student {k:02d}", f"127.0.3.{k + 1}")
                    for k in range(CLASS_SIZE)]
        for student in students:
            student.register()
        pids = [server.process.pid for server in deployment.servers]
        the_class = Class()
        with ThreadPoolExecutor(max_workers=CLASS_SIZE * len(QUESTIONS)) as pool:
            jobs = [pool.submit(the_class.submit_until_stopped, student, question)
                    for student in students for question in QUESTIONS]
            try:
                wait_for(lambda: the_class.count("up") >= KILL_AFTER, f"{KILL_AFTER} answers before the kill", jobs)
                with the_class.lock:
                    the_class.phase = "down"
                cluster.kill()
                wait_for(lambda: the_class.refused["down"] >= DOWN_ANSWERS,
                         f"{DOWN_ANSWERS} answers refused while the database is down", jobs)
                cluster.start_again()
                with the_class.lock:
                    the_class.phase = "again"
                wait_for(lambda: the_class.count("again") >= AFTER_RESTART,
                         f"{AFTER_RESTART} answers after the restart", jobs)
            finally:
                the_class.stop.set()
            for job in jobs:
                job.result(timeout=GUARD_S)
        print(f"acknowledged {the_class.count('up')} before the kill, {the_class.count('down')} while down, "
              f"{the_class.count('again')} after the restart; refused (503) {the_class.refused}")
        refusals = [line for server in deployment.servers
                    for line in server.log.read_text(errors="replace").splitlines() if "503 for" in line]
        print("\n".join(refusals[:5] + ["…"] + refusals[-5:]))
        assert the_class.wrong == [], the_class.wrong
        for server in deployment.servers:            # each refusal is one line with its reason, no traceback
            lines = server.log.read_text(errors="replace").splitlines()
            assert not [line for line in lines if "Exception in ASGI application" in line or "500 for" in line]
            refusal_then = [lines[i + 1] for i, line in enumerate(lines[:-1]) if "503 for" in line]
            assert not [line for line in refusal_then if line.startswith("Traceback")]
            assert all("cannot use the database PostgreSQL" in line for line in lines if "503 for" in line)
        assert [server.process.pid for server in deployment.servers] == pids and \
            all(server.process.poll() is None for server in deployment.servers), "an app server was restarted"
        checker = Student(proxy.url, created["id"], "Checker", "127.0.3.200")
        checker.register()
        for number, server in enumerate(deployment.servers):   # each server, asked directly, stores answers again
            value = 5000.0 + number
            answer = httpx.post(f"{server.url}{API}/assignments/{created['id']}/submissions",
                                json={"question": QUESTIONS[0], "answer": value},
                                headers={"Authorization": f"Bearer {checker.secret}"}, timeout=60)
            assert answer.status_code == 200, answer.text
            the_class.acknowledged.append((checker.key, QUESTIONS[0], value, answer.json()["attempt"], "direct"))
        students.append(checker)
        stored = stored_submissions(deployment.env, created["id"])
        for student in students:
            student.close()
    by_answer: dict[tuple, list[int]] = {}
    for s in stored:
        by_answer.setdefault((s.student_key, s.question, s.answer), []).append(s.attempt)
    for key, question, value, attempt, phase in the_class.acknowledged:
        assert by_answer.get((key, question, value)) == [attempt], \
            f"acknowledged ({phase}) {key} {question} {value} attempt {attempt}: stored {by_answer.get((key, question, value))}"
    for student in students:
        for question in QUESTIONS:
            numbers = sorted(s.attempt for s in stored if s.student_key == student.key and s.question == question)
            assert numbers == list(range(1, len(numbers) + 1)), f"{student.name} {question}: attempts {numbers}"
