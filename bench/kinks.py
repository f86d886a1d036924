"""Benchmark: the exact answers of the general machines a class drags (the Whitworth mechanism, the shaping machine,
the student's own six-bar: resisting-moment, equation-of-motion and flywheel scenes), each round at new slider
values, so that nothing a machine keeps (its kinks, its friction solves) is reused: what a student waits for
when a slider lands on a value not asked before. Most of such an answer is finding the machine's kinks (the
switching functions' and the normal forces' sign changes, refined to a few doubles: server/core/dynamics/brackets.py).

Round r draws every slider of the variant from the values it can express with the seed r, the same in both trees;
in-process, through the endpoints' bodies (validation included, no HTTP, no cache).

    python bench/kinks.py [--repeats 15] [--old PATH]

With ``--old PATH`` (another checkout, warmed up: ``python -m server.core.warm_up`` in it) both trees in two worker
processes, round by round in turn; the table is printed and written to bench/results/kinks.md.
"""
from __future__ import annotations

import os
import platform
import random
import statistics
import time

import side_by_side

CASES = [("resisting-moment", "whitworth"), ("resisting-moment", "shaping"), ("resisting-moment", "own"),
         ("equation-of-motion", "whitworth"), ("equation-of-motion", "shaping"), ("equation-of-motion", "own"),
         ("flywheel", "shaping"), ("flywheel", "own")]


def requests(repeat: int) -> dict[str, list[tuple[str, dict]]]:
    """Label → [(endpoint, body)]: each case at the round's slider values."""
    from server.lessons.requests import scene_request, slider_values
    from server.lessons.scenes import scenes
    out = {}
    for scene_id, variant_id in CASES:
        scene = scenes()[scene_id]
        variant = next(v for v in scene.variants if v.id == variant_id)
        rng = random.Random(f"{scene_id}/{variant_id}/{repeat}")
        values = {slider.id: rng.choice(slider_values(slider)) for slider in variant.sliders}
        out[f"{scene_id} ({variant_id})"] = [(scene.endpoint, scene_request(scene, variant, values))]
    return out


def one_round(repeat: int) -> dict[str, float]:
    return side_by_side.timed(requests(repeat))


def header() -> str:
    return (f"# General machines' exact answers at new slider values ({time.strftime('%Y-%m-%d %H:%M')} UTC, "
            f"Python {platform.python_version()}, {os.cpu_count()} CPUs, load {os.getloadavg()[0]:.1f})")


def compared(old: str, repeats: int) -> str:
    times = side_by_side.in_turn(__file__, old, repeats)
    lines = [header(), "", f"`python bench/kinks.py --repeats {repeats} --old {old}`. Old tree: the checkout at "
             f"`{old}`; new tree: this checkout; {repeats} rounds each at new slider values, the two trees in turn.",
             "", "| request | old median ms | new median ms | new/old | old p90 ms | new p90 ms |",
             "|---|---:|---:|---:|---:|---:|"]
    for label, old_ms, new_ms in side_by_side.medians_ms(times):
        p90 = [1e3 * sorted(times[tag][label])[int(0.9 * (len(times[tag][label]) - 1))] for tag in ("old", "new")]
        lines.append(f"| {label} | {old_ms:.1f} | {new_ms:.1f} | {new_ms / old_ms:.2f} | {p90[0]:.1f} | {p90[1]:.1f} |")
    return "\n".join(lines) + "\n"


def single(repeats: int) -> str:
    times = side_by_side.alone(one_round, repeats)
    lines = [header(), "", f"`python bench/kinks.py --repeats {repeats}`", "", "| request | median ms |", "|---|---:|"]
    lines += [f"| {label} | {1e3 * statistics.median(values):.1f} |" for label, values in times.items()]
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    side_by_side.main(__doc__, 15, "kinks.md", one_round, compared, single)
