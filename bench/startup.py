"""Benchmark: the start-up of the equation of motion (POST /motion with outputs ["startup"]) computed in-process for
every variant of the equation-of-motion scene at its defaults, and the linear motor with a flat characteristic
(b = 0.05, the class benchmark's slowest exact answer), interleaved so that all see the same machine and load.
Reports the medians; the start-up is refined level by level until its Richardson estimate meets rtol
(server/core/dynamics/motion.py, ``startup``).

With ``--old PATH`` (another checkout, e.g. ``git worktree add --detach /tmp/old <commit>``) the same requests
run in two worker processes, one importing this tree's server and one the other's, round by round in turn (so
both see the same load), and the table gives both medians and their ratio new/old.

    python bench/startup.py [--repeats 20] [--old PATH]

Prints a Markdown table and writes it to bench/results/startup.md.
"""
from __future__ import annotations

import os
import platform
import statistics
import time

import side_by_side

FLAT = {"M0": 60.0, "b": 0.05, "omega0": 0.5, "f": 0.1}


def cases() -> dict[str, dict]:
    from server.lessons.requests import scene_request
    from server.lessons.scenes import scenes
    scene = scenes()["equation-of-motion"]
    out = {f"{variant.id}, defaults": scene_request(scene, variant, outputs=["startup"]) for variant in scene.variants}
    linear = next(variant for variant in scene.variants if variant.id == "linear")
    out["linear, b = 0.05"] = scene_request(scene, linear, FLAT, outputs=["startup"])
    return out


def one_round(_repeat: int) -> dict[str, float]:
    """Seconds of each request, in order, by label (every round the same requests)."""
    return side_by_side.timed({label: [("motion", body)] for label, body in cases().items()})


def header() -> str:
    return (f"# The start-up of the equation of motion ({time.strftime('%Y-%m-%d %H:%M')}, Python "
            f"{platform.python_version()}, {os.cpu_count()} CPUs, load {os.getloadavg()[0]:.1f})")


def compared(old: str, repeats: int) -> str:
    times = side_by_side.in_turn(__file__, old, repeats)
    lines = [header(), "", f"Old tree: {old}; new tree: this checkout; {repeats} rounds each, in turn.", "",
             "| request | old median ms | new median ms | new/old |", "|---|---|---|---|"]
    for label, old_ms, new_ms in side_by_side.medians_ms(times):
        lines.append(f"| {label} | {old_ms:.1f} | {new_ms:.1f} | {new_ms / old_ms:.2f} |")
    return "\n".join(lines) + "\n"


def single(repeats: int) -> str:
    times = side_by_side.alone(one_round, repeats)
    lines = [header(), "", "| request | median ms |", "|---|---|"]
    lines += [f"| {label} | {1e3 * statistics.median(values):.1f} |" for label, values in times.items()]
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    side_by_side.main(__doc__, 20, "startup.md", one_round, compared, single)
