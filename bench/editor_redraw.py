"""How fast the mechanism editor (/editor) redraws after a length is edited (target: 100 ms) and while a joint is
dragged (target: a frame, 16 ms, once the answer is there; the exact answer after release within 100 ms), in parts.

    python3 bench/editor_redraw.py [--edits 40] [--out bench/results/editor_redraw.md]

Starts the app (uvicorn, a free port) and Debian's Chromium; loads the shaping machine preset; then
1. server: the table the page asks per edit (361 angles, positions and analogs of every joint, link and slide,
   the structure), computed in-process (median of 50) and as an HTTP round trip (p50, p95);
2. browser, edit → drawn: a length slider moved (an `input` event), until the page has drawn the answer;
3. browser, one frame: the crank angle slider moved (drawing, plot cursor, groups apart), synchronous time;
4. browser, a joint dragged with the mouse (the ram's slider E along its guide, real pointer events a frame
   apart): each frame drawn from the dragged geometry, each answer drawn (the page's own performance measures
   "editor-drag-preview-drawn" and "editor-drag-answer-drawn", view/drag.js); a pointer moved and the answer
   to it drawn (HTTP included); the pointer let go and the exact answer shown (the table, the plans' question
   and the list, as after any edit).
Prints a Markdown table and writes it to --out.
"""
from __future__ import annotations

import argparse
import json
import math
import os
import platform
import socket
import subprocess
import sys
import time
from pathlib import Path

import httpx
import numpy as np

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))

from server.core.mechanisms.general import compute_general  # noqa: E402
from server.core.structure.presets import presets  # noqa: E402

TABLE = ["structure", "joints", "joints_d1", "joints_d2", "angles", "angles_d1", "angles_d2", "slides", "slides_d1",
         "slides_d2"]       # web/static/js/editor/model/table.js TABLE_OUTPUTS

EDIT = """(value) => new Promise((resolve) => {
    const stage = document.querySelector("#editor-drawing");
    const answers = Number(stage.dataset.answers);
    const range = document.querySelector('[data-group="1"] input[type=range]');
    const start = performance.now();
    range.value = String(value);
    range.dispatchEvent(new Event("input"));
    const check = () => (Number(stage.dataset.answers) > answers ? resolve(performance.now() - start)
                                                                    : requestAnimationFrame(check));
    check(); })"""
FRAME = """(k) => { const phi = document.querySelector("#editor-phi"); const start = performance.now();
    phi.value = String(k); phi.dispatchEvent(new Event("input")); return performance.now() - start; }"""
CLIENT = """([x, y]) => { const svg = document.querySelector("#editor-drawing svg");
    const [x0, y0, k] = svg.dataset.view.split(" ").map(Number);
    const p = svg.createSVGPoint(); p.x = (x - x0) * k; p.y = (y0 - y) * k;
    const q = p.matrixTransform(svg.getScreenCTM()); return [q.x, q.y]; }"""
WATCH = """() => { window.benchMoves = []; window.benchUp = null; window.benchShown = null;
    window.addEventListener("pointermove", () => window.benchMoves.push(performance.now()), true);
    window.addEventListener("pointerup", () => { window.benchUp = performance.now(); }, true);
    const stage = document.querySelector("#editor-drawing");            // the page's answers, as they are shown
    new MutationObserver(() => { if (stage.dataset.state === "ready") window.benchShown = performance.now(); })
      .observe(stage, { attributes: true, attributeFilter: ["data-answers", "data-state"] }); }"""
LINKAGE = """() => { const m = new URLSearchParams(location.search).get("m").replace(/-/g, "+").replace(/_/g, "/");
    return JSON.parse(new TextDecoder().decode(Uint8Array.from(atob(m), (c) => c.charCodeAt(0)))); }"""
MEASURES = """(name) => performance.getEntriesByName(name).map((e) => e.duration)"""
ANSWERED = """(n) => performance.getEntriesByName("editor-drag-answer-drawn").length > n"""
SHOWN = """(n) => { const stage = document.querySelector("#editor-drawing");
    return Number(stage.dataset.answers) > n && stage.dataset.state === "ready"; }"""


def percentiles(values) -> tuple[float, float]:
    return float(np.percentile(values, 50)), float(np.percentile(values, 95))


def free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return sock.getsockname()[1]


