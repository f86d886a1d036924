"""Every scene's default answer from a server that warmed its cache (MDL_WARM_DEFAULTS), against the HTTP floor.

Starts the app of this tree (``python3 -m server``, 1 worker) with ``MDL_WARM_DEFAULTS=ru``, waits until its log
says the default answers are in the cache (how long after the start, how many, the worker's CPU for them), and
starts the floor (bench/floor_app.py, a bare Starlette app) answering each scene's request with the very bytes the
app sent for it. Then, scene by scene (the first variant at its defaults, ``?lang=ru``, as the page's first
request): the default request (a cache hit) and the floor take turns ``--requests`` times, each server's CPU per
request from /proc over them; then the same request nudged by 1 + k·1e-8 (computed every time)
``--computed-requests`` times, the app's CPU per request over those. CPU, not the wall clock, is the measure on a
loaded machine; both are written.

    python bench/warm_defaults.py [--requests 50] [--computed-requests 10] [--scenes ID ...]
                                  [--output bench/results/warm_defaults.md]
"""
from __future__ import annotations

import argparse
import os
import re
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from http_floor import (LANG, SCENE_FLOOR_TARGET, Target, capture_scenes, chosen_scenes, encoded, fmt,  # noqa: E402
                        nudged_request, session_cpu_s, variant_of)
from trees import ROOT, machine_line, percentiles, running_server, write_result  # noqa: E402

WARMED = re.compile(r"default answers in the cache: (\d+) of (\d+) requests \(([\d.]+) s, ([\d.]+) CPU-s\)")
GUARD_S = 900


def wait_warmed(process) -> re.Match:
    """Wait (a guard against a hang) until the server's log (its standard output, trees.running_server's log
    file) says its default answers are in the cache."""
    log = Path(os.readlink(f"/proc/{process.pid}/fd/1"))
    deadline = time.monotonic() + GUARD_S
    while not (found := WARMED.search(log.read_text(errors="replace"))):
        if time.monotonic() > deadline:
            raise RuntimeError("the server did not finish warming its default answers")
        time.sleep(0.5)
    return found


def measure(port: int, floor_port: int, session: int, floor_session: int, scene, requests: int,
            computed: int) -> dict:
    variant = variant_of(scene)
    path = f"/api/v1/{scene.endpoint}?lang={LANG}"
    warm, floor, fresh = Target("warm", port, path), Target("floor", floor_port, f"/scene-{scene.id}"), \
        Target("computed", port, path)
    default = encoded(nudged_request(scene, variant, 0))
    for target in (warm, floor):
        target.post(default, keep=False)
    app_cpu, floor_cpu = session_cpu_s(session), session_cpu_s(floor_session)
    for k in range(requests):
        for target in ((warm, floor) if k % 2 else (floor, warm)):
            target.post(default)
    app_cpu, floor_cpu = session_cpu_s(session) - app_cpu, session_cpu_s(floor_session) - floor_cpu
    cpu = session_cpu_s(session)
    for k in range(1, computed + 1):
        fresh.post(encoded(nudged_request(scene, variant, -k)))
    return {"scene": scene, "variant": variant, "warm": warm, "floor": floor, "computed": fresh,
            "warm_cpu": 1000 * app_cpu / requests, "floor_cpu": 1000 * floor_cpu / requests,
            "computed_cpu": 1000 * (session_cpu_s(session) - cpu) / computed}


def markdown(args, rows: list[dict], warmed: re.Match, startup_s: float) -> str:
    answered, total, seconds, cpu_s = warmed.groups()
    lines = ["# Default answers from a warmed cache against the HTTP floor", "",
             f"{machine_line()}. `python bench/warm_defaults.py --requests {args.requests} --computed-requests "
             f"{args.computed_requests}{' --scenes ' + ' '.join(args.scenes) if args.scenes else ''}`; load average "
             f"at the end {os.getloadavg()[0]:.1f}.", "",
             f"The server (`MDL_WARM_DEFAULTS=ru python3 -m server`, 1 worker) answered after {startup_s:.1f} s and "
             f"had computed {answered} of {total} default requests (every variant of every scene) {seconds} s "
             f"later, using {cpu_s} CPU-s of its worker (the elastic machines' and the course project's in the "
             "heavy processes besides). Times in ms; CPU per request from /proc (1/100 s ticks) over the timed "
             f"requests. Target: ≤ {SCENE_FLOOR_TARGET:g}× the floor.", "",
             "| scene | variant | X-Cache | warm p50 | floor p50 | warm × floor (p50) | warm CPU | floor CPU "
             "| warm CPU × floor | computed CPU | computed CPU × floor | computed X-Cache |",
             "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---|"]
    for row in rows:
        w50, f50 = percentiles(row["warm"].times)[0], percentiles(row["floor"].times)[0]
        floor_cpu = max(row["floor_cpu"], 1e-9)
        cache = ", ".join(f"{k} {v}" for k, v in sorted(row["warm"].cache.items()))
        fresh = ", ".join(f"{k} {v}" for k, v in sorted(row["computed"].cache.items()))
        lines.append(f"| {row['scene'].id} | {row['variant'].id} | {cache} | {fmt(w50)} | {fmt(f50)} | "
                     f"{w50 / f50:.1f}× | {row['warm_cpu']:.2f} | {row['floor_cpu']:.2f} | "
                     f"{row['warm_cpu'] / floor_cpu:.1f}× | {fmt(row['computed_cpu'])} | "
                     f"{row['computed_cpu'] / floor_cpu:.0f}× | {fresh} |")
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--requests", type=int, default=50, help="default requests (cache hits) per scene")
    parser.add_argument("--computed-requests", type=int, default=10, help="nudged (computed) requests per scene")
    parser.add_argument("--scenes", nargs="*", help="only these scene ids (default: every scene)")
    parser.add_argument("--output", type=Path, default=ROOT / "bench" / "results" / "warm_defaults.md")
    args = parser.parse_args(argv)
    with running_server(env={"MDL_WARM_DEFAULTS": LANG}) as (port, process), \
            tempfile.TemporaryDirectory(prefix="mdl-floor-") as directory:
        warmed = wait_warmed(process)
        capture_scenes(port, Path(directory), args.scenes)
        floor_command = [sys.executable, str(Path(__file__).resolve().parent / "floor_app.py"), "{port}", directory]
        with running_server(command=floor_command, ready_path="/ready") as (floor_port, floor_process):
            rows = [measure(port, floor_port, process.pid, floor_process.pid, scene, args.requests,
                            args.computed_requests) for scene in chosen_scenes(args.scenes)]
        startup_s = process.startup_s
    text = markdown(args, rows, warmed, startup_s)
    print(text)
    write_result(text, args.output)
    return 0


if __name__ == "__main__":
    sys.exit(main())
