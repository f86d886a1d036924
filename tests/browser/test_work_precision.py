"""The live work–precision study in a real browser: it runs only when its button is clicked, draws error
against run time with a line per method (the app's own one bold), is greyed as soon as a value changes,
and a refused study says why in the reader's language; a panel of a kind the page has no view for is
left out without breaking the page."""
from __future__ import annotations

import json
import re
from urllib.parse import urlencode

import pytest

from conftest import ARTIFACTS, drag_slider, interface_texts, read_scene, screenshot

pytestmark = pytest.mark.browser

MOTION = read_scene("equation_of_motion")
FOUR_BAR = read_scene("elastic_four_bar")
STUDY_TIMEOUT = 60_000          # ms; the study has a budget of 6 s of server time, plus the reference
GRAPH = "document.querySelector('#panel-study .graph')"


def open_study(page, scene: dict, lang: str, **state) -> list[str]:
    """Open the scene, wait for its own answer (the numerics), bring the study panel into view; returns
    the list the study requests are kept in."""
    studies = []
    page.on("request", lambda request: "/work-precision/" in request.url and studies.append(request.url))
    page.goto(f"/scenes/{scene['id']}?{urlencode({'lang': lang, **state})}")
    page.wait_for_selector("#panel-numerics", state="visible", timeout=STUDY_TIMEOUT)
    page.locator("#panel-study").scroll_into_view_if_needed()
    return studies


def run_study(page, texts: dict[str, str]) -> tuple[dict, list[dict]]:
    """Click the button and wait for the chart: the study's answer and the traces drawn from it."""
    with page.expect_response(lambda response: "/work-precision/" in response.url, timeout=STUDY_TIMEOUT) as answer:
        page.click("#panel-study .study-run")
        assert page.is_disabled("#panel-study .study-run")            # busy until the answer is drawn
        assert page.inner_text("#panel-study .study-state") == texts["study_running"]
    page.wait_for_function(f"() => {GRAPH}?.data?.length > 0")
    traces = page.evaluate(f"""() => {GRAPH}.data.map(t => ({{
        name: t.name.replace(/<\\/?b>/g, ""), bold: t.name.startsWith("<b>"), points: t.x.length,
        width: t.line.width, text: t.text }}))""")
    return answer.value.json()["study"], traces


def check_chart(page, study: dict, traces: list[dict], texts: dict[str, str]) -> None:
    """A line per method of the answer with a point per run, ours bold; what was skipped said in words."""
    rows, ours = {}, {}
    for row in study["rows"]:
        rows[row["method"]] = rows.get(row["method"], 0) + 1
        ours[row["method"]] = row["ours"]
    assert {trace["name"]: trace["points"] for trace in traces} == rows
    assert all(trace["bold"] == ours[trace["name"]] for trace in traces)
    assert all(trace["text"][0].startswith("10") for trace in traces)      # the loosest tolerance, 10⁻³
    axes = page.evaluate(f"() => [{GRAPH}._fullLayout.xaxis.type, {GRAPH}._fullLayout.yaxis.type]")
    assert axes == ["log", "log"]
    details = page.inner_text("#panel-study .study-details")
    assert f"{texts['study_quantity']}: {study['quantity']}" in details
    assert f"{texts['study_reference']}: {study['reference']}" in details
    if study["skipped"]:
        assert f"{texts['study_skipped']}: {'; '.join(study['skipped'])}" in details
    assert page.inner_text("#panel-study .study-state") == ""
    assert page.get_attribute("#panel-study .study-run", "disabled") is None
    assert "NaN" not in page.inner_text("#panel-study")


def picture(page, name: str) -> None:
    page.locator("#panel-study").screenshot(path=ARTIFACTS / f"{name}.png")


