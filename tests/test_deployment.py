"""Several app servers behind nginx with one database, as a university runs them.

Two app servers (`python3 -m server --port P`, as docs/deployment.md starts them) on loopback share one database,
behind a real nginx running the shipped `deploy/nginx/mdl.conf` (tests/nginx.py). An assignment is made
through nginx; a class of students, each on a loopback address of their own (127.0.1.k, so every student is
a client address of their own as behind a real proxy), registers and submits wrong answers through nginx,
two at a time per question, until the server refuses for want of attempts; one app server is killed
(SIGKILL) mid-burst, counted in acknowledged answers, not in seconds. Then:
- every acknowledged answer (HTTP 200) is stored, with the attempt number it was acknowledged with;
- no student has more than `attempts` answers to a question, though retries after the kill and the
  concurrent pairs land on both servers;
- the results, and every student's page, are the same from either server and through nginx.
Point 10: the app reads X-Forwarded-For only from the proxies it is told to trust (none by default), so a
spoofed header does not change the address the submission limit counts; behind nginx the student's own
address is counted.
No assertion depends on the machine's speed: waits are guards against a hang, with a message.
"""
from __future__ import annotations

import itertools
import os
import re
import signal
import subprocess
import sys
import threading
import time
from concurrent.futures import ThreadPoolExecutor
from contextlib import ExitStack, contextmanager
from pathlib import Path

import httpx
import pytest

from server.__main__ import uvicorn_options
from server.classroom.assignment_store import DATABASE_FILE
from server.classroom.names import normalise
from server.classroom.store import SQLiteStore
from server.classroom.store.postgres import PostgresStore
from server.lessons.family_requests import family_request
from server.lessons.scenes import scenes
from nginx import SITE, free_port, nginx_proxy
from postgres import fresh_database, postgres_url  # noqa: F401 (postgres_url is a fixture)

REPO = Path(__file__).resolve().parents[1]
API = "/api/v1"
SPEC = {"scene": "transfer-functions", "variant": "slider_crank",
        "sliders": {"lambda": {"vary": {"min": 2.5, "max": 5.0}}},
        "questions": [{"id": "u31_max"}, {"id": "du31_min"}], "attempts": 3}
QUESTIONS = [q["id"] for q in SPEC["questions"]]
CLASS_SIZE = 24
KILL_AFTER = 40                # acknowledged answers before the kill: about a third of the 144 the class can give
PER_MINUTE = 30                # the submission limit per address in these servers; a student stores at most 6
START_SECONDS = 240            # a cold numba cache compiles for about a minute per server on a loaded machine
BURST_SECONDS = 300            # guard against a hang only


# --- the student's side: the only place that knows how a student identifies themself -----------------------

class Student:
    """One student's browser: a client address of its own (`address`), talking to `base` (nginx). Registration
    is a POST, as the page sends it (with its Origin); the personal secret comes back as a cookie, which the
    browser then sends with every request through nginx. Asking a server directly, the test sends the same
    secret as `Authorization: Bearer`, as an API client would."""

    def __init__(self, base: str, assignment: str, name: str, address: str = "127.0.0.1"):
        self.base, self.assignment, self.name, self.secret = base, assignment, name, None
        self.http = httpx.Client(base_url=base, timeout=60, transport=httpx.HTTPTransport(local_address=address))

    def register(self) -> dict:
        response = self.http.post(f"{API}/assignments/{self.assignment}/students", json={"name": self.name},
                                  headers={"Origin": self.base})
        assert response.status_code == 201, response.text
        assert self.http.cookies, "the secret's cookie did not come through"
        assert response.json()["personal_url"].startswith(f"{self.base}/"), "a personal link past nginx"
        self.secret = response.json()["secret"]
        return response.json()

    def page(self, base: str | None = None) -> dict:
        """The student's variant and answers so far, through nginx (the cookie) or from the server at `base`."""
        headers = {"Authorization": f"Bearer {self.secret}"} if base else None
        response = self.http.get(f"{base or ''}{API}/assignments/{self.assignment}/me", headers=headers)
        response.raise_for_status()
        return response.json()

    def submit(self, question: str, answer: float, headers: dict | None = None) -> httpx.Response:
        return self.http.post(f"{API}/assignments/{self.assignment}/submissions", headers=headers,
                              json={"question": question, "answer": answer})

    @property
    def key(self) -> str:
        return normalise(self.name)

    def close(self) -> None:
        self.http.close()


