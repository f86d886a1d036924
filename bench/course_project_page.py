"""How fast the course-project page (/project) draws the whole project once its answer is there (target: 2 s).

    python3 bench/course_project_page.py [--loads 10] [--out bench/results/course_project_page.md]

Starts the app (the README's command, a free port, bench/trees.py) and Debian's Chromium; opens the project of
a six-bar with friction at 24 positions from its address (the shaping machine and the jaw crusher, their
presets' design data with f = 0.1 and r = 20 mm in every pair) and reloads it --loads times. Per load:
the answer's arrival (the POST's responseEnd, the Resource Timing API) to the page drawn (the status's answer
count incremented, after the report and its drawings are built synchronously: a MutationObserver's timestamp),
and the server's time for the request (responseStart − requestStart). Prints a Markdown table and writes it to --out.
"""
from __future__ import annotations

import argparse
import base64
import json
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))
sys.path.insert(0, str(REPO / "bench"))

from trees import machine_line, percentiles, running_server  # noqa: E402

CHROMIUM = "/usr/bin/chromium"
MACHINES = ("shaping_machine", "jaw_crusher")
FRICTION = {"friction": 0.1, "pair_radius": 0.02}
WATCH = """() => new Promise((resolve) => {
    const status = document.querySelector("#project-status");
    const done = () => {
        const post = performance.getEntriesByType("resource").filter((e) => e.name.includes("/api/v1/course-project"))
            .pop();
        resolve({drawn: performance.now() - post.responseEnd, server: post.responseStart - post.requestStart,
                 state: status.dataset.state, bytes: post.encodedBodySize});
    };
    if (Number(status.dataset.answers ?? 0) > 0) return done();
    new MutationObserver((_, observer) => { observer.disconnect(); done(); })
        .observe(status, {attributes: true, attributeFilter: ["data-answers"]});
})"""


def encoded(data: dict) -> str:
    return base64.urlsafe_b64encode(json.dumps(data).encode()).decode().rstrip("=")


def address(name: str) -> str:
    from server.core.structure.presets import presets
    preset = presets()[name]
    dynamics = preset["dynamics"] | {"masses": preset["dynamics"]["masses"] | FRICTION}
    return (f"/project?lang=ru&m={encoded(preset['linkage'])}&d={encoded(dynamics)}"
            f"&p={encoded({'positions': 24, 'title': {'student': 'bench'}})}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--loads", type=int, default=10, help="page loads per machine (the first is not counted)")
    parser.add_argument("--out", default=str(REPO / "bench" / "results" / "course_project_page.md"))
    args = parser.parse_args()
    from playwright.sync_api import sync_playwright
    rows = []
    with running_server() as (port, _), sync_playwright() as playwright:
        browser = playwright.chromium.launch(executable_path=CHROMIUM, headless=True, args=["--no-sandbox"])
        page = browser.new_page(viewport={"width": 1280, "height": 900})
        for name in MACHINES:
            drawn, server, size = [], [], 0
            for load in range(args.loads + 1):
                page.goto(f"http://127.0.0.1:{port}{address(name)}", wait_until="domcontentloaded")
                result = page.evaluate(WATCH)
                assert result["state"] == "ready", result
                if load:                   # the first load fills the browser's and the server's caches of code
                    drawn.append(result["drawn"])
                    server.append(result["server"])
                    size = result["bytes"]
            rows.append((name, percentiles(drawn), percentiles(server), size))
        browser.close()
    lines = [f"# The course-project page drawn after its answer", "", machine_line() + f"; {args.loads} loads per "
             "machine after a first one; 24 positions, f = 0.1; Chromium headless, 1280 × 900.", "",
             "| machine | answer → page drawn p50, ms | p95, ms | server time p50, ms | p95, ms | answer, kB (gzip) |",
             "|---|---:|---:|---:|---:|---:|"]
    for name, (d50, d95), (s50, s95), size in rows:
        lines.append(f"| {name} | {d50:.0f} | {d95:.0f} | {s50:.0f} | {s95:.0f} | {size / 1024:.0f} |")
    text = "\n".join(lines) + "\n"
    print(text)
    Path(args.out).write_text(text, encoding="utf-8")


if __name__ == "__main__":
    main()
