"""Benchmark: how long the kinematics of one scene take, in the core and over HTTP on loopback.

For each mechanism (default parameters, plus a change-point four-bar) it measures
  * the median time of ``compute_kinematics`` for 721 crank angles and every output a scene
    requests (s, u31, du31, s2, u21, du21, joints, special), in this process;
  * p50 and p95 of N sequential POST /api/v1/kinematics round trips with the same request,
    against ``python -m server`` started as a subprocess on a free loopback port with its response cache
    turned off (MDL_CACHE_BYTES=0), so every round trip computes the answer: the run stops if any answer
    says X-Cache: hit or the server's /api/v1/cache says the cache is on.

Prints a Markdown table and writes it to bench/results/kinematics.md.

    python bench/kinematics.py [--requests 200] [--repeats 50] [--no-write] [--output PATH]
"""
from __future__ import annotations

import argparse
import os
import platform
import socket
import statistics
import subprocess
import sys
import time
from pathlib import Path

import httpx
import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from server.core.kinematics import compute_kinematics  # noqa: E402

SCENE_OUTPUTS = ["s", "u31", "du31", "s2", "u21", "du21", "joints", "special"]
POINTS = 721
START_GUARD_S = 180       # a guard against a hang: a first start may load or compile the numerical kernels
CASES = [  # (label, mechanism, params)
    ("sine", "sine", {}),
    ("slider_crank", "slider_crank", {}),
    ("slotted_link", "slotted_link", {}),
    ("four_bar", "four_bar", {}),
    ("four_bar, change point (4π)", "four_bar", {"l0": 2, "l1": 1, "l2": 4, "l3": 3, "limiter": 0}),
]


def core_median_ms(mechanism: str, params: dict, repeats: int) -> float:
    """Median wall time of one compute_kinematics call, after two warm-up calls."""
    for _ in range(2):
        compute_kinematics(mechanism, params, SCENE_OUTPUTS, n=POINTS)
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        compute_kinematics(mechanism, params, SCENE_OUTPUTS, n=POINTS)
        times.append(time.perf_counter() - start)
    return 1000 * statistics.median(times)


def free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return sock.getsockname()[1]


def start_server(port: int) -> subprocess.Popen:
    """``python -m server --port PORT`` from the repository root; returns once it answers."""
    process = subprocess.Popen([sys.executable, "-m", "server", "--port", str(port)], cwd=ROOT,
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                               env=os.environ | {"MDL_CACHE_BYTES": "0"})     # every request computed
    deadline = time.monotonic() + START_GUARD_S
    while time.monotonic() < deadline:
        if process.poll() is not None:
            raise RuntimeError(f"the server exited with code {process.returncode}")
        try:
            if httpx.get(f"http://127.0.0.1:{port}/api/v1/mechanisms", timeout=1).status_code == 200:
                if httpx.get(f"http://127.0.0.1:{port}/api/v1/cache", timeout=5).json()["enabled"]:
                    process.terminate()
                    raise RuntimeError("the server's response cache is on: the round trips would time cache hits")
                return process
        except httpx.TransportError:
            time.sleep(0.1)
    process.terminate()
    process.wait(timeout=30)
    raise RuntimeError(f"the server did not answer within {START_GUARD_S} s")


def round_trips_ms(client: httpx.Client, url: str, body: dict, requests: int) -> tuple[float, float, int, int]:
    """p50, p95 (ms) of sequential POSTs, and the JSON size and on-the-wire (gzip) size in bytes."""
    for _ in range(3):   # warm-up: connection, first-call imports
        client.post(url, json=body).raise_for_status()
    times = []
    for _ in range(requests):
        start = time.perf_counter()
        response = client.post(url, json=body)
        response.raise_for_status()
        times.append(time.perf_counter() - start)
        if response.headers.get("x-cache") == "hit":
            raise RuntimeError("an answer came from the response cache: the round trips must compute")
    wire = int(response.headers.get("content-length", len(response.content)))
    p50, p95 = np.percentile(1000 * np.array(times), [50, 95])
    return float(p50), float(p95), len(response.content), wire


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--requests", type=int, default=200, help="sequential HTTP requests per mechanism")
    parser.add_argument("--repeats", type=int, default=50, help="compute_kinematics calls per mechanism")
    parser.add_argument("--output", type=Path, default=ROOT / "bench" / "results" / "kinematics.md",
                        help="the Markdown file written (default: %(default)s)")
    parser.add_argument("--no-write", action="store_true", help="print the table only, write no file")
    args = parser.parse_args()

    core = {label: core_median_ms(mech, params, args.repeats) for label, mech, params in CASES}
    port = free_port()
    server = start_server(port)
    try:
        with httpx.Client(timeout=30) as client:   # one keep-alive connection, gzip accepted like a browser
            http = {label: round_trips_ms(client, f"http://127.0.0.1:{port}/api/v1/kinematics",
                                          {"mechanism": mech, "params": params, "n": POINTS,
                                           "outputs": SCENE_OUTPUTS}, args.requests)
                    for label, mech, params in CASES}
    finally:
        server.terminate()
        try:
            server.wait(timeout=10)
        except subprocess.TimeoutExpired:
            server.kill()

    lines = [
        f"# Kinematics benchmark: {POINTS} crank angles, outputs {', '.join(SCENE_OUTPUTS)}",
        "",
        f"{time.strftime('%Y-%m-%d %H:%M')}, Python {platform.python_version()}, {platform.machine()}, "
        f"{os.cpu_count()} CPUs; core: median of {args.repeats} calls; HTTP: {args.requests} sequential POSTs "
        "on one keep-alive loopback connection to `python -m server` (1 worker, response cache off: "
        "MDL_CACHE_BYTES=0, every answer computed), gzip accepted.",
        "",
        "| mechanism | core compute_kinematics, median (ms) | HTTP round trip p50 (ms) | HTTP p95 (ms) "
        "| JSON size (kB) | gzip on the wire (kB) |",
        "|---|---:|---:|---:|---:|---:|",
    ]
    for label, _, _ in CASES:
        p50, p95, size, wire = http[label]
        lines.append(f"| {label} | {core[label]:.2f} | {p50:.2f} | {p95:.2f} | {size / 1000:.0f} | {wire / 1000:.0f} |")
    table = "\n".join(lines) + "\n"
    print(table)
    if not args.no_write:
        args.output.parent.mkdir(parents=True, exist_ok=True)
        args.output.write_text(table, encoding="utf-8")
        print(f"written to {args.output}")


if __name__ == "__main__":
    main()
