"""Browser tests: the app served by uvicorn on a free port, Debian's Chromium driven by Playwright.

Playwright cannot download its own browsers here; it launches /usr/bin/chromium (tests/run.sh installs
it). Screenshots go to test-artifacts/ for a person to look at.
"""
from __future__ import annotations

import json
import os
import socket
import subprocess
import sys
import time
from pathlib import Path

import httpx
import pytest

from server.lessons.scenes import scene_documents

REPO = Path(__file__).resolve().parents[2]
ARTIFACTS = REPO / "test-artifacts"
CHROMIUM = Path("/usr/bin/chromium")
# --process-per-site: the pages of the app's one origin share a renderer process (with the keeper page of
# keep_a_renderer) instead of one process per new page: about 7 % less Chromium CPU over the page-heavy modules
# (test_notation and test_scene_words, run in turn with and without it)
CHROMIUM_ARGS = ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run", "--process-per-site",
                 "--disable-background-networking", "--disable-component-update", "--disable-sync"]
START_SECONDS = 240          # the app's start: a guard against a hang; a loaded CI machine imports slowly
WAIT_MS = 120_000            # Playwright's waits (its own default is 30 s): guards, the tests wait for conditions
# every text on screen: the page's words (with what <sub> holds) and the text of every SVG (drawings, plots)
SCREEN_TEXT = """() => document.body.innerText + "\\n" +
  [...document.querySelectorAll("svg text")].map((node) => node.textContent).join("\\n")"""


def read_scene(name: str) -> dict:
    """A scene of content/scenes as the app reads it (shared sliders and inheriting variants resolved),
    e.g. read_scene("transfer_functions")."""
    return scene_documents()[name]


SCENE = read_scene("transfer_functions")


def interface_texts(lang: str) -> dict[str, str]:
    return json.loads((REPO / "content" / "i18n" / f"{lang}.json").read_text(encoding="utf-8"))


def shown(text: str) -> str:
    """An interface text as the page's innerText reads it: its notation markup gone ("M_с0" → "Mс0"), the
    subscripts being <sub> elements (web/static/js/common/view/notation.js)."""
    from server.lessons.markup import notation_parts
    return "".join(run for run, _ in notation_parts(text))


def plot_text(text: str) -> str:
    """An interface text as the page gives it to Plotly ("M_c0" → "M<sub>c0</sub>"; notation.js plotText)."""
    from server.api.routers.pages import notation
    return str(notation(text))


FAMILY_ENDS = ("family-full-arrived", "family-unrefined", "family-failed", "family-given-up")


def families_arrived(page) -> None:
    """Every slider family the page asked for has ended: arrived in full, answered coarse by a busy server
    (unrefined), failed, or given up by a later grab (family_preview.js marks each): a family is a heavy
    computation, and a client with two of them in flight is answered 429 (retried, but said on the console)."""
    ended = " + ".join(f"performance.getEntriesByName('{name}').length" for name in FAMILY_ENDS)
    page.wait_for_function(f"() => {ended} >= performance.getEntriesByName('family-requested').length")


def drag_slider(page, selector: str, fraction: float) -> None:
    """Press the mouse on the range input's thumb and drag it to `fraction` of the track."""
    page.locator(selector).scroll_into_view_if_needed()
    box = page.locator(selector).bounding_box()
    value, low, high = page.eval_on_selector(selector, "e => [e.value, e.min, e.max].map(Number)")
    x = lambda f: box["x"] + 8 + (box["width"] - 16) * f      # the thumb's centre stays 8 px inside the track
    y = box["y"] + box["height"] / 2
    page.mouse.move(x((value - low) / (high - low)), y)
    page.mouse.down()
    page.mouse.move(x(fraction), y, steps=5)
    page.mouse.up()


def screenshot(page, name: str) -> None:
    page.screenshot(path=ARTIFACTS / f"{name}.png", full_page=True)


def _free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return sock.getsockname()[1]


@pytest.fixture(scope="session")
def app_url(tmp_path_factory):
    """Base address of the app, started with uvicorn in a subprocess for the whole session; its
    assignments database lives in a temporary directory."""
    port = _free_port()
    # the heavy lanes at the server's own priority (the other test processes keep the CPUs busy, and a family at
    # nice 15 would wait for idle CPU that never comes) and a family's wall-clock bound (5 s) raised: on a
    # loaded machine a family cut short would fail what the tests compare with its contract, which holds for
    # the complete family
    env = os.environ | {"MDL_DATA_DIR": str(tmp_path_factory.mktemp("data")), "MDL_FAMILY_BUDGET_S": "60",
                        "MDL_HEAVY_NICE": "0", "MDL_SHARED_CACHE": str(suite_families(tmp_path_factory)),
                        "MDL_REGISTRATIONS_PER_HOUR": "100000"}    # every browser test registers from 127.0.0.1
    ARTIFACTS.mkdir(exist_ok=True)
    url = f"http://127.0.0.1:{port}"
    log = server_log(url).open("w", encoding="utf-8")     # its access log and errors, for a failure to quote
    server = subprocess.Popen(
        [sys.executable, "-m", "uvicorn", "server.api.app:app", "--host", "127.0.0.1", "--port", str(port)],
        cwd=REPO, env=env, stdout=log, stderr=subprocess.STDOUT)
    deadline = time.monotonic() + START_SECONDS
    while True:
        try:
            if httpx.get(f"{url}/", timeout=1).status_code == 200:
                break
        except httpx.TransportError:
            pass
        if server.poll() is not None or time.monotonic() > deadline:
            server.kill()
            pytest.fail("the app did not start")
        time.sleep(0.1)
    yield url
    server.terminate()
    server.wait(timeout=10)
    log.close()