# --- the servers --------------------------------------------------------------------------------------------

class AppServer:
    """`python3 -m server --port P` in a subprocess, started (again) and killed by the test; its log (uvicorn's
    access log included) goes to a file in `directory`, never to a pipe that nobody empties."""

    def __init__(self, env: dict, directory: Path):
        self.port, self.env, self.process = free_port(), env, None
        self.url = f"http://127.0.0.1:{self.port}"
        self.log = directory / f"server-{self.port}.log"

    def start(self) -> None:
        with open(self.log, "ab") as log:
            self.process = subprocess.Popen([sys.executable, "-m", "server", "--port", str(self.port)], cwd=REPO,
                                            env=self.env, stdout=log, stderr=subprocess.STDOUT)

    def wait_ready(self) -> None:
        deadline = time.monotonic() + START_SECONDS
        while time.monotonic() < deadline:
            if self.process.poll() is not None:
                raise RuntimeError(f"the app server on port {self.port} exited with {self.process.returncode}:\n"
                                   + self.log.read_text(errors="replace")[-3000:])
            try:
                if httpx.get(f"{self.url}{API}/mechanisms", timeout=2).status_code == 200:
                    return
            except httpx.HTTPError:
                pass
            time.sleep(0.2)
        raise RuntimeError(f"the app server on port {self.port} was not ready within {START_SECONDS} s:\n"
                           + self.log.read_text(errors="replace")[-3000:])

    def kill(self) -> None:
        self.process.send_signal(signal.SIGKILL)
        self.process.wait(timeout=30)

    def stop(self) -> None:
        if self.process is not None and self.process.poll() is None:
            self.process.terminate()
            try:
                self.process.wait(timeout=30)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait(timeout=10)


def stored_submissions(env: dict, assignment: str) -> list:
    """Every submission in the deployment's database, read by the test itself."""
    if env.get("MDL_DATABASE_URL"):
        store = PostgresStore(env["MDL_DATABASE_URL"], pool_size=1)
        try:
            return store.submissions(assignment)
        finally:
            store.close()
    return SQLiteStore(Path(env["MDL_DATA_DIR"]) / DATABASE_FILE).submissions(assignment)


class Deployment:
    def __init__(self, servers: list[AppServer], proxy, env: dict):
        self.servers, self.proxy, self.env = servers, proxy, env


@contextmanager
def deployment_on(tmp: Path, database: dict):
    """Two app servers on the `database` environment behind nginx; stopped afterwards."""
    env = os.environ | {"MDL_DATA_DIR": str(tmp)} | database | {
        "MDL_SUBMISSIONS_PER_MINUTE": str(PER_MINUTE),
        "MDL_FORWARDED_ALLOW_IPS": "127.0.0.1",      # nginx's address, as deploy/mdl.env.example sets it
        "MDL_SHARED_CACHE": str(tmp / "families.sqlite"),   # one file for the host's servers, as it says too
        "MDL_HEAVY_PROCESSES": "0"}                   # light scenes only: no process pools beside the servers
    servers = [AppServer(env, tmp) for _ in range(2)]
    with ExitStack() as stack:
        for server in servers:
            stack.callback(server.stop)
            server.start()
        for server in servers:
            server.wait_ready()
        proxy = stack.enter_context(nginx_proxy(tmp / "nginx", [s.port for s in servers]))
        yield Deployment(servers, proxy, env)


