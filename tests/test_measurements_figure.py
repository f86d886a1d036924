"""The measurements page's figures as the server hands them to the browser (data-figure, bench_pages.study_figure):
- one figure per study of bench/results/work_precision.md, its traces holding exactly the points of the study's
  table: one trace per method in the table's order, x its run times (ms) and y its errors as the table writes them;
- every word in the reader's language: the trace names are the methods as the page's table names them, the axis
  titles content/i18n's measurements_axis_*, each point's hover text its tolerance, error and run time as the
  table writes them; in ru/uk no Latin word but the solvers' own names and a decimal comma in every number;
- no NaN or infinity in the JSON, and no inline executable script on the page.
"""
from __future__ import annotations

import html
import json
import re
from pathlib import Path

import pytest
from fastapi.testclient import TestClient

from server.api.app import app
from server.lessons.scenes import interface_texts

REPO = Path(__file__).resolve().parents[1]
MEASUREMENTS = REPO / "bench" / "results" / "work_precision.md"
PROPER_NAMES = {"RK45", "DOP853", "Radau", "LSODA", "SciPy", "BDF"}     # the solvers' own names, said as is
FIGURE = re.compile(r'data-figure="([^"]*)"')
TABLE = re.compile(r"<table>.*?</table>", re.S)
client = TestClient(app)


def latin_words(text: str) -> list[str]:
    """Runs of Latin letters and digits with two letters or more ("RK4", "ms", "error"), the solvers' names
    left out."""
    return [run for run in re.findall(r"[A-Za-z0-9]+", text)
            if len(re.findall(r"[A-Za-z]", run)) >= 2 and run not in PROPER_NAMES]


def bench_tables() -> list[list[list[str]]]:
    """Each study's table of work_precision.md as rows of cells (method, tolerance, error, run time, ms)."""
    tables, rows = [], None
    for line in MEASUREMENTS.read_text(encoding="utf-8").splitlines():
        if line.startswith("|"):
            if rows is None:
                rows = []
                tables.append(rows)
            rows.append([cell.strip() for cell in line.strip().strip("|").split("|")])
        else:
            rows = None
    return [table[2:] for table in tables]


def no_constant(name):
    raise ValueError(f"{name} in a figure's JSON")


def page_figures(lang: str) -> tuple[list[dict], list[list[list[str]]]]:
    """The page's figures (the JSON of data-figure) and its tables' cells as the page shows them."""
    page = client.get(f"/measurements?lang={lang}")
    assert page.status_code == 200
    article = page.text.split('<article class="measurements"', 1)[1].split("</article>", 1)[0]
    figures = [json.loads(html.unescape(data), parse_constant=no_constant) for data in FIGURE.findall(article)]
    shown = [[[html.unescape(re.sub(r"<[^>]+>", "", cell)) for cell in re.findall(r"<td>(.*?)</td>", row)]
              for row in re.findall(r"<tr>(.*?)</tr>", table) if "<td>" in row]
             for table in TABLE.findall(article)]
    return figures, shown


@pytest.mark.parametrize("lang", ["ru", "uk", "en"])
def test_each_figure_holds_exactly_the_points_of_its_studys_table(lang):
    figures, _ = page_figures(lang)
    tables = bench_tables()
    assert len(tables) == 6 and len(figures) == len(tables)
    for figure, rows in zip(figures, tables):
        methods = list(dict.fromkeys(row[0] for row in rows))        # in the table's order
        assert len(figure["traces"]) == len(methods)
        for trace, method in zip(figure["traces"], methods):
            own = [row for row in rows if row[0] == method]
            assert trace["x"] == [float(row[3]) for row in own], method
            assert trace["y"] == [float(row[2]) for row in own], method
            assert len(trace["hover"]) == len(own)
            assert trace["ours"] == method.startswith("ours")


@pytest.mark.parametrize("lang", ["ru", "uk", "en"])
def test_the_figures_words_are_the_pages_own(lang):
    """Trace names as the page's table names the methods, axis titles from content/i18n, each point's hover
    text the row's tolerance, error and run time as the table writes them."""
    figures, shown = page_figures(lang)
    texts = interface_texts(lang)
    assert len(shown) == len(figures) == 6
    for figure, rows in zip(figures, shown):
        assert [trace["name"] for trace in figure["traces"]] == list(dict.fromkeys(row[0] for row in rows))
        assert figure["x_title"] == texts["measurements_axis_run_time"]
        assert figure["y_title"] == texts["measurements_axis_error"]
        hovers = [(trace["name"], hover) for trace in figure["traces"] for hover in trace["hover"]]
        by_row = sorted(rows, key=lambda row: [trace["name"] for trace in figure["traces"]].index(row[0]))
        for (name, hover), (method, tolerance, error, run_time) in zip(hovers, by_row):
            assert name == method
            assert hover == (f"{texts['measurements_column_tolerance']}: {tolerance}<br>"
                             f"{texts['measurements_column_error']}: {error}<br>"
                             f"{texts['measurements_column_run_time']}: {run_time}")


@pytest.mark.parametrize("lang", ["ru", "uk"])
def test_the_figures_say_no_english_word_and_write_a_decimal_comma(lang):
    figures, _ = page_figures(lang)
    words = [figure["x_title"] for figure in figures] + [figure["y_title"] for figure in figures] + [
        text for figure in figures for trace in figure["traces"] for text in [trace["name"], *trace["hover"]]]
    said = "\n".join(re.sub(r"<br>", "\n", text) for text in words)
    assert latin_words(said) == []
    assert not re.search(r"\d\.\d", said)
    assert re.search(r"\d,\d", said)                                      # "2,5", "3,8": there are decimals
    names = {trace["name"] for figure in figures for trace in figure["traces"]}
    texts = interface_texts(lang)
    assert {"SciPy RK45", texts["measurements_method_shooting"], texts["measurements_method_simpson"]} <= names


def test_the_page_draws_its_figures_with_our_plotly_and_no_inline_script():
    page = client.get("/measurements?lang=uk").text
    assert re.search(r'<script src="/vendor/plotly/[^"]*plotly\.min\.js" defer></script>', page)
    assert re.search(r'<script type="module" src="/static/[^"]*/js/measurements/measurements_page\.js">', page)
    scripts = re.findall(r"<script\b([^>]*)>(.*?)</script>", page, re.S)
    assert all("src=" in attrs or 'type="application/json"' in attrs for attrs, _ in scripts)
    assert "<img" not in page.split('<article class="measurements"', 1)[1]
