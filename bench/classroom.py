"""Classroom load test: N students working the sliders of the scenes, against the server started as the README says.

The server is ``python3 -m server --port <free port>`` (then ``--workers 2``), with MDL_DATA_DIR in a temporary
folder, as a subprocess on loopback (``--tree`` names another source tree to run, e.g. the commit before a
change). Each simulated student keeps to one scene, the class spread over the scenes by SCENE_MIX (largest
remainders), and behaves like a scene page in one of two request patterns (``--pattern``):

* **old** (the page before slider families): drags one slider of one of the scene's variants for 3–8 s, then picks
  another variant and slider: a random walk over the values the slider can express (``slider_values``), a few
  positions per move, one move every 100 ms (TICK_S), without pauses (a worst case: real students also read);
  sends the request the page sends for the values (``scene_request``, the Python twin of the pages' request
  builders) with at most one request in flight: while an answer is awaited, moves only change the values, and
  the latest ones are sent as soon as the answer arrives (web/static/js/common/model/api.js).
* **new** (dragging is a lookup): grabs a slider of a variant and at once asks for its family (one
  ``POST /api/v1/family``, bench/family_request.py, on a connection of its own); drags it 1–3 s with the same
  random walk; while the family has not arrived the page sends the old pattern's coalesced exact requests,
  marked as a drag's (``X-MDL-Drag: 1``: the server serves them after the requests at rest) and reported apart
  as previews, once it is there no request at all; on release one exact request for the final value (unless
  that very request was the last one sent and answered); looks 1–2 s; grabs again. A grab while the last grab's
  family is still on its way aborts it (its connection shut, as the page's fetch abort does): counted as given
  up, not as an error.

Only the main panel is simulated (the kinematics page's λ overlay is off by default). Accept-Encoding: gzip,
like a browser; each student keeps its cookies (a client id such as ``mdl_client``), got first from its scene's
page. A 429 is waited out as its Retry-After says and the request sent again, as the page does; the latency of
that answer counts from the first send.

Reported per endpoint, and for exact answers (at rest, and during a drag) and families on the light and the
elastic scenes: requests, throughput, p50/p95/p99 latency (send to last byte), errors (non-2xx other than a 429
waited out, or network), 429s, the cache's hit rate (X-Cache headers), answers cut short by a time budget, the
cache counters every worker logs as it stops, and the server's and the client's CPU time. The client runs on the same CPUs as the
server. A short comparison of two client implementations (asyncio + httpx, threads + http.client; old pattern)
measures which costs the client less CPU per request; the lighter one drives the main runs.

    python bench/classroom.py [--students 60] [--seconds 60] [--workers 1 2] [--pattern old new]
                              [--tree .] [--client threads] [--compare-clients 15]
                              [--output bench/results/classroom.md]
"""
from __future__ import annotations

import argparse
import asyncio
import gzip
import http.client
import json
import math
import os
import platform
import random
import re
import socket
import sys
import threading
import time
from collections import Counter, defaultdict
from http.cookies import SimpleCookie
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from family_request import page_family_body  # noqa: E402
from trees import (OUTLIVE_GRACE_S, ROOT, check_tree, lessons, running_server,  # noqa: E402
                   server_cpu_s, tree_label, write_result)

sys.path.insert(0, str(ROOT))
PAGE_TREE = ROOT          # the tree whose page's family request the students send (main sets --tree)
scenes, scene_request, slider_values, _, _ = lessons()

TICK_S = 0.1                    # a slider move every 100 ms while dragging
DRAG_TICKS = (30, 80)           # old pattern: one drag lasts 3–8 s, no pauses
GRAB_DRAG_S = (1.0, 3.0)        # new pattern: one drag lasts 1–3 s …
LOOK_S = (1.0, 2.0)             # … then the student looks 1–2 s
# new pattern: when each student first grabs, after the clock starts. together: all within one slider tick (the
# whole class grabs at once: a burst of 30 families and their exact requests in the first second); staggered: after
# a look of 0–2 s, as a class some way into its work is spread over its students' cycles of drag and look
STARTS = {"together": TICK_S, "staggered": LOOK_S[1]}
START_SPREAD_S = STARTS["together"]
STEP_POSITIONS = (1, 3)         # positions per move
TURN_PROBABILITY = 0.2          # the hand changes direction
LANG = "ru"
WARM_GUARD_S = 1800          # the longest a server's warming may take before the run gives up (--warm)
HEADERS = {"Content-Type": "application/json", "Accept-Encoding": "gzip", "Accept": "*/*"}
DRAG = {"X-MDL-Drag": "1"}       # an exact request sent while a slider is dragged without its family (api.js)
REQUEST_TIMEOUT_S = 60
DEFAULT_RETRY_AFTER_S = 1.0     # a 429 without a readable Retry-After
BUDGETED = ("motion", "elastic")                 # endpoints that stop at a wall-clock time budget
BUDGET_MARKERS = (b"time budget", b"work bound")  # server/core/dynamics/motion.py, server/core/elastic/simulate.py
CACHE_AT_EXIT = "response cache at exit:"        # server/runtime/response_cache.py: each worker logs its counters
ELASTIC = "elastic"
# Targets at 100 students, ms: p95 of exact answers and of families, light and elastic scenes.
TARGETS_P95_MS = {("exact", "light"): 150, ("exact", "elastic"): 500, ("coarse", "light"): 500,
                  ("coarse", "elastic"): 1500, ("family", "light"): 500, ("family", "elastic"): 1500}
