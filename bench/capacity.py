"""Capacity: the largest class a deployment holds at the class targets, on one CPU, on two, and as two app servers
behind nginx.

The class is bench/classroom.py's, new page pattern (its scene mix; a student grabs a slider, which asks for the
coarse family, then the full one; drags 1–3 s, sending exact requests only until the family is there; releases:
one exact request; looks 1–2 s; grabs again), driven by its threads client. The class runs on the same machine as
the servers, over loopback, on every CPU unless ``--client-cpus`` pins it. Three deployments:

* **one-cpu**: ``taskset -c 0 python3 -m server --port P`` (one worker, and the heavy processes it starts, on CPU 0);
* **two-workers**: ``taskset -c 0,1 python3 -m server --port P --workers 2``;
* **two-servers**: two app servers of one worker each, ``taskset -c 0`` and ``taskset -c 1``, behind a real nginx
  running the shipped site deploy/nginx/mdl.conf (bench/nginx_proxy.py), the class talking to nginx; the two
  servers name one file for the slider families they share (``MDL_SHARED_CACHE``, as docs/deployment.md says for
  servers on one host), so that a family one of them computed is not computed by the other.

Every server starts afresh for each class (its caches empty) and is left to settle (its processes idle, the heavy
processes warm) before the students open their pages, with MDL_DATA_DIR in a temporary folder,
``MDL_ADDRESS_CONCURRENCY=0`` (every student is 127.0.0.1: each browser cookie counts as a client of its own, as
in bench/classroom.py) and ``MDL_FORWARDED_ALLOW_IPS=127.0.0.1`` (nginx is trusted, as the deployment says). The
slider requests never use the classroom's database, so each server keeps its own SQLite file.

A class *holds* when, over the run (each p95 interpolated between the ranks, as bench/classroom.py's tables, by
which point 1's targets are read): exact answers p95 ≤ 150 ms on the light scenes and ≤ 500 ms on the elastic
ones; the first preview of a grab (its coarse family) p95 ≤ 500 ms light and ≤ 1.5 s elastic, a coarse family
given up by the student's next grab (at least 2 s after it was asked) counted as later than its target; no error
(any answer but 2xx or a 429 waited out, full families included); nothing cut short by a time budget. Classes of
``--sizes`` students are run in turn until one fails; then the largest that holds is bisected between the last
class that held and the first that failed, to within ``--resolution`` of it (one run per size: the search takes
the result as monotonic in the class size). Students per CPU and the ratio two-servers / one-cpu (target ≥ 1.8)
are written with every run's numbers, the load average before it and the commands to bench/results/capacity.md
(rewritten after every run, so an interrupted search leaves what it found).

    python3 bench/capacity.py [--seconds 30] [--configurations one-cpu two-workers two-servers]
                              [--sizes 10 20 30 45 60 80 100 130 160 200] [--resolution 0.1] [--client-cpus 2 3]
    python3 bench/capacity.py --quick --output /tmp/capacity.md     # 2 students, 3 s, one-cpu and two-servers
"""
from __future__ import annotations

import argparse
import math
import os
import platform
import random
import signal
import subprocess
import sys
import tempfile
import time
from contextlib import ExitStack, contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Callable


sys.path.insert(0, str(Path(__file__).resolve().parent))
import classroom  # noqa: E402
from nginx_proxy import nginx_binary, nginx_proxy  # noqa: E402
from trees import ROOT, running_server, server_cpu_s, session_processes, tree_label  # noqa: E402

