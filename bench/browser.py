"""Benchmark: dragging a slider in Chromium, drawn from the slider's family.

For every scene (its first variant with sliders, and that variant's first slider) on a fresh page at 1400 × 900, from the page's own
performance marks (web/static/js: controls_view, family_preview, *_scene):
  first visit     navigation start → the first exact answer drawn (exact-drawn)
  family          the grab (pointer down: family-requested) → the coarse family arrived (family-coarse-arrived:
                  "stage": "coarse", the 9 start members) and → the full one (family-full-arrived), which the
                  page asks for when the coarse one has arrived; a server without stages answers only the full one
  input → drawn   each `input` event of the drag once the family is there (slider-input) → the preview
                  drawn (plots-drawn: Plotly.react's promise for every plot in view, the drawing updated)
  release → exact pointer up → the exact answer drawn (exact-drawn)
and beside it the same drag on a page whose family never arrives (the request is held: the page as it was
before families), where an input is followed by the next exact answer drawn: input → that draw.

The drag is a hand's: the thumb pressed, moved through STEPS positions over DRAG_FRACTION of the track,
MOVE_PAUSE_S apart, and released. The app runs under uvicorn on a free loopback port (as the browser
tests start it); Chromium is Debian's /usr/bin/chromium, headless. A run prints a Markdown table and
writes it to bench/results/browser.md.

With --stages, each scene's family (the body the page sent on the grab) is then asked for over HTTP in three
ways, each on a fresh family: coarse, then full once the coarse has arrived (the page's way); both at once; the
full one alone (the page before stages).

    python bench/browser.py [--scenes transfer_functions,flywheel] [--stages] [--out bench/results/browser.md]
"""
from __future__ import annotations

import argparse
import json
import os
import platform
import socket
import statistics
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import httpx

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "bench"))
from trees import tree_label  # noqa: E402  (bench/ is not a package)

CHROMIUM = "/usr/bin/chromium"
CHROMIUM_ARGS = ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                 "--disable-background-networking", "--disable-component-update", "--disable-sync"]
VIEWPORT = {"width": 1400, "height": 900}
STEPS = 40
MOVE_PAUSE_S = 0.03
DRAG_FRACTION = 0.25
FAMILY_WAIT_S = 90
ANSWER_WAIT_S = 60

# The page's marks and the bench's own (pointer up), as startTime in ms from navigation start.
MARKS_JS = """() => Object.fromEntries(["slider-input", "plots-drawn", "family-requested", "family-arrived",
  "family-coarse-arrived", "family-full-arrived", "exact-requested", "exact-drawn", "bench-release"].map((n) => [n, performance.getEntriesByName(n).map((e) => e.startTime)]))"""
RELEASE_MARK_JS = "document.addEventListener('pointerup', () => performance.mark('bench-release'), true);"


def scenes() -> list[dict]:
    if str(ROOT) not in sys.path:
        sys.path.insert(0, str(ROOT))
    from server.lessons.scenes import scene_documents      # shared sliders and inheriting variants resolved
    loaded = list(scene_documents().values())
    return sorted(loaded, key=lambda s: s["order"])


def free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return sock.getsockname()[1]


def start_app(data_dir: str) -> tuple[subprocess.Popen, str]:
    port = free_port()
    server = subprocess.Popen(
        [sys.executable, "-m", "uvicorn", "server.api.app:app", "--host", "127.0.0.1", "--port", str(port)],
        cwd=ROOT, env=os.environ | {"MDL_DATA_DIR": data_dir}, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    url = f"http://127.0.0.1:{port}"
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline:
        try:
            if httpx.get(f"{url}/", timeout=1).status_code == 200:
                return server, url
        except httpx.TransportError:
            time.sleep(0.1)
    server.kill()
    raise SystemExit("the app did not start")


def after(times: list[float], t: float) -> float | None:
    """The first of times at or after t."""
    later = [x for x in times if x >= t]
    return min(later) if later else None


def percentile(values: list[float], q: float) -> float:
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, round(q * (len(ordered) - 1)))]