@pytest.fixture(scope="module")
def deployment(tmp_path_factory, postgres_url):
    """The university's set-up: one PostgreSQL (a database of its own on the tests' server)."""
    with deployment_on(tmp_path_factory.mktemp("deployment"), {"MDL_DATABASE_URL": fresh_database(postgres_url)}) \
            as running:
        yield running


@pytest.fixture(scope="module")
def sqlite_deployment(tmp_path_factory):
    """Several servers of one machine on one SQLite file (as the workers of one server share it)."""
    with deployment_on(tmp_path_factory.mktemp("sqlite-deployment"), {"MDL_DATABASE_URL": ""}) as running:
        yield running


# --- the tests ----------------------------------------------------------------------------------------------

def make_assignment(base: str) -> dict:
    response = httpx.post(f"{base}{API}/assignments", json=SPEC, timeout=60)
    assert response.status_code == 201, response.text
    return response.json()


def test_nginx_passes_the_apps_compression_and_caching_through(deployment):
    """gzip off in nginx: the app's own gzip arrives as the app made it; its Cache-Control is untouched."""
    body = {"mechanism": "slider_crank", "n": 361, "outputs": ["s", "u31", "du31"]}
    direct = httpx.post(f"{deployment.servers[0].url}{API}/kinematics", json=body, headers={"Accept-Encoding": "gzip"})
    proxied = httpx.post(f"{deployment.proxy.url}{API}/kinematics", json=body, headers={"Accept-Encoding": "gzip"})
    assert proxied.status_code == 200 and proxied.headers["content-encoding"] == "gzip"
    assert proxied.json() == direct.json()
    page = httpx.get(f"{deployment.proxy.url}/")
    assert page.headers["cache-control"] == "no-cache"
    stylesheet = re.search(r'href="(/static/[^"]+\.css)"', page.text).group(1)
    assert httpx.get(f"{deployment.proxy.url}{stylesheet}").headers["cache-control"] == \
        "public, max-age=31536000, immutable"


def test_a_family_one_server_computed_is_answered_by_the_other_from_their_shared_file(deployment):
    """The host's servers name one MDL_SHARED_CACHE file (deploy/mdl.env.example): a slider's family asked of
    one server and then of the other is computed once, and the second answer is the first's, byte for byte."""
    scene = scenes()["wear"]
    variant = scene.variants[0]
    body = family_request(scene, variant, variant.sliders[0]) | {"stage": "coarse"}
    first, second = (httpx.post(f"{server.url}{API}/family?lang=en", json=body, timeout=120,
                                headers={"Accept-Encoding": "gzip"}) for server in deployment.servers)
    assert (first.status_code, second.status_code) == (200, 200), (first.text[:300], second.text[:300])
    assert (first.headers["x-cache"], second.headers["x-cache"]) == ("miss", "hit")
    assert second.content == first.content


def test_an_assignment_made_through_nginx_links_back_to_nginx(deployment):
    created = make_assignment(deployment.proxy.url)
    assert created["student_url"].startswith(f"{deployment.proxy.url}/assignments/{created['id']}")
    for server in deployment.servers:                # stored once, seen by every server
        assert httpx.get(f"{server.url}{API}/assignments/{created['id']}").status_code == 200
    page = httpx.get(created["student_url"])
    assert page.status_code == 200 and "text/html" in page.headers["content-type"]
    assets = re.findall(r'(?:src|href)="(/(?:static|vendor)/[^"]+)"', page.text)
    assert assets
    for server in deployment.servers:              # the versioned URLs of one server's page, from every server
        for asset in assets:
            assert httpx.get(f"{server.url}{asset}").status_code == 200, (server.url, asset)