# Share of the class on each scene (%): kinematics first, then the dynamics lessons; the three elastic scenes
# share 5 %, the wear scene (a calculator read once) gets none.
SCENE_MIX = {"transfer-functions": 30, "equation-of-motion": 15, "flywheel": 15, "resisting-moment": 10,
             "reduced-inertia": 10, "forces-friction": 10, "angular-acceleration": 5,
             "elastic-transmission": 2, "elastic-linkage": 1.5, "elastic-four-bar": 1.5}


def apportion(students: int, mix: dict[str, float]) -> list[str]:
    """Scene ids for the students: each scene's share by largest remainders, in SCENE_MIX's order."""
    total = sum(mix.values())
    quotas = {scene: students * weight / total for scene, weight in mix.items()}
    counts = {scene: int(quota) for scene, quota in quotas.items()}
    for scene in sorted(quotas, key=lambda s: quotas[s] - counts[s], reverse=True)[:students - sum(counts.values())]:
        counts[scene] += 1
    return [scene for scene in mix for _ in range(counts[scene])]


class Student:
    """One student's hand on the sliders of one scene: a random walk, one move per tick."""

    def __init__(self, scene, rng: random.Random):
        self.scene, self.rng = scene, rng
        self.variants = [v for v in scene.variants if v.sliders]
        self.values: dict[str, dict[str, float]] = {}
        self.moves = 0
        self.cookies: dict[str, str] = {}
        self._new_drag()

    def _new_drag(self) -> None:
        self.variant = self.rng.choice(self.variants)
        self.slider = self.rng.choice(self.variant.sliders)
        self.positions = slider_values(self.slider)
        values = self.values.setdefault(self.variant.id, {})
        current = values.get(self.slider.id, self.slider.default)
        self.index = min(range(len(self.positions)), key=lambda k: abs(self.positions[k] - current))
        self.direction = self.rng.choice((-1, 1))
        self.ticks_left = self.rng.randint(*DRAG_TICKS)

    def grab(self) -> None:
        """New pattern: take hold of a slider (of any variant), for as long as the page script says."""
        self._new_drag()
        self.ticks_left = -1                             # never ends by itself

    def move(self) -> None:
        if self.ticks_left == 0:
            self._new_drag()
        self.ticks_left -= 1
        self.moves += 1
        if self.rng.random() < TURN_PROBABILITY:
            self.direction = -self.direction
        last = len(self.positions) - 1
        index = self.index + self.direction * self.rng.randint(*STEP_POSITIONS)
        if index < 0 or index > last:                    # bounce off the end of the track
            index = -index if index < 0 else 2 * last - index
            self.direction = -self.direction
        self.index = min(max(index, 0), last)
        self.values[self.variant.id][self.slider.id] = self.positions[self.index]

    def body(self) -> bytes:
        request = scene_request(self.scene, self.variant, self.values[self.variant.id])
        return json.dumps(request, separators=(",", ":")).encode()

    def family(self, stage: str = "full") -> bytes:
        request = page_family_body(self.scene, self.variant, self.slider, PAGE_TREE,      # fields and packed where
                                   self.values[self.variant.id]) | {"stage": stage}     # that tree's page has them
        return json.dumps(request, separators=(",", ":")).encode()

    @property
    def path(self) -> str:
        return f"/api/v1/{self.scene.endpoint}?lang={LANG}"

    family_path = f"/api/v1/family?lang={LANG}"

    @property
    def light(self) -> str:
        return ELASTIC if self.scene.endpoint == ELASTIC else "light"

    def cookie_header(self) -> dict:
        return {"Cookie": "; ".join(f"{k}={v}" for k, v in self.cookies.items())} if self.cookies else {}

    def keep_cookies(self, headers: list[tuple[str, str]]) -> None:
        for name, value in headers:
            if name.lower() == "set-cookie":
                for key, morsel in SimpleCookie(value).items():
                    self.cookies[key] = morsel.value


def page_script(student: Student, start: float, end: float):
    """The old page, as commands for a driver: a float is a wait in seconds; bytes are a body to post, and the
    driver comes back once its answer has arrived. The moves made meanwhile only change the values; the latest
    are sent next (one request in flight, like web/static/js/common/model/api.js); the same body is not sent twice in a
    row."""
    next_tick = start + student.rng.uniform(0, TICK_S)
    last_sent = None
    while True:
        now = time.monotonic()
        if now >= end:
            return
        moved = False
        while next_tick <= now:
            student.move()
            next_tick += TICK_S
            moved = True
        body = student.body() if moved else last_sent
        if body != last_sent:
            last_sent = body
            yield body
        else:
            yield max(0.0, min(next_tick, end) - now)


def cut_short(endpoint: str, raw: bytes, encoding: str | None, partial_header: str | None = None) -> bool:
    """Whether an answer (or a family of answers) says a budget cut it short: the header X-Partial: 1,
    or, from an endpoint with a wall-clock time budget (motion, elastic), the core's sentence in
    numerics.message (English in every language)."""
    if partial_header == "1":
        return True
    if endpoint not in BUDGETED:
        return False
    body = gzip.decompress(raw) if encoding == "gzip" else raw
    return any(marker in body for marker in BUDGET_MARKERS)


def answered_coarse(raw: bytes, encoding: str | None) -> bool:
    """Whether a family asked in full came as the coarse family (a busy server does not refine)."""
    body = gzip.decompress(raw) if encoding == "gzip" else raw
    return b'"stage":"coarse"' in body