def drag(page, slider_id: str, direction: int, hold_family: bool) -> dict:
    """Grab the slider, wait for its family (unless held), drag, release, wait for the exact answer drawn;
    returns the page's marks."""
    selector = f"#slider-{slider_id}"
    page.locator(selector).scroll_into_view_if_needed()
    box = page.locator(selector).bounding_box()
    value, low, high = page.eval_on_selector(selector, "e => [e.value, e.min, e.max].map(Number)")
    x = lambda f: box["x"] + 8 + (box["width"] - 16) * f
    y = box["y"] + box["height"] / 2
    start = (value - low) / (high - low)
    if not 0 <= start + direction * DRAG_FRACTION <= 1:
        direction = -direction
    page.mouse.move(x(start), y)
    page.mouse.down()
    family = None
    if not hold_family:
        try:
            page.wait_for_function("() => performance.getEntriesByName('family-arrived').length > 0",
                                   timeout=FAMILY_WAIT_S * 1000)
            family = True
        except Exception:            # noqa: BLE001 - no family in time: the drag is measured as it comes
            family = False
    for k in range(1, STEPS + 1):
        page.mouse.move(x(start + direction * DRAG_FRACTION * k / STEPS), y)
        page.wait_for_timeout(MOVE_PAUSE_S * 1000)
    drawn = len(page.evaluate(MARKS_JS)["exact-drawn"])
    page.mouse.up()
    if hold_family:                  # the last value was asked on its input: its answer may be drawn already
        page.wait_for_load_state("networkidle")
        page.wait_for_timeout(500)
    else:
        page.wait_for_function("n => performance.getEntriesByName('exact-drawn').length > n", arg=drawn,
                               timeout=ANSWER_WAIT_S * 1000)
    if family:                       # the full family may come after the drag: its arrival is measured still
        try:
            page.wait_for_function("() => performance.getEntriesByName('family-full-arrived').length > 0",
                                   timeout=FAMILY_WAIT_S * 1000)
        except Exception:            # noqa: BLE001 - it never came: the table says so
            pass
    marks = page.evaluate(MARKS_JS)
    marks["family_in_time"] = family
    return marks


def measure_scene(browser, url: str, scene: dict) -> dict:
    variant = next(v for v in scene["variants"] if v.get("sliders"))
    slider = variant["sliders"][0]
    address = f"{url}/scenes/{scene['id']}?lang=en&variant={variant['id']}"
    row = {"scene": f"{scene['id']} ({variant['id']})", "endpoint": scene.get("endpoint", "kinematics"), "slider": slider["id"]}

    for held in (True, False):       # without the family first, so the family's drag meets no cached answers
        context = browser.new_context(viewport=VIEWPORT)
        context.add_init_script(RELEASE_MARK_JS)
        page = context.new_page()
        problems = []
        page.on("pageerror", lambda error: problems.append(str(error)))
        held_routes = []
        if not held:
            page.on("request", lambda r: "/api/v1/family?" in r.url and "family_body" not in row
                    and row.__setitem__("family_body", json.loads(r.post_data)))
        if held:
            page.route("**/api/v1/family?*", lambda route: held_routes.append(route))
        page.goto(address)
        page.wait_for_function("() => performance.getEntriesByName('exact-drawn').length > 0",
                               timeout=ANSWER_WAIT_S * 1000)
        page.wait_for_load_state("networkidle")
        first_visit = page.evaluate("() => performance.getEntriesByName('exact-drawn')[0].startTime")
        graphs = page.evaluate("() => [...document.querySelectorAll('.graph')].filter((g) => g.data"
                               " && g.getBoundingClientRect().top < innerHeight).length")
        marks = drag(page, slider["id"], +1 if held else -1, held)
        for route in held_routes:
            route.abort()
        context.close()
        release = marks["bench-release"][-1]
        inputs = [t for t in marks["slider-input"] if t < release]
        if held:             # the scene's first visit: nothing of it computed or cached before
            row["first_visit_ms"] = first_visit
            row["graphs_in_view"] = graphs
            row["old_input_ms"] = [after(marks["exact-drawn"], t) - t for t in inputs if after(marks["exact-drawn"], t)]
            row["old_release_ms"] = max(0.0, marks["exact-drawn"][-1] - release)
            continue
        row["problems"] = problems
        requested, arrived = marks["family-requested"], marks["family-arrived"]
        for stage in ("coarse", "full"):
            stage_arrived = marks[f"family-{stage}-arrived"]
            row[f"{stage}_ms"] = stage_arrived[0] - requested[0] if requested and stage_arrived else None
        covered = [t for t in inputs if arrived and t >= arrived[0]]
        row["inputs"] = len(covered)
        row["input_ms"] = [after(marks["plots-drawn"], t) - t for t in covered if after(marks["plots-drawn"], t)]
        row["release_ms"] = after(marks["exact-drawn"], release) - release
    return row


