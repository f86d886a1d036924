"""Server compute of every scene over slider sweeps, old tree beside new (target ≤ 20 ms at p95).

For every scene, variant and slider, the slider is swept across its range (``--points`` values in equal steps,
log steps on a log slider, each the nearest value the slider can express; the other sliders
at their defaults; a variant without sliders counts once, at its defaults), and the request the page sends for
those values (the tree's ``scene_request``) is computed in-process by each tree's ``compute`` (see
bench/tree_runner.py for exactly what is timed), each tree in a process of its own with its own ``server``
package. The two processes take turns point by point (old first on even points, new first on odd ones) so they
share the machine's load. Each process first computes every scene's default request once (warm-up: imports,
compilation, disk caches; its time is reported). Answers refused with a 422 (a geometry that does not assemble)
are timed and counted too. The two trees' answers at each point are compared as well (the largest
difference relative to each quantity's span), as a check that the faster answers are the same answers.

    python bench/scene_sweep.py [--old /tmp/mdl-old] [--new .] [--points 21] [--rounds 1] [--scenes ID ...]
                                [--output bench/results/scene_sweep.md]
"""
from __future__ import annotations

import argparse
import json
import subprocess
import sys
import time
from collections import defaultdict
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from trees import ROOT, add_tree_arguments, check_tree, lessons, machine_line, tree_label, write_result  # noqa: E402

sys.path.insert(0, str(ROOT))
TARGET_MS = 20.0
RUNNER = Path(__file__).resolve().parent / "tree_runner.py"


class Tree:
    """One tree's runner process: a JSON command in, a JSON answer out."""

    def __init__(self, name: str, path: Path):
        self.name, self.path = name, path
        self.process = subprocess.Popen([sys.executable, str(RUNNER), str(path)], cwd=path, text=True,
                                        stdin=subprocess.PIPE, stdout=subprocess.PIPE, bufsize=1)

    def ask(self, **command) -> dict:
        self.process.stdin.write(json.dumps(command) + "\n")
        line = self.process.stdout.readline()
        if not line:
            raise RuntimeError(f"the {self.name} tree's runner ended (its stderr is above)")
        return json.loads(line)

    def close(self) -> None:
        self.process.stdin.close()
        self.process.wait(timeout=30)


def sweep_values(slider, slider_values, points: int) -> list[float]:
    """`points` values across the slider's range, both ends included, in equal steps of the value (of its
    logarithm on a log slider), each moved to the nearest value the slider can express."""
    positions = np.array(slider_values(slider))
    count = min(points, len(positions))
    if slider.log:
        targets = np.geomspace(positions[0], positions[-1], count)
        nearest = np.abs(np.log(positions)[None, :] - np.log(targets)[:, None]).argmin(axis=1)
    else:
        targets = np.linspace(positions[0], positions[-1], count)
        nearest = np.abs(positions[None, :] - targets[:, None]).argmin(axis=1)
    return [float(positions[k]) for k in sorted(set(nearest.tolist()))]


def sweep_plan(points: int, only: list[str] | None, shared: dict) -> list[tuple[str, str, str, dict]]:
    """(scene, variant, slider or '', values) of every point, for the scenes and sliders both trees have."""
    scenes, _, slider_values, _, _ = lessons()
    plan = []
    for scene in scenes().values():
        if only and scene.id not in only or scene.id not in shared:
            continue
        for variant in scene.variants:
            if variant.id not in shared[scene.id]:
                continue
            sliders = [s for s in variant.sliders if s.id in shared[scene.id][variant.id]]
            if not sliders:
                plan.append((scene.id, variant.id, "", {}))
            for slider in sliders:
                plan += [(scene.id, variant.id, slider.id, {slider.id: value})
                         for value in sweep_values(slider, slider_values, points)]
    return plan


NEAR_CONSTANT = 1e-3
UNCOMPARED = {"numerics", "warnings", "study", "message", "messages", "notices"}


def numeric_array(value) -> np.ndarray | None:
    """A list of numbers (or nulls: NaN), or of such lists of one shape, as one flat float array; else None."""
    try:
        array = np.array(value, dtype=float)          # None → NaN; ragged or non-numeric lists raise
    except (TypeError, ValueError):
        return None
    return array.ravel() if array.dtype == float and array.size else None


def numeric_leaves(value, path: str = ""):
    """(path, flat float array) for every number and every (nested) array of numbers in an answer, leaving out
    the keys that describe the computation rather than its result (UNCOMPARED)."""
    if isinstance(value, dict):
        for key, item in value.items():
            if key not in UNCOMPARED:
                yield from numeric_leaves(item, f"{path}.{key}" if path else key)
    elif isinstance(value, list):
        array = numeric_array(value) if not any(isinstance(v, (str, dict, bool)) for v in value) else None
        if array is not None:
            yield path, array
        else:
            for k, item in enumerate(value):
                yield from numeric_leaves(item, f"{path}[{k}]")
    elif isinstance(value, (int, float)) and not isinstance(value, bool):
        yield path, np.array([value], float)