def suite_families(tmp_path_factory) -> Path:
    """The slider families' file that the app servers of the test processes share, as two app servers on one
    host may (server/runtime/shared_cache.py, MDL_SHARED_CACHE): the pages of every process grab the same
    sliders at the same defaults, and a family one server has computed is not computed again by the others.
    In the run's temporary folder (that of all the processes under xdist), which pytest removes in time."""
    base = tmp_path_factory.getbasetemp()
    return (base.parent if os.environ.get("PYTEST_XDIST_WORKER") else base) / "families.sqlite"


def server_log(app_url: str) -> Path:
    """The file the app at `app_url` writes its log to (uvicorn's access lines and any traceback)."""
    return ARTIFACTS / f"server-{app_url.rsplit(':', 1)[1]}.log"


def server_log_tail(app_url: str, lines: int = 40) -> str:
    """The last `lines` lines of that log, for a failure message: what the server answered while a page waited."""
    return "\n".join(server_log(app_url).read_text(encoding="utf-8", errors="replace").splitlines()[-lines:])


@pytest.fixture(scope="session")
def chromium():
    if not CHROMIUM.exists():
        pytest.skip("Chromium is not installed at /usr/bin/chromium (tests/run.sh installs it)")
    from playwright.sync_api import sync_playwright
    with sync_playwright() as playwright:
        browser = playwright.chromium.launch(executable_path=str(CHROMIUM), headless=True, args=CHROMIUM_ARGS)
        yield PatientBrowser(browser)
        browser.close()


class PatientBrowser:
    """The launched browser, whose every new context waits up to WAIT_MS for a condition or a navigation
    (Playwright's 30 s default fails a correct page on a loaded machine running the suite in parallel)."""

    def __init__(self, browser):
        self._browser = browser

    def new_context(self, **options):
        context = self._browser.new_context(**options)
        context.set_default_timeout(WAIT_MS)
        context.set_default_navigation_timeout(WAIT_MS)
        return context

    def __getattr__(self, name):
        return getattr(self._browser, name)


@pytest.fixture(scope="session")
def desktop(chromium, app_url):
    """One desktop browser context (1400 × 900) per test process, whose HTTP cache every test's page shares:
    plotly.js and the page modules, served on versioned immutable URLs, are fetched and compiled once, as a
    student's browser does after the first page (a fresh context per test spent about a third of the browser's
    CPU on a page load fetching and compiling them again). Nothing else is shared: browser_page leaves no page,
    cookie or permission behind (the app keeps its state in the address, not in the browser's storage)."""
    context = chromium.new_context(base_url=app_url, viewport={"width": 1400, "height": 900})
    keep_a_renderer(context)
    yield context
    context.close()


def keep_a_renderer(context) -> None:
    """Keep a page of the app's origin open in a shared context for the whole session (the app's icon, no
    script): Chromium gives the tests' new pages of the same origin its renderer process instead of starting one
    for each, which cost about 0.7 CPU-s per page in its first second (a lesson page 1.5 CPU-s against 2.2 in
    all, measured on this machine). _page_of closes every page of a test but this one."""
    context.keeper = context.new_page()
    context.keeper.goto("/favicon.ico")


@pytest.fixture
def browser_page(desktop):
    """A fresh page at 1400 × 900 whose console errors and uncaught exceptions are kept in page.problems."""
    yield from _page_of(desktop)


def _page_of(context):
    """A new page of a shared context, its problems kept; then the test's pages (any it opened too), cookies and
    permissions removed from the context."""
    ARTIFACTS.mkdir(exist_ok=True)
    page = context.new_page()
    page.problems = []
    page.on("console", lambda message: message.type == "error" and page.problems.append(message.text))
    page.on("pageerror", lambda error: page.problems.append(error.stack or str(error)))
    yield page
    for opened in context.pages:
        if opened is not getattr(context, "keeper", None):
            opened.close()
    context.clear_cookies()
    context.clear_permissions()


PHONE = {"width": 390, "height": 844}


@pytest.fixture(scope="session")
def phone_context(chromium, app_url):
    """The phone-sized context of a test process, shared as desktop is; CSP bypassed only so that a test may
    inject axe-core (the app never serves it)."""
    context = chromium.new_context(base_url=app_url, viewport=PHONE, bypass_csp=True, device_scale_factor=1)
    keep_a_renderer(context)
    yield context
    context.close()


@pytest.fixture
def phone(phone_context):
    """A page at phone size whose problems are kept as browser_page's."""
    yield from _page_of(phone_context)
