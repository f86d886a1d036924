"""What one slider family costs the server and the wire, old page and engine beside new ("Dragging is
a lookup"; not a test).

For every scene, variant and slider (the variant's default values), each tree answers the family request its
own page sends on a grab (bench/family_request.py: a page without family_fields.js sends the endpoint's whole
answers; one with it names the leaves its panels draw, ``fields`` run in Node (web/static/js/common/model/family_fields.js), and asks for the family
``packed``). The old tree (--old; default /tmp/mdl-engine-old, a ``git worktree add --detach`` of OLD_COMMIT,
made here if absent) and the new one (this repository) each run in a process of their own, the two taking
turns family by family so that both see the same load.

Each worker times what the server does for a family: the family's answer (family_answer, as in the heavy
process), its JSON (serialise, as the route sends it) and its gzip (level GZIP_LEVEL, as the app's middleware),
in three situations:
  cold   the memo of members empty: the page's grab sequence, the coarse stage then the full family (the full
         one reusing the coarse members), the two summed;
  warm   the full family again with every member in the memo (a neighbouring student's grab of the same
         family, or one the response cache no longer holds);
and reports the full family's members, exact computations, interpolation error, JSON and gzip bytes. Each
time is the fastest of COLD_RUNS (cold) or WARM_RUNS (warm) runs, the one least disturbed by other work on a
shared machine.
Results: printed and written to bench/results/family_cost.md.

    python3 bench/family_cost.py                       # every scene (several minutes on 2 CPUs)
    python3 bench/family_cost.py --scenes wear flywheel
    python3 bench/family_cost.py --scenes equation-of-motion --old /tmp/mdl-eom-old --out /tmp/eom.md
"""
from __future__ import annotations

import argparse
import gzip
import json
import os
import platform
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
OLD_COMMIT = "5a15c56"         # before the stacked engine and the cubic rule (an earlier run: d0a7cb5, whole answers)
DEFAULT_OLD = Path("/tmp/mdl-engine-old")
HEAVY = ("elastic-", "forces-friction", "flywheel", "equation-of-motion")
GZIP_LEVEL = 3                  # server/runtime/response_cache.py: the app's GZip middleware's level
COLD_RUNS, WARM_RUNS = 2, 3     # the fastest of these runs is kept: the least disturbed by other work


def worker(tree: str) -> None:
    """Answer family requests from stdin (one JSON line each) with their cost on stdout, in the given tree."""
    sys.path[:0] = [tree, str(ROOT / "bench")]
    os.chdir(tree)
    from server.core.warm_up import warm_up
    warm_up()
    from server.api import family_batch as batch
    from server.api.routers import family as route
    from server.api.serialise import serialise

    def timed(body: dict) -> dict:
        started = time.perf_counter()
        answer, partial = route.family_answer(json.loads(json.dumps(body)), "en")
        built = time.perf_counter()
        text = serialise(answer, None)                  # the route sends the family's own rounding
        packed = gzip.compress(text, GZIP_LEVEL)
        done = time.perf_counter()
        return {"ms": 1e3 * (done - started), "build_ms": 1e3 * (built - started), "members": len(answer["values"]),
                "computed": answer["numerics"].get("computed", 0), "error": answer["interpolation_error"], "partial": partial,
                "json": len(text), "gzip": len(packed), "message": answer["numerics"]["message"]}

    def fastest(runs: list[dict]) -> dict:
        return min(runs, key=lambda run: run["ms"])

    print(json.dumps({"ready": True}), flush=True)
    for line in sys.stdin:
        body = json.loads(line)
        colds = []
        for _ in range(COLD_RUNS):
            batch.MEMO.store.clear()
            batch.MEMO.held = 0
            coarse = timed(body | {"stage": "coarse"})
            colds.append((coarse, timed(body | {"stage": "full"})))
        coarse, full = min(colds, key=lambda pair: pair[0]["ms"] + pair[1]["ms"])
        warm = fastest([timed(body | {"stage": "full"}) for _ in range(WARM_RUNS)])
        print(json.dumps({"coarse": coarse, "full": full, "warm": warm,
                          "cold_ms": coarse["ms"] + full["ms"]}), flush=True)


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