def nudged(body: dict, k: int) -> dict:
    """The family body with its first fixed (not varied) non-zero float × (1 + 1e-7·k): a family that neither
    the response cache nor the server's memo of members holds, the same work as the scene's own."""
    body = json.loads(json.dumps(body))
    varied = {item["path"] for item in body["vary"]}

    def nudge(node: dict, prefix: str) -> bool:
        for key, value in node.items():
            if isinstance(value, float) and value and f"{prefix}{key}" not in varied:
                node[key] = value * (1 + 1e-7 * k)
                return True
            if isinstance(value, dict) and nudge(value, f"{prefix}{key}."):
                return True
        return False

    nudge(body["request"], "")
    return body


def stage_orders(url: str, row: dict, k: int) -> dict:
    """Family arrival in ms after the grab for three ways of asking (each on a fresh family): coarse, then full
    when the coarse has arrived (the page's way); both at once; the full one alone (the page before stages)."""
    coarse = row["family_body"]
    address = f"{url}/api/v1/family?lang=en"

    def ask(body: dict, started: float) -> float:
        reply = httpx.post(address, json=body, timeout=FAMILY_WAIT_S)
        reply.raise_for_status()
        return (time.perf_counter() - started) * 1000

    full = lambda body: {key: value for key, value in body.items() if key != "stage"}
    body = nudged(coarse, 3 * k)
    started = time.perf_counter()
    sequential = (ask(body, started), ask(full(body), started))
    body = nudged(coarse, 3 * k + 1)
    started = time.perf_counter()
    with ThreadPoolExecutor(2) as pool:
        together = tuple(f.result() for f in [pool.submit(ask, body, started), pool.submit(ask, full(body), started)])
    alone = ask(full(nudged(coarse, 3 * k + 2)), time.perf_counter())
    return {"sequential": sequential, "together": together, "alone": alone}


def stage_table(rows: list[dict]) -> str:
    lines = ["| scene | coarse, then full: coarse / full, ms | both at once: coarse / full, ms | full alone, ms |",
             "|---|---:|---:|---:|"]
    for r in rows:
        if "stages" in r:
            (c1, f1), (c2, f2), alone = r["stages"]["sequential"], r["stages"]["together"], r["stages"]["alone"]
            lines.append(f"| {r['scene']} | {c1:.0f} / {f1:.0f} | {c2:.0f} / {f2:.0f} | {alone:.0f} |")
    return "\n".join(lines)


def summary(values: list[float]) -> str:
    if not values:
        return "—"
    return f"{statistics.median(values):.1f} / {percentile(values, 0.95):.1f} / {max(values):.1f}"