PATTERN = "new"
# The class targets, p95 in ms: exact answers, and the first preview of a grab (the coarse family).
TARGETS_MS = {("exact", "light"): 150, ("exact", "elastic"): 500, ("coarse", "light"): 500, ("coarse", "elastic"): 1500}
TARGET_RATIO = 1.8              # capacity of two servers / one server on one CPU
DEFAULT_SIZES = [10, 20, 30, 45, 60, 80, 100, 130, 160, 200]
QUICK = {"sizes": [2], "seconds": 3.0, "configurations": ["one-cpu", "two-servers"]}
# servers idle: < 0.08 CPU-s in 1 s per worker (their heavy processes warm; an idle worker and its supervisor take
# about 0.04 each: uvicorn's tick every 0.1 s and its ping every 0.5 s), waited ≤ 120 s
SETTLE = (0.08, 1.0, 120.0)
SERVER_ENV = {"MDL_ADDRESS_CONCURRENCY": "0", "MDL_FORWARDED_ALLOW_IPS": "127.0.0.1"}
NAMES = {("exact", "light"): "exact, light", ("exact", "elastic"): "exact, elastic",
         ("coarse", "light"): "first preview, light", ("coarse", "elastic"): "first preview, elastic"}


@dataclass(frozen=True)
class Deployment:
    """App servers, each (CPU list for taskset, workers), alone or behind nginx."""
    name: str
    title: str
    servers: tuple[tuple[str, int], ...]
    behind_nginx: bool
    shared_families: bool = False   # the servers name one MDL_SHARED_CACHE file

    @property
    def cpus(self) -> int:
        return len({cpu for cpus, _ in self.servers for cpu in cpus.split(",")})

    def server_command(self, cpus: str, workers: int, port: str = "{port}") -> list[str]:
        return ["taskset", "-c", cpus, sys.executable, "-m", "server", "--port", port,
                *(["--workers", str(workers)] if workers > 1 else [])]

    def commands(self) -> list[str]:
        shared = ["MDL_SHARED_CACHE=DIR/families.sqlite"] if self.shared_families else []
        shown = [" ".join([*shared, "taskset", "-c", cpus, "python3", "-m", "server", "--port", f"P{k + 1}",
                           *(["--workers", str(workers)] if workers > 1 else [])])
                 for k, (cpus, workers) in enumerate(self.servers)]
        if self.behind_nginx:
            shown.append("nginx -p DIR -c DIR/nginx.conf (the shipped deploy/nginx/mdl.conf, upstream "
                         + ", ".join(f"127.0.0.1:P{k + 1}" for k in range(len(self.servers))) + ")")
        return shown


DEPLOYMENTS = {d.name: d for d in (
    Deployment("one-cpu", "one server, 1 worker, on CPU 0", (("0", 1),), False),
    Deployment("two-workers", "one server, 2 workers, on CPUs 0–1", (("0,1", 2),), False),
    Deployment("two-servers", "two servers of 1 worker (CPU 0, CPU 1) behind nginx, sharing the families' file",
               (("0", 1), ("1", 1)), True, shared_families=True),
)}


@contextmanager
def deployed(deployment: Deployment, tree: Path = ROOT):
    """Start the deployment's servers (and nginx); yield (the port the class talks to, the server processes,
    the Nginx or None). Everything started is stopped on the way out, nginx first."""
    with ExitStack() as stack:
        folder = Path(stack.enter_context(tempfile.TemporaryDirectory(prefix="mdl-deployed-")))
        env = SERVER_ENV | ({"MDL_SHARED_CACHE": str(folder / "families.sqlite")} if deployment.shared_families
                            else {})
        servers = [stack.enter_context(running_server(workers, tree=tree, env=env,
                                                      command=deployment.server_command(cpus, workers)))
                   for cpus, workers in deployment.servers]
        proxy = None
        if deployment.behind_nginx:
            proxy = stack.enter_context(nginx_proxy(folder, [port for port, _ in servers]))
        yield (proxy.port if proxy else servers[0][0]), [process for _, process in servers], proxy


def settle(processes: list[subprocess.Popen], workers: int) -> float:
    """Wait until the servers' sessions, of `workers` workers in all, are idle (the heavy processes each worker
    starts have loaded their compiled kernels, which the readiness check does not wait for); returns the seconds
    waited."""
    per_worker, window, longest = SETTLE
    quiet = per_worker * workers
    started = time.monotonic()
    before = sum(server_cpu_s(p) for p in processes)
    while time.monotonic() - started < longest:
        time.sleep(window)
        now = sum(server_cpu_s(p) for p in processes)
        if now - before < quiet:
            break
        before = now
    return time.monotonic() - started


