"""Benchmark: POST /friction-influence computed in this process (the scene's default request: 13 f's from 0 to 0.3,
181 angles, wear and flywheel), beside the forces scene's default /forces request (baseline: one f, 361 angles, the
textbook's table), interleaved so that both see the same machine and load; also the scene's request with the cycle
alone (f = 0 and f) and one member of an f slider's family computed with eight others (the batch shares one Study).
Wall-clock and CPU (process) medians and their ratio to the baseline (the target: the default request ≤ ~50 ms of
server compute).

    python bench/friction_influence.py [--repeats 20]

Prints a Markdown table and writes it to bench/results/friction_influence.md.
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

from server.api.endpoints import compute_answer, compute_answers  # noqa: E402
from server.lessons.requests import scene_request  # noqa: E402
from server.lessons.scenes import scenes  # noqa: E402


def default(scene_id: str) -> tuple[str, dict]:
    scene = scenes()[scene_id]
    return scene.endpoint, scene_request(scene, scene.variants[0])


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--repeats", type=int, default=20)
    args = parser.parse_args()
    forces, explorer = default("forces-friction"), default("friction-influence")
    family = [explorer[1] | {"f": 0.3 * k / 8} for k in range(9)]
    cases = {
        "forces scene, /forces (baseline)": lambda: compute_answer(*forces),
        "friction-influence scene, default": lambda: compute_answer(*explorer),
        "the same, outputs ['cycle'] only": lambda: compute_answer(explorer[0], explorer[1] | {"outputs": ["cycle"]}),
        "an f family's member (9 in one batch)": lambda: compute_answers(explorer[0], family),
    }
    per_call = {"an f family's member (9 in one batch)": len(family)}
    walls, cpus = {label: [] for label in cases}, {label: [] for label in cases}
    for run in cases.values():
        run()                                                       # warm up
    for _ in range(args.repeats):
        for label, run in cases.items():
            wall, cpu = time.perf_counter(), time.process_time()
            run()
            walls[label].append((time.perf_counter() - wall) / per_call.get(label, 1))
            cpus[label].append((time.process_time() - cpu) / per_call.get(label, 1))
    base_wall = statistics.median(walls["forces scene, /forces (baseline)"])
    base_cpu = statistics.median(cpus["forces scene, /forces (baseline)"])
    lines = [f"# /friction-influence ({time.strftime('%Y-%m-%d %H:%M')}, Python {platform.python_version()}, "
             f"{os.cpu_count()} CPUs, load {os.getloadavg()[0]:.1f})", "",
             "| request | wall median ms | ratio | CPU median ms | ratio |", "|---|---|---|---|---|"]
    for label in cases:
        wall, cpu = statistics.median(walls[label]), statistics.median(cpus[label])
        lines.append(f"| {label} | {1e3 * wall:.1f} | {wall / base_wall:.2f} | {1e3 * cpu:.1f} "
                     f"| {cpu / base_cpu:.2f} |")
    text = "\n".join(lines) + "\n"
    print(text)
    (ROOT / "bench" / "results" / "friction_influence.md").write_text(text, encoding="utf-8")


if __name__ == "__main__":
    main()
