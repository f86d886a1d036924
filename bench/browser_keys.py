"""Benchmark: a slider's keys in Chromium, key → visible change, per scene.

For every scene with sliders (its first variant with sliders, that variant's first slider that moves) on a fresh
page at 1400 × 900: the slider takes the focus (a grab: the page asks for its family) and, once the family has
arrived,
  held key        an arrow key is held down for KEYS keydowns (the keyboard's auto-repeat; each KEY_GAP_S after the
                  previous one's change is on the screen), then released: the page previews every keydown and
                  asks for the exact answer once, when the keys rest;
  single presses  PRESSES presses (down and up), each once the previous exact answer is drawn: the first key
                  after an exact answer, whose preview may leave the exact drawing's axes (a full redraw).
For each keydown, the time from it (a capturing listener, the first to see it) to the end of the first frame in
which a panel in view (a plot, a drawing, a table: .panel elements, and the linkage's drawing) changed: a
MutationObserver on them notes the first change after the keydown, and the end of its frame is the first task
after it (a MessageChannel message posted from the frame's own requestAnimationFrame callbacks, which run before
the frame's style, layout and paint; a change made outside a frame waits for the next frame). Also the held
key's release → the exact answer drawn (the page's exact-drawn mark; it includes the page's wait for the keys to
rest), and the exact answers the page asked for (exact-requested marks) while the key was held and per press.

The app is started as the README says (python -m server, one worker) from this tree or --tree on a free
loopback port and stopped at the end; Chromium is Debian's /usr/bin/chromium, headless. The machine's load
(os.getloadavg) is noted before and after, since the times depend on it. Prints a Markdown table and writes it
to bench/results/keyboard.md (--out; --no-write: print only).

    python bench/browser_keys.py [--scenes transfer_functions,flywheel] [--keys 10] [--tree PATH]
"""
from __future__ import annotations

import argparse
import os
import platform
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "bench"))
from trees import running_server, tree_label  # noqa: E402  (bench/ is not a package)

CHROMIUM = "/usr/bin/chromium"
CHROMIUM_ARGS = ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                 "--disable-background-networking", "--disable-component-update", "--disable-sync"]
VIEWPORT = {"width": 1400, "height": 900}
KEYS = 10                 # keydowns of a held key (the keyboard's auto-repeat)
PRESSES = 3               # single presses, each at rest (after the previous one's exact answer)
KEY_GAP_S = 0.08          # after a key's change is shown, before the next key (shorter than the page's rest)
FAMILY_WAIT_S = 120       # guards against a hang, not measures
CHANGE_WAIT_S = 20
ANSWER_WAIT_S = 60

# Installed before the page's scripts: the keydown times, and the end of the frame that first changed a panel after each.
MEASURE_JS = """(() => {
  const keys = window.__benchKeys = [];
  const keyUps = window.__benchKeyUps = [];
  const tasks = [];
  const channel = new MessageChannel();
  channel.port1.onmessage = () => tasks.shift()();
  const afterThisTask = (then) => { tasks.push(then); channel.port2.postMessage(null); };
  const frame = window.requestAnimationFrame.bind(window);
  let inFrame = false;                 // the page's requestAnimationFrame callbacks of a frame are running
  window.requestAnimationFrame = (callback) => frame((time) => {
    if (!inFrame) {
      inFrame = true;
      afterThisTask(() => { inFrame = false; });
    }
    return callback(time);
  });
  let waiting = null;                  // the key whose change is not yet seen
  const isSlider = (target) => target instanceof HTMLInputElement && target.type === "range";
  document.addEventListener("keydown", (event) => {
    if (!isSlider(event.target)) return;
    waiting = { key: event.key, down: performance.now(), changed: null, shown: null };
    keys.push(waiting);
  }, true);
  document.addEventListener("keyup", (event) => { if (isSlider(event.target)) keyUps.push(performance.now()); }, true);
  const observer = new MutationObserver(() => {
    const entry = waiting;
    if (!entry) return;
    waiting = null;
    entry.changed = performance.now();
    const shown = () => { entry.shown = performance.now(); };
    if (inFrame) afterThisTask(shown);
    else frame(() => afterThisTask(shown));
  });
  window.__benchObserve = () => {
    const inView = (e) => { const r = e.getBoundingClientRect(); return r.bottom > 0 && r.top < innerHeight && r.height > 0; };
    const targets = [...document.querySelectorAll(".panel:not([hidden]), #linkage")].filter(inView);
    for (const target of targets) observer.observe(target, { subtree: true, childList: true, attributes: true, characterData: true });
    return targets.length;
  };
})();"""

MARKS_JS = """() => Object.fromEntries(["exact-requested", "exact-drawn", "family-requested", "family-coarse-arrived",
  "family-full-arrived", "preview-coarse", "preview-full"].map((n) => [n, performance.getEntriesByName(n).map((e) => e.startTime)]))"""