def run_class(deployment: Deployment, students: int, seconds: float, seed: int, tree: Path = ROOT) -> dict:
    """One class against a fresh deployment: the numbers of bench/classroom.py's run, and the load average
    before it, nginx's CPU and its requests per app server."""
    all_scenes = classroom.scenes()
    rng = random.Random(seed)
    class_ = [classroom.Student(all_scenes[scene], random.Random(rng.random()))
              for scene in classroom.apportion(students, classroom.SCENE_MIX)]
    record = classroom.Record()
    load_before = os.getloadavg()
    with deployed(deployment, tree) as (port, processes, proxy):
        settled = settle(processes, sum(workers for _, workers in deployment.servers))
        connections = classroom.open_pages(port, class_, record)
        nginx_cpu = (lambda: sum(session_processes(proxy.process.pid).values())) if proxy else (lambda: 0.0)
        server_cpu, proxy_cpu = sum(server_cpu_s(p) for p in processes), nginx_cpu()
        client_cpu, busy = time.process_time(), classroom.machine_busy_cpu_s()
        start = time.monotonic() + 0.2
        wall = time.perf_counter()
        classroom.drive_threads(connections, start, start + seconds, PATTERN)
        wall = time.perf_counter() - wall
        server_cpu = sum(server_cpu_s(p) for p in processes) - server_cpu
        proxy_cpu, client_cpu = nginx_cpu() - proxy_cpu, time.process_time() - client_cpu
        busy = classroom.machine_busy_cpu_s() - busy
        load = os.getloadavg()
        upstreams = proxy.upstreams() if proxy else {}
    after = [counters for p in processes for counters in classroom.cache_counters_at_exit(p.log_text)]
    workers = sum(w for _, w in deployment.servers)
    return {"deployment": deployment.name, "workers": workers, "client": "threads", "pattern": PATTERN,
            "students": students, "seconds": seconds, "wall": wall, "rows": record.rows,
            "throttled": record.throttled, "abandoned": record.abandoned, "given_up": record.given_up,
            "resent": record.resent, "unrefined": getattr(record, "unrefined", []), "load": load,
            "load_before": load_before, "settled": settled, "moves": sum(s.moves for s in class_),
            "server_cpu": server_cpu,
            "nginx_cpu": proxy_cpu, "client_cpu": client_cpu,
            "other_cpu": max(0.0, busy - server_cpu - proxy_cpu - client_cpu),
            "outlived": sum(p.outlived for p in processes), "upstreams": dict(upstreams),
            "cache": {"hits": sum(s["hits"] for s in after), "misses": sum(s["misses"] for s in after),
                      "workers": len(after), "entries": sum(s["entries"] for s in after),
                      "bytes": sum(s["bytes"] for s in after)},
            "command": "; ".join(deployment.commands()),
            "scenes": {scene: sum(1 for s in class_ if s.scene.id == scene) for scene in classroom.SCENE_MIX}}


def verdict(result: dict) -> dict:
    """Whether the class held: p95 per target (a coarse family given up counts as later than any target),
    errors and answers cut short over every answer, and the reasons it did not hold."""
    cells, reasons = {}, []
    for (kind, light), target in TARGETS_MS.items():
        latencies = [1000 * r[1] for r in result["rows"] if r[5] == kind and r[6] == light]
        late = sum(1 for k, lt in result["given_up"] if k == kind and lt == light) if kind == "coarse" else 0
        if not latencies and not late:
            cells[kind, light] = None
            continue
        p95 = p95_of(latencies, late)
        cells[kind, light] = (p95, len(latencies), late)
        if not p95 <= target:
            reasons.append(f"{NAMES[kind, light]} p95 {fmt_ms(p95)} > {target} ms")
    errors = sum(1 for r in result["rows"] if not 200 <= r[2] < 300)
    partial = sum(1 for r in result["rows"] if r[4])
    if errors:
        reasons.append(f"{errors} error{'s' if errors > 1 else ''}")
    if partial:
        reasons.append(f"{partial} cut short")
    if not result["rows"]:
        reasons.append("no answer at all")
    return {"cells": cells, "errors": errors, "partial": partial, "held": not reasons, "reasons": reasons}