def test_steady_cycle_study_runs_on_click_and_puts_ours_in_bold(browser_page):
    page = browser_page
    texts = interface_texts("ru")
    studies = open_study(page, MOTION, "ru", variant="linear")
    assert page.inner_text("#panel-study .study-run") == texts["study_run"]
    assert page.inner_text("#panel-study .note") == MOTION["panels"]["study"]["note"]["ru"]
    drag_slider(page, "#slider-M0", 0.6)               # a slider move asks for the scene, not for the study
    page.wait_for_timeout(500)
    assert studies == [] and page.is_hidden("#panel-study .graph")

    study, traces = run_study(page, texts)
    assert len(studies) == 1 and "work-precision/motion?lang=ru" in studies[0]
    check_chart(page, study, traces, texts)
    # the methods drawn and the runs the 6 s budget stopped, named: as many as a quiet machine draws, whatever the load
    assert len(traces) >= 1 and len(traces) + len(study["skipped"]) >= 3
    ours = [trace for trace in traces if trace["bold"]]
    assert len(ours) == 1 and ours[0]["points"] > 0
    assert ours[0]["width"] > max(trace["width"] for trace in traces if trace is not ours[0])
    picture(page, "work_precision_motion")

    drag_slider(page, "#slider-b", 0.7)                 # the chart now belongs to the previous values
    page.wait_for_selector("#panel-study .study-result.earlier")
    assert page.inner_text("#panel-study .study-state") == texts["study_earlier"]
    assert len(studies) == 1
    picture(page, "work_precision_motion_earlier")
    assert page.problems == []


def test_elastic_four_bar_study_draws_every_method(browser_page):
    page = browser_page
    texts = interface_texts("en")
    studies = open_study(page, FOUR_BAR, "en")
    study, traces = run_study(page, texts)
    assert len(studies) == 1 and "work-precision/elastic?lang=en" in studies[0]
    check_chart(page, study, traces, texts)
    assert len(traces) >= 1 and len(traces) + len(study["skipped"]) >= 2    # the rest named as skipped (the budget)
    picture(page, "work_precision_elastic_four_bar")
    screenshot(page, "work_precision_elastic_four_bar_page")
    assert page.problems == []


def test_refused_study_says_why_in_the_readers_language(browser_page):
    page = browser_page
    texts = interface_texts("uk")
    open_study(page, MOTION, "uk", variant="constant", beta=0)   # a constant torque and no viscous friction
    page.click("#panel-study .study-run")
    page.wait_for_selector("#panel-study .refusal", timeout=STUDY_TIMEOUT)
    assert page.inner_text("#panel-study .refusal strong") == texts["study_refused"]
    assert page.inner_text("#panel-study .refusal p") == texts["err_study_needs_speed"]
    assert page.is_hidden("#panel-study .graph")
    assert page.locator("#notices .refusal").count() == 0          # the scene itself still computes
    picture(page, "work_precision_refused")
    assert [p for p in page.problems if "422" not in p] == []        # the browser logs the refused request


def test_panels_of_unknown_kinds_are_left_out_without_breaking_the_page(browser_page):
    page = browser_page
    scene_data = re.compile(r'(<script type="application/json" id="scene-data">)(.*?)(</script>)', re.S)

    def with_unknown_panels(match) -> str:
        """The page's scene with a panel of a later kind, one named like a property of every object, and
        an id no panel has, first in every variant."""
        scene = json.loads(match[2].replace("<\\/", "</"))
        scene["panels"] |= {"future": {"kind": "future_kind", "needs": []}, "inherited": {"kind": "constructor"}}
        for variant in scene["variants"]:
            variant["panels"] = ["future", "inherited", "not_in_panels", *variant["panels"]]
        return match[1] + json.dumps(scene, ensure_ascii=False).replace("</", "<\\/") + match[3]

    page.route(f"**/scenes/{MOTION['id']}?*", lambda route: route.fulfill(
        body=scene_data.sub(with_unknown_panels, route.fetch().text(), count=1), content_type="text/html; charset=utf-8"))
    open_study(page, MOTION, "en")
    assert page.locator("#panel-future, #panel-inherited, #panel-not_in_panels").count() == 0
    assert page.locator(".refusal").count() == 0
    assert page.problems == []


def test_six_bar_study_runs_on_a_general_mechanism(browser_page):
    """The shaping machine (a general mechanism of Assur groups) has the same live study as the crank-slider."""
    page = browser_page
    texts = interface_texts("ru")
    studies = open_study(page, MOTION, "ru", variant="shaping")
    study, traces = run_study(page, texts)
    assert len(studies) == 1 and "work-precision/motion?lang=ru" in studies[0]
    check_chart(page, study, traces, texts)
    assert len(traces) >= 1 and len(traces) + len(study["skipped"]) >= 3
    assert sum(trace["bold"] for trace in traces) == 1                   # ours among them, bold
    picture(page, "work_precision_motion_shaping")
    assert page.problems == []
