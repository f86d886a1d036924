"""Fairness: one client's heavy load against another client's kinematics, old server beside new (the
target: kinematics p95 ≤ 100 ms while another client holds 64 concurrent heavy requests).

For each tree and each load (none; a heavy client that honours Retry-After; one that does not), a fresh server
is started as the README says (``python3 -m server --port P``, one worker unless ``--workers``) and two clients
work on it over loopback, each a browser of its own (its own cookies, e.g. a client id ``mdl_client``, first
got from its scene's page):

* the heavy client holds ``--heavy`` requests in flight on as many keep-alive connections: half the default
  request of the elastic four-bar scene (``POST /api/v1/elastic``), half the live work–precision study of the
  same machine (``POST /api/v1/work-precision/elastic``), each answer followed at once by the next request; the
  damping b is scaled by 1 + k·1e-8 per request so that the response cache never answers for the server. A 429
  is either waited out for its Retry-After (*honours*) or sent again at once (*ignores*);
* after ``--ramp`` seconds the light client sends the kinematics page's default request (transfer functions,
  sine; the crank length nudged against the cache in the same way) one after another for ``--seconds``,
  timing each round trip (send to last byte).

The light client does the same on the idle server first. Reported: the light client's p50/p95/p99 with and
without the load, its errors and 429s; the heavy requests sent, answered, refused with 429 and failed while
the heavy client ran; the server's and the clients' CPU while the light client ran (the clients share the
machine's CPUs with the server: a client sending again at once costs CPU of its own).

    python bench/fairness.py [--old /tmp/mdl-old] [--new .] [--heavy 64] [--seconds 20] [--ramp 3]
                             [--workers 1] [--output bench/results/fairness.md]
"""
from __future__ import annotations

import argparse
import http.client
import json
import sys
import threading
import time
from http.cookies import SimpleCookie
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from http_floor import encoded, nudged_request, variant_of  # noqa: E402
from trees import (ROOT, add_tree_arguments, check_tree, commit_of, lessons, machine_line,  # noqa: E402
                   percentiles, running_server, server_cpu_s)

HEADERS = {"Content-Type": "application/json", "Accept-Encoding": "gzip", "Accept": "*/*"}
LANG = "ru"
TIMEOUT_S = 300
TARGET_P95_MS = 100.0
DEFAULT_RETRY_AFTER_S = 1.0
NETWORK = "network error"
HEAVY_SCENE = "elastic-four-bar"
HEAVY_PATHS = ("/api/v1/elastic", "/api/v1/work-precision/elastic")
LIGHT_SCENE = ("transfer-functions", "sine")
LOADS = {"none": "no heavy load", "honours": "heavy client honours Retry-After",
         "ignores": "heavy client ignores Retry-After (sends again at once)"}


class Browser:
    """One client: its cookies, shared by its connections."""

    def __init__(self, port: int):
        self.port, self.cookies, self.lock = port, {}, threading.Lock()

    def connection(self) -> http.client.HTTPConnection:
        return http.client.HTTPConnection("127.0.0.1", self.port, timeout=TIMEOUT_S)

    def headers(self) -> dict:
        with self.lock:
            return {**HEADERS, **({"Cookie": "; ".join(f"{k}={v}" for k, v in self.cookies.items())}
                                  if self.cookies else {})}

    def keep(self, answer: http.client.HTTPResponse) -> None:
        for name, value in answer.getheaders():
            if name.lower() == "set-cookie":
                with self.lock:
                    self.cookies.update({k: m.value for k, m in SimpleCookie(value).items()})

    def open_page(self, path: str) -> None:
        connection = self.connection()
        try:
            connection.request("GET", path)
            answer = connection.getresponse()
            answer.read()
            self.keep(answer)
        finally:
            connection.close()

    def post(self, connection: http.client.HTTPConnection, path: str, body: bytes):
        """(status or 0 for a network error, Retry-After header, seconds, connection to use next)."""
        start = time.perf_counter()
        try:
            connection.request("POST", path, body=body, headers=self.headers())
            answer = connection.getresponse()
            answer.read()
        except (OSError, http.client.HTTPException):
            connection.close()
            return 0, None, time.perf_counter() - start, self.connection()
        self.keep(answer)
        return answer.status, answer.getheader("retry-after"), time.perf_counter() - start, connection