def test_nginx_logs_a_personal_link_without_its_secret(deployment):
    """The shipped site's access log (format mdl) writes /assignments/<id>/me/(secret): a student's secret that
    went through nginx is nowhere in the log, while the request is (so the line was written)."""
    created = make_assignment(deployment.proxy.url)
    student = Student(deployment.proxy.url, created["id"], "Логова Олена")
    link = student.register()["personal_url"]
    opened = httpx.get(link, follow_redirects=False)
    assert opened.status_code in (200, 302, 303, 307)
    deadline = time.monotonic() + 60               # nginx logs a request after answering it: wait for the line
    while not (lines := [line for line in deployment.proxy.access_log() if f"/assignments/{created['id']}/me/" in line]):
        assert time.monotonic() < deadline, "nginx logged no line for the personal link"
        time.sleep(0.05)
    assert all("/me/(secret)" in line for line in lines)
    assert not [line for line in deployment.proxy.access_log() if student.secret in line]


def test_nginx_logs_the_results_pages_and_api_without_the_token(deployment):
    """The instructor's results token that went through nginx (the page, the JSON, the CSV, the links) is nowhere
    in the shipped site's access log; each line is there with `/results/(token)`."""
    created = make_assignment(deployment.proxy.url)
    token, base = created["results_token"], f"{deployment.proxy.url}{API}/assignments/{created['id']}/results"
    assert httpx.get(created["results_url"]).status_code == 200
    assert httpx.get(f"{base}/{token}").status_code == 200
    assert httpx.get(f"{base}/{token}/csv").status_code == 200
    assert httpx.post(f"{base}/{token}/links?only_new=true").status_code == 200
    deadline = time.monotonic() + 60               # nginx logs a request after answering it: wait for the lines
    while len(lines := [line for line in deployment.proxy.access_log() if f"{created['id']}/results/" in line]) < 4:
        assert time.monotonic() < deadline, f"nginx logged {len(lines)} of the 4 results requests"
        time.sleep(0.05)
    assert all("/results/(token)" in line for line in lines)
    assert not [line for line in deployment.proxy.access_log() if token in line]


class Burst:
    """What the class saw: acknowledged answers, and every status that was not an acknowledgement."""

    def __init__(self):
        self.acknowledged: list[tuple[str, str, float, int]] = []   # (student key, question, answer, attempt)
        self.other: list[str] = []
        self.lost_connection = 0
        self.bad_gateway = 0          # nginx's 502/504: the server died under the request (saved or not)
        self.values = itertools.count(1)
        self.lock = threading.Lock()

    def answer(self) -> float:
        with self.lock:
            return 1000.0 + next(self.values)     # far from every right answer: each one uses an attempt

    def until_refused(self, student: Student, question: str) -> None:
        """Submit new wrong answers until the server says no attempt is left; retry after a lost answer."""
        while True:
            value = self.answer()
            try:
                response = student.submit(question, value)
            except httpx.TransportError:
                with self.lock:
                    self.lost_connection += 1
                continue
            if response.status_code == 200:
                self.acknowledged.append((student.key, question, value, response.json()["attempt"]))
            elif response.status_code == 409:
                return
            elif response.status_code in (502, 504):
                with self.lock:
                    self.bad_gateway += 1
            elif response.status_code == 503:      # the variant's answers still being computed: no attempt used
                time.sleep(min(float(response.headers.get("retry-after", "1")), 5.0))
            else:
                self.other.append(f"{response.status_code} {response.text[:200]}")
                return