FAMILIES_ARRIVED_JS = ("() => performance.getEntriesByName('family-arrived').length > 0 && "
                       + " + ".join(f"performance.getEntriesByName('{end}').length" for end in
                                    ("family-full-arrived", "family-unrefined", "family-failed", "family-given-up"))
                       + " >= performance.getEntriesByName('family-requested').length")


def scenes() -> list[dict]:
    """Every scene whose page has sliders (not the course project's cards), in the course's order."""
    if str(ROOT) not in sys.path:
        sys.path.insert(0, str(ROOT))
    from server.lessons.scenes import scene_documents      # shared sliders and inheriting variants resolved
    loaded = [s for s in scene_documents().values() if s.get("kind") != "project"
              and any(v.get("sliders") for v in s["variants"])]
    return sorted(loaded, key=lambda s: s["order"])


def key_and_room(page, selector: str) -> str:
    """ArrowRight, or ArrowLeft when the thumb stands in the upper half of its track (room for the keys)."""
    value, low, high = page.eval_on_selector(selector, "e => [e.value, e.min, e.max].map(Number)")
    return "ArrowLeft" if (value - low) / (high - low) > 0.5 else "ArrowRight"


def shown_within(page, k: int) -> None:
    """Wait (a guard, not a measure) until the k-th slider keydown's change is on the screen; a key that changed
    nothing is left as it is (counted as such)."""
    try:
        page.wait_for_function("k => window.__benchKeys[k]?.shown != null", arg=k, timeout=CHANGE_WAIT_S * 1000)
    except Exception:                # noqa: BLE001
        pass


def exact_drawn_after(page, t: float) -> float | None:
    """The first exact-drawn mark after t (ms), waiting for it (a guard); None if none came."""
    try:
        page.wait_for_function("t => performance.getEntriesByName('exact-drawn').some((m) => m.startTime > t)",
                               arg=t, timeout=ANSWER_WAIT_S * 1000)
    except Exception:                # noqa: BLE001 - said in the table
        return None
    return page.evaluate("t => performance.getEntriesByName('exact-drawn').find((m) => m.startTime > t).startTime", t)


def measure_scene(browser, url: str, scene: dict, keys: int, presses: int) -> dict:
    """A held key repeating `keys` times, then released; then `presses` single presses, each once the previous
    one's exact answer is drawn."""
    variant = next(v for v in scene["variants"] if v.get("sliders"))
    slider = next((s for s in variant["sliders"] if not s.get("locked")), variant["sliders"][0])
    row = {"scene": f"{scene['id']} ({variant['id']})", "slider": slider["id"], "problems": []}
    context = browser.new_context(viewport=VIEWPORT)
    context.add_init_script(MEASURE_JS)
    page = context.new_page()
    page.on("pageerror", lambda error: row["problems"].append(str(error)))
    page.on("console", lambda message: message.type == "error" and row["problems"].append(message.text))
    asked = lambda start, end: sum(1 for t in page.evaluate(MARKS_JS)["exact-requested"] if start <= t <= end)
    try:
        page.goto(f"{url}/scenes/{scene['id']}?lang=en&variant={variant['id']}")
        page.wait_for_function("() => performance.getEntriesByName('exact-drawn').length > 0", timeout=ANSWER_WAIT_S * 1000)
        page.wait_for_load_state("networkidle")
        selector = f"#slider-{slider['id']}"
        page.locator(selector).scroll_into_view_if_needed()
        row["observed"] = page.evaluate("() => window.__benchObserve()")
        page.focus(selector)
        try:
            page.wait_for_function(FAMILIES_ARRIVED_JS, timeout=FAMILY_WAIT_S * 1000)
            row["family"] = True
        except Exception:            # noqa: BLE001 - no family in time: the keys are measured as they come
            row["family"] = False
        key = row["key"] = key_and_room(page, selector)

        for k in range(keys):        # held: keydown repeats, no keyup until the end
            page.keyboard.down(key)
            shown_within(page, k)
            page.wait_for_timeout(KEY_GAP_S * 1000)
        page.keyboard.up(key)
        held = page.evaluate("() => window.__benchKeys")
        released = page.evaluate("() => window.__benchKeyUps.at(-1)")
        drawn = exact_drawn_after(page, released)
        row["held_ms"] = [e["shown"] - e["down"] for e in held if e["shown"] is not None]
        row["held_keys"] = len(held)
        row["held_asked"] = asked(held[0]["down"], released) if held else 0
        row["rest_ms"] = drawn - released if drawn is not None else None

        row["single_ms"], row["single_asked"] = [], []
        for _ in range(presses):     # one press at rest: the first key after an exact answer
            n = len(page.evaluate("() => window.__benchKeys"))
            page.keyboard.press(key)
            shown_within(page, n)
            entry = page.evaluate("n => window.__benchKeys[n]", n)
            up = page.evaluate("() => window.__benchKeyUps.at(-1)")
            exact_drawn_after(page, up)
            if entry and entry["shown"] is not None:
                row["single_ms"].append(entry["shown"] - entry["down"])
            page.wait_for_load_state("networkidle")
            row["single_asked"].append(asked(entry["down"] if entry else up, page.evaluate("() => performance.now()")))
        row["presses"] = presses
        row["previews"] = sum(len(page.evaluate(MARKS_JS)[name]) for name in ("preview-coarse", "preview-full"))
    finally:
        context.close()
    return row


