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

import os
import platform
import statistics
import time

import side_by_side
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


def one_round(_repeat: int) -> dict[str, float]:
    """Seconds of each request, in order, by label (every round the same requests)."""
    return side_by_side.timed({label: [("forces", body)] for label, body in cases().items()})


def header() -> str:
    return (f"# /forces by structural groups ({time.strftime('%Y-%m-%d %H:%M')}, Python {platform.python_version()}, "
            f"{os.cpu_count()} CPUs, load {os.getloadavg()[0]:.1f})")


def compared(old: str, repeats: int) -> str:
    times = side_by_side.in_turn(__file__, old, repeats)
    base = statistics.median(times["new"][BASELINE_LABEL])
    lines = [header(), "", f"Old tree: {old}; new tree: this checkout; {repeats} rounds each, in turn.", "",
             "| request (361 angles) | old median ms | new median ms | new/old | new ratio to baseline |",
             "|---|---|---|---|---|"]
    for label, old_ms, new_ms in side_by_side.medians_ms(times):
        lines.append(f"| {label} | {old_ms:.1f} | {new_ms:.1f} | {new_ms / old_ms:.2f} | {new_ms / 1e3 / base:.2f} |")
    return "\n".join(lines) + "\n"


def single(repeats: int) -> str:
    times = side_by_side.alone(one_round, repeats)
    base = statistics.median(times[BASELINE_LABEL])
    lines = [header(), "", "| request (361 angles) | median ms | ratio to baseline |", "|---|---|---|"]
    for label, values in times.items():
        median = statistics.median(values)
        lines.append(f"| {label} | {1e3 * median:.1f} | {median / base:.2f} |")
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    side_by_side.main(__doc__, 30, "group_forces.md", one_round, compared, single)