def families(only: list[str], old: Path):
    """(scene, variant, slider, the old page's body, the new page's body) for every slider."""
    sys.path[:0] = [str(ROOT), str(ROOT / "bench")]
    from family_request import page_family_body
    from trees import lessons
    for scene in lessons()[0]().values():
        if only and scene.id not in only:
            continue
        for variant in scene.variants:
            for slider in variant.sliders:
                yield (scene.id, variant.id, slider.id, page_family_body(scene, variant, slider, old),
                       page_family_body(scene, variant, slider, ROOT))


def cell(x) -> str:
    return "—" if x is None else f"{x:.3g}"


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--worker")
    parser.add_argument("--old", type=Path, default=DEFAULT_OLD)
    parser.add_argument("--scenes", nargs="*", default=[])
    parser.add_argument("--out", type=Path, default=ROOT / "bench" / "results" / "family_cost.md",
                        help="where the tables go (default bench/results/family_cost.md, overwritten)")
    args = parser.parse_args()
    if args.worker:
        worker(args.worker)
        return
    old_path = old_tree(args.old)
    old, new = start(old_path), start(ROOT)
    rows = []
    for turn, (scene, variant, slider, old_body, new_body) in enumerate(families(args.scenes, old_path)):
        pair = {}
        order = (("old", old, old_body), ("new", new, new_body))
        for name, process, body in (order if turn % 2 == 0 else order[::-1]):
            pair[name] = ask(process, body)
        o, n = pair["old"], pair["new"]
        rows.append((scene, variant, slider, o, n))
        print(f"{scene:22s} {variant:14s} {slider:14s} members {o['full']['members']:2d}→{n['full']['members']:2d} "
              f"gz {o['full']['gzip'] / 1e3:6.0f}→{n['full']['gzip'] / 1e3:5.0f} kB  cold {o['cold_ms']:6.0f}→"
              f"{n['cold_ms']:6.0f} ms  warm {o['warm']['ms']:5.0f}→{n['warm']['ms']:4.0f} ms  err "
              f"{cell(o['full']['error'])}→{cell(n['full']['error'])}", flush=True)
    for process in (old, new):
        process.stdin.close()
        process.wait()
    from trees import tree_label
    write(rows, tree_label(old_path), tree_label(ROOT), args.out)


def ratio(a: float, b: float) -> str:
    return f"{a / b:.1f}×" if b else "—"