@pytest.mark.parametrize("set_up", ["deployment", "sqlite_deployment"])
def test_a_class_through_nginx_survives_the_death_of_a_server(request, set_up):
    deployment = request.getfixturevalue(set_up)
    proxy, (doomed, survivor) = deployment.proxy, deployment.servers
    created = make_assignment(proxy.url)
    students = [Student(proxy.url, created["id"], f"Student {k:02d}", f"127.0.1.{k + 1}") for k in range(CLASS_SIZE)]
    burst = Burst()
    for student in students:
        student.register()
    with ThreadPoolExecutor(max_workers=2 * len(QUESTIONS) * CLASS_SIZE) as pool:
        jobs = [pool.submit(burst.until_refused, student, question)
                for student in students for question in QUESTIONS for _ in range(2)]
        deadline = time.monotonic() + BURST_SECONDS
        while len(burst.acknowledged) < KILL_AFTER and not all(j.done() for j in jobs):
            assert time.monotonic() < deadline, f"only {len(burst.acknowledged)} answers in {BURST_SECONDS} s"
            time.sleep(0.01)
        doomed.kill()
        killed_at = len(burst.acknowledged)
        for job in jobs:
            job.result(timeout=BURST_SECONDS)
    assert killed_at >= KILL_AFTER, "the burst ended before the kill"
    assert len(burst.acknowledged) > killed_at, "no answer was acknowledged after the kill"
    assert burst.other == [], burst.other
    served_by = {line.rsplit("upstream=", 1)[1] for line in proxy.access_log() if "/submissions" in line}
    assert {f"127.0.0.1:{s.port}" for s in deployment.servers} <= {a.split(", ")[0] for a in served_by}
    print(f"{len(burst.acknowledged)} answers acknowledged ({killed_at} before the kill), "
          f"{burst.bad_gateway} answers cut off by the kill (502), {burst.lost_connection} connections lost")

    stored = stored_submissions(deployment.env, created["id"])
    attempts = {(s.student_key, s.question, s.answer): s.attempt for s in stored}
    for key, question, value, attempt in burst.acknowledged:
        assert attempts.get((key, question, value)) == attempt, f"acknowledged answer lost: {key} {question} {value}"
    for student in students:
        for question in QUESTIONS:
            numbers = sorted(s.attempt for s in stored if s.student_key == student.key and s.question == question)
            assert numbers == list(range(1, SPEC["attempts"] + 1)), f"{student.name} {question}: attempts {numbers}"

    doomed.start()                                  # back, on the same database, to be asked too
    doomed.wait_ready()
    results = f"{API}/assignments/{created['id']}/results/{created['results_token']}"
    seen = [httpx.get(f"{base}{results}", timeout=60).json() for base in (doomed.url, survivor.url, proxy.url)]
    assert seen[0] == seen[1] == seen[2]
    assert {row["student"] for row in seen[0]["students"]} == {s.name for s in students}
    assert all(row["attempts"] == len(QUESTIONS) * SPEC["attempts"] for row in seen[0]["students"])
    for student in students:
        pages = [student.page(base) for base in (doomed.url, survivor.url, None)]
        assert pages[0] == pages[1] == pages[2]
        mine = {(s.question, s.answer) for s in stored if s.student_key == student.key}
        assert {(q["id"], a) for q in pages[0]["questions"] for a in q["answers"]} == mine
        student.close()


# --- point 10: whose X-Forwarded-For counts -----------------------------------------------------------------

def submissions_until_refused(student_pool) -> int:
    """Submit the students' answers in turn, each claiming a new address in X-Forwarded-For; the number
    acknowledged before the first 429 (the submission limit per address)."""
    count = 0
    for student in student_pool:
        for question in QUESTIONS:
            for _ in range(SPEC["attempts"]):
                response = student.submit(question, 1000.0 + count, {"X-Forwarded-For": f"203.0.113.{count}"})
                if response.status_code == 429:
                    return count
                assert response.status_code == 200, response.text
                count += 1
    return count


def classmates(base: str, assignment: str, address: str, how_many: int, prefix: str) -> list[Student]:
    pool = [Student(base, assignment, f"{prefix} {k}", address) for k in range(how_many)]
    for student in pool:
        student.register()
    return pool


def test_behind_nginx_the_limit_counts_each_students_own_address(deployment):
    """Through nginx, one address is refused after PER_MINUTE answers, a spoofed X-Forwarded-For does not
    help it, and a student on another address is still served: the app sees the students' addresses."""
    created = make_assignment(deployment.proxy.url)
    crowd = classmates(deployment.proxy.url, created["id"], "127.0.2.1", 6, "crowd")
    assert submissions_until_refused(crowd) == PER_MINUTE
    other = classmates(deployment.proxy.url, created["id"], "127.0.2.2", 1, "other")[0]
    assert other.submit(QUESTIONS[0], 1.0).status_code == 200


