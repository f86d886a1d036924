"""App servers for the LTI tests: `python3 -m server --port P` in a process group of its own (killed as a group at
the end, nothing left behind), with its own data directory, MDL_ADMIN_TOKEN, and its log in a file; plus what the
tests ask the app (an assignment, its results, a student's variant and the right answer to a question).
"""
from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from contextlib import ExitStack, contextmanager
from pathlib import Path

import httpx

from lti_platform import free_port

REPO = Path(__file__).resolve().parents[1]
API = "/api/v1"
ADMIN_TOKEN = "lti-admin-" + "x" * 24
START_SECONDS = 240          # a guard against a hang: a loaded machine imports the app slowly
SPEC = {"scene": "transfer-functions", "variant": "slider_crank", "title": "Crank-slider transfer functions",
        "sliders": {"lambda": {"vary": {"min": 2.5, "max": 5.0}}},
        "questions": [{"id": "u31_max"}, {"id": "du31_min"}], "attempts": 3}


class AppServer:
    def __init__(self, env: dict, directory: Path):
        self.port, self.env = free_port(), env
        self.url = f"http://127.0.0.1:{self.port}"
        self.log = directory / f"server-{self.port}.log"
        self.process: subprocess.Popen | None = None

    def start(self) -> None:
        with open(self.log, "ab") as log:
            self.process = subprocess.Popen([sys.executable, "-m", "server", "--port", str(self.port)], cwd=REPO,
                                            env=self.env, stdout=log, stderr=subprocess.STDOUT,
                                            start_new_session=True)

    def wait_ready(self) -> None:
        deadline = time.monotonic() + START_SECONDS
        while time.monotonic() < deadline:
            if self.process.poll() is not None:
                raise RuntimeError(f"the app server on port {self.port} exited:\n{self.log_tail()}")
            try:
                if httpx.get(f"{self.url}{API}/mechanisms", timeout=2).status_code == 200:
                    return
            except httpx.HTTPError:
                pass
            time.sleep(0.2)
        raise RuntimeError(f"the app server on port {self.port} was not ready in {START_SECONDS} s:\n"
                           + self.log_tail())

    def log_tail(self, characters: int = 4000) -> str:
        return self.log.read_text(errors="replace")[-characters:] if self.log.exists() else ""

    def stop(self) -> None:
        if self.process is None or self.process.poll() is not None:
            return
        os.killpg(self.process.pid, signal.SIGTERM)
        try:
            self.process.wait(timeout=30)
        except subprocess.TimeoutExpired:
            os.killpg(self.process.pid, signal.SIGKILL)
            self.process.wait(timeout=10)
        try:                                     # anything the server started and left in its group
            os.killpg(self.process.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass


@contextmanager
def app_servers(directory: Path, count: int = 1, env: dict | None = None, admin_token: str = ADMIN_TOKEN):
    """`count` app servers sharing one database (the SQLite file in `directory`, or the MDL_DATABASE_URL in
    `env`, which is added to the environment), started together; stopped when the block ends."""
    environment = os.environ | {"MDL_DATA_DIR": str(directory), "MDL_ADMIN_TOKEN": admin_token,
                                "MDL_HEAVY_PROCESSES": "0", "MDL_DATABASE_URL": ""} | (env or {})
    servers = [AppServer(environment, directory) for _ in range(count)]
    with ExitStack() as stack:
        for server in servers:
            stack.callback(server.stop)
            server.start()
        for server in servers:
            server.wait_ready()
        yield servers


def make_assignment(base: str, spec: dict = SPEC) -> dict:
    response = httpx.post(f"{base}{API}/assignments", json=spec, timeout=60)
    assert response.status_code == 201, response.text
    return response.json()


def results(base: str, created: dict) -> dict:
    response = httpx.get(f"{base}{API}/assignments/{created['id']}/results/{created['results_token']}", timeout=60)
    assert response.status_code == 200, response.text
    return response.json()


def right_answer(variant: dict, question: str, spec: dict = SPEC) -> float:
    """The exact answer to `question` for a student's variant (`GET …/me`), computed here as the server does (through
    the endpoints the app gives the classroom)."""
    from server.api.endpoints import parsed_answer
    from server.classroom.answers import correct_answer, use_endpoints
    from server.classroom.spec import AssignmentSpec
    from server.classroom.variants import plan
    from server.lessons.scenes import scenes
    use_endpoints(parsed_answer)
    return correct_answer(plan(AssignmentSpec.model_validate(spec), scenes()), variant["values"], question)