class Record:
    """Every answer: (endpoint, latency s, status or 0 for a network error, X-Cache or '', cut short, kind:
    'exact' or 'family', 'light' or 'elastic'); the 429s waited out, and the requests still waiting one out
    when the run ended."""

    def __init__(self):
        self.rows: list[tuple] = []
        self.throttled: list[tuple[str, str, str]] = []  # (kind, light, endpoint) of every 429 received
        self.abandoned = 0
        self.given_up: list[tuple[str, str]] = []       # (kind, light) of every family given up by a new grab
        self.resent = 0         # requests sent again on a new connection: the idle one had been closed
        self.unrefined: list[str] = []   # light of every full family the server answered coarse (busy)
        self.first_previews: list[tuple[float, str]] = []   # (s, X-Cache) of each student's first coarse family

    def add(self, endpoint: str, seconds: float, status: int, cache: str, partial: bool = False,
            kind: str = "exact", light: str = "light", timing: str = "") -> None:
        self.rows.append((endpoint, seconds, status, cache, partial, kind, light, server_timing(timing)))


def server_timing(header: str) -> dict[str, float] | None:
    """The parts of the answer's Server-Timing header, in s, None without one: for an answer admitted to a lane
    (server/runtime/admission.py) *lane*, the wait for its place, and *compute*, from the place to the answer's
    first byte; for one computed in a heavy process (server/runtime/heavy.py; a family's has only these) *queue*,
    its wait in the heavy lane's queue, *run* and *cpu*, its wall and CPU time there."""
    found = {name: float(value) / 1e3 for name, value in re.findall(r"([a-z]+);dur=([0-9.]+)", header or "")}
    return found or None


# What a request on a keep-alive connection the server closed while it was idle fails with, before any answer
STALE = (http.client.RemoteDisconnected, ConnectionResetError, BrokenPipeError)


def retry_after_s(value: str | None) -> float:
    try:
        return max(0.0, float(value))
    except (TypeError, ValueError):
        return DEFAULT_RETRY_AFTER_S


class Connection:
    """One student's keep-alive http.client connection: posts a body, waits out 429s, records the answer."""

    def __init__(self, port: int, student: Student, record: Record, end: float):
        self.port, self.student, self.record, self.end = port, student, record, end
        self.connection = http.client.HTTPConnection("127.0.0.1", port, timeout=REQUEST_TIMEOUT_S)
        self.aborted = False          # the request in flight was given up (abort): not an error
        self.in_flight = False
        self.reused = False           # an answer has come on this connection (it may since have been closed idle)
        self.flight = threading.Lock()

    def _reopen(self) -> None:
        self.reused = False
        self.connection.close()
        self.connection = http.client.HTTPConnection("127.0.0.1", self.port, timeout=REQUEST_TIMEOUT_S)

    def get(self, path: str) -> None:
        """A page load: keeps the cookies it sets; not recorded."""
        try:
            self.connection.request("GET", path, headers={"Accept-Encoding": "gzip"})
            answer = self.connection.getresponse()
            answer.read()
            self.student.keep_cookies(answer.getheaders())
            self.reused = True        # the server may close it while idle before the first post: sent again then
        except (OSError, http.client.HTTPException):
            self._reopen()

    def post(self, path: str, body: bytes, kind: str = "exact") -> int:
        """Post until answered (a 429 waited out and sent again; given up when the run ends while waiting);
        returns the status (0: network error, -1: given up)."""
        student, sent = self.student, time.perf_counter()
        while True:
            try:
                with self.flight:
                    self.in_flight = True
                self.connection.request("POST", path, body=body, headers={**HEADERS, **student.cookie_header(),
                                                                          **(DRAG if kind == "drag" else {})})
                answer = self.connection.getresponse()
                raw = answer.read()
                with self.flight:
                    self.in_flight = False
                    if self.aborted:             # given up just as its answer had come: the socket is shut
                        self.aborted = False
                        self._reopen()
            except (OSError, http.client.HTTPException) as error:
                with self.flight:
                    self.in_flight = False
                if self.aborted:
                    self.record.given_up.append((kind, student.light))
                    self.aborted = False
                    self._reopen()
                    return -2
                if self.reused and isinstance(error, STALE):    # the server closed it while idle (keep-alive
                    self.record.resent += 1                       # timeout, 5 s): sent again on a new one, as
                    self._reopen()                                # browsers do
                    continue
                self.record.add(student.scene.endpoint, time.perf_counter() - sent, 0, "", False, kind, student.light)
                self._reopen()
                return 0
            self.reused = True
            student.keep_cookies(answer.getheaders())
            if answer.status != 429:
                break
            self.record.throttled.append((kind, student.light, student.scene.endpoint))
            wait = retry_after_s(answer.getheader("retry-after"))
            if time.monotonic() + wait >= self.end:
                self.record.abandoned += 1
                return -1
            time.sleep(wait)
        if kind == "family" and answer.status == 200 and answered_coarse(raw, answer.getheader("content-encoding")):
            self.record.unrefined.append(student.light)
        self.last = (time.perf_counter() - sent, answer.getheader("x-cache", ""))
        self.record.add(student.scene.endpoint, time.perf_counter() - sent, answer.status,
                        answer.getheader("x-cache", ""),
                        cut_short(student.scene.endpoint, raw, answer.getheader("content-encoding"),
                                  answer.getheader("x-partial")), kind,
                        student.light, answer.getheader("server-timing", ""))
        return answer.status

    def abort(self) -> None:
        """Give up the request in flight, as a page's fetch abort does: its connection is shut (the server sees
        the client gone); the posting thread records it as given up, not as an error."""
        with self.flight:
            sock = self.connection.sock
            if self.in_flight and sock is not None:
                self.aborted = True
                try:
                    sock.shutdown(socket.SHUT_RDWR)
                except OSError:
                    pass

    def close(self) -> None:
        self.connection.close()