def summary(values: list[float], count: int) -> str:
    if not values:
        return f"— (0/{count})"
    return f"{statistics.median(values):.1f} / {max(values):.1f} ({len(values)}/{count})"


def table(rows: list[dict]) -> str:
    lines = ["| scene (variant) | slider, key | panels in view | family before the keys "
             "| held key: key → visible change, median / max, ms (changed / keydowns) | exact asked while held "
             "| released → exact drawn, ms | single presses at rest: key → visible change, median / max, ms "
             "| exact asked per single press |",
             "|---|---|---:|---|---|---:|---:|---|---|"]
    for r in rows:
        rest = f"{r['rest_ms']:.0f}" if r["rest_ms"] is not None else "—"
        lines.append(f"| {r['scene']} | {r['slider']}, {r['key']} | {r['observed']} | {'yes' if r['family'] else 'no'} "
                     f"| {summary(r['held_ms'], r['held_keys'])} | {r['held_asked']} | {rest} "
                     f"| {summary(r['single_ms'], r['presses'])} | {', '.join(map(str, r['single_asked'])) or '—'} |")
    return "\n".join(lines)


def load() -> str:
    return " / ".join(f"{x:.2f}" for x in os.getloadavg())


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--scenes", help="comma-separated scene file names (content/scenes/<name>.json); all by default")
    parser.add_argument("--keys", type=int, default=KEYS, help=f"keydowns of the held key per scene (default {KEYS})")
    parser.add_argument("--presses", type=int, default=PRESSES, help=f"single presses at rest per scene (default {PRESSES})")
    parser.add_argument("--tree", type=Path, default=ROOT, help="the source tree whose app is measured (default this one)")
    parser.add_argument("--out", "--output", type=Path, default=ROOT / "bench" / "results" / "keyboard.md")
    parser.add_argument("--no-write", action="store_true", help="print the table only")
    args = parser.parse_args()
    chosen = scenes()
    if args.scenes:
        names = set(args.scenes.split(","))
        chosen = [s for s in chosen if s["id"].replace("-", "_") in names]
        if not chosen:
            raise SystemExit(f"no scene with sliders among {sorted(names)}")

    from playwright.sync_api import sync_playwright

    rows, load_before = [], load()
    started = time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime())
    with running_server(tree=args.tree.resolve()) as (port, server):
        with sync_playwright() as playwright:
            browser = playwright.chromium.launch(executable_path=CHROMIUM, headless=True, args=CHROMIUM_ARGS)
            try:
                for scene in chosen:
                    rows.append(measure_scene(browser, f"http://127.0.0.1:{port}", scene, args.keys, args.presses))
                    print(table(rows[-1:]).splitlines()[-1], flush=True)
            finally:
                browser.close()
    load_after = load()
    problems = [f"{r['scene']}: {p}" for r in rows for p in r["problems"]]
    report = "\n".join([
        "# Browser: a slider's keys, key → visible change",
        "",
        f"`python bench/browser_keys.py` on {tree_label(args.tree)}, {started}; {platform.processor() or platform.machine()}, "
        f"{os.cpu_count()} CPUs, load average (1 / 5 / 15 min) {load_before} before and {load_after} after (the times "
        f"depend on the machine's load); Chromium headless at {VIEWPORT['width']} × {VIEWPORT['height']}; "
        f"the app as the README starts it (one worker) on loopback; per scene a key held for {args.keys} keydowns "
        f"(each {KEY_GAP_S * 1000:.0f} ms after the previous one's change was shown), then {args.presses} single presses at rest.",
        "",
        "*key → visible change*: a keydown → the end of the first frame in which a panel in view (a plot, a drawing, a "
        "table; the linkage's drawing) changed (MutationObserver, then the first task after that frame); — where the "
        "keys changed nothing in view (a preview redraws what the slider's family holds; numbers wait for the exact answer). *held key*: the keydowns of a held "
        "key (auto-repeat), drawn from the slider's family; *exact asked while held*: the page's exact-requested marks "
        "meanwhile (the keys ask at rest, not per key); *released → exact drawn*: includes the page's wait for the keys "
        "to rest. *single presses at rest*: a press once the previous exact answer is drawn, the first key of a run "
        "(its preview may need the axes of the exact drawing widened: a full Plotly redraw of the plots in view); "
        "*exact asked per single press*: 1 each expected.",
        "",
        table(rows),
        "",
        f"Processes outliving the server: {server.outlived}.",
        *(["", "Page errors: " + "; ".join(problems)] if problems else []),
        "",
    ])
    print()
    print(report)
    if not args.no_write:
        args.out.parent.mkdir(parents=True, exist_ok=True)
        args.out.write_text(report, encoding="utf-8")
        print(f"written to {args.out}")


if __name__ == "__main__":
    main()
