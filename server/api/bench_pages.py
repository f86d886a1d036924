"""The benchmarks' stored figures at /bench-results (bench/results/): plotly's own HTML export, which draws
its figure with two inline scripts and plotly.js from this server (/vendor/plotly/plotly.min.js).

The app's Content-Security-Policy allows no inline script, so each such page gets the policy widened by the
sha256 of exactly its own inline scripts (CSP Level 2 hash sources): no 'unsafe-inline', no 'unsafe-eval',
no other origin. Every other file there keeps the app's policy.
"""
from __future__ import annotations

import base64
import hashlib
import json
import math
import re
from functools import lru_cache

from markupsafe import Markup, escape
from starlette.staticfiles import StaticFiles

from .messages import signed
from .security import policy_with_script_hashes

INLINE_SCRIPT = re.compile(r"<script(?![^>]*\bsrc=)[^>]*>(.*?)</script>", re.S | re.I)


def inline_script_hashes(html: str) -> list[str]:
    """The base64 sha256 of each inline script's text, as the browser hashes it (the exact characters
    between the tags, UTF-8)."""
    return [base64.b64encode(hashlib.sha256(text.encode()).digest()).decode() for text in INLINE_SCRIPT.findall(html)]


@lru_cache(maxsize=64)
def _page_policy(path: str, mtime_ns: int, size: int) -> str:
    with open(path, encoding="utf-8") as page:
        return policy_with_script_hashes(inline_script_hashes(page.read()))


class BenchResults(StaticFiles):
    """StaticFiles whose HTML pages carry a policy that lets exactly their own inline scripts run."""

    def file_response(self, full_path, stat_result, scope, status_code=200):
        response = super().file_response(full_path, stat_result, scope, status_code)
        if str(full_path).endswith(".html"):
            response.headers["content-security-policy"] = _page_policy(
                str(full_path), stat_result.st_mtime_ns, stat_result.st_size)
        return response


# --- the measurements page: bench/results/work_precision.md in the reader's language ---------------------------
# The bench writes its tables in English; the page's own words (headings, references, figure captions, the
# fastest-method sentence, the table's head and the method names) are said in ru, uk or en from content/i18n
# (keys measurements_*), the numbers written the reader's way. A line the page does not know stays as written.
# Each study's figure is drawn in the browser (web/static/js/measurements) from the points of its own table,
# handed over in the page with every word already in the reader's language; the bench's own pictures
# (wp_<key>.png, .html) stay for the readers of work_precision.md.

FASTEST = re.compile(r"(?:Fastest to error|error) ≤ (\S+): (.+?) in ([\d.]+) ms")
PICKED = re.compile(r"ours \(picked by stiffness ratio ([^)]+)\): (\w+)")
STUDY = re.compile(r"wp_(\w+)\.png")
COLUMNS = ["method", "tolerance", "error", "run time, ms"]
REFERENCES = {"DOP853 at rtol 1e-13 in time, cycles until periodic": "measurements_reference_dop853",
              "ours on 32768 steps per turn": "measurements_reference_fine_grid",
              "rtol 1e-11 by another method than ours": "measurements_reference_other_method"}
METHODS = {"ours (Newton shooting, RK4 in φ)": "measurements_method_shooting",
           "ours (Simpson on the cycle grid)": "measurements_method_simpson"}


def _number(text: str, lang: str) -> str:
    """A number of the bench's tables written the reader's way (decimal comma in ru/uk, a true minus, powers of
    ten written out: "1e-03" → "10⁻³"), as the pages' decimal filter writes it."""
    try:
        value = float(text)
    except ValueError:
        return text
    written = f"{value:.6g}"
    return signed(written if lang == "en" else written.replace(".", ","))


def _value(text: str) -> float | None:
    """A number of a table as the figure plots it; None (a gap) for a cell that is no finite number."""
    try:
        value = float(text)
    except ValueError:
        return None
    return value if math.isfinite(value) else None


def _method(text: str, t: dict, lang: str) -> str:
    """A method's name in the reader's language: ours by what it does, SciPy's by its own name."""
    if text in METHODS:
        return t[METHODS[text]]
    if picked := PICKED.fullmatch(text):
        return t["measurements_method_picked"].format(ratio=_number(picked.group(1), lang), method=picked.group(2))
    return text.replace("solve_ivp ", "SciPy ")


def _fastest(line: str, t: dict, lang: str) -> str:
    """'Fastest to error ≤ 1e-04: ours (…) in 3.2 ms; …' as one sentence in the reader's language."""
    parts = [t["measurements_fastest_item"].format(error=_number(error, lang), method=_method(method, t, lang),
                                                    ms=_number(ms, lang))
             for error, method, ms in FASTEST.findall(line)]
    return t["measurements_fastest"].format(items="; ".join(parts)) + "."


def _cells(rows: list[str]) -> list[list[str]]:
    """A Markdown table's rows as lists of cells, its head first (the line under the head left out)."""
    cells = [[cell.strip() for cell in row.strip().strip("|").split("|")] for row in rows]
    return cells[:1] + cells[2:]