def p95_of(latencies: list[float], late: int) -> float:
    """The 95th percentile by linear interpolation between the ranks (numpy's default, as bench/classroom.py
    reports every p95 of point 1), `late` answers given up counted as later than any (infinite): infinite when
    the interpolation reaches one of them."""
    values = sorted(latencies) + [math.inf] * late
    rank = 0.95 * (len(values) - 1)
    below, above = values[math.floor(rank)], values[math.ceil(rank)]
    return math.inf if math.isinf(above) else below + (above - below) * (rank - math.floor(rank))


def search(holds: Callable[[int], bool], sizes: list[int], resolution: float, bisect: bool = True) -> dict:
    """The largest class that holds: `sizes` in turn until one fails, then bisection between the last that held
    (0 if none) and the first that failed until they are within max(1, resolution × the one that held).
    Returns held (0 if none), failed (the smallest size seen to fail, None if none) and whether every size held."""
    held, failed = 0, None
    for size in sorted(sizes):
        if holds(size):
            held = size
        else:
            failed = size
            break
    if failed is not None and bisect:
        while failed - held > max(1, math.ceil(resolution * held)):
            middle = (held + failed) // 2
            if holds(middle):
                held = middle
            else:
                failed = middle
    return {"held": held, "failed": failed, "bounded": failed is not None}


def plural(count: int, noun: str) -> str:
    return f"{count} {noun}{'' if count == 1 else 's'}"


def fmt_ms(value: float) -> str:
    return "∞ (given up)" if value == math.inf else f"{value:,.0f}"


def cell(value) -> str:
    if value is None:
        return "–"
    p95, answered, late = value
    return fmt_ms(p95) + (f" ({late} given up)" if late else "")


def loads(values) -> str:
    return " / ".join(f"{x:.1f}" for x in values)


def machine() -> str:
    model = next((line.split(":", 1)[1].strip() for line in Path("/proc/cpuinfo").read_text().splitlines()
                  if line.startswith("model name")), platform.processor() or "unknown CPU")
    nginx = subprocess.run([nginx_binary(), "-v"], capture_output=True, text=True).stderr.strip()
    return (f"{platform.node()}: {os.cpu_count()} CPUs ({model}), Linux {platform.release()}, Python "
            f"{platform.python_version()}, {nginx}")


def held_text(found: dict | None) -> str:
    if found is None:
        return "–"
    return f"{found['held']}" if found["bounded"] else f"≥ {found['held']} (every class tried held)"


def ratio_text(found: dict, base: dict | None, target: float | None = None) -> str:
    if base is None or found is None or base["held"] == 0 or (not found["bounded"] and not base["bounded"]):
        return "–"
    ratio = found["held"] / base["held"]
    sign = "≥ " if not found["bounded"] else ("≤ " if not base["bounded"] else "")
    text = f"{sign}{ratio:.2f}"
    if target is not None:
        met = ratio >= target and sign != "≤ "
        text += f" ({'met' if met else '**not met**'}: target ≥ {target})"
    return text