class HeavyClient:
    """`count` connections, each keeping one heavy request in flight until stopped."""

    def __init__(self, browser: Browser, count: int, honours: bool):
        scene = lessons()[0]()[HEAVY_SCENE]
        self.scene, self.variant = scene, variant_of(scene)
        self.browser, self.honours = browser, honours
        self.counter, self.lock = 0, threading.Lock()
        self.stop = threading.Event()
        self.counts = {"sent": 0, "answered": 0, "429": 0, "failed": 0}
        self.threads = [threading.Thread(target=self._run, args=(HEAVY_PATHS[i % 2],), daemon=True)
                        for i in range(count)]

    def _body(self) -> bytes:
        with self.lock:
            self.counter += 1
            k = self.counter
        return encoded(nudged_request(self.scene, self.variant, k))

    def _count(self, key: str) -> None:
        if not self.stop.is_set():
            with self.lock:
                self.counts[key] += 1

    def _run(self, path: str) -> None:
        connection = self.browser.connection()
        while not self.stop.is_set():
            self._count("sent")
            status, retry_after, _, connection = self.browser.post(connection, f"{path}?lang={LANG}", self._body())
            if self.stop.is_set():
                break
            if status == 429:
                self._count("429")
                if self.honours:
                    try:
                        wait = max(0.0, float(retry_after))
                    except (TypeError, ValueError):
                        wait = DEFAULT_RETRY_AFTER_S
                    self.stop.wait(wait)
            elif 200 <= status < 300:
                self._count("answered")
            else:
                self._count("failed")
                if status == 0:
                    self.stop.wait(0.1)

    def start(self) -> None:
        for thread in self.threads:
            thread.start()


def light_client(browser: Browser, seconds: float) -> dict:
    scene = lessons()[0]()[LIGHT_SCENE[0]]
    variant = variant_of(scene, LIGHT_SCENE[1])
    connection = browser.connection()
    times, statuses = [], {}
    end, k = time.monotonic() + seconds, 0
    browser.post(connection, f"/api/v1/kinematics?lang={LANG}", encoded(nudged_request(scene, variant, 0)))
    while time.monotonic() < end:
        k += 1
        status, _, elapsed, connection = browser.post(connection, f"/api/v1/kinematics?lang={LANG}",
                                                      encoded(nudged_request(scene, variant, k)))
        statuses[status] = statuses.get(status, 0) + 1
        if status == 200:
            times.append(1000 * elapsed)
    connection.close()
    return {"times": times, "statuses": statuses}


def phase(tree: Path, load: str, args) -> dict:
    with running_server(args.workers, tree=tree) as (port, process):
        light_browser, heavy_browser = Browser(port), Browser(port)
        light_browser.open_page(f"/scenes/{LIGHT_SCENE[0]}")
        heavy = None
        if load != "none":
            heavy_browser.open_page(f"/scenes/{HEAVY_SCENE}")
            heavy = HeavyClient(heavy_browser, args.heavy, honours=load == "honours")
            heavy.start()
            time.sleep(args.ramp)
        cpu, client_cpu, wall = server_cpu_s(process), time.process_time(), time.perf_counter()
        light = light_client(light_browser, args.seconds)
        if heavy:
            heavy.stop.set()
        wall, cpu = time.perf_counter() - wall, server_cpu_s(process) - cpu
        client_cpu = time.process_time() - client_cpu
    return {"light": light, "heavy": heavy.counts if heavy else None, "wall": wall, "server_cpu": cpu,
            "client_cpu": client_cpu,
            "cookies": {"light": sorted(light_browser.cookies), "heavy": sorted(heavy_browser.cookies)}}


def fmt(ms: float) -> str:
    return "–" if ms != ms else (f"{ms:.0f}" if ms >= 100 else f"{ms:.1f}")


