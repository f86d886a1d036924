"""Benchmark: what opening a lesson costs the browser, with the vendored plotly.js beside a baseline bundle.

Every scene (its default variant, in Russian) is opened LOADS times in headless Chromium at 1400 × 900 with each
of two plotly.js files, the two given the same page in turn (one browser context each, so that each keeps its own
HTTP and code cache as a returning student's browser does; the first load of a context is a first visit):
  CPU      the page's main-thread work from navigation until it has settled (no request for 300 ms, then
           1.5 s more for the panels drawn while idle): Chromium's TaskDuration (CDP Performance.getMetrics)
  answer   navigation start → the first exact answer drawn (the page's performance mark exact-drawn)
Both files are served by the app's own URL (the request answered by Playwright from the file, for both bundles
alike). The baseline is the plotly.min.js vendored before the current one (git history), or --baseline FILE.
Writes bench/results/page_load.md.

    python bench/page_load.py [--loads 5] [--scenes wear,flywheel] [--baseline FILE] [--no-write]
"""
from __future__ import annotations

import argparse
import statistics
import subprocess
from pathlib import Path

from browser import scenes
from trees import ROOT, machine_line, running_server, write_result

PLOTLY = ROOT / "web" / "vendor" / "plotly" / "plotly.min.js"
SETTLE_MS = 1500


def previous_bundle() -> tuple[bytes, str]:
    """The plotly.min.js vendored before the current one, and how it names itself."""
    log = subprocess.run(["git", "log", "--format=%H", "--", str(PLOTLY.relative_to(ROOT))], cwd=ROOT,
                         capture_output=True, text=True, check=True).stdout.split()
    if len(log) < 2:
        raise SystemExit("no earlier plotly.min.js in the history: give --baseline FILE")
    data = subprocess.run(["git", "show", f"{log[1]}:{PLOTLY.relative_to(ROOT)}"], cwd=ROOT, capture_output=True,
                          check=True).stdout
    return data, "the previously vendored plotly.min.js"


def header(data: bytes) -> str:
    """The bundle's own description (its first comment's first line after the opening)."""
    lines = data[:400].decode("utf-8", "replace").splitlines()
    return next((line.lstrip("* ").strip() for line in lines[1:] if "plotly.js" in line), "?")


def load(context, scene_id: str) -> tuple[float, float | None]:
    """Open the scene once: (main-thread CPU in ms until settled, ms to the first exact answer drawn or None)."""
    page = context.new_page()
    cdp = context.new_cdp_session(page)
    cdp.send("Performance.enable")
    page.goto(f"/scenes/{scene_id}?lang=ru")
    page.wait_for_load_state("networkidle")
    page.wait_for_timeout(300)
    page.wait_for_load_state("networkidle")
    page.wait_for_timeout(SETTLE_MS)
    metrics = {m["name"]: m["value"] for m in cdp.send("Performance.getMetrics")["metrics"]}
    drawn = page.evaluate("() => performance.getEntriesByName('exact-drawn').map((e) => e.startTime)")
    page.close()
    return metrics["TaskDuration"] * 1000, (min(drawn) if drawn else None)


def serving(body: bytes):
    """A route handler answering with this script, cached as the app caches its versioned scripts."""
    def answer(route) -> None:
        route.fulfill(status=200, body=body, headers={"Content-Type": "text/javascript; charset=utf-8",
                                                      "Cache-Control": "public, max-age=31536000, immutable"})
    return answer


def measure(port: int, scene_ids: list[str], bundles: dict[str, bytes], loads: int) -> dict:
    from playwright.sync_api import sync_playwright
    results = {(name, scene): {"cpu": [], "answer": [], "first_cpu": None} for name in bundles for scene in scene_ids}
    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path="/usr/bin/chromium", args=["--no-sandbox"])
        contexts = {}
        for name, body in bundles.items():
            context = browser.new_context(base_url=f"http://127.0.0.1:{port}", viewport={"width": 1400, "height": 900})
            context.route("**/vendor/plotly/**/plotly.min.js", serving(body))
            contexts[name] = context
        for round_ in range(loads):
            order = list(bundles) if round_ % 2 == 0 else list(reversed(bundles))
            for scene in scene_ids:
                for name in order:
                    cpu, answer = load(contexts[name], scene)
                    entry = results[(name, scene)]
                    if entry["first_cpu"] is None:
                        entry["first_cpu"] = cpu
                    else:
                        entry["cpu"].append(cpu)
                    if answer is not None:
                        entry["answer"].append(answer)
        browser.close()
    return results


