"""Benchmark: POST /forces computed in this process for the six-bar presets by structural groups (their own masses
and loads, content/mechanisms/*.json 'dynamics'), without and with friction (f = 0.1, r = 0.01 m in every pair),
beside the dedicated crank-slider's /forces (baseline, the forces scene's default request with f = 0.1 in every
pair), 361 crank angles each, interleaved so that all see the same machine and load.  Reports the medians and
their ratio to the baseline (the target: every dynamics request of a six-bar ≤ 20 ms of server compute).

    python bench/group_forces.py [--repeats 30]

Prints a Markdown table and writes it to bench/results/group_forces.md.
"""
from __future__ import annotations

import argparse
import os
import platform
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from server.api.endpoints import compute_answer  # noqa: E402
from server.core.structure.presets import presets  # noqa: E402

SIX_BARS = ("shaping_machine", "jaw_crusher", "lever_ram", "whitworth", "knuckle_press")
BASELINE = {"n": 361, "loads": {"m2": 2.0, "J_S2": 0.03, "m3": 1.5, "omega": 10.0, "force": 800.0},
            "pairs": {"f14": 0.1, "f12": 0.1, "f23": 0.1, "f34": 0.1}}


def general(name: str, friction: float) -> dict:
    preset = presets()[name]
    masses = {**preset["dynamics"]["masses"], "friction": friction, "pair_radius": 0.01}
    return {"mechanism": "general", "linkage": preset["linkage"], "masses": masses, "n": 361,
            "loads": {"omega": 10.0}}


def timed(body: dict) -> float:
    start = time.perf_counter()
    compute_answer("forces", body, "en")
    return time.perf_counter() - start


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--repeats", type=int, default=30)
    args = parser.parse_args()
    cases = {"crank-slider, dedicated (baseline)": BASELINE}
    for name in SIX_BARS:
        if "dynamics" in presets()[name]:
            cases[f"{name}, f = 0"] = general(name, 0.0)
            cases[f"{name}, f = 0.1"] = general(name, 0.1)
    times = {label: [] for label in cases}
    for body in cases.values():
        compute_answer("forces", body, "en")                     # warm up
    for _ in range(args.repeats):
        for label, body in cases.items():
            times[label].append(timed(body))
    base = statistics.median(times["crank-slider, dedicated (baseline)"])
    lines = [f"# /forces by structural groups ({time.strftime('%Y-%m-%d %H:%M')}, Python {platform.python_version()}, "
             f"{os.cpu_count()} CPUs, load {os.getloadavg()[0]:.1f})", "",
             "| request (361 angles) | median ms | ratio to baseline |", "|---|---|---|"]
    for label, values in times.items():
        median = statistics.median(values)
        lines.append(f"| {label} | {1e3 * median:.1f} | {median / base:.2f} |")
    text = "\n".join(lines) + "\n"
    print(text)
    (ROOT / "bench" / "results" / "group_forces.md").write_text(text, encoding="utf-8")


if __name__ == "__main__":
    main()