def drag_joint(page, moves: int) -> dict[str, list[float]]:
    """The shaping machine's ram slider E dragged along its guide with the mouse, back and forth by ±2 cm: first
    `moves` moves a frame apart (every frame and answer drawn timed by the page), then `moves` moves each waited
    for until its answer is drawn, then `moves` drags of 1 cm let go, each until the exact answer is shown."""
    page.evaluate(WATCH)
    linkage = page.evaluate(LINKAGE)
    slider = linkage["groups"][1]["inner"]

    def where() -> tuple[float, float]:
        """The slider's drawn place in metres."""
        x, y = map(float, (page.get_attribute(f'#editor-drawing [data-joint="{slider}"]', a) for a in ("cx", "cy")))
        x0, y0, k = map(float, page.get_attribute("#editor-drawing svg", "data-view").split())
        return x0 + x / k, y0 - y / k

    start = where()
    at = lambda dx: page.evaluate(CLIENT, [start[0] + dx, start[1]])
    offsets = [0.02 * math.sin(math.pi * i / 12) for i in range(moves)]
    page.mouse.move(*at(0))
    page.mouse.down()
    for dx in offsets:
        page.mouse.move(*at(dx))
        page.wait_for_timeout(16)
    latency = []
    for dx in offsets:
        answered = len(page.evaluate(MEASURES, "editor-drag-answer-drawn"))
        page.mouse.move(*at(dx + 0.001))
        page.wait_for_function(ANSWERED, arg=answered)
        latency.append(page.evaluate("() => performance.getEntriesByName('editor-drag-answer-drawn').at(-1).startTime"
                                     " + performance.getEntriesByName('editor-drag-answer-drawn').at(-1).duration"
                                     " - window.benchMoves.at(-1)"))
    page.mouse.up()
    release = []
    for k in range(moves):
        page.wait_for_function("() => document.querySelector('#editor-drawing').dataset.state === 'ready'")
        start = where()
        page.mouse.move(*at(0))
        page.mouse.down()
        answered = len(page.evaluate(MEASURES, "editor-drag-answer-drawn"))
        page.mouse.move(*at(0.01 if k % 2 else -0.01))          # 1 cm back and forth
        page.wait_for_function(ANSWERED, arg=answered)
        shown = int(page.get_attribute("#editor-drawing", "data-answers"))
        page.mouse.up()
        page.wait_for_function(SHOWN, arg=shown)
        release.append(page.evaluate("() => window.benchShown - window.benchUp"))
    return {"preview": page.evaluate(MEASURES, "editor-drag-preview-drawn"),
            "answer": page.evaluate(MEASURES, "editor-drag-answer-drawn"), "latency": latency, "release": release}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--edits", type=int, default=40)
    parser.add_argument("--out", type=Path, default=REPO / "bench" / "results" / "editor_redraw.md")
    args = parser.parse_args()
    linkage = presets()["shaping_machine"]["linkage"]

    compute_general(linkage, TABLE, n=361)
    core = []
    for _ in range(50):
        start = time.perf_counter()
        compute_general(linkage, TABLE, n=361)
        core.append(1000 * (time.perf_counter() - start))

    port = free_port()
    server = subprocess.Popen([sys.executable, "-m", "uvicorn", "server.api.app:app", "--port", str(port)], cwd=REPO,
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    url = f"http://127.0.0.1:{port}"
    try:
        for _ in range(300):
            try:
                httpx.get(url, timeout=1)
                break
            except httpx.TransportError:
                time.sleep(0.2)
        body = {"mechanism": "general", "linkage": linkage, "n": 361, "outputs": TABLE}
        trips = []
        with httpx.Client(base_url=url) as client:
            for k in range(args.edits):
                body["linkage"]["groups"][1]["length"] = 0.15 + 1e-4 * k      # a new question each time
                start = time.perf_counter()
                client.post("/api/v1/kinematics?lang=ru", json=body).raise_for_status()
                trips.append(1000 * (time.perf_counter() - start))

        from playwright.sync_api import sync_playwright
        with sync_playwright() as playwright:
            browser = playwright.chromium.launch(executable_path="/usr/bin/chromium", headless=True,
                                                 args=["--no-sandbox", "--disable-gpu"])
            page = browser.new_page(viewport={"width": 1400, "height": 900})
            page.goto(f"{url}/editor?lang=ru")
            page.select_option("#editor-preset", "shaping_machine")
            page.wait_for_function("() => document.querySelector('#editor-drawing').dataset.state === 'ready'")
            edits = [page.evaluate(EDIT, 0.15 + 2e-4 * (k + 1)) for k in range(args.edits)]
            frames = [page.evaluate(FRAME, k % 360) for k in range(args.edits)]
            page.locator("#editor-drawing svg").scroll_into_view_if_needed()
            dragged = drag_joint(page, args.edits)
            browser.close()
    finally:
        server.terminate()
        server.wait(timeout=10)

    load = os.getloadavg()[0]
    rows = [("server: table computed in-process (median of 50)", float(np.median(core)), None),
            ("server: table over HTTP", *percentiles(trips)),
            ("browser: length edited → drawn (HTTP included)", *percentiles(edits)),
            ("browser: one frame at a new crank angle (drawing, plot cursor, groups apart)", *percentiles(frames)),
            ("browser, a joint dragged: a frame drawn from the dragged geometry", *percentiles(dragged["preview"])),
            ("browser, a joint dragged: an answer drawn (**target: 16 ms**)", *percentiles(dragged["answer"])),
            ("browser, a joint dragged: pointer moved → its answer drawn (HTTP included)", *percentiles(dragged["latency"])),
            ("browser, a joint dragged: let go → the exact answer shown (**target: 100 ms**)",
             *percentiles(dragged["release"]))]
    text = "\n".join([
        "# Mechanism editor: redraw after an edit",
        "",
        f"`python3 bench/editor_redraw.py --edits {args.edits}`; shaping machine (crank + RPR + RRP), 361 angles; "
        f"{platform.node()}, {os.cpu_count()} CPUs, load average {load:.1f} at the end of the run.",
        "",
        "| part | p50 (ms) | p95 (ms) |",
        "|---|---:|---:|",
        *[f"| {name} | {p50:.1f} | {'—' if p95 is None else f'{p95:.1f}'} |" for name, p50, p95 in rows],
        ""])
    print(text)
    args.out.write_text(text, encoding="utf-8")


if __name__ == "__main__":
    main()