async def drive_asyncio(port: int, students: list[Student], start: float, end: float, record: Record) -> None:
    """Old pattern only: one coroutine and one keep-alive httpx.AsyncClient connection per student."""
    import httpx

    async def one(student: Student) -> None:
        async with httpx.AsyncClient(base_url=f"http://127.0.0.1:{port}", timeout=REQUEST_TIMEOUT_S,
                                     limits=httpx.Limits(max_connections=1)) as client:
            for command in page_script(student, start, end):
                if isinstance(command, float):
                    await asyncio.sleep(command)
                    continue
                sent = time.perf_counter()
                try:
                    async with client.stream("POST", student.path, content=command, headers=HEADERS) as answer:
                        raw = b"".join([chunk async for chunk in answer.aiter_raw()])   # not decompressed
                    record.add(student.scene.endpoint, time.perf_counter() - sent, answer.status_code,
                               answer.headers.get("x-cache", ""),
                               cut_short(student.scene.endpoint, raw, answer.headers.get("content-encoding")),
                               "exact", student.light, answer.headers.get("server-timing", ""))
                except httpx.HTTPError:
                    record.add(student.scene.endpoint, time.perf_counter() - sent, 0, "", False, "exact",
                               student.light)

    await asyncio.gather(*(one(student) for student in students))


def open_pages(port: int, students: list[Student], record: Record) -> list[Connection]:
    """Each student's connection, its scene's page opened (its cookies kept; not recorded) before the clock
    starts, as a class opens its pages before it drags: on a loaded machine a slow page load does not eat the
    run's window."""
    connections = [Connection(port, student, record, math.inf) for student in students]
    for connection in connections:
        connection.get(f"/scenes/{connection.student.scene.id}")
    return connections


def old_page(connection: Connection, start: float, end: float) -> None:
    student = connection.student
    for command in page_script(student, start, end):
        if isinstance(command, float):
            time.sleep(command)
        else:
            connection.post(student.path, command)
    connection.close()


class FamilyFetcher:
    """The new page's family requests: a thread and a connection of their own, one family in flight; a grab
    while one is in flight gives that one up (its request aborted) and asks for its own. Each grab asks for the
    coarse family (the first preview) and, once it has come back, the full one, as
    web/static/js/common/view/family_preview.js does."""

    def __init__(self, port: int, student: Student, record: Record, end: float):
        self.connection = Connection(port, student, record, end)
        self.end = end
        self.changed = threading.Condition()
        self.wanted: tuple[int, bytes] | None = None
        self.arrived_grab = 0
        self.thread = threading.Thread(target=self._run, daemon=True)
        self.thread.start()

    def ask(self, grab: int, student: Student) -> None:
        with self.changed:
            self.wanted = (grab, student.family("coarse"), student.family("full"))
            self.changed.notify()
        self.connection.abort()

    def arrived(self, grab: int) -> bool:
        return self.arrived_grab == grab

    def _run(self) -> None:
        while True:
            with self.changed:
                while self.wanted is None and time.monotonic() < self.end:
                    self.changed.wait(timeout=0.2)
                if self.wanted is None:
                    break
                (grab, coarse, full), self.wanted = self.wanted, None
            if self.connection.post(Student.family_path, coarse, kind="coarse") == 200:
                self.arrived_grab = grab
                if grab == 1:                    # the student's first grab: the lesson's first preview
                    self.connection.record.first_previews.append(self.connection.last)
                self.connection.post(Student.family_path, full, kind="family")
        self.connection.close()


def new_page(exact: Connection, start: float, end: float) -> None:
    """Grab → family (asynchronous) → drag 1–3 s (exact requests only while the family is missing) → release:
    one exact request → look 1–2 s → grab again."""
    student = exact.student
    families = FamilyFetcher(exact.port, student, exact.record, end)
    time.sleep(max(0.0, start + student.rng.uniform(0, START_SPREAD_S) - time.monotonic()))
    grab = 0
    while time.monotonic() < end:
        grab += 1
        student.grab()
        families.ask(grab, student)
        release = min(end, time.monotonic() + student.rng.uniform(*GRAB_DRAG_S))
        next_tick, last_sent = time.monotonic(), None
        while (now := time.monotonic()) < release:
            while next_tick <= now:
                student.move()
                next_tick += TICK_S
            body = student.body()
            if not families.arrived(grab) and body != last_sent:
                last_sent = body
                exact.post(student.path, body, "drag")
            else:
                time.sleep(max(0.0, min(next_tick, release) - time.monotonic()))
        if time.monotonic() >= end:
            break
        body = student.body()
        if body != last_sent:                      # the exact answer for where the slider came to rest
            exact.post(student.path, body)
        time.sleep(max(0.0, min(end, time.monotonic() + student.rng.uniform(*LOOK_S)) - time.monotonic()))
    exact.close()
    families.thread.join(timeout=REQUEST_TIMEOUT_S)


PAGES = {"old": old_page, "new": new_page}


def drive_threads(connections: list[Connection], start: float, end: float, pattern: str = "old") -> None:
    """One thread and one keep-alive http.client connection per student (and per family fetcher)."""
    for connection in connections:
        connection.end = end
    threads = [threading.Thread(target=PAGES[pattern], args=(connection, start, end), daemon=True)
               for connection in connections]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()


CLIENTS = {"asyncio": "asyncio + httpx.AsyncClient", "threads": "threads + http.client"}


def cache_counters_at_exit(log: str) -> list[dict]:
    """The response cache's counters that every worker logs as it stops (CACHE_AT_EXIT).

    Asking GET /api/v1/cache of each worker is no way to collect them: the workers share one listening socket,
    and an idle worker's event loop accepts every pending connection at once, so a few hundred requests in a
    row may all reach the same worker."""
    counters = []
    for line in log.splitlines():
        if CACHE_AT_EXIT in line:
            counters.append(json.loads(line.split(CACHE_AT_EXIT, 1)[1]))
    return counters