def difference(old: dict, new: dict) -> tuple[float, str]:
    """The largest |new − old| relative to the old leaf's span (max − min, at least NEAR_CONSTANT of its largest
    magnitude: a leaf constant up to rounding noise is compared by its size; a single number: its size) over the numeric leaves both answers have, and where; inf where the sizes or the nulls differ."""
    new_leaves = dict(numeric_leaves(new))
    worst = (0.0, "")
    for path, a in numeric_leaves(old):
        b = new_leaves.get(path)
        if b is None:
            continue
        if a.size != b.size:
            return float("inf"), f"{path}: {a.size} numbers old, {b.size} new"
        if not np.array_equal(np.isnan(a), np.isnan(b)):
            return float("inf"), f"{path}: nulls differ"
        a, b = a[~np.isnan(a)], b[~np.isnan(b)]
        if not a.size:
            continue
        span = np.abs(a[0]) if a.size == 1 else max(np.ptp(a), NEAR_CONSTANT * np.abs(a).max())
        gap = np.abs(b - a).max()
        relative = gap / span if span else (0.0 if gap == 0 else float("inf"))
        if relative > worst[0]:
            worst = (float(relative), path)
    return worst


def shared_scenes(old: dict, new: dict) -> dict:
    return {scene: {variant: [s for s in sliders if s in old[scene][variant]]
                    for variant, sliders in variants.items() if variant in old[scene]}
            for scene, variants in new.items() if scene in old}


def run(args) -> dict:
    trees = [Tree("old", check_tree(args.old)), Tree("new", check_tree(args.new))]
    try:
        infos = {tree.name: tree.ask(op="info") for tree in trees}
        warm = {tree.name: tree.ask(op="warm", scenes=args.scenes)["ms"] for tree in trees}
        plan = sweep_plan(args.points, args.scenes, shared_scenes(infos["old"]["scenes"], infos["new"]["scenes"]))
        rows = []           # (scene, variant, slider, value, tree, ms, outcome, detail)
        differences = []    # (scene, variant, slider, value, largest relative difference, where)
        started = time.monotonic()
        for round_ in range(args.rounds):
            for k, (scene, variant, slider, values) in enumerate(plan):
                answers = {}
                for tree in (trees if (k + round_) % 2 == 0 else trees[::-1]):
                    answer = tree.ask(op="time", scene=scene, variant=variant, values=values, answer=round_ == 0)
                    rows.append((scene, variant, slider, values.get(slider), tree.name, answer["ms"],
                                 answer["outcome"], answer["detail"]))
                    answers[tree.name] = answer.get("answer")
                if answers["old"] is not None and answers["new"] is not None:
                    differences.append((scene, variant, slider, values.get(slider),
                                        *difference(answers["old"], answers["new"])))
                if k % 50 == 0:
                    print(f"round {round_ + 1}, point {k + 1}/{len(plan)} ({scene} {variant} {slider}), "
                          f"{time.monotonic() - started:.0f} s", file=sys.stderr, flush=True)
    finally:
        for tree in trees:
            tree.close()
    return {"infos": infos, "warm": warm, "rows": rows, "differences": differences, "points": args.points,
            "rounds": args.rounds,
            "labels": {"old": tree_label(args.old), "new": tree_label(args.new)}}


def group_stats(rows: list, key) -> dict:
    """{group: {tree: times (ms)}} and the refused / failed counts."""
    times: dict = defaultdict(lambda: {"old": [], "new": []})
    outcomes: dict = defaultdict(lambda: defaultdict(int))
    worst: dict = {}
    for row in rows:
        group = key(row)
        scene, variant, slider, value, tree, ms, outcome, detail = row
        times[group][tree].append(ms)
        outcomes[group][(tree, outcome)] += 1
        if tree == "new" and ms > worst.get(group, (0,))[0]:
            worst[group] = (ms, f"{variant} {slider}={value:g}" if slider else f"{variant} (defaults)")
    return times, outcomes, worst


def fmt(ms: float) -> str:
    return "–" if ms != ms else (f"{ms:.0f}" if ms >= 100 else f"{ms:.1f}")


