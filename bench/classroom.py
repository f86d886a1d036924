"""Classroom load test: N students dragging sliders of the scenes, against the server started as the README says.

The server is ``python3 -m server --port <free port>`` (then ``--workers 2``), with MDL_DATA_DIR in a temporary
folder, as a subprocess on loopback. Each simulated student behaves like a scene page:

* keeps to one scene, the class spread over the scenes by SCENE_MIX (largest remainders);
* drags one slider of one of the scene's variants for 3–8 s, then picks another variant and slider: a random
  walk over the values the slider can express (``slider_values``), a few positions per move, one move every
  100 ms (TICK_S), without pauses (a worst case: real students also read);
* sends the request the page sends for the values (``scene_request``, the Python twin of the pages' request
  builders) with at most one request in flight: while an answer is awaited, moves only change the values,
  and the latest ones are sent as soon as the answer arrives (web/static/js/api.js). Only the main panel is
  simulated (the kinematics page's λ overlay is off by default). Accept-Encoding: gzip, like a browser.

Reported per endpoint: requests, throughput, p50/p95/p99 latency (send to last byte), errors (non-2xx or
network), the cache's hit rate (X-Cache headers), the cache counters every worker logs as it stops, and the
server's and the client's CPU time. The client runs on the same CPUs as the server.
A short comparison of two client implementations (asyncio + httpx, threads + http.client) measures which
costs the client less CPU per request; the lighter one drives the main runs.

    python bench/classroom.py [--students 60] [--seconds 60] [--workers 1 2] [--client threads]
                              [--compare-clients 15] [--output bench/results/classroom.md]
"""
from __future__ import annotations

import argparse
import asyncio
import gzip
import http.client
import json
import os
import platform
import signal
import random
import socket
import subprocess
import sys
import tempfile
import threading
import time
from collections import defaultdict
from contextlib import contextmanager
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from server.lessons.scenes import Scene, scenes  # noqa: E402
from server.api.response_cache import CACHE_AT_EXIT  # noqa: E402
from server.lessons.requests import scene_request, slider_values  # noqa: E402

TICK_S = 0.1                    # a slider move every 100 ms while dragging
DRAG_TICKS = (30, 80)           # one drag lasts 3–8 s
STEP_POSITIONS = (1, 3)         # positions per move
TURN_PROBABILITY = 0.2          # the hand changes direction
LANG = "ru"
HEADERS = {"Content-Type": "application/json", "Accept-Encoding": "gzip", "Accept": "*/*"}
REQUEST_TIMEOUT_S = 60
BUDGETED = ("motion", "elastic")                 # endpoints that stop at a wall-clock time budget
BUDGET_MARKERS = (b"time budget", b"work bound")  # server/core/dynamics/motion.py, server/core/elastic/simulate.py
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

    def __init__(self, scene: Scene, rng: random.Random):
        self.scene, self.rng = scene, rng
        self.variants = [v for v in scene.variants if v.sliders]
        self.values: dict[str, dict[str, float]] = {}
        self.moves = 0
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

    @property
    def path(self) -> str:
        return f"/api/v1/{self.scene.endpoint}?lang={LANG}"


def page_script(student: Student, start: float, end: float):
    """What the page does, as commands for a driver: a float is a wait in seconds; bytes are a body to post,
    and the driver comes back once its answer has arrived. The moves made meanwhile only change the values;
    the latest are sent next (one request in flight, like web/static/js/api.js); the same body is not
    sent twice in a row."""
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


def cut_short(endpoint: str, raw: bytes, encoding: str | None) -> bool:
    """Whether an answer of an endpoint with a wall-clock time budget (motion, elastic) says it stopped there
    with a partial result (the core's sentence in numerics.message, English in every language)."""
    if endpoint not in BUDGETED:
        return False
    body = gzip.decompress(raw) if encoding == "gzip" else raw
    return any(marker in body for marker in BUDGET_MARKERS)