def machine_busy_cpu_s() -> float:
    """CPU seconds all processes of the machine have used so far, summed over the CPUs (from /proc/stat)."""
    fields = [int(v) for v in Path("/proc/stat").read_text().splitlines()[0].split()[1:]]
    idle = fields[3] + (fields[4] if len(fields) > 4 else 0)          # idle, iowait
    return (sum(fields[:8]) - idle) / os.sysconf("SC_CLK_TCK")       # guest time is already in user time


def warmed(process, workers: int) -> float:
    """Wait until every worker of the server has logged the end of its warming (MDL_WARM_DEFAULTS: the scenes'
    default answers, and the families of their first variants' sliders: server/runtime/default_answers.py);
    the seconds waited. A guard against a warming that never ends, not a measure."""
    started = time.monotonic()
    while process.log_path.read_text(errors="replace").count("default answers in the cache:") < workers:
        if time.monotonic() - started > WARM_GUARD_S or process.poll() is not None:
            raise RuntimeError(f"the server's warming did not end within {WARM_GUARD_S} s")
        time.sleep(1)
    return time.monotonic() - started


def run(workers: int, client: str, students: int, seconds: float, seed: int, pattern: str = "old",
        tree: Path = ROOT, warm: bool = False) -> dict:
    """One configuration: start the server (warmed first in the class's language when `warm`), let the class
    work for `seconds`, collect the numbers."""
    all_scenes = scenes()
    rng = random.Random(seed)
    class_ = [Student(all_scenes[scene_id], random.Random(rng.random())) for scene_id in apportion(students, SCENE_MIX)]
    record = Record()
    # A real class comes from many addresses (or raises the cap behind one NAT address, as the README says); on
    # loopback every simulated student shares 127.0.0.1, so the per-address cap is off and each student's own
    # per-client limit (its mdl_client cookie) applies.
    env = {"MDL_ADDRESS_CONCURRENCY": "0", "MDL_WARM_DEFAULTS": LANG if warm else "0"}
    with running_server(workers, tree=tree, env=env) as (port, process):
        warming_s = warmed(process, workers) if warm else None
        connections = open_pages(port, class_, record) if client == "threads" else []
        server_cpu, client_cpu, busy = server_cpu_s(process), time.process_time(), machine_busy_cpu_s()
        start = time.monotonic() + 0.2
        wall = time.perf_counter()
        if client == "threads":
            drive_threads(connections, start, start + seconds, pattern)
        else:
            asyncio.run(drive_asyncio(port, class_, start, start + seconds, record))
        wall = time.perf_counter() - wall
        server_cpu, client_cpu = server_cpu_s(process) - server_cpu, time.process_time() - client_cpu
        busy = machine_busy_cpu_s() - busy
        load = os.getloadavg()
    after = cache_counters_at_exit(process.log_text)   # the caches start empty: their counters at exit are the run's
    return {"workers": workers, "client": client, "pattern": pattern, "students": students, "seconds": seconds,
            "wall": wall, "warming_s": warming_s, "rows": record.rows, "throttled": record.throttled, "abandoned": record.abandoned,
            "given_up": record.given_up, "first_previews": record.first_previews, "resent": record.resent, "unrefined": record.unrefined,
            "load": load,
            "moves": sum(s.moves for s in class_), "server_cpu": server_cpu,
            "client_cpu": client_cpu, "outlived": process.outlived,
            "other_cpu": max(0.0, busy - server_cpu - client_cpu),
            "cache": {"hits": sum(s["hits"] for s in after), "misses": sum(s["misses"] for s in after),
                      "workers": len(after), "entries": sum(s["entries"] for s in after),
                      "bytes": sum(s["bytes"] for s in after)},
            "command": "python3 -m server --port <free port>" + (f" --workers {workers}" if workers > 1 else ""),
            "scenes": {scene: sum(1 for s in class_ if s.scene.id == scene) for scene in SCENE_MIX}}


def first_previews(result: dict) -> str:
    """A sentence: the students' first grabs' coarse families (the lesson's first previews), p50 / p95 and hits."""
    first = result.get("first_previews", [])
    if not first:
        return "First grabs: none answered (old page pattern, or the run too short)."
    p50, p95 = np.percentile(1000 * np.array([seconds for seconds, _ in first]), [50, 95])
    hits = sum(1 for _, cache in first if cache == "hit")
    return (f"Each student's first grab (its coarse family, the lesson's first preview): {len(first)} answered, "
            f"p50 {p50:.0f} ms, p95 {p95:.0f} ms, {hits} of them cache hits.")


KIND_NAMES = {"drag": "during a drag", "coarse": "coarse family", "family": "family"}


def row_name(row: tuple) -> str:
    return row[0] if row[5] == "exact" else f"{KIND_NAMES[row[5]]} ({row[0]})"


def latency_row(name: str, rows: list, wall: float, throttled: int) -> dict:
    latencies = 1000 * np.array([r[1] for r in rows]) if rows else np.full(1, np.nan)
    p50, p95, p99 = np.percentile(latencies, [50, 95, 99])
    looked_up = [r for r in rows if r[3] in ("hit", "miss")]
    return {"endpoint": name, "requests": len(rows), "rate": len(rows) / wall, "p50": p50, "p95": p95,
            "p99": p99, "client_errors": sum(1 for r in rows if 400 <= r[2] < 500),
            "server_errors": sum(1 for r in rows if r[2] >= 500), "network_errors": sum(1 for r in rows if r[2] == 0),
            "throttled": throttled,
            "hit_rate": sum(1 for r in looked_up if r[3] == "hit") / len(looked_up) if looked_up else None,
            "partial": sum(1 for r in rows if r[4])}