def test_a_trusted_proxy_address_may_name_the_client(deployment):
    """The deployment's servers trust 127.0.0.1 (nginx): from there, X-Forwarded-For names the client, so
    answers spoofed as many addresses are never refused; the default below trusts nobody."""
    server = deployment.servers[1]
    created = make_assignment(server.url)
    crowd = classmates(server.url, created["id"], "127.0.0.1", 6, "trusted")
    assert submissions_until_refused(crowd) == len(crowd) * len(QUESTIONS) * SPEC["attempts"] > PER_MINUTE


def test_by_default_no_proxy_is_trusted(tmp_path):
    """A server started with the defaults counts the connection's address, whatever X-Forwarded-For says."""
    env = os.environ | {"MDL_DATA_DIR": str(tmp_path), "MDL_DATABASE_URL": "", "MDL_SUBMISSIONS_PER_MINUTE": "4",
                        "MDL_HEAVY_PROCESSES": "0"}
    env.pop("MDL_FORWARDED_ALLOW_IPS", None)
    server = AppServer(env, tmp_path)
    server.start()
    try:
        server.wait_ready()
        created = make_assignment(server.url)
        crowd = classmates(server.url, created["id"], "127.0.0.1", 2, "local")
        assert submissions_until_refused(crowd) == 4
    finally:
        server.stop()


def test_the_default_options_trust_no_proxy(monkeypatch):
    monkeypatch.delenv("MDL_FORWARDED_ALLOW_IPS", raising=False)
    assert uvicorn_options([])["proxy_headers"] is False
    named = uvicorn_options(["--forwarded-allow-ips", "10.0.0.5"])
    assert named["proxy_headers"] is True and named["forwarded_allow_ips"] == "10.0.0.5"
    monkeypatch.setenv("MDL_FORWARDED_ALLOW_IPS", "127.0.0.1")
    assert uvicorn_options([])["forwarded_allow_ips"] == "127.0.0.1"


# --- the shipped files say the same as the deployment guide and the app ------------------------------------


def test_nginx_drops_an_idle_upstream_connection_before_the_app_does():
    """A POST sent on a kept-alive connection the app is closing fails (502) and is not retried: the shipped site
    keeps its idle upstream connections for less time than the app does."""
    conf = (REPO / "deploy" / "nginx" / "mdl.conf").read_text()
    upstream = re.search(r"upstream mdl \{(.*?)\}", conf, re.S).group(1)
    seconds = float(re.search(r"^\s*keepalive_timeout (\d+)s;", upstream, re.M).group(1))
    assert re.search(r"^\s*keepalive \d+;", upstream, re.M)
    assert 0 < seconds < uvicorn_options([])["timeout_keep_alive"]

def test_the_deployment_guide_shows_the_shipped_nginx_site():
    guide = (REPO / "docs" / "deployment.md").read_text(encoding="utf-8")
    assert re.search(r"```nginx\n(.+?)```", guide, re.S).group(1) == SITE.read_text(encoding="utf-8")


def test_the_settings_file_names_only_what_the_app_or_the_unit_reads():
    unit = (REPO / "deploy" / "systemd" / "mdl@.service").read_text(encoding="utf-8")
    start = re.search(r"^ExecStart=(.+)$", unit, re.M).group(1)
    assert start.startswith("/opt/mdl/.venv/bin/python3 -m server ") and "--port %i" in start   # the venv's Python
    code = "\n".join(p.read_text(encoding="utf-8") for p in (REPO / "server").rglob("*.py"))
    example = (REPO / "deploy" / "mdl.env.example").read_text(encoding="utf-8")
    names = re.findall(r"^([A-Z_]+)=", example, re.M)
    assert "MDL_DATABASE_URL" in names and "MDL_FORWARDED_ALLOW_IPS" in names
    for name in names:
        assert f'"{name}"' in code or "${" + name + "}" in start, f"{name} is read by neither the app nor the unit"