class Record:
    """Every answer: (endpoint, latency s, status or 0 for a network error, X-Cache or '', cut short)."""

    def __init__(self):
        self.rows: list[tuple[str, float, int, str, bool]] = []

    def add(self, endpoint: str, seconds: float, status: int, cache: str, partial: bool = False) -> None:
        self.rows.append((endpoint, seconds, status, cache, partial))      # list.append is atomic in CPython


async def drive_asyncio(port: int, students: list[Student], start: float, end: float, record: Record) -> None:
    """One coroutine and one keep-alive httpx.AsyncClient connection per student."""
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
                               cut_short(student.scene.endpoint, raw, answer.headers.get("content-encoding")))
                except httpx.HTTPError:
                    record.add(student.scene.endpoint, time.perf_counter() - sent, 0, "")

    await asyncio.gather(*(one(student) for student in students))


def drive_threads(port: int, students: list[Student], start: float, end: float, record: Record) -> None:
    """One thread and one keep-alive http.client connection per student."""

    def one(student: Student) -> None:
        connection = http.client.HTTPConnection("127.0.0.1", port, timeout=REQUEST_TIMEOUT_S)
        for command in page_script(student, start, end):
            if isinstance(command, float):
                time.sleep(command)
                continue
            sent = time.perf_counter()
            try:
                connection.request("POST", student.path, body=command, headers=HEADERS)
                answer = connection.getresponse()
                raw = answer.read()
                record.add(student.scene.endpoint, time.perf_counter() - sent, answer.status,
                           answer.getheader("x-cache", ""),
                           cut_short(student.scene.endpoint, raw, answer.getheader("content-encoding")))
            except (OSError, http.client.HTTPException):
                record.add(student.scene.endpoint, time.perf_counter() - sent, 0, "")
                connection.close()
                connection = http.client.HTTPConnection("127.0.0.1", port, timeout=REQUEST_TIMEOUT_S)
        connection.close()

    threads = [threading.Thread(target=one, args=(student,), daemon=True) for student in students]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()


CLIENTS = {"asyncio": ("asyncio + httpx.AsyncClient", lambda *a: asyncio.run(drive_asyncio(*a))),
           "threads": ("threads + http.client", drive_threads)}


def free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return sock.getsockname()[1]


def get_json(port: int, path: str) -> dict:
    """GET on a fresh connection."""
    connection = http.client.HTTPConnection("127.0.0.1", port, timeout=5)
    try:
        connection.request("GET", path, headers={"Connection": "close"})
        answer = connection.getresponse()
        if answer.status != 200:
            raise RuntimeError(f"GET {path}: HTTP {answer.status}")
        return json.loads(answer.read())
    finally:
        connection.close()


def started_workers(log: str) -> int:
    """Worker processes that have said 'Application startup complete.' in the server's log."""
    return log.count("Application startup complete.")


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


def server_command(port: int, workers: int) -> list[str]:
    """The README's command: python3 -m server, plus --port (and --workers when more than one)."""
    return [sys.executable, "-m", "server", "--port", str(port), *(["--workers", str(workers)] if workers > 1 else [])]


def session_processes(session: int, zombies: bool = True) -> dict[int, float]:
    """The processes of a session (the server started with start_new_session: its workers, and the processes
    they start for long computations, which a forkserver may reparent to init) and their user + system CPU
    seconds so far, from /proc. ``zombies=False`` leaves out those that have ended but are not yet reaped
    (an orphan's parent is init, which on some machines reaps late or never)."""
    ticks = os.sysconf("SC_CLK_TCK")
    found = {}
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            fields = (entry / "stat").read_text().rsplit(")", 1)[1].split()
        except OSError:
            continue
        if int(fields[3]) == session and (zombies or fields[0] != "Z"):   # state, ppid, pgrp, session, …
            found[int(entry.name)] = (int(fields[11]) + int(fields[12])) / ticks   # utime, stime
    return found


