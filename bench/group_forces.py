"""Benchmark: POST /forces computed in-process for the six-bar presets by structural groups (their own masses
and loads, content/mechanisms/*.json 'dynamics'), without and with friction (f = 0.1, r = 0.01 m in every pair),
beside the dedicated crank-slider's /forces (baseline, the forces scene's default request with f = 0.1 in every
pair), 361 crank angles each, interleaved so that all see the same machine and load.  Reports the medians and
their ratio to the baseline (the target: every dynamics request of a six-bar ≤ 20 ms of server compute).

With ``--old PATH`` (another checkout, e.g. ``git worktree add --detach /tmp/old <commit>``) the same requests
run in two worker processes, one importing this tree's server and one the other's, round by round in turn (so
both see the same load), and the table gives both medians and their ratio new/old.

    python bench/group_forces.py [--repeats 30] [--old PATH]

Prints a Markdown table and writes it to bench/results/group_forces.md.
"""
from __future__ import annotations

import argparse
import json
import os
import platform
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SIX_BARS = ("shaping_machine", "jaw_crusher", "lever_ram", "whitworth", "knuckle_press")
BASELINE_LABEL = "crank-slider, dedicated (baseline)"
BASELINE = {"n": 361, "loads": {"m2": 2.0, "J_S2": 0.03, "m3": 1.5, "omega": 10.0, "force": 800.0},
            "pairs": {"f14": 0.1, "f12": 0.1, "f23": 0.1, "f34": 0.1}}


def general(preset: dict, friction: float) -> dict:
    masses = {**preset["dynamics"]["masses"], "friction": friction, "pair_radius": 0.01}
    return {"mechanism": "general", "linkage": preset["linkage"], "masses": masses, "n": 361,
            "loads": {"omega": 10.0}}


def cases() -> dict[str, dict]:
    from server.core.structure.presets import presets
    out = {BASELINE_LABEL: BASELINE}
    for name in SIX_BARS:
        if "dynamics" in presets()[name]:
            out[f"{name}, f = 0"] = general(presets()[name], 0.0)
            out[f"{name}, f = 0.1"] = general(presets()[name], 0.1)
    return out


def one_round(bodies: dict[str, dict]) -> dict[str, float]:
    from server.api.endpoints import compute_answer
    times = {}
    for label, body in bodies.items():
        start = time.perf_counter()
        compute_answer("forces", body, "en")
        times[label] = time.perf_counter() - start
    return times


def serve(root: str) -> None:
    """A worker: import the server of ``root``, warm up, then one round per line read, its times as JSON."""
    sys.path.insert(0, root)
    bodies = cases()
    one_round(bodies)
    print("ready", flush=True)
    for _ in sys.stdin:
        print(json.dumps(one_round(bodies)), flush=True)


def header() -> str:
    return (f"# /forces by structural groups ({time.strftime('%Y-%m-%d %H:%M')}, Python {platform.python_version()}, "
            f"{os.cpu_count()} CPUs, load {os.getloadavg()[0]:.1f})")


def compare(old: str, repeats: int) -> str:
    workers = {}
    for tag, root in (("old", old), ("new", str(ROOT))):
        workers[tag] = subprocess.Popen([sys.executable, __file__, "--serve", root], stdin=subprocess.PIPE,
                                        stdout=subprocess.PIPE, text=True)
        assert workers[tag].stdout.readline().strip() == "ready"
    times = {tag: {} for tag in workers}
    for _ in range(repeats):
        for tag, worker in workers.items():
            worker.stdin.write("round\n")
            worker.stdin.flush()
            for label, seconds in json.loads(worker.stdout.readline()).items():
                times[tag].setdefault(label, []).append(seconds)
    for worker in workers.values():
        worker.stdin.close()
        worker.wait()
    base = statistics.median(times["new"][BASELINE_LABEL])
    lines = [header(), "", f"Old: {old}; new: this tree; {repeats} rounds each, in turn.", "",
             "| request (361 angles) | old median ms | new median ms | new/old | new ratio to baseline |",
             "|---|---|---|---|---|"]
    for label, values in times["new"].items():
        old_ms, new_ms = 1e3 * statistics.median(times["old"][label]), 1e3 * statistics.median(values)
        lines.append(f"| {label} | {old_ms:.1f} | {new_ms:.1f} | {new_ms / old_ms:.2f} | {new_ms / 1e3 / base:.2f} |")
    return "\n".join(lines) + "\n"


def alone(repeats: int) -> str:
    sys.path.insert(0, str(ROOT))
    bodies = cases()
    one_round(bodies)                                       # warm up
    times = {label: [] for label in bodies}
    for _ in range(repeats):
        for label, seconds in one_round(bodies).items():
            times[label].append(seconds)
    base = statistics.median(times[BASELINE_LABEL])
    lines = [header(), "", "| request (361 angles) | median ms | ratio to baseline |", "|---|---|---|"]
    for label, values in times.items():
        median = statistics.median(values)
        lines.append(f"| {label} | {1e3 * median:.1f} | {median / base:.2f} |")
    return "\n".join(lines) + "\n"


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--repeats", type=int, default=30)
    parser.add_argument("--old", help="another checkout to compare with, side by side")
    parser.add_argument("--serve", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.serve:
        serve(args.serve)
        return
    text = compare(args.old, args.repeats) if args.old else alone(args.repeats)
    print(text)
    (ROOT / "bench" / "results" / "group_forces.md").write_text(text, encoding="utf-8")


if __name__ == "__main__":
    main()
