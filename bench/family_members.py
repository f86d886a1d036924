"""What a cold full family's members cost, before beside after computing them at once (not a test).

For every scene, variant and slider (the variant's default values, the page's own family body with its
``fields``, bench/family_request.py), each tree answers the full family with an empty memo of members, in a
process of its own, the two processes taking turns family by family so that both see the same load. Each
worker times the members' computation alone (the time spent inside the members(values, deadline) calls that
family.build makes, server/api/family_batch.py: the endpoint's answers and the engine's pruning and rounding of
each member, family.Member.of), the endpoint's part alone (compute_answer per member before, compute_answers per
chunk after) and the whole family answer; each is the fastest of RUNS cold runs, the least disturbed by other
work on a shared machine. Per scene, the mean over its sliders (a grab picks
one); the weighted row uses the class mix of bench/classroom.py (SCENE_MIX).

    python3 bench/family_members.py --old /work/main            # every scene
    python3 bench/family_members.py --old /work/main --scenes flywheel wear
"""
from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
RUNS = 3                # cold runs per family and tree (--runs)


def worker(tree: str, repeat: int = RUNS) -> None:
    """Answer family bodies from stdin (one JSON line each) with their cold cost on stdout, in the given tree."""
    sys.path[:0] = [tree, str(ROOT / "bench")]
    os.chdir(tree)
    from server.core.warm_up import warm_up
    warm_up()
    from server.api import family_batch as batch
    from server.api.routers import family as route
    spent = [0.0]
    original = route.member_batch

    def timed_batch(*args, **kwargs):
        members = original(*args, **kwargs)

        def timed(values, deadline):
            started = time.perf_counter()
            try:
                return members(values, deadline)
            finally:
                spent[0] += time.perf_counter() - started
        return timed

    route.member_batch = timed_batch
    computing = [0.0]                   # inside the endpoint: compute_answer per member (before), compute_answers (after)
    name = "compute_answers" if hasattr(batch, "compute_answers") else "compute_answer"
    endpoint_function = getattr(batch, name)

    def timed_endpoint(*args, **kwargs):
        started = time.perf_counter()
        try:
            return endpoint_function(*args, **kwargs)
        finally:
            computing[0] += time.perf_counter() - started

    setattr(batch, name, timed_endpoint)
    print(json.dumps({"ready": True}), flush=True)
    for line in sys.stdin:
        body = json.loads(line)
        runs = []
        for _ in range(repeat):
            batch.MEMO.store.clear()
            batch.MEMO.held = 0
            spent[0] = computing[0] = 0.0
            started = time.perf_counter()
            answer, partial = route.family_answer(json.loads(json.dumps(body | {"stage": "full"})), "en")
            runs.append({"ms": 1e3 * (time.perf_counter() - started), "members_ms": 1e3 * spent[0],
                         "endpoint_ms": 1e3 * computing[0],
                         "members": len(answer["values"]), "partial": partial})
        best = {key: min(run[key] for run in runs) for key in ("ms", "members_ms", "endpoint_ms")}
        whole = min(runs, key=lambda run: run["ms"])      # the least disturbed run's family (a loaded machine may
        best |= {"members": whole["members"], "partial": whole["partial"]}   # cut another at the family's budget)
        print(json.dumps(best), flush=True)


def start(tree: Path, runs: int) -> subprocess.Popen:
    process = subprocess.Popen([sys.executable, __file__, "--worker", str(tree), "--runs", str(runs)], stdin=subprocess.PIPE,
                               stdout=subprocess.PIPE, text=True, cwd=str(tree))
    assert json.loads(process.stdout.readline())["ready"]
    return process


def ask(process: subprocess.Popen, body: dict) -> dict:
    process.stdin.write(json.dumps(body) + "\n")
    process.stdin.flush()
    return json.loads(process.stdout.readline())


def families(only: list[str]):
    sys.path[:0] = [str(ROOT), str(ROOT / "bench")]
    from family_request import page_family_body
    from trees import lessons
    for scene in lessons()[0]().values():
        if only and scene.id not in only:
            continue
        for variant in scene.variants:
            for slider in variant.sliders:
                yield scene.id, variant.id, slider.id, page_family_body(scene, variant, slider, ROOT)


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--worker")
    parser.add_argument("--old", type=Path, required=False)
    parser.add_argument("--scenes", nargs="*", default=[])
    parser.add_argument("--runs", type=int, default=RUNS)
    args = parser.parse_args()
    if args.worker:
        worker(args.worker, args.runs)
        return
    sys.path[:0] = [str(ROOT / "bench")]
    from classroom import SCENE_MIX
    old, new = start(args.old, args.runs), start(ROOT, args.runs)
    per_scene: dict[str, list] = {}
    for turn, (scene, variant, slider, body) in enumerate(families(args.scenes)):
        pair = {}
        order = (("old", old), ("new", new))
        for name, process in (order if turn % 2 == 0 else order[::-1]):
            pair[name] = ask(process, body)
        per_scene.setdefault(scene, []).append(pair)
        print(f"{scene:22s} {variant:14s} {slider:14s} members {pair['old']['members']:2d}/{pair['new']['members']:2d}"
              f"  endpoint {pair['old']['endpoint_ms']:7.1f} → {pair['new']['endpoint_ms']:6.1f} ms"
              f"  members' cost {pair['old']['members_ms']:7.1f} → {pair['new']['members_ms']:6.1f} ms"
              f"  family {pair['old']['ms']:7.1f} → {pair['new']['ms']:6.1f} ms", flush=True)
    for process in (old, new):
        process.stdin.close()
        process.wait()
    print("\n| scene | sliders | members (mean) | endpoint before (ms) | after (ms) | ratio | members' cost before (ms) "
          "| after (ms) | ratio | family before (ms) | after (ms) |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    keys = ("endpoint_ms", "members_ms", "ms")
    weighted = {(who, key): 0.0 for who in ("old", "new") for key in keys}
    total_weight = 0.0
    for scene, pairs in per_scene.items():
        mean = {(who, key): sum(p[who][key] for p in pairs) / len(pairs) for who in ("old", "new") for key in keys}
        print(f"| {scene} | {len(pairs)} | {sum(p['new']['members'] for p in pairs) / len(pairs):.0f} | "
              + " | ".join(f"{mean['old', key]:.1f} | {mean['new', key]:.1f} | "
                           f"{mean['old', key] / mean['new', key]:.1f}×" if key != "ms" else
                           f"{mean['old', key]:.1f} | {mean['new', key]:.1f}" for key in keys) + " |")
        weight = SCENE_MIX.get(scene, 0.0)
        total_weight += weight
        for index in weighted:
            weighted[index] += weight * mean[index]
    if total_weight:
        w = {index: value / total_weight for index, value in weighted.items()}
        print("| weighted by the class mix (scenes measured) | | | "
              + " | ".join(f"{w['old', key]:.1f} | {w['new', key]:.1f} | {w['old', key] / w['new', key]:.1f}×"
                           if key != "ms" else f"{w['old', key]:.1f} | {w['new', key]:.1f}" for key in keys) + " |")


if __name__ == "__main__":
    main()