def markdown(args, argv: list[str], runs: dict[str, list[dict]], found: dict[str, dict], done: bool) -> str:
    client = (f"pinned to CPUs {','.join(map(str, args.client_cpus))}" if args.client_cpus
              else "on every CPU, beside the servers (the same 2 CPUs: the class's own CPU use is given per run)")
    lines = [
        "# Capacity: the class a deployment holds at the targets", "",
        f"{time.strftime('%Y-%m-%d %H:%M %Z')}; {machine()}; server tree: {tree_label(args.tree)}.",
        f"`python3 bench/capacity.py {' '.join(argv)}`" + ("" if done else " — **in progress**: the search has "
                                                             "not finished"), "",
        f"The simulated class (bench/classroom.py, new page pattern, threads client, seed {args.seed}, "
        f"{args.seconds:g} s per class) runs on the same machine as the servers, over loopback, {client}. "
        "Every class starts fresh servers (empty caches), left to settle (idle, their heavy processes warm) "
        "before the students open their pages. A class holds when exact answers p95 ≤ 150 ms light, "
        "≤ 500 ms elastic; the first preview of a grab (its coarse family) p95 ≤ 500 ms light, ≤ 1.5 s elastic, "
        "one given up by the student's next grab counted as later than its target; no error; nothing cut short "
        "by a time budget. Sizes tried in turn until one fails, then bisected to within "
        f"{100 * args.resolution:g} % (one run per size).", "",
    ]
    lines += ["Scene mix (share of the class, by largest remainders): " + ", ".join(
        f"{scene} {share:g} %" for scene, share in classroom.SCENE_MIX.items()) + ".", ""]
    loaded = max((r["load_before"][0] for results in runs.values() for r in results), default=0.0)
    if loaded > (os.cpu_count() or 1):
        lines += [f"**Not the measurement: the machine was busy with other jobs** (load average up to {loaded:.1f} "
                  f"on {os.cpu_count()} CPUs before a class): they took CPU from the servers and the class, so the "
                  "classes held below understate what the deployments hold. Run it again on a quiet machine.", ""]
    base = found.get("one-cpu")
    lines += ["| deployment | CPUs | students held | students per CPU | × one CPU | runs | minutes |",
              "|---|---:|---:|---:|---|---:|---:|"]
    for name, result in found.items():
        deployment = DEPLOYMENTS[name]
        per_cpu = f"{'≥ ' if not result['bounded'] else ''}{result['held'] / deployment.cpus:.1f}"
        times = "1" if name == "one-cpu" else ratio_text(result, base, TARGET_RATIO if name == "two-servers" else None)
        minutes = sum(r.get("duration", 0.0) for r in runs[name]) / 60
        lines.append(f"| {name}: {deployment.title} | {deployment.cpus} | {held_text(result)} | {per_cpu} | {times} | "
                     f"{len(runs[name])} | {minutes:.0f} |")
    lines.append("")
    for name, results in runs.items():
        deployment = DEPLOYMENTS[name]
        lines += [f"## {name}: {deployment.title}", "", "Commands, per class (P: free loopback ports):", ""]
        lines += [f"    {command}" for command in deployment.commands()]
        lines += ["", "| students | load before (1 / 5 / 15 min) | " + " | ".join(f"{NAMES[k]} p95 (ms) ≤ {t:,}"
                                                                              for k, t in TARGETS_MS.items())
                  + " | errors | cut short | CPU s: servers / nginx / class / others | held |",
                  "|---:|---|" + "---:|" * len(TARGETS_MS) + "---:|---:|---|---|"]
        for result in results:
            judged = verdict(result)
            upstreams = result["upstreams"]
            lines.append(
                f"| {result['students']} | {loads(result['load_before'])} | "
                + " | ".join(cell(judged["cells"][key]) for key in TARGETS_MS)
                + f" | {judged['errors']} | {judged['partial']} | {result['server_cpu']:.0f} / "
                f"{result['nginx_cpu']:.1f} / {result['client_cpu']:.0f} / {result['other_cpu']:.0f} "
                f"in {result['wall']:.0f} s | "
                + ("yes" if judged["held"] else "**no**: " + "; ".join(judged["reasons"]))
                + (f"; requests per app server: {', '.join(f'{n}' for n in upstreams.values())}" if upstreams else "")
                + " |")
        lines.append("")
    details = [(name, r) for name, results in runs.items() for r in results
               if found.get(name) and r["students"] in (found[name]["held"], found[name]["failed"])]
    if details:
        lines += ["## Details: the largest class held and the smallest that failed", ""]
        for name, result in details:
            lines += classroom.markdown_run(result, f"{name}, {plural(result['students'], 'student')}")
    return "\n".join(lines) + "\n"