def _table(cells: list[list[str]], t: dict, lang: str, notation) -> str:
    head = [t["measurements_column_method"], t["measurements_column_tolerance"], t["measurements_column_error"],
            t["measurements_column_run_time"]] if cells[0] == COLUMNS else cells[0]
    body = []
    for row in cells[1:]:
        shown = [_method(row[0], t, lang)] + [_number(cell, lang) for cell in row[1:]]
        body.append("<tr>" + "".join(f"<td>{notation(cell)}</td>" for cell in shown) + "</tr>")
    return ("<table><thead><tr>" + "".join(f"<th>{escape(cell)}</th>" for cell in head) + "</tr></thead><tbody>"
            + "".join(body) + "</tbody></table>")


def study_figure(cells: list[list[str]], t: dict, lang: str) -> dict:
    """The figure of a study's table (head method, tolerance, error, run time in ms) as the page draws it:
    one trace per method in the table's order, named as the table names it (ours: the app's own method); x the
    run time (ms) and y the error of each of its rows, as the table writes them (None: no finite number); each
    point's hover text its tolerance, error and run time in the reader's words; the axes' titles. Every word
    and every written number is the reader's: the browser only draws (web/static/js/measurements)."""
    traces: dict[str, dict] = {}
    for method, tolerance, error, run_time in (row[:4] for row in cells[1:]):
        trace = traces.setdefault(method, {"name": _method(method, t, lang), "ours": method.startswith("ours"),
                                           "x": [], "y": [], "hover": []})
        trace["x"].append(_value(run_time))
        trace["y"].append(_value(error))
        trace["hover"].append("<br>".join(f"{t[key]}: {_number(cell, lang)}" for key, cell in (
            ("measurements_column_tolerance", tolerance), ("measurements_column_error", error),
            ("measurements_column_run_time", run_time))))
    return {"traces": list(traces.values()), "x_title": t["measurements_axis_run_time"],
            "y_title": t["measurements_axis_error"]}


def _figure(cells: list[list[str]], title: str, t: dict, lang: str, notation, notation_parts) -> str:
    """A study's figure: the graph the page draws from data-figure (its text alternative the caption said
    after the study's title), and the caption."""
    caption = t["measurements_figure"]
    alt = "".join(run for run, _ in notation_parts(f"{title} — {caption}"))
    data = json.dumps(study_figure(cells, t, lang), ensure_ascii=False, allow_nan=False, separators=(",", ":"))
    return (f'<figure class="study-figure"><div class="graph" role="img" aria-label="{escape(alt)}" '
            f'data-figure="{escape(data)}"></div><figcaption>{notation(caption)}</figcaption></figure>')


def _next_table(lines: list[str], i: int) -> list[list[str]] | None:
    """The cells of the first table after line i within its study (before the next heading), if any."""
    for j in range(i + 1, len(lines)):
        if lines[j].startswith("#"):
            return None
        if lines[j].startswith("|"):
            end = j
            while end < len(lines) and lines[end].startswith("|"):
                end += 1
            return _cells(lines[j:end])
    return None


def measurements_html(markdown: str, t: dict, lang: str, notation, notation_parts) -> Markup:
    """The work–precision tables as HTML in lang: the first heading left to the page, each study's heading,
    reference, figure (drawn by the page from the points of the study's table, with its caption), sentence of
    the fastest method and table in the reader's words. notation is the pages' filter (subscripts as <sub>,
    all else escaped), notation_parts its reading of the markup (for the figure's text alternative, plain)."""
    html, lines, i, title = [], markdown.splitlines(), 0, ""
    while i < len(lines):
        line = lines[i]
        if line.startswith("# "):
            i += 1
            continue
        if line.startswith("## "):
            found = STUDY.search("\n".join(lines[i + 1:i + 4]))
            title = t.get(f"measurements_study_{found.group(1)}" if found else "", line[3:])
            html.append(f"<h2>{notation(title)}</h2>")
        elif line.startswith("Reference: "):
            reference = line[len("Reference: "):].split(". ![", 1)[0].rstrip(".")
            said = t[REFERENCES[reference]] if reference in REFERENCES else reference
            html.append(f"<p>{escape(t['measurements_reference'])}: {notation(said)}.</p>")
            if (cells := _next_table(lines, i)) and cells[0] == COLUMNS:
                html.append(_figure(cells, title, t, lang, notation, notation_parts))
        elif line.startswith("Fastest to error"):
            html.append(f"<p>{notation(_fastest(line, t, lang))}</p>")
        elif line.startswith("|"):
            end = i
            while end < len(lines) and lines[end].startswith("|"):
                end += 1
            html.append(_table(_cells(lines[i:end]), t, lang, notation))
            i = end
            continue
        elif line.strip():
            html.append(f'<p lang="en">{escape(line)}</p>')
        i += 1
    return Markup("\n".join(html))
