"""The benchmarks' stored figures (/bench-results/wp_*.html, plotly's HTML export) draw in a real browser
under the app's Content-Security-Policy (once 0 of them drew, their inline scripts blocked).

Each page's policy lets run exactly its own inline scripts, named by sha256 (no 'unsafe-inline', no
'unsafe-eval', plotly.js from this server); a page draws one SVG trace per trace of its figure, with no
console error, not even the favicon's 404.
"""
from __future__ import annotations

import httpx
import pytest

from server.api.security import CONTENT_SECURITY_POLICY
from conftest import REPO, screenshot

pytestmark = pytest.mark.browser

PAGES = sorted(p.name for p in (REPO / "bench" / "results").glob("wp_*.html"))
DRAW_TIMEOUT = 60_000          # ms; plotly.js (3.5 MB) parsed on a loaded machine
GRAPH = "document.querySelector('.plotly-graph-div')"


def script_sources(policy: str) -> list[str]:
    directives = {d.split()[0]: d.split()[1:] for d in policy.split(";") if d.strip()}
    return directives["script-src"]


def test_there_are_figures_to_draw():
    assert len(PAGES) >= 3, PAGES


@pytest.mark.parametrize("name", PAGES)
def test_a_stored_figure_draws_with_no_console_error(browser_page, name):
    page = browser_page
    response = page.goto(f"/bench-results/{name}")
    sources = script_sources(response.headers["content-security-policy"])
    assert sources[0] == "'self'" and len(sources) > 1
    assert all(s.startswith("'sha256-") for s in sources[1:]), sources      # no unsafe-*, no other origin
    page.wait_for_function(f"{GRAPH} && {GRAPH}._fullLayout && {GRAPH}.querySelectorAll('g.trace').length > 0",
                           timeout=DRAW_TIMEOUT)
    traces = page.evaluate(f"{GRAPH}.data.length")
    drawn = page.evaluate(f"[...{GRAPH}.querySelectorAll('g.trace path.js-line')].filter(p => "
                          f"(p.getAttribute('d') || '').length > 10).length")
    assert traces >= 2 and drawn == traces, (traces, drawn)
    screenshot(page, f"bench_{name.removesuffix('.html')}")
    assert page.problems == []


def test_other_files_keep_the_apps_policy(app_url):
    for path in ("/bench-results/work_precision.md", "/bench-results/wp_flywheel.png", "/"):
        assert httpx.get(app_url + path).headers["content-security-policy"] == CONTENT_SECURITY_POLICY