def markdown(result: dict, args) -> str:
    rows = result["rows"]
    lines = [
        "# Server compute over slider sweeps, old beside new", "",
        f"{machine_line()}. `python bench/scene_sweep.py --points {args.points} --rounds {args.rounds}`.", "",
        f"* old tree: {result['labels']['old']}, timed: "
        f"{result['infos']['old']['compute']}; warm-up (every scene's default request once) "
        f"{result['warm']['old'] / 1000:.1f} s.",
        f"* new tree: {result['labels']['new']}, timed: "
        f"{result['infos']['new']['compute']}; warm-up {result['warm']['new'] / 1000:.1f} s.",
        f"* Each slider swept over {args.points} of the values it can express (log steps on log sliders), the "
        "other sliders at their defaults, the page's request (`scene_request`); both trees in their own process, "
        "taking turns point by point. Times in ms, in-process (no HTTP). Target: p95 ≤ "
        f"{TARGET_MS:g} ms per scene (new).", "",
        "| scene | endpoint | requests per tree | refused (422) old / new | failed old / new | p50 old | p95 old "
        "| p50 new | p95 new | p50 old/new | p95 old/new | slowest new (ms, where) | p95 ≤ 20 ms |",
        "|---|---|---:|---|---|---:|---:|---:|---:|---:|---:|---|---|",
    ]
    scenes = lessons()[0]()
    times, outcomes, worst = group_stats(rows, lambda r: r[0])
    for scene_id in times:
        t = times[scene_id]
        p50o, p95o = np.percentile(t["old"], [50, 95])
        p50n, p95n = np.percentile(t["new"], [50, 95])
        o = outcomes[scene_id]
        w = worst.get(scene_id, (float("nan"), ""))
        lines.append(
            f"| {scene_id} | {scenes[scene_id].endpoint} | {len(t['new'])} | {o[('old', 'refused')]} / "
            f"{o[('new', 'refused')]} | {o[('old', 'error')]} / {o[('new', 'error')]} | {fmt(p50o)} | {fmt(p95o)} | "
            f"{fmt(p50n)} | {fmt(p95n)} | {p50o / p50n:.1f}× | {p95o / p95n:.1f}× | {fmt(w[0])} ({w[1]}) | "
            f"{'yes' if p95n <= TARGET_MS else '**no**'} |")
    lines += ["", "## Per slider", "",
              "| scene | variant | slider | points | p95 old | p95 new | max new | p95 old/new |",
              "|---|---|---|---:|---:|---:|---:|---:|"]
    times, outcomes, worst = group_stats(rows, lambda r: (r[0], r[1], r[2]))
    for (scene_id, variant, slider), t in times.items():
        p95o, p95n = np.percentile(t["old"], 95), np.percentile(t["new"], 95)
        lines.append(f"| {scene_id} | {variant} | {slider or '(defaults)'} | {len(t['new'])} | {fmt(p95o)} | "
                     f"{fmt(p95n)} | {fmt(max(t['new']))} | {p95o / p95n:.1f}× |")
    lines += ["", "## Do old and new give the same answers?", "",
              "At every point both answered, the largest |new − old| over every number and array of the answer "
              "(not numerics, warnings, study), relative to the old leaf's span (at least 0.1 % of its largest magnitude; a single number: relative to itself): the new answers are sent with the "
              "plot precision (7 significant digits: ~1e-7) where the old ones had every digit, and a different "
              "integrator agrees only to its tolerance. A size or null pattern that differs shows as inf (a run cut short by a wall-clock budget gives a shorter history).", "",
              "| scene | points compared | largest relative difference | where (slider, value, leaf) |",
              "|---|---:|---:|---|"]
    by_scene: dict = defaultdict(list)
    for item in result["differences"]:
        by_scene[item[0]].append(item)
    for scene_id, items in by_scene.items():
        worst = max(items, key=lambda item: item[4])
        where = f"{worst[1]} {worst[2]}={worst[3]:g}, {worst[5]}" if worst[2] else f"{worst[1]}, {worst[5]}"
        lines.append(f"| {scene_id} | {len(items)} | {worst[4]:.1e} | {where} |")
    failures = sorted({(r[4], r[0], r[1], r[2], r[7]) for r in rows if r[6] == "error"})
    if failures:
        lines += ["", "## Failures (not a 422)", ""] + [f"* {t} {s} {v} {sl}: {d}" for t, s, v, sl, d in failures[:40]]
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_tree_arguments(parser)
    parser.add_argument("--points", type=int, default=21, help="values per slider sweep")
    parser.add_argument("--rounds", type=int, default=1, help="times each sweep is repeated")
    parser.add_argument("--scenes", nargs="*", help="only these scene ids")
    parser.add_argument("--output", type=Path, default=ROOT / "bench" / "results" / "scene_sweep.md")
    args = parser.parse_args(argv)
    text = markdown(run(args), args)
    print(text)
    write_result(text, args.output)
    return 0


if __name__ == "__main__":
    sys.exit(main())