def server_cpu_s(process: subprocess.Popen) -> float:
    return sum(session_processes(process.pid).values())


def machine_busy_cpu_s() -> float:
    """CPU seconds all processes of the machine have used so far, summed over the CPUs (from /proc/stat)."""
    fields = [int(v) for v in Path("/proc/stat").read_text().splitlines()[0].split()[1:]]
    idle = fields[3] + (fields[4] if len(fields) > 4 else 0)          # idle, iowait
    return (sum(fields[:8]) - idle) / os.sysconf("SC_CLK_TCK")       # guest time is already in user time


OUTLIVE_GRACE_S = 3.0           # multiprocessing's resource tracker may still be cleaning up as the server exits


def end_session(session: int) -> int:
    """End what is left of the server's session once the server has stopped (its own process group, by id)
    and OUTLIVE_GRACE_S has passed; returns how many processes had outlived it."""
    left = live_after(session, OUTLIVE_GRACE_S)
    if left:
        for sig in (signal.SIGTERM, signal.SIGKILL):
            try:
                os.killpg(session, sig)
            except ProcessLookupError:
                break
            if not live_after(session, 3.0):
                break
    return len(left)


def live_after(session: int, seconds: float) -> dict[int, float]:
    """The session's live processes once they have all ended or `seconds` have passed."""
    deadline = time.monotonic() + seconds
    while (live := session_processes(session, zombies=False)) and time.monotonic() < deadline:
        time.sleep(0.1)
    return live


@contextmanager
def running_server(workers: int):
    """The server on a free loopback port with MDL_DATA_DIR in a temporary folder; yields (port, process).
    Ready once every worker has started and one of them answers; once stopped, ``process.cache_at_exit`` holds
    the cache counters its workers logged and ``process.outlived`` the processes that outlived it."""
    with tempfile.TemporaryDirectory(prefix="mdl-classroom-") as data_dir:
        port = free_port()
        log_path = Path(data_dir) / "server.log"
        log = open(log_path, "wb")
        process = subprocess.Popen(server_command(port, workers), cwd=ROOT, stdout=log, stderr=subprocess.STDOUT,
                                   env={**os.environ, "MDL_DATA_DIR": data_dir}, start_new_session=True)
        try:
            deadline = time.monotonic() + 60
            while True:
                if process.poll() is not None:
                    raise RuntimeError(f"the server exited with code {process.returncode}: "
                                       + log_path.read_text(errors="replace")[-2000:])
                try:
                    if started_workers(log_path.read_text(errors="replace")) >= workers:
                        get_json(port, "/api/v1/cache")
                        break
                except (OSError, RuntimeError, http.client.HTTPException):
                    pass
                if time.monotonic() > deadline:
                    raise RuntimeError(f"the server's {workers} worker(s) did not all start and answer within 60 s")
                time.sleep(0.2)
            yield port, process
        finally:
            process.terminate()
            try:
                process.wait(timeout=15)
            except subprocess.TimeoutExpired:
                process.kill()
                process.wait()
            process.outlived = end_session(process.pid)
            log.close()
            process.cache_at_exit = cache_counters_at_exit(log_path.read_text(errors="replace"))


