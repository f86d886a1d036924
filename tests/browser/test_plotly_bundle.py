"""plotly.js is vendored as a partial bundle (web/vendor/plotly/README.md): the trace types the app's figures
draw, no more, so that a page evaluates a quarter of the full bundle's code. Every trace type named in our
modules must be registered in the bundle a page loads, and the bench figures shown at /bench-results draw
only registered types."""
from __future__ import annotations

import json
import re

import pytest

from conftest import REPO

pytestmark = pytest.mark.browser

# every trace type of plotly.js 4.1.1 (its lib/*.js but the index files, core, calendars and locales)
PLOTLY_TRACES = set("""bar barpolar box candlestick carpet choropleth choroplethmap cone contour contourcarpet
densitymap funnel funnelarea heatmap histogram histogram2d histogram2dcontour icicle image indicator isosurface
mesh3d ohlc parcats parcoords pie quiver sankey scatter scatter3d scattercarpet scattergeo scattergl scattermap
scatterpolar scatterpolargl scattersmith scatterternary splom streamtube sunburst surface table treemap violin
volume waterfall""".split())
NAMED_TYPE = re.compile(r"""\btype:\s*["'](\w+)["']""")


def traces_named_in(files) -> set[str]:
    return {name for path in files for name in NAMED_TYPE.findall(path.read_text("utf-8")) if name in PLOTLY_TRACES}


def figure_data(html: str) -> list[dict]:
    """The traces of plotly's HTML export: the array after the div's id in Plotly.newPlot(id, data, layout)."""
    start = html.index("[", html.index("Plotly.newPlot("))
    return json.JSONDecoder().raw_decode(html, start)[0]


def test_the_bundle_registers_every_trace_type_the_app_draws_and_no_other(browser_page):
    page = browser_page
    page.goto("/scenes/wear?lang=en")
    page.wait_for_function("() => window.Plotly?.PlotSchema !== undefined")
    registered = set(page.evaluate("() => Object.keys(Plotly.PlotSchema.get().traces)"))
    ours = traces_named_in((REPO / "web" / "static" / "js").rglob("*.js"))
    assert ours == {"scatter", "scatterpolar", "bar"}          # the figures' own trace types, found by the scan
    assert ours <= registered
    assert registered == ours                                   # nothing else evaluated on every page load
    drawn = {trace.get("type", "scatter") for path in (REPO / "bench" / "results").glob("*.html")
             for trace in figure_data(path.read_text("utf-8"))}
    assert drawn and drawn <= registered, drawn
    assert page.problems == []
