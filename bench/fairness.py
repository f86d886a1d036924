"""Fairness per person: one address floods the server with many clients of invented cookies, and another
student's light and elastic answers are timed with the flood and without, old tree beside new.

Each tree's server is started as the README says (``python3 -m server --port P --workers W``, default 2 workers;
both at once, their starts being most of the run). The student (source address 127.0.0.1) opens the kinematics
page (its ``mdl_client`` cookie) and runs two clients, each on a keep-alive connection, one request after another:
*light*, the kinematics page's default request (transfer functions, sine), and *elastic*, the elastic four-bar's
default machine (``POST /api/v1/elastic``), each nudged against the response cache (bench/http_floor.py). The
flood, a process of its own per server (its threads do not take the student's interpreter) on another address
(127.0.0.2): ``--flood`` threads, each with its own random cookie id, half sending the light request and half the
elastic one (nudged apart from the student's and each other's), one after another, a 429 waited out for its
Retry-After as the page does. The student is timed for ``--seconds`` alone and as long under the flood, in
``--slices`` alternating slices (tree after tree: alone, then ``--ramp`` s into the flood, then the flood paused
until its requests in flight are answered), so that the machine's changing load falls on every tree and phase
alike.

Reported per tree: the student's requests, p50 and p95 (send to last byte) alone and under the flood, its
non-200 answers; the flood's answered and 429 requests; the server's CPU while the student was timed; and the
ratios flood / alone (the target: light p95 ≤ 2×).

    python bench/fairness.py [--old /tmp/mdl-fair-old] [--new .] [--flood 64] [--seconds 10] [--ramp 1]
                             [--slices 5] [--workers 2] [--output bench/results/fairness.md]
"""
from __future__ import annotations

import argparse
import http.client
import json
import multiprocessing
import os
import secrets
import sys
import threading
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from http_floor import encoded, nudged_request, variant_of  # noqa: E402
from trees import (ROOT, add_tree_arguments, check_tree, lessons, machine_line,  # noqa: E402
                   percentiles, running_server, server_cpu_s, tree_label, write_result)

HEADERS = {"Content-Type": "application/json", "Accept-Encoding": "gzip", "Accept": "*/*"}
LANG = "ru"
TIMEOUT_S = 120
TARGET_RATIO = 2.0
STARTUP_S = 400                 # two servers starting at once on a loaded machine
DEFAULT_RETRY_AFTER_S = 1.0
NETWORK = "network error"
READING = ("Reading: the student sends each request as soon as the last is answered, so it wants a whole worker, and "
           "a fair share between it and the flood is half: its request waits for the flood's one computing in its "
           "worker (the place passes to the flood in the instant between two of the student's requests), then "
           "computes. With several workers the flood's share is counted across them (while the student asks, what "
           "all the workers but one may hold: server/runtime/server_shares.py), so it leaves one worker's CPU to "
           "the student; beside the student it still takes its share of the heavy processes, the flooding client's "
           "own CPU and the event loop's reading, checking and answering of its requests. On a loaded machine "
           "every one of these waits is stretched, and the ratios move from one run to the next.")
STUDENT, FLOOD = "127.0.0.1", "127.0.0.2"       # two source addresses on loopback
KINDS = {"light": ("transfer-functions", "sine", "/api/v1/kinematics"),
         "elastic": ("elastic-four-bar", None, "/api/v1/elastic")}


def request_of(kind: str):
    """(path, k → the body nudged by k) of a kind of request."""
    scene_id, variant_id, path = KINDS[kind]
    scene = lessons()[0]()[scene_id]
    variant = variant_of(scene, variant_id)
    return f"{path}?lang={LANG}", lambda k: encoded(nudged_request(scene, variant, k))


