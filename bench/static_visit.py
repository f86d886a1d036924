"""First and repeat visit of a scene in Chromium: bytes on the wire, requests, time to the first answer drawn.

For each source tree given (e.g. the commit before a change and the change, side by side) the app is started
with uvicorn on a free port, and for each scene a fresh browser context visits the scene page twice:

- first visit (empty cache): bytes transferred (the Network domain's encodedDataLength: headers and the
  compressed body as they crossed the wire), split into the page + static files and the API answers, the
  number of requests, and the time from navigation start to the first plot drawn (a Plotly SVG on the page,
  `performance.now()` when it appears);
- repeat visit (same context, a new navigation to the same page): the same counts. Files served
  `immutable` are not asked for again; files without caching headers may be revalidated (304) or reused
  by the browser's heuristic freshness.

    python3 bench/static_visit.py --tree /work/main --tree . [--scene transfer-functions ...] [--runs 3]

Prints a Markdown table (medians over the runs). Loopback, so times are the server's and the browser's work.
"""
from __future__ import annotations

import argparse
import os
import socket
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import httpx
from playwright.sync_api import sync_playwright

CHROMIUM = "/usr/bin/chromium"
CHROMIUM_ARGS = ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                 "--disable-background-networking", "--disable-component-update", "--disable-sync"]
SCENES = ["transfer-functions", "equation-of-motion", "forces-friction", "flywheel", "elastic-transmission"]
DRAWN = "() => document.querySelector('.graph .main-svg') ? performance.now() : false"


def free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return sock.getsockname()[1]


def start_server(tree: Path) -> tuple[subprocess.Popen, str]:
    port = free_port()
    env = os.environ | {"MDL_DATA_DIR": tempfile.mkdtemp(prefix="mdl-visit-")}
    server = subprocess.Popen([sys.executable, "-m", "uvicorn", "server.api.app:app", "--host", "127.0.0.1",
                               "--port", str(port)], cwd=tree, env=env, stdout=subprocess.DEVNULL,
                              stderr=subprocess.DEVNULL)
    url = f"http://127.0.0.1:{port}"
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline:
        try:
            if httpx.get(url + "/", timeout=1).status_code == 200:
                return server, url
        except httpx.TransportError:
            time.sleep(0.2)
    server.kill()
    raise RuntimeError(f"the app in {tree} did not start")


def visit(page, session, url: str) -> dict:
    """One navigation: bytes and requests on the network by kind (requests served from the browser's cache
    apart, revalidations (304) counted), and the time to the first plot drawn (ms)."""
    kinds, cached = {}, set()
    sizes = {"page+static": 0, "api": 0}
    counts = {"page+static": 0, "api": 0, "cached": 0, "304": 0}

    def on_request(event):
        kinds[event["requestId"]] = "api" if "/api/" in event["request"]["url"] else "page+static"

    def on_response(event):
        if event["response"].get("fromDiskCache") or event["response"].get("fromPrefetchCache"):
            cached.add(event["requestId"])
        elif event["response"]["status"] == 304:
            counts["304"] += 1

    def on_finished(event):
        if event["requestId"] in cached:
            counts["cached"] += 1
            return
        kind = kinds.get(event["requestId"], "page+static")
        sizes[kind] += event["encodedDataLength"]
        counts[kind] += 1

    handlers = {"Network.requestWillBeSent": on_request, "Network.responseReceived": on_response,
                "Network.requestServedFromCache": lambda event: cached.add(event["requestId"]),
                "Network.loadingFinished": on_finished}
    for name, handler in handlers.items():
        session.on(name, handler)
    page.goto(url)
    drawn = page.wait_for_function(DRAWN, timeout=120_000).json_value()
    page.wait_for_load_state("networkidle")
    for name, handler in handlers.items():
        session.remove_listener(name, handler)
    return {"drawn_ms": drawn, "kB": {k: v / 1000 for k, v in sizes.items()}, "requests": counts}


def measure(browser, base: str, scene: str) -> tuple[dict, dict]:
    context = browser.new_context(viewport={"width": 1400, "height": 900})
    page = context.new_page()
    session = context.new_cdp_session(page)
    session.send("Network.enable")
    first = visit(page, session, f"{base}/scenes/{scene}?lang=en")
    page.goto("about:blank")
    repeat = visit(page, session, f"{base}/scenes/{scene}?lang=en")
    context.close()
    return first, repeat


def median_of(runs: list[dict], *path) -> float:
    values = []
    for run in runs:
        value = run
        for key in path:
            value = value[key]
        values.append(value)
    return statistics.median(values)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--tree", action="append", required=True, help="a source tree to serve (repeatable)")
    parser.add_argument("--scene", action="append", help=f"scene ids (default: {' '.join(SCENES)})")
    parser.add_argument("--runs", type=int, default=3)
    args = parser.parse_args()
    print("| tree | scene | first: kB page+static / api (network requests) | first: drawn ms | repeat: kB "
          "page+static / api (network requests; from cache; 304) | repeat: drawn ms |")
    print("|---|---|---|---|---|---|")
    with sync_playwright() as playwright:
        browser = playwright.chromium.launch(executable_path=CHROMIUM, headless=True, args=CHROMIUM_ARGS)
        for tree in args.tree:
            server, base = start_server(Path(tree).resolve())
            try:
                for scene in args.scene or SCENES:
                    runs = [measure(browser, base, scene) for _ in range(args.runs)]
                    cells = []
                    for index in (0, 1):
                        visits = [run[index] for run in runs]
                        cells.append(f"{median_of(visits, 'kB', 'page+static'):.1f} / {median_of(visits, 'kB', 'api'):.1f}"
                                     f" ({median_of(visits, 'requests', 'page+static'):.0f}+"
                                     f"{median_of(visits, 'requests', 'api'):.0f}; "
                                     f"{median_of(visits, 'requests', 'cached'):.0f}; "
                                     f"{median_of(visits, 'requests', '304'):.0f})")
                        cells.append(f"{median_of(visits, 'drawn_ms'):.0f}")
                    print(f"| {tree} | {scene} | " + " | ".join(cells) + " |", flush=True)
            finally:
                server.terminate()
                server.wait(10)
        browser.close()


if __name__ == "__main__":
    main()