def run(workers: int, client: str, students: int, seconds: float, seed: int) -> dict:
    """One configuration: start the server, let the class work for `seconds`, collect the numbers."""
    all_scenes = scenes()
    rng = random.Random(seed)
    class_ = [Student(all_scenes[scene_id], random.Random(rng.random())) for scene_id in apportion(students, SCENE_MIX)]
    record = Record()
    with running_server(workers) as (port, process):
        server_cpu, client_cpu, busy = server_cpu_s(process), time.process_time(), machine_busy_cpu_s()
        start = time.monotonic() + 0.2
        wall = time.perf_counter()
        CLIENTS[client][1](port, class_, start, start + seconds, record)
        wall = time.perf_counter() - wall
        server_cpu, client_cpu = server_cpu_s(process) - server_cpu, time.process_time() - client_cpu
        busy = machine_busy_cpu_s() - busy
    after = process.cache_at_exit           # the caches start empty: their counters at exit are the run's
    return {"workers": workers, "client": client, "students": students, "seconds": seconds, "wall": wall,
            "rows": record.rows, "moves": sum(s.moves for s in class_), "server_cpu": server_cpu,
            "client_cpu": client_cpu, "outlived": process.outlived, "other_cpu": max(0.0, busy - server_cpu - client_cpu), "cache": {"hits": sum(s["hits"] for s in after), "misses": sum(s["misses"] for s in after),
                                                "workers": len(after), "entries": sum(s["entries"] for s in after),
                                                "bytes": sum(s["bytes"] for s in after)},
            "command": "python3 -m server --port <free port>" + (f" --workers {workers}" if workers > 1 else ""),
            "scenes": {scene: sum(1 for s in class_ if s.scene.id == scene) for scene in SCENE_MIX}}


def endpoint_rows(result: dict) -> list[dict]:
    """Per endpoint (and all together): requests, req/s, latency percentiles (ms), errors, hit rate."""
    groups: dict[str, list] = defaultdict(list)
    for row in result["rows"]:
        groups[row[0]].append(row)
    table = []
    for name, rows in [*sorted(groups.items()), ("all", result["rows"])]:
        latencies = 1000 * np.array([r[1] for r in rows]) if rows else np.zeros(1)
        p50, p95, p99 = np.percentile(latencies, [50, 95, 99])
        looked_up = [r for r in rows if r[3] in ("hit", "miss")]
        table.append({
            "endpoint": name, "requests": len(rows), "rate": len(rows) / result["wall"], "p50": p50, "p95": p95,
            "p99": p99, "client_errors": sum(1 for r in rows if 400 <= r[2] < 500),
            "server_errors": sum(1 for r in rows if r[2] >= 500), "network_errors": sum(1 for r in rows if r[2] == 0),
            "hit_rate": sum(1 for r in looked_up if r[3] == "hit") / len(looked_up) if looked_up else None,
            "partial": sum(1 for r in rows if r[4]) if name in (*BUDGETED, "all") else None})
    return table


def errors(result: dict) -> int:
    return sum(1 for r in result["rows"] if not 200 <= r[2] < 300)


def percent(value: float | None) -> str:
    return "–" if value is None else f"{100 * value:.0f} %"