def markdown(results: dict, scene_ids: list[str], bundles: dict[str, bytes], names: dict[str, str], loads: int) -> str:
    base, ours = list(bundles)
    med = statistics.median
    ms = lambda xs: f"{statistics.median(xs):.0f}" if xs else "—"     # a page that draws no exact answer
    rows = []
    for scene in scene_ids:
        b, o = results[(base, scene)], results[(ours, scene)]
        rows.append(f"| {scene} | {b['first_cpu']:.0f} | {o['first_cpu']:.0f} | {med(b['cpu']):.0f} | {med(o['cpu']):.0f} "
                    f"| {med(o['cpu']) / med(b['cpu']):.2f} | {ms(b['answer'])} | {ms(o['answer'])} |")
    total = lambda name: statistics.median([c for s in scene_ids for c in results[(name, s)]["cpu"]])
    return "\n".join([
        "# Opening a lesson: the browser's work, two plotly.js bundles side by side", "",
        f"`python bench/page_load.py --loads {loads}`, {machine_line()}; Chromium headless at 1400 × 900, one "
        "uvicorn worker on loopback, every scene's default variant in Russian.", "",
        f"- **baseline**: {names[base]} ({header(bundles[base])}, {len(bundles[base]) / 1e6:.1f} MB)",
        f"- **ours**: the vendored web/vendor/plotly/plotly.min.js ({header(bundles[ours])}, "
        f"{len(bundles[ours]) / 1e6:.1f} MB)", "",
        "*CPU*: the page's main-thread work (Chromium's TaskDuration) from navigation until settled (no request "
        f"for 300 ms, then {SETTLE_MS} ms for the panels drawn while idle); *first visit* is a context's first page "
        f"(empty caches), the median over the {loads - 1} later loads of each scene a returning browser's. *Answer*: "
        "navigation start → the first exact answer drawn (median). The two bundles load the same page in turn.", "",
        "| scene | first visit CPU, baseline, ms | first visit CPU, ours, ms | CPU, baseline, ms | CPU, ours, ms "
        "| ratio ours / baseline | answer drawn, baseline, ms | answer drawn, ours, ms |",
        "|---|---:|---:|---:|---:|---:|---:|---:|",
        *rows, "",
        f"Median over every later load: baseline {total(base):.0f} ms, ours {total(ours):.0f} ms of main-thread "
        f"work ({total(ours) / total(base):.2f}×).", ""])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--loads", type=int, default=5, help="loads of each scene with each bundle (≥ 2)")
    parser.add_argument("--scenes", help="scene ids, comma-separated (default: every scene)")
    parser.add_argument("--baseline", type=Path, help="the baseline plotly.js file (default: the one vendored before)")
    parser.add_argument("--output", type=Path, default=ROOT / "bench" / "results" / "page_load.md")
    parser.add_argument("--no-write", action="store_true", help="print the table only")
    args = parser.parse_args()
    if args.loads < 2:
        parser.error("--loads must be at least 2 (a first visit and a returning one)")
    scene_ids = args.scenes.split(",") if args.scenes else [s["id"] for s in scenes()]
    base, base_name = ((args.baseline.read_bytes(), str(args.baseline)) if args.baseline else previous_bundle())
    bundles = {"baseline": base, "ours": PLOTLY.read_bytes()}
    names = {"baseline": base_name, "ours": "ours"}
    with running_server() as (port, _):
        results = measure(port, scene_ids, bundles, args.loads)
    text = markdown(results, scene_ids, bundles, names, args.loads)
    print(text)
    if not args.no_write:
        write_result(text, args.output)


if __name__ == "__main__":
    main()