def markdown(args, results: dict) -> str:
    lines = ["# Fairness: another client's kinematics under one client's heavy load", "",
             f"{machine_line()}. `python bench/fairness.py --heavy {args.heavy} --seconds {args.seconds:g} --ramp "
             f"{args.ramp:g} --workers {args.workers}`.", "",
             f"* old: `{args.old}` ({commit_of(args.old)}), new: `{args.new}` ({commit_of(args.new)}); a fresh "
             f"`python3 -m server --port <free port>{f' --workers {args.workers}' if args.workers > 1 else ''}` "
             "for every row.",
             f"* Heavy client: {args.heavy} requests in flight (half `/api/v1/elastic`, half "
             f"`/api/v1/work-precision/elastic`, the {HEAVY_SCENE} scene's default machine, nudged against the "
             f"cache), started {args.ramp:g} s before the light client. Light client: the kinematics page's default "
             f"request (sine, 361 angles, nudged against the cache) one after another for {args.seconds:g} s. "
             "Each client keeps its own cookies. Target: light p95 ≤ 100 ms under the load (new).", "",
             "| tree | load | light requests | light p50 (ms) | light p95 (ms) | light p99 (ms) | p95 loaded / idle "
             "| light ≤ 100 ms p95 | light non-200 | heavy sent | heavy answered | heavy 429 | heavy failed "
             "| server CPU (s) | clients' CPU (s) | cookies light / heavy |",
             "|---|---|---:|---:|---:|---:|---:|---|---|---:|---:|---:|---:|---:|---:|---|"]
    for load, label in LOADS.items():
        for tree in ("old", "new"):
            result = results.get((tree, load))
            if result is None:
                continue
            p50, p95, p99 = percentiles(result["light"]["times"], (50, 95, 99))
            idle = percentiles(results[(tree, "none")]["light"]["times"], (95,))[0] \
                if (tree, "none") in results else float("nan")
            heavy = result["heavy"] or {}
            others = {s: n for s, n in result["light"]["statuses"].items() if s != 200}
            lines.append(
                f"| {tree} | {label} | {len(result['light']['times'])} | {fmt(p50)} | {fmt(p95)} | {fmt(p99)} | "
                f"{p95 / idle:.1f}× | {'yes' if p95 <= TARGET_P95_MS else '**no**'} | "
                f"{', '.join(f'{s or NETWORK}: {n}' for s, n in others.items()) or '0'} | "
                f"{heavy.get('sent', '–')} | {heavy.get('answered', '–')} | {heavy.get('429', '–')} | "
                f"{heavy.get('failed', '–')} | {result['server_cpu']:.1f} | {result['client_cpu']:.1f} | "
                f"{', '.join(result['cookies']['light']) or '–'} / {', '.join(result['cookies']['heavy']) or '–'} |")
    for load, label in list(LOADS.items())[1:]:
        if ("old", load) in results and ("new", load) in results:
            old = percentiles(results[("old", load)]["light"]["times"], (95,))[0]
            new = percentiles(results[("new", load)]["light"]["times"], (95,))[0]
            lines.append(f"\n* {label}: light p95 old/new {old / new:.1f}×.")
    lines.append("\nHeavy counts: from the heavy client's start to the light client's end (requests still in "
                 "flight then are counted as sent only); CPU of the server (its session) and of both clients (this "
                 "process, on the same CPUs): while the light client ran.")
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_tree_arguments(parser)
    parser.add_argument("--heavy", type=int, default=64, help="heavy requests the heavy client holds in flight")
    parser.add_argument("--seconds", type=float, default=20, help="how long the light client works in each row")
    parser.add_argument("--ramp", type=float, default=3, help="seconds of heavy load before the light client starts")
    parser.add_argument("--workers", type=int, default=1)
    parser.add_argument("--loads", nargs="+", choices=sorted(LOADS), default=list(LOADS))
    parser.add_argument("--output", type=Path, default=ROOT / "bench" / "results" / "fairness.md")
    args = parser.parse_args(argv)
    args.old, args.new = check_tree(args.old), check_tree(args.new)
    results = {}
    for load in args.loads:
        for tree, path in (("old", args.old), ("new", args.new)):
            results[(tree, load)] = phase(path, load, args)
            print(f"{tree}, {LOADS[load]}: {json.dumps(results[(tree, load)]['heavy'])}", file=sys.stderr, flush=True)
    text = markdown(args, results)
    print(text)
    args.output.parent.mkdir(parents=True, exist_ok=True)
    args.output.write_text(text, encoding="utf-8")
    print(f"written to {args.output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