def interrupted(signum, frame):
    raise KeyboardInterrupt(f"signal {signum}")


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--configurations", nargs="+", choices=list(DEPLOYMENTS), default=None,
                        help="deployments to measure (default: all three)")
    parser.add_argument("--sizes", type=int, nargs="+", default=None,
                        help=f"classes tried in turn (default {' '.join(map(str, DEFAULT_SIZES))})")
    parser.add_argument("--seconds", type=float, default=None, help="length of each class run (default 30)")
    parser.add_argument("--resolution", type=float, default=0.1,
                        help="bisect until the first failing size is within this share of the largest held")
    parser.add_argument("--no-bisect", action="store_true", help="only the sizes given, in turn")
    parser.add_argument("--client-cpus", type=int, nargs="+", default=None,
                        help="pin the simulated class to these CPUs (on a machine with more than two)")
    parser.add_argument("--start", choices=sorted(classroom.STARTS), default="together",
                        help="the class grabs at once when the clock starts (together), or each student after a "
                             "look of 0–2 s (staggered): bench/classroom.py --start")
    parser.add_argument("--seed", type=int, default=2026)
    parser.add_argument("--tree", type=Path, default=ROOT, help="the source tree whose server runs")
    parser.add_argument("--quick", action="store_true",
                        help=f"a smoke run: {QUICK['sizes']} students for {QUICK['seconds']:g} s on "
                             f"{' and '.join(QUICK['configurations'])}, no bisection; writes only to --output")
    parser.add_argument("--output", type=Path, default=None, help="default bench/results/capacity.md")
    parser.add_argument("--no-write", action="store_true", help="print only")
    args = parser.parse_args(argv)
    classroom.START_SPREAD_S = classroom.STARTS[args.start]
    if args.quick:
        args.sizes = args.sizes or QUICK["sizes"]
        args.seconds = args.seconds or QUICK["seconds"]
        args.configurations = args.configurations or QUICK["configurations"]
        args.no_bisect = True
    else:
        args.output = args.output or ROOT / "bench" / "results" / "capacity.md"
    args.sizes = args.sizes or DEFAULT_SIZES
    args.seconds = args.seconds or 30.0
    args.configurations = args.configurations or list(DEPLOYMENTS)
    args.tree = args.tree.resolve()
    if not {0, 1} <= os.sched_getaffinity(0):
        parser.error("the deployments need CPUs 0 and 1")
    if args.client_cpus:
        os.sched_setaffinity(0, set(args.client_cpus))
    output = None if args.no_write else args.output

    # SIGTERM unwinds like Ctrl-C, so every server and nginx started is stopped on the way out.
    signal.signal(signal.SIGTERM, interrupted)
    runs: dict[str, list[dict]] = {name: [] for name in args.configurations}
    found: dict[str, dict] = {}

    def write(done: bool) -> str:
        text = markdown(args, argv, runs, found, done)
        if output is not None:
            output.parent.mkdir(parents=True, exist_ok=True)
            output.write_text(text, encoding="utf-8")
        return text

    for name in args.configurations:
        deployment = DEPLOYMENTS[name]

        def holds(students: int) -> bool:
            started = time.monotonic()
            result = run_class(deployment, students, args.seconds, args.seed, args.tree)
            result["duration"] = time.monotonic() - started        # start-up, settling and stop included
            runs[name].append(result)
            judged = verdict(result)
            print(f"{name}: {plural(students, 'student')}, load before {loads(result['load_before'])}, servers "
                  f"settled in {result['settled']:.0f} s: "
                  + ("held" if judged["held"] else "failed (" + "; ".join(judged["reasons"]) + ")"), flush=True)
            write(False)
            return judged["held"]

        found[name] = search(holds, args.sizes, args.resolution, bisect=not args.no_bisect)
    text = write(True)
    print(text)
    if output is not None:
        print(f"written to {output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