def write(rows, old_label: str, new_label: str, out: Path) -> None:
    lines = [f"# Family cost, old ({old_label}) beside new ({new_label}), each with its own page's request",
             "", f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, Python {platform.python_version()}, "
             f"{os.cpu_count()} CPUs shared with other work (compare the ratios, not the figures). `python3 "
             "bench/family_cost.py`: each family answered in-process by each tree, the two in processes of their "
             "own taking turns. Server time = the family's answer + its JSON + gzip (level 3, as the app), the fastest of "
             f"{COLD_RUNS} runs (cold) or {WARM_RUNS} (warm). cold: "
             "empty memo, the page's grab sequence (coarse stage, then the full family reusing its members); "
             "warm: the full family again with every member in the memo. Bytes and error: the full family. err: "
             "the reported interpolation error / span (target 0.005; in the new tree over the drawn fields, plus 5e-5 for "
             "packing).", "", "## Per scene (sums over its sliders)", "",
             "| scene | families | members old → new | fewer | JSON MB old → new | gzip kB old → new | smaller (gzip) "
             "| cold ms old → new | cheaper (cold) | warm ms old → new | cheaper (warm) | computed old → new |",
             "|" + "---|" * 12]
    by_scene: dict[str, list] = {}
    for row in rows:
        by_scene.setdefault(row[0], []).append(row)
    total = lambda part, side, key: sum(r[3 if side == "old" else 4]["full"][key] for r in part)
    for scene, part in [*by_scene.items(), ("**heavy scenes**", [r for r in rows if r[0].startswith(HEAVY)]),
                        ("**all**", rows)]:
        if not part:
            continue
        cold = [sum(r[k]["cold_ms"] for r in part) for k in (3, 4)]
        warm = [sum(r[k]["warm"]["ms"] for r in part) for k in (3, 4)]
        members = [total(part, side, "members") for side in ("old", "new")]
        lines.append(f"| {scene} | {len(part)} | {members[0]} → {members[1]} | {ratio(*members)} | "
                     f"{total(part, 'old', 'json') / 1e6:.2f} → "
                     f"{total(part, 'new', 'json') / 1e6:.2f} | {total(part, 'old', 'gzip') / 1e3:.0f} → "
                     f"{total(part, 'new', 'gzip') / 1e3:.0f} | "
                     f"{ratio(total(part, 'old', 'gzip'), total(part, 'new', 'gzip'))} | {cold[0]:.0f} → {cold[1]:.0f} | "
                     f"{ratio(*cold)} | {warm[0]:.0f} → {warm[1]:.0f} | {ratio(*warm)} | "
                     f"{total(part, 'old', 'computed')} → {total(part, 'new', 'computed')} |")
    lines += ["", "## Per family", "",
              "| scene | variant | slider | members old → new | err old → new | JSON kB old → new | gzip kB old → new "
              "| cold ms old → new | warm ms old → new | warm build ms old → new |", "|" + "---|" * 10]
    for scene, variant, slider, o, n in rows:
        lines.append(f"| {scene} | {variant} | {slider} | {o['full']['members']} → {n['full']['members']} | "
                     f"{cell(o['full']['error'])} → {cell(n['full']['error'])} | {o['full']['json'] / 1e3:.0f} → "
                     f"{n['full']['json'] / 1e3:.0f} | {o['full']['gzip'] / 1e3:.0f} → {n['full']['gzip'] / 1e3:.0f} | "
                     f"{o['cold_ms']:.0f} → {n['cold_ms']:.0f} | {o['warm']['ms']:.0f} → {n['warm']['ms']:.0f} | "
                     f"{o['warm']['build_ms']:.0f} → {n['warm']['build_ms']:.0f} |")
    above = [r for r in rows if (r[4]["full"]["error"] or 0) > 0.005]
    lines += ["", f"Families whose new estimate is above 0.005: {len(above)} of {len(rows)} (old: "
              f"{sum(1 for r in rows if (r[3]['full']['error'] or 0) > 0.005)}); their messages:", ""]
    lines += [f"- {r[0]} / {r[1]} / {r[2]}: {r[4]['full']['message']}" for r in above if r[4]["full"]["message"]]
    p95 = lambda xs: sorted(xs)[min(len(xs) - 1, int(0.95 * len(xs)))]
    lines += ["", "p95 over families, new tree: cold " f"{p95([r[4]['cold_ms'] for r in rows]):.0f} ms, warm "
              f"{p95([r[4]['warm']['ms'] for r in rows]):.0f} ms, gzip {p95([r[4]['full']['gzip'] for r in rows]) / 1e3:.0f} kB"
              f"; old tree: cold {p95([r[3]['cold_ms'] for r in rows]):.0f} ms, warm {p95([r[3]['warm']['ms'] for r in rows]):.0f} ms, "
              f"gzip {p95([r[3]['full']['gzip'] for r in rows]) / 1e3:.0f} kB. Median old/new warm: "
              f"{statistics.median(r[3]['warm']['ms'] / r[4]['warm']['ms'] for r in rows):.1f}×. The family's own work "
              "per member (warm build ms / members, the members from the memo: the engine), median over families: "
              f"old {statistics.median(r[3]['warm']['build_ms'] / r[3]['full']['members'] for r in rows):.2f} ms, new "
              f"{statistics.median(r[4]['warm']['build_ms'] / r[4]['full']['members'] for r in rows):.2f} ms; members "
              f"{sum(r[3]['full']['members'] for r in rows)} → {sum(r[4]['full']['members'] for r in rows)}."]
    out.write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