def post(connection: http.client.HTTPConnection, path: str, body: bytes, cookie: str):
    """(status or 0 for a network error, Retry-After, seconds)."""
    start = time.perf_counter()
    try:
        connection.request("POST", path, body=body, headers={**HEADERS, "Cookie": f"mdl_client={cookie}"})
        answer = connection.getresponse()
        answer.read()
    except (OSError, http.client.HTTPException):
        connection.close()
        return 0, None, time.perf_counter() - start
    return answer.status, answer.getheader("retry-after"), time.perf_counter() - start


def connect(port: int, source: str) -> http.client.HTTPConnection:
    return http.client.HTTPConnection("127.0.0.1", port, timeout=TIMEOUT_S, source_address=(source, 0))


def student_cookie(port: int) -> str:
    """The cookie the kinematics page gives the student."""
    connection = connect(port, STUDENT)
    try:
        connection.request("GET", f"/scenes/{KINDS['light'][0]}")
        answer = connection.getresponse()
        answer.read()
        cookie = answer.getheader("set-cookie") or ""
    finally:
        connection.close()
    return cookie.split(";")[0].partition("=")[2] or secrets.token_urlsafe(16)


def student(port: int, cookie: str, kind: str, seconds: float, out: dict) -> None:
    """One of the student's clients: `kind` requests one after another for `seconds`; times of the 200s."""
    path, body = request_of(kind)
    connection, times, statuses = connect(port, STUDENT), [], {}
    end, k = time.monotonic() + seconds, 0
    while time.monotonic() < end:
        k += 1
        status, _, elapsed = post(connection, path, body(k), cookie)
        statuses[status] = statuses.get(status, 0) + 1
        if status == 200:
            times.append(1000 * elapsed)
    connection.close()
    out[kind] = {"times": times, "statuses": statuses}


def timed_student(port: int, cookie: str, seconds: float) -> dict:
    out: dict = {}
    threads = [threading.Thread(target=student, args=(port, cookie, kind, seconds, out)) for kind in KINDS]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    return out


