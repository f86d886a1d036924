"""Benchmark: a six-bar's kinematics through the general path (server/core/structure/) beside the existing
closed-form slider-crank module, 721 crank angles each, in this process, interleaved so that both see the same
machine and load.  Reports the medians and their ratio (the target: ≤ 2 ms of server compute).

  * general: ``compute_general`` for each six-bar preset (shaping machine, jaw crusher, lever with a ram) with
    every array output (joints and their first and second analogs, link angles θ, θ′, θ″, slides s, s′, s″)
    and the structural analysis; the assembly check over the turn is part of it (as in the endpoint);
  * baseline: ``compute_kinematics("slider_crank", …)`` with the scene's outputs (s, u31, du31, s2, u21, du21,
    joints, special).

    python bench/general_kinematics.py [--repeats 200]

Prints a Markdown table and writes it to bench/results/general_kinematics.md.
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

from server.core.kinematics import compute_kinematics  # noqa: E402
from server.core.mechanisms.general import compute_general  # noqa: E402
from server.core.structure.presets import presets  # noqa: E402

POINTS = 721
GENERAL_OUTPUTS = ["structure", "joints", "joints_d1", "joints_d2", "angles", "angles_d1", "angles_d2",
                   "slides", "slides_d1", "slides_d2"]
SCENE_OUTPUTS = ["s", "u31", "du31", "s2", "u21", "du21", "joints", "special"]
SIX_BARS = ("shaping_machine", "jaw_crusher", "lever_ram")


def timed(call) -> float:
    start = time.perf_counter()
    call()
    return time.perf_counter() - start


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--repeats", type=int, default=200)
    args = parser.parse_args()
    cases = {name: (lambda name=name: compute_general(presets()[name]["linkage"], GENERAL_OUTPUTS, n=POINTS))
             for name in SIX_BARS}
    baseline = lambda: compute_kinematics("slider_crank", {}, SCENE_OUTPUTS, n=POINTS)  # noqa: E731
    times = {name: [] for name in (*SIX_BARS, "slider_crank")}
    for call in (*cases.values(), baseline):
        call(), call()                                   # warm-up
    for _ in range(args.repeats):                        # interleaved: the same load for every case
        for name, call in cases.items():
            times[name].append(timed(call))
        times["slider_crank"].append(timed(baseline))
    base = statistics.median(times["slider_crank"])
    rows = ["| mechanism | median, ms | ratio to slider_crank |", "|---|---:|---:|"]
    for name, values in times.items():
        median = statistics.median(values)
        rows.append(f"| {name} | {1000 * median:.3f} | {median / base:.2f} |")
    head = (f"# General six-bar kinematics, {POINTS} angles ({time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())})\n\n"
            f"Python {platform.python_version()}, {os.cpu_count()} CPUs, load {os.getloadavg()[0]:.1f}, "
            f"{args.repeats} interleaved repeats; general outputs: {', '.join(GENERAL_OUTPUTS)} "
            "(+ the assembly check over the turn); slider_crank: the scene's outputs.\n\n")
    text = head + "\n".join(rows) + "\n"
    print(text)
    out = ROOT / "bench" / "results" / "general_kinematics.md"
    out.write_text(text, encoding="utf-8")


if __name__ == "__main__":
    main()