def endpoint_rows(result: dict) -> list[dict]:
    """Per endpoint (families apart) and all together: requests, req/s, latency percentiles (ms), errors, 429s,
    hit rate, answers cut short."""
    groups: dict[str, list] = defaultdict(list)
    for row in result["rows"]:
        groups[row_name(row)].append(row)
    throttled = defaultdict(int)
    for kind, _, endpoint in result["throttled"]:
        throttled[endpoint if kind == "exact" else f"{KIND_NAMES[kind]} ({endpoint})"] += 1
    table = [latency_row(name, rows, result["wall"], throttled[name]) for name, rows in sorted(groups.items())]
    table.append(latency_row("all", result["rows"], result["wall"], len(result["throttled"])))
    return table


def kind_rows(result: dict) -> list[dict]:
    """Exact answers and families, on the light and on the elastic scenes, with the issue's p95 targets; then the
    answers asked during a drag without a family (previews of the values the slider passes: no target)."""
    table = []
    for (kind, light), target in [*TARGETS_P95_MS.items(), (("drag", "light"), None), (("drag", ELASTIC), None)]:
        rows = [r for r in result["rows"] if r[5] == kind and r[6] == light]
        throttled = sum(1 for t in result["throttled"] if t[:2] == (kind, light))
        if rows or throttled:
            label = {"exact": "exact", "coarse": "coarse family", "family": "full family",
                     "drag": "exact during a drag (a preview)"}[kind]
            table.append(latency_row(f"{label}, {'elastic' if light == ELASTIC else 'light'} scenes", rows,
                                     result["wall"], throttled) | {"target": target})
    return table


def errors(result: dict) -> int:
    return sum(1 for r in result["rows"] if not 200 <= r[2] < 300)


def given_up(result: dict) -> str:
    counts = Counter(result.get("given_up", []))
    if not counts:
        return "none"
    names = {"coarse": "coarse", "family": "full"}
    return ", ".join(f"{counts[key]} {names[key[0]]} ({'elastic' if key[1] == ELASTIC else 'light'} scenes)"
                     for key in sorted(counts))


def unrefined(result: dict) -> str:
    asked = Counter(r[6] for r in result["rows"] if r[5] == "family" and r[2] == 200)
    coarse = Counter(result.get("unrefined", []))
    if not asked:
        return "none asked"
    return ", ".join(f"{coarse[light]} of {asked[light]} ({'elastic' if light == ELASTIC else 'light'} scenes)"
                     for light in sorted(asked))


def percent(value: float | None) -> str:
    return "–" if value is None else f"{100 * value:.0f} %"


def ms(value: float) -> str:
    return "–" if value != value else f"{value:.0f}"


