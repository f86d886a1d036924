"""What one slider family costs, old engine beside new (issue 13, "Dragging is a lookup"; not a test).

For every scene, variant and slider (the variant's default values, the page's family request from
bench/family_request.py), one family is computed in-process by the old tree (default /tmp/mdl-fam-old, a
``git worktree add --detach`` of commit 9b8d9d3, made here if absent) and by the new one (this repository),
each in a process of its own, the two taking turns family by family so that both see the same load. Each
worker counts the exact endpoint computations (endpoints.compute_answer) and times the family. The new worker
starts each family with an empty memo of members, and also times the page's sequence: the coarse stage (what
the grab asks first) and then the full family (reusing the coarse members).

Columns: members, exact computations, ms (wall clock of the family) and interpolation error (old: measured at
the midpoints; new: the estimate h²|f''|/8) for old and new; the new coarse stage's ms and the full family's ms
right after it. Results: printed and written to bench/results/family_cost.md.

    python3 bench/family_cost.py                       # every scene (a few minutes on 2 CPUs)
    python3 bench/family_cost.py --scenes wear flywheel
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
OLD_COMMIT = "9b8d9d3"
DEFAULT_OLD = Path("/tmp/mdl-fam-old")
ELASTIC = ("elastic-",)


def worker(tree: str) -> None:
    """Answer family requests from stdin (one JSON line each) with their cost on stdout, in the given tree."""
    sys.path[:0] = [tree, str(ROOT / "bench")]
    os.chdir(tree)
    from server.core.warm_up import warm_up
    warm_up()
    from server.api import endpoints
    from server.api.routers import family as route
    try:
        from server.api import family_batch as batch
    except ImportError:
        batch = None
    original, count = endpoints.compute_answer, [0]

    def counted(*args, **kwargs):
        count[0] += 1
        return original(*args, **kwargs)

    (batch or route).compute_answer = counted
    print(json.dumps({"ready": True}), flush=True)
    for line in sys.stdin:
        body = json.loads(line)
        result = {}
        stages = ("full", "coarse", "after") if batch else ("full",)
        for stage in stages:
            if batch and stage != "after":
                batch.MEMO.store.clear()
                batch.MEMO.held = 0
            request = dict(body, stage="full" if stage == "after" else stage) if batch else body
            count[0] = 0
            started = time.perf_counter()
            answer, partial = route.family_answer(json.loads(json.dumps(request)), "en")
            result[stage] = {"ms": 1e3 * (time.perf_counter() - started), "members": answer["numerics"]["points"],
                             "computed": count[0], "error": answer["interpolation_error"], "partial": partial,
                             "message": answer["numerics"]["message"]}
        print(json.dumps(result), flush=True)


def old_tree(path: Path) -> Path:
    if not (path / "server").is_dir():
        subprocess.run(["git", "-C", str(ROOT), "worktree", "add", "--detach", str(path), OLD_COMMIT], check=True)
    return path


def start(tree: Path) -> subprocess.Popen:
    process = subprocess.Popen([sys.executable, __file__, "--worker", str(tree)], stdin=subprocess.PIPE,
                               stdout=subprocess.PIPE, text=True, cwd=str(tree))
    assert json.loads(process.stdout.readline())["ready"]
    return process


def ask(process: subprocess.Popen, body: dict) -> dict:
    process.stdin.write(json.dumps(body) + "\n")
    process.stdin.flush()
    return json.loads(process.stdout.readline())


def families(only: list[str]):
    sys.path[:0] = [str(ROOT), str(ROOT / "bench")]
    from family_request import family_body
    from trees import lessons
    scenes = lessons()[0]()
    for scene in scenes.values():
        if only and scene.id not in only:
            continue
        for variant in scene.variants:
            for slider in variant.sliders:
                yield scene.id, variant.id, slider.id, family_body(scene, variant, slider)


def cell(x) -> str:
    return "—" if x is None else f"{x:.3g}"


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--worker")
    parser.add_argument("--old", type=Path, default=DEFAULT_OLD)
    parser.add_argument("--scenes", nargs="*", default=[])
    args = parser.parse_args()
    if args.worker:
        worker(args.worker)
        return
    old, new = start(old_tree(args.old)), start(ROOT)
    rows = []
    for turn, (scene, variant, slider, body) in enumerate(families(args.scenes)):
        pair = {}
        for name, process in ((("old", old), ("new", new)) if turn % 2 == 0 else (("new", new), ("old", old))):
            pair[name] = ask(process, body)
        o, n = pair["old"]["full"], pair["new"]
        rows.append((scene, variant, slider, o, n))
        print(f"{scene:22s} {variant:16s} {slider:14s} old {o['members']:3d}/{o['computed']:3d} {o['ms']:7.0f} ms "
              f"err {cell(o['error'])} | new {n['full']['members']:3d}/{n['full']['computed']:3d} "
              f"{n['full']['ms']:7.0f} ms err {cell(n['full']['error'])} | coarse {n['coarse']['ms']:6.0f} ms, "
              f"full after {n['after']['ms']:6.0f} ms", flush=True)
    for process in (old, new):
        process.stdin.close()
        process.wait()
    write(rows, args)


def write(rows, args) -> None:
    lines = [f"# Family cost, old ({OLD_COMMIT}) beside new", "",
             f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, Python {platform.python_version()}, "
             f"{os.cpu_count()} CPUs (shared with other work: compare the ratios, not the figures). Each family "
             "computed once per engine, in-process, the two engines in their own processes taking turns. "
             "members/computed: members sent / exact endpoint computations. err: the reported interpolation "
             "error / span (old: measured at the checked midpoints; new: estimated, h²|f''|/8), target 0.005. "
             "coarse: the new coarse stage (9 members) from an empty memo; after: the full family asked right "
             "after it (the page's grab sequence).", "",
             "| scene | variant | slider | old members/computed | old ms | old err | new members/computed | "
             "new ms | new err | coarse ms | after ms | old/new ms |", "|" + "---|" * 12]
    for scene, variant, slider, o, n in rows:
        f = n["full"]
        lines.append(f"| {scene} | {variant} | {slider} | {o['members']}/{o['computed']} | {o['ms']:.0f} | "
                     f"{cell(o['error'])} | {f['members']}/{f['computed']} | {f['ms']:.0f} | {cell(f['error'])} | "
                     f"{n['coarse']['ms']:.0f} | {n['after']['ms']:.0f} | {o['ms'] / f['ms']:.2f} |")
    lines += ["", "## Summary", "", "| families | computed old → new | ms old → new (sum) | median old/new | "
              "p95 ms new full | p95 ms new coarse | above 0.005 old → new |", "|---|---|---|---|---|---|---|"]
    for label, keep in (("light", lambda r: not r[0].startswith(ELASTIC)), ("elastic", lambda r: r[0].startswith(ELASTIC)),
                        ("all", lambda r: True)):
        part = [r for r in rows if keep(r)]
        if not part:
            continue
        full = sorted(r[4]["full"]["ms"] for r in part)
        coarse = sorted(r[4]["coarse"]["ms"] for r in part)
        p95 = lambda xs: xs[min(len(xs) - 1, int(0.95 * len(xs)))]
        above = lambda side: sum(1 for r in part if (side(r)["error"] or 0) > 0.005)
        lines.append(f"| {label} ({len(part)}) | {sum(r[3]['computed'] for r in part)} → "
                     f"{sum(r[4]['full']['computed'] for r in part)} | {sum(r[3]['ms'] for r in part):.0f} → "
                     f"{sum(r[4]['full']['ms'] for r in part):.0f} | "
                     f"{statistics.median(r[3]['ms'] / r[4]['full']['ms'] for r in part):.2f} | {p95(full):.0f} | "
                     f"{p95(coarse):.0f} | {above(lambda r: r[3])} → {above(lambda r: r[4]['full'])} |")
    lines += ["", "## Messages of the new families that name what they cannot resolve", ""]
    lines += [f"- {r[0]} / {r[1]} / {r[2]}: {r[4]['full']['message']}" for r in rows if r[4]["full"]["message"]]
    out = ROOT / "bench" / "results" / "family_cost.md"
    out.write_text("\n".join(lines) + "\n")
    print("\n".join(lines[-(len(rows) + 20):]))


if __name__ == "__main__":
    main()