def flood(port: int, count: int, active, stop, counts: dict) -> None:
    """The flood (in a process of its own): `count` threads, each its own random cookie, sending while `active`
    is set, until `stop` is; counts["busy"] the requests in flight."""
    requests = {kind: request_of(kind) for kind in KINDS}

    def add(name: str, n: int) -> None:
        with counts[name].get_lock():
            counts[name].value += n

    def run(n: int) -> None:
        cookie, (path, body) = secrets.token_urlsafe(16), requests[list(KINDS)[n % 2]]
        connection, sent = connect(port, FLOOD), 0
        while not stop.is_set():
            if not active.wait(0.2):
                continue
            sent += 1
            add("busy", 1)
            status, retry_after, _ = post(connection, path, body(-(1 + n + count * sent)), cookie)
            add("busy", -1)
            if status == 0:
                connection = connect(port, FLOOD)
            add("answered" if status == 200 else "429" if status == 429 else "failed", 1)
            if status == 429:
                try:
                    stop.wait(max(0.0, float(retry_after)))
                except (TypeError, ValueError):
                    stop.wait(DEFAULT_RETRY_AFTER_S)
        connection.close()

    threads = [threading.Thread(target=run, args=(n,), daemon=True) for n in range(count)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join(TIMEOUT_S)


class Flood:
    """A paused flood on one server, in a process of its own."""

    def __init__(self, port: int, count: int):
        context = multiprocessing.get_context("fork")
        self.active, self.stop = context.Event(), context.Event()
        self.counts = {name: context.Value("i", 0) for name in ("answered", "429", "failed", "busy")}
        self.process = context.Process(target=flood, args=(port, count, self.active, self.stop, self.counts))
        self.process.start()

    def pause(self) -> None:
        """Stop sending and wait (a guard against a hang) until the requests in flight are answered."""
        self.active.clear()
        deadline = time.monotonic() + TIMEOUT_S
        while self.counts["busy"].value > 0 and time.monotonic() < deadline:
            time.sleep(0.05)

    def tally(self) -> dict:
        return {name: value.value for name, value in self.counts.items() if name != "busy"}

    def end(self) -> None:
        self.stop.set()
        self.process.join(TIMEOUT_S)
        if self.process.is_alive():
            self.process.kill()
            self.process.join()


def measure(servers: dict, args) -> dict:
    """The student alone and under the flood on each tree's server, in --slices alternating slices (tree after
    tree, alone then flooded), so that a change in the machine's load falls on every tree and phase alike."""
    results = {name: {phase: {kind: {"times": [], "statuses": {}} for kind in KINDS} | {"cpu": 0.0}
                      for phase in ("alone", "flood")} for name in servers}
    cookies, floods = {}, {}
    try:
        for name, (port, _) in servers.items():
            cookies[name] = student_cookie(port)
            for kind in KINDS:                                # the first answers (imports, a heavy process's start)
                path, body = request_of(kind)
                post(connect(port, STUDENT), path, body(0), cookies[name])
            floods[name] = Flood(port, args.flood)
        seconds = args.seconds / args.slices
        for _ in range(args.slices):
            for name, (port, process) in servers.items():
                for phase in ("alone", "flood"):
                    if phase == "flood":
                        floods[name].active.set()
                        time.sleep(args.ramp)
                    cpu = server_cpu_s(process)
                    slice_ = timed_student(port, cookies[name], seconds)
                    results[name][phase]["cpu"] += server_cpu_s(process) - cpu
                    for kind in KINDS:
                        kept = results[name][phase][kind]
                        kept["times"] += slice_[kind]["times"]
                        for status, n in slice_[kind]["statuses"].items():
                            kept["statuses"][status] = kept["statuses"].get(status, 0) + n
                    if phase == "flood":
                        floods[name].pause()
        for name in servers:
            results[name]["flood"]["flood"] = floods[name].tally()
    finally:
        for each in floods.values():
            each.end()
    return results


def measured_trees(trees: dict[str, Path], args) -> dict:
    """Each tree's server started at once (their starts overlap: most of the run's wall time), then measured
    while both run."""
    servers, ready, done, failed = {}, threading.Semaphore(0), threading.Event(), []

    def serve(name: str, tree: Path) -> None:
        try:
            with running_server(args.workers, tree=tree, startup_s=STARTUP_S) as server:
                servers[name] = server
                ready.release()
                done.wait()
        except Exception as error:               # noqa: BLE001 — reported by the main thread
            failed.append(f"{name}: {error}")
            ready.release()

    threads = [threading.Thread(target=serve, args=item) for item in trees.items()]
    for thread in threads:
        thread.start()
    try:
        for _ in threads:
            ready.acquire()
        if failed:
            raise RuntimeError("; ".join(failed))
        return measure({name: servers[name] for name in trees}, args)
    finally:
        done.set()
        for thread in threads:
            thread.join()


def fmt(ms: float) -> str:
    return "–" if ms != ms else (f"{ms:,.0f}" if ms >= 100 else f"{ms:.1f}")


def markdown(args, results: dict, load_end: float) -> str:
    old_tree = f"`{args.old}` ({args.old_label})" if args.old_label else tree_label(args.old)
    lines = ["# Fairness per person: another student's answers under one address's flood", "",
             f"{machine_line()}, {load_end:.1f} at the end"
             + (": **the machine was loaded** (other work on its CPUs; every time longer than on a quiet machine)"
                if load_end > (os.cpu_count() or 1) else "")
             + f". `python bench/fairness.py --flood {args.flood} "
             f"--seconds {args.seconds:g} --ramp {args.ramp:g} --slices {args.slices} --workers {args.workers}`.", "",
             f"* old tree: {old_tree}, new tree: {tree_label(args.new)}; a fresh "
             f"`python3 -m server --port <free port> --workers {args.workers}` for each.",
             f"* Flood: one address ({FLOOD}), {args.flood} threads in a process of their own, each with its own "
             "random `mdl_client` id; half send the kinematics default request, half the elastic four-bar's, one "
             "after another (a 429 waited out for its Retry-After). The student (another address, its page's "
             "cookie): a light client (kinematics, sine) and an elastic client (the elastic four-bar), each one "
             f"request after another for {args.seconds:g} s alone and as long under the flood, in {args.slices} "
             f"alternating slices (tree after tree; timed from {args.ramp:g} s into the flood). Every request "
             "nudged against the response cache.", "",
             "| tree | flood | light requests | light p50 (ms) | light p95 (ms) | elastic requests | elastic p50 (ms) "
             "| elastic p95 (ms) | student non-200 | flood answered | flood 429 | server CPU (s) |",
             "|---|---|---:|---:|---:|---:|---:|---:|---|---:|---:|---:|"]
    for tree in ("old", "new"):
        for phase in ("alone", "flood"):
            result = results[tree][phase]
            light, elastic = (result[kind]["times"] for kind in KINDS)
            others = {s: n for kind in KINDS for s, n in result[kind]["statuses"].items() if s != 200}
            flood_counts = result.get("flood", {})
            lines.append(
                f"| {tree} | {'yes' if phase == 'flood' else 'no'} | {len(light)} | "
                f"{' | '.join(fmt(p) for p in percentiles(light, (50, 95)))} | {len(elastic)} | "
                f"{' | '.join(fmt(p) for p in percentiles(elastic, (50, 95)))} | "
                f"{', '.join(f'{s or NETWORK}: {n}' for s, n in others.items()) or '0'} | "
                f"{flood_counts.get('answered', '–')} | {flood_counts.get('429', '–')} | {result['cpu']:.1f} |")
    lines += ["", "| tree | light p50 flood / alone | light p95 flood / alone | elastic p50 flood / alone "
                  "| elastic p95 flood / alone | light p95 ≤ 2× |", "|---|---:|---:|---:|---:|---|"]
    for tree in ("old", "new"):
        ratios = []
        for kind in KINDS:
            alone = percentiles(results[tree]["alone"][kind]["times"], (50, 95))
            flooded = percentiles(results[tree]["flood"][kind]["times"], (50, 95))
            ratios += [f / a for f, a in zip(flooded, alone)]
        lines.append(f"| {tree} | {' | '.join(f'{r:.1f}×' for r in ratios)} | "
                     f"{'yes' if ratios[1] <= TARGET_RATIO else '**no**'} |")
    lines += ["", READING]
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_tree_arguments(parser)
    parser.add_argument("--flood", type=int, default=64, help="threads of the flooding address, each its own cookie")
    parser.add_argument("--seconds", type=float, default=10, help="how long the student is timed, alone and flooded")
    parser.add_argument("--ramp", type=float, default=1, help="seconds of flood before the student is timed")
    parser.add_argument("--slices", type=int, default=5, help="alternating slices of alone and flooded timing")
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--old-label", default=None, help="what the old tree is, when it is not a checkout")
    parser.add_argument("--trees", nargs="+", choices=("old", "new"), default=["old", "new"])
    parser.add_argument("--output", type=Path, default=ROOT / "bench" / "results" / "fairness.md")
    args = parser.parse_args(argv)
    args.old, args.new = check_tree(args.old), check_tree(args.new)
    results = measured_trees({tree: args.old if tree == "old" else args.new for tree in args.trees}, args)
    for tree, result in results.items():
        print(f"{tree}: " + json.dumps({phase: {kind: [len(r[kind]["times"]), *map(fmt, percentiles(
            r[kind]["times"], (50, 95)))] for kind in KINDS} for phase, r in result.items()}), file=sys.stderr)
    if len(results) < 2:
        return 0
    text = markdown(args, results, os.getloadavg()[0])
    print(text)
    write_result(text, args.output)
    return 0


if __name__ == "__main__":
    sys.exit(main())