def where_the_time_goes(result: dict) -> list[str]:
    """The exact answers' latency split by the Server-Timing header: waiting for a place in admission's lane,
    from the place to the first byte (computing), and the rest (the worker's event loop and the CPU queues before
    and after, the network, the client): at the median and over the slowest 5 %."""
    lines = ["", "Where an exact answer's time goes (Server-Timing: *lane* the wait for a place in admission's "
             "lane, *compute* from the place to the first byte, *rest* the latency less both: the event loop, "
             "waiting for a CPU, sending and reading; medians, and means over the answers slower than the "
             "kind's p95):", "", "| answers | with timing | lane p50 | compute p50 | rest p50 | slowest 5 %: "
             "latency | lane | compute | rest |", "|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for light in ("light", "elastic"):
        rows = [r for r in result["rows"] if r[5] == "exact" and r[6] == light and r[2] == 200
                and r[7] is not None and "lane" in r[7]]
        if not rows:
            continue
        parts = 1000 * np.array([(r[1], r[7]["lane"], r[7]["compute"], r[1] - r[7]["lane"] - r[7]["compute"])
                                 for r in rows])
        slow = parts[parts[:, 0] >= np.percentile(parts[:, 0], 95)]
        p50 = np.median(parts, axis=0)
        lines.append(f"| exact, {light} scenes | {len(rows)} | {p50[1]:.1f} | {p50[2]:.1f} | {p50[3]:.1f} | "
                     + " | ".join(f"{x:.0f}" for x in slow.mean(axis=0)) + " |")
    if len(lines) == 5:
        return []
    lines += in_the_heavy_process(result)
    computed = defaultdict(list)
    for r in result["rows"]:
        if r[5] == "exact" and r[2] == 200 and r[7] is not None and "compute" in r[7]:
            computed[r[0]].append(1000 * r[7]["compute"])
    lines += ["", "The exact answers' *compute* by endpoint (ms): the long ones hold the worker's light place "
              "(or a heavy process) while the others wait:", "", "| endpoint | answers | p50 | p95 | max |",
              "|---|---:|---:|---:|---:|"]
    lines += [f"| `{endpoint}` | {len(values)} | {np.median(values):.1f} | {np.percentile(values, 95):.1f} | "
              f"{max(values):.1f} |" for endpoint, values in sorted(computed.items())]
    return lines


def in_the_heavy_process(result: dict) -> list[str]:
    """The answers computed in a heavy process (exact ones, and the families: a preview is the coarse stage), by
    the Server-Timing header's heavy parts: the wait in the heavy lane's queue (behind the job running there), the
    job's wall time in its process and the CPU time it took (run − cpu: the process waiting for the CPU, beside
    the worker and the other lanes)."""
    lines = []
    for kind, name in (("exact", "exact"), ("coarse", "first preview"), ("family", "full family")):
        rows = [r for r in result["rows"] if r[5] == kind and r[2] == 200 and r[7] is not None and "queue" in r[7]]
        if not rows:
            continue
        parts = 1000 * np.array([(r[1], r[7]["queue"], r[7]["run"], r[7]["cpu"]) for r in rows])
        slow = parts[parts[:, 0] >= np.percentile(parts[:, 0], 95)]
        p50 = np.median(parts, axis=0)
        lines.append(f"| {name} | {len(rows)} | {p50[1]:.1f} | {p50[2]:.1f} | {p50[3]:.1f} | "
                     + " | ".join(f"{x:.0f}" for x in slow.mean(axis=0)) + " |")
    return (["", "Those computed in a heavy process (*queue* the wait in its lane's queue, *run* the job's wall time "
             "there, *cpu* the CPU time it took; medians, and means over the slowest 5 %; families answered from a "
             "cache or joined to one being computed carry none):", "",
             "| answers | computed there | queue p50 | run p50 | cpu p50 | slowest 5 %: latency | queue | run | cpu |",
             "|---|---:|---:|---:|---:|---:|---:|---:|---:|", *lines] if lines else [])


def markdown_run(result: dict, title: str) -> list[str]:
    cpus = os.cpu_count() or 1
    requests = len(result["rows"])
    cache = result["cache"]
    looked_up = cache["hits"] + cache["misses"]
    lines = [f"## {title}", "", f"`{result['command']}`; client: {CLIENTS[result['client']]}; "
             f"{result['pattern']} page pattern.", "",
             "| endpoint | requests | req/s | p50 (ms) | p95 (ms) | p99 (ms) | errors (4xx / 5xx / network) | 429s "
             "| cache hits | cut short by a budget |", "|---|---:|---:|---:|---:|---:|---|---:|---:|---:|"]
    for row in endpoint_rows(result):
        name = f"**{row['endpoint']}**" if row["endpoint"] == "all" else f"`{row['endpoint']}`"
        lines.append(f"| {name} | {row['requests']} | {row['rate']:.1f} | {ms(row['p50'])} | {ms(row['p95'])} | "
                     f"{ms(row['p99'])} | {row['client_errors'] + row['server_errors'] + row['network_errors']} "
                     f"({row['client_errors']} / {row['server_errors']} / {row['network_errors']}) | "
                     f"{row['throttled']} | {percent(row['hit_rate'])} | {row['partial']} |")
    lines += ["", "| answers | requests | p50 (ms) | p95 (ms) | p99 (ms) | errors | 429s | cut short | p95 target (ms) "
                  "| met |", "|---|---:|---:|---:|---:|---:|---:|---:|---:|---|"]
    for row in kind_rows(result):
        failed = row["client_errors"] + row["server_errors"] + row["network_errors"]
        met = "–" if row["target"] is None else (
            "yes" if row["p95"] <= row["target"] and failed == 0 and not row["partial"] else "**no**")
        lines.append(f"| {row['endpoint']} | {row['requests']} | {ms(row['p50'])} | {ms(row['p95'])} | "
                     f"{ms(row['p99'])} | {failed} | {row['throttled']} | {row['partial']} | "
                     f"{'–' if row['target'] is None else row['target']} | {met} |")
    lines += where_the_time_goes(result)
    lines += ["", f"* Slider moves: {result['moves']}; requests sent: {requests} "
                  f"({percent(1 - requests / result['moves']) if result['moves'] else '–'} of the moves coalesced "
                  "into a later request while an answer was awaited, or previewed from a family).",
              f"* 429 answers waited out: {len(result['throttled'])}; requests still waiting one out when the run "
              f"ended: {result['abandoned']}.",
              f"* Requests sent again on a new connection because the server had closed the idle keep-alive one "
              f"(uvicorn's 5-s timeout; a browser does the same): {result.get('resent', 0)}.",
              f"* Families given up by the student's next grab (aborted in flight, as the page does; not in the "
              f"latencies above): {given_up(result)}.",
              f"* {first_previews(result)}",
              f"* Full families the server answered with the coarse family, busy (no refinement): "
              f"{unrefined(result)}.",
              f"* Cache, the counters each worker process logs as it stops ({cache['workers']} of "
              f"{result['workers']}): "
              f"{cache['hits']} hits, {cache['misses']} misses (hit rate {percent(cache['hits'] / looked_up if looked_up else None)}), "
              f"{cache['entries']} entries, {cache['bytes'] / 1e6:.1f} MB at the end; the clients saw "
              f"{sum(1 for r in result['rows'] if r[3] == 'hit')} answers with X-Cache: hit."
              + (f" The warming before the class took {result['warming_s']:.0f} s."
                 if result.get("warming_s") is not None else ""),
              f"* Server CPU: {result['server_cpu']:.1f} s in {result['wall']:.1f} s "
              f"({100 * result['server_cpu'] / result['wall'] / cpus:.0f} % of the {cpus} CPUs); "
              f"client CPU: {result['client_cpu']:.1f} s ({100 * result['client_cpu'] / result['wall'] / cpus:.0f} % "
              f"of the {cpus} CPUs, {1000 * result['client_cpu'] / max(requests, 1):.1f} ms per request); "
              f"other processes on the machine: {result['other_cpu']:.1f} s "
              f"({100 * result['other_cpu'] / result['wall'] / cpus:.0f} % of the {cpus} CPUs); load average at "
              f"the end of the run: {' / '.join(f'{x:.1f}' for x in result.get('load', ()))} (1 / 5 / 15 min).",
              f"* Processes of the server's session still running {OUTLIVE_GRACE_S:g} s after it stopped "
              f"(SIGTERM, 15 s): "
              f"{result['outlived']}{' (ended by the benchmark)' if result['outlived'] else ''}.", ""]
    return lines


def markdown(results: list[dict], comparison: list[dict], args) -> str:
    first = results[0] if results else comparison[0]
    mix = ", ".join(f"{scene} {SCENE_MIX[scene]:g} % ({count})" for scene, count in first["scenes"].items())
    lines = [
        f"# Classroom load test: {args.students} students, {args.seconds:g} s",
        "",
        f"{time.strftime('%Y-%m-%d %H:%M')}, Python {platform.python_version()}, {platform.machine()}, "
        f"**{os.cpu_count()} CPUs shared by the server and the client** (the simulated class runs on the same "
        f"machine, over loopback; its CPU use is reported below). `python bench/classroom.py --students "
        f"{args.students} --seconds {args.seconds:g} --pattern {' '.join(args.pattern)} --start {args.start}"
        f"{' --warm' if args.warm else ''}`, "
        f"seed {args.seed}; "
        f"server tree: {tree_label(args.tree)}.",
        "",
        f"Each student keeps to one scene (share of the class, students): {mix}. Every student opens its scene's page before the clock starts (threads client); "
        f"{'the whole class grabs at once when it starts' if args.start == 'together' else 'each student first grabs after a look of 0–2 s'} "
        "(`--start`). *Old page pattern*: a student "
        "drags one slider of one variant for 3–8 s, then another: a random walk over the slider's values, 1–3 "
        "positions every 100 ms, no pauses; the page's request (`scene_request`) with at most one in flight, the "
        "latest values sent when the answer arrives (`web/static/js/common/model/api.js`). *New page pattern*: grab a slider → "
        "one `POST /api/v1/family` (bench/family_request.py) → drag 1–3 s (the old pattern's exact requests only "
        "until the family has arrived, marked `X-MDL-Drag: 1` as the page marks them: the server serves them after "
        "the requests at rest, and they are reported apart, as previews) → release: one exact request → look 1–2 s → "
        "grab again. A 429 is waited "
        "out (Retry-After) and sent again; its answer's latency counts from the first send. Latency: from "
        "sending to the last byte of the gzip answer. "
        + ("The server is started with `MDL_WARM_DEFAULTS=ru` and the class begins once every worker has warmed "
           "its cache (every scene's default answers, and the family of every slider of every variant at its defaults, "
           "as a server started before the lesson has; `--warm`): the cache counters below include the "
           "warming's own requests. " if args.warm else "The cache starts empty. ")
        + "The cache is at its default size "
        "(MDL_CACHE_BYTES). *Cut short*: answers marked `X-Partial: 1`, or answers of /motion and /elastic (or "
        "families of them) that say they stopped at their wall-clock time budget with a partial result. Targets (at 100 students): "
        "p95 ≤ 150 ms for exact answers on the light scenes, ≤ 500 ms on the elastic ones; families ≤ 500 ms "
        "light, ≤ 1.5 s elastic; no errors, nothing cut short. Other jobs may share the machine: their CPU time "
        "during each run is given, and when it is large the numbers understate what the server does on its own.",
        "",
    ]
    for result in results:
        lines += markdown_run(result, f"{result['workers']} worker{'s' if result['workers'] > 1 else ''}, "
                                      f"{result['pattern']} page pattern")
    if comparison:
        lines += ["## Client implementations", "",
                  f"The same class for {comparison[0]['seconds']:g} s each against one worker, old page pattern; the "
                  "client's CPU per request decides which drives the runs above.", "",
                  "| client | requests | client CPU (s) | client CPU per request (ms) | share of the CPUs |",
                  "|---|---:|---:|---:|---:|"]
        for result in comparison:
            requests = max(len(result["rows"]), 1)
            lines.append(f"| {CLIENTS[result['client']]} | {len(result['rows'])} | {result['client_cpu']:.1f} | "
                         f"{1000 * result['client_cpu'] / requests:.2f} | "
                         f"{100 * result['client_cpu'] / result['wall'] / (os.cpu_count() or 1):.0f} % |")
        lines.append("")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--students", type=int, default=60)
    parser.add_argument("--seconds", type=float, default=60)
    parser.add_argument("--workers", type=int, nargs="+", default=[1, 2], help="server configurations to run")
    parser.add_argument("--pattern", choices=sorted(PAGES), nargs="+", default=["old", "new"],
                        help="the pages' request patterns to run (new: a family on each grab)")
    parser.add_argument("--tree", type=Path, default=ROOT, help="the source tree whose server runs (default: this one)")
    parser.add_argument("--client", choices=sorted(CLIENTS), default="threads", help="the client of the runs")
    parser.add_argument("--compare-clients", type=float, default=15, metavar="SECONDS",
                        help="also run both clients for SECONDS against one worker, old pattern (0: skip)")
    parser.add_argument("--start", choices=sorted(STARTS), default="together",
                        help="new pattern: the whole class grabs at once when the clock starts (together), or each "
                             "student after a look of 0–2 s (staggered)")
    parser.add_argument("--warm", action="store_true",
                        help="start the server with its cache warming on (MDL_WARM_DEFAULTS, in the class's language) "
                             "and the class once it has ended, as for a server started before the lesson")
    parser.add_argument("--seed", type=int, default=2026)
    parser.add_argument("--output", type=Path, default=ROOT / "bench" / "results" / "classroom.md")
    args = parser.parse_args(argv)
    args.tree = check_tree(args.tree)
    global PAGE_TREE, START_SPREAD_S
    PAGE_TREE = args.tree.resolve()
    START_SPREAD_S = STARTS[args.start]
    if args.client != "threads" and "new" in args.pattern:
        parser.error("the new page pattern runs on the threads client")

    comparison = [run(1, client, args.students, args.compare_clients, args.seed, "old", args.tree)
                  for client in sorted(CLIENTS)] if args.compare_clients > 0 else []
    results = [run(workers, args.client, args.students, args.seconds, args.seed, pattern, args.tree, args.warm)
               for workers in args.workers for pattern in args.pattern]
    text = markdown(results, comparison, args)
    print(text)
    write_result(text, args.output)
    return 0


if __name__ == "__main__":
    sys.exit(main())