def markdown_run(result: dict, title: str) -> list[str]:
    cpus = os.cpu_count() or 1
    requests = len(result["rows"])
    cache = result["cache"]
    looked_up = cache["hits"] + cache["misses"]
    lines = [f"## {title}", "", f"`{result['command']}`; client: {CLIENTS[result['client']][0]}.", "",
             "| endpoint | requests | req/s | p50 (ms) | p95 (ms) | p99 (ms) | errors (4xx / 5xx / network) "
             "| cache hits | cut short by the time budget |", "|---|---:|---:|---:|---:|---:|---|---:|---:|"]
    for row in endpoint_rows(result):
        name = f"**{row['endpoint']}**" if row["endpoint"] == "all" else f"`/api/v1/{row['endpoint']}`"
        lines.append(f"| {name} | {row['requests']} | {row['rate']:.1f} | {row['p50']:.0f} | {row['p95']:.0f} | "
                     f"{row['p99']:.0f} | {row['client_errors'] + row['server_errors'] + row['network_errors']} "
                     f"({row['client_errors']} / {row['server_errors']} / {row['network_errors']}) | "
                     f"{percent(row['hit_rate'])} | {'–' if row['partial'] is None else row['partial']} |")
    lines += ["", f"* Slider moves: {result['moves']}; requests sent: {requests} "
                  f"({percent(1 - requests / result['moves']) if result['moves'] else '–'} of the moves coalesced "
                  "into a later request while an answer was awaited).",
              f"* Cache, the counters each worker process logs as it stops ({cache['workers']} of "
              f"{result['workers']}): "
              f"{cache['hits']} hits, {cache['misses']} misses (hit rate {percent(cache['hits'] / looked_up if looked_up else None)}), "
              f"{cache['entries']} entries, {cache['bytes'] / 1e6:.1f} MB at the end; the clients saw "
              f"{sum(1 for r in result['rows'] if r[3] == 'hit')} answers with X-Cache: hit.",
              f"* Server CPU: {result['server_cpu']:.1f} s in {result['wall']:.1f} s "
              f"({100 * result['server_cpu'] / result['wall'] / cpus:.0f} % of the {cpus} CPUs); "
              f"client CPU: {result['client_cpu']:.1f} s ({100 * result['client_cpu'] / result['wall'] / cpus:.0f} % "
              f"of the {cpus} CPUs, {1000 * result['client_cpu'] / max(requests, 1):.1f} ms per request); "
              f"other processes on the machine: {result['other_cpu']:.1f} s "
              f"({100 * result['other_cpu'] / result['wall'] / cpus:.0f} % of the {cpus} CPUs).",
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
        f"{args.students} --seconds {args.seconds:g}`, seed {args.seed}.",
        "",
        f"Each student keeps to one scene (share of the class, students): {mix}. A student drags one slider of "
        "one variant for 3–8 s, then another: a random walk over the slider's values, 1–3 positions every "
        "100 ms, no pauses; the page's request (`server/lessons/requests.py`) with at most one in flight, "
        "the latest values sent when the answer arrives (`web/static/js/api.js`). Latency: from sending to the "
        "last byte of the gzip answer. The cache starts empty, at its default size (64 MB per worker process; "
        "MDL_CACHE_BYTES). *Cut short*: answers of /motion and /elastic that stopped at their wall-clock time "
        "budget with a partial result (and say so). Other jobs may share the machine: their CPU time during each "
        "run is given, and when it is large the numbers understate what the server does on its own.",
        "",
    ]
    for result in results:
        lines += markdown_run(result, f"{result['workers']} worker{'s' if result['workers'] > 1 else ''}")
    if comparison:
        lines += ["## Client implementations", "",
                  f"The same class for {comparison[0]['seconds']:g} s each against one worker; the client's CPU per "
                  "request decides which drives the runs above.", "",
                  "| client | requests | client CPU (s) | client CPU per request (ms) | share of the CPUs |",
                  "|---|---:|---:|---:|---:|"]
        for result in comparison:
            requests = max(len(result["rows"]), 1)
            lines.append(f"| {CLIENTS[result['client']][0]} | {len(result['rows'])} | {result['client_cpu']:.1f} | "
                         f"{1000 * result['client_cpu'] / requests:.2f} | "
                         f"{100 * result['client_cpu'] / result['wall'] / (os.cpu_count() or 1):.0f} % |")
        lines.append("")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--students", type=int, default=60)
    parser.add_argument("--seconds", type=float, default=60)
    parser.add_argument("--workers", type=int, nargs="+", default=[1, 2], help="server configurations to run")
    parser.add_argument("--client", choices=sorted(CLIENTS), default="threads", help="the client of the runs")
    parser.add_argument("--compare-clients", type=float, default=15, metavar="SECONDS",
                        help="also run both clients for SECONDS against one worker (0: skip)")
    parser.add_argument("--seed", type=int, default=2026)
    parser.add_argument("--output", type=Path, default=ROOT / "bench" / "results" / "classroom.md")
    args = parser.parse_args(argv)

    comparison = [run(1, client, args.students, args.compare_clients, args.seed) for client in sorted(CLIENTS)
                  ] if args.compare_clients > 0 else []
    results = [run(workers, args.client, args.students, args.seconds, args.seed) for workers in args.workers]
    text = markdown(results, comparison, args)
    print(text)
    args.output.parent.mkdir(parents=True, exist_ok=True)
    args.output.write_text(text, encoding="utf-8")
    print(f"written to {args.output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