def table(rows: list[dict]) -> str:
    lines = [
        "| scene | endpoint | slider | plots in view | first visit, ms | coarse family after grab, ms "
        "| full family after grab, ms | input → preview drawn p50 / p95 / max, ms (inputs) | release → exact drawn, ms "
        "| without family: input → next answer drawn p50 / p95 / max, ms | without family: release → exact drawn, ms |",
        "|---|---|---|---:|---:|---:|---:|---|---:|---|---:|"]
    for r in rows:
        coarse, full = (f"{r[k]:.0f}" if r[k] is not None else "—" for k in ("coarse_ms", "full_ms"))
        drawn = f"{summary(r['input_ms'])} ({len(r['input_ms'])}/{r['inputs']})"
        lines.append(f"| {r['scene']} | {r['endpoint']} | {r['slider']} | {r['graphs_in_view']} | {r['first_visit_ms']:.0f} "
                     f"| {coarse} | {full} | {drawn} | {r['release_ms']:.0f} | {summary(r['old_input_ms'])} | {r['old_release_ms']:.0f} |")
    return "\n".join(lines)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--scenes", help="comma-separated scene file names (content/scenes/<name>.json); all by default")
    parser.add_argument("--out", type=Path, default=ROOT / "bench" / "results" / "browser.md")
    parser.add_argument("--stages", action="store_true", help="also time the ways of asking for the two stages")
    args = parser.parse_args()
    chosen = scenes()
    if args.scenes:
        names = set(args.scenes.split(","))
        chosen = [s for s in chosen if s["id"].replace("-", "_") in names]

    from playwright.sync_api import sync_playwright

    rows = []
    with tempfile.TemporaryDirectory() as data_dir:
        server, url = start_app(data_dir)
        try:
            with sync_playwright() as playwright:
                browser = playwright.chromium.launch(executable_path=CHROMIUM, headless=True, args=CHROMIUM_ARGS)
                for scene in chosen:
                    rows.append(measure_scene(browser, url, scene))
                    print(table(rows[-1:]).splitlines()[-1], flush=True)
                browser.close()
            for k, row in enumerate(rows):
                if args.stages and row.get("family_body", {}).get("stage") == "coarse":
                    row["stages"] = stage_orders(url, row, k)
                    print(stage_table([row]).splitlines()[-1], flush=True)
        finally:
            server.terminate()
            server.wait(timeout=10)

    problems = [f"{r['scene']}: {p}" for r in rows for p in r["problems"]]
    report = "\n".join([
        "# Browser: dragging a slider drawn from its family",
        "",
        f"`python bench/browser.py` on {tree_label(ROOT)}, {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}; "
        f"{platform.processor() or platform.machine()}, {os.cpu_count()} CPUs; Chromium headless at "
        f"{VIEWPORT['width']} × {VIEWPORT['height']}; one uvicorn worker on loopback; a drag of {STEPS} moves "
        f"{MOVE_PAUSE_S * 1000:.0f} ms apart over {DRAG_FRACTION:.0%} of the slider's track.",
        "",
        "Times from the page's performance marks. *first visit*: navigation start → the first exact answer drawn "
        "(a fresh browser context). *coarse / full family after grab*: pointer down → the coarse family arrived "
        "(\"stage\": \"coarse\"; — where the server has no stages), → the full one. *input → preview drawn*: "
        "a slider `input` event once the family is there → every plot in view redrawn from the family "
        "(Plotly.react's promise) and the drawing updated; inputs counted are those that had a preview drawn. "
        "*release → exact drawn*: pointer up → the exact answer drawn in every plot in view. The last two columns are "
        "the same drag on a page whose family request is held (the page as before families): an input is followed "
        "by the next exact answer drawn.",
        "",
        table(rows),
        "",
        *(["Asking for the two stages (--stages; over HTTP, no browser, each on a family nobody asked before): "
           "times after the first request was sent.", "", stage_table(rows), ""] if args.stages else []),
        *(["Page errors: " + "; ".join(problems), ""] if problems else []),
    ])
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(report, encoding="utf-8")
    print(f"\nwritten to {args.out}")


if __name__ == "__main__":
    main()
