"""A course-project assignment in the browser: the instructor opens the course-project scene, makes an assignment
for the shaping machine with per-student |OA| and cutting force P in the builder (clicking and typing), two
students register in browsers of their own, see different variant numbers, open their variant on the
course-project page from their assignment page, read J_fw and M_b (by the groups and by Zhukovsky's lever) off
that page and type them in; the instructor's results page shows both scores."""
from __future__ import annotations

import json
import re

import httpx
import pytest

from server.classroom.names import normalise
from server.classroom.spec import AssignmentSpec
from server.classroom.variants import plan
from server.lessons.project_links import read_base64url
from server.lessons.scenes import scenes

from conftest import screenshot, server_log_tail
from test_assignment_flow import open_as_student, own_variant
from test_project_report import fact, page_number, settled

pytestmark = pytest.mark.browser
QUESTIONS = ["J_flywheel", "M_b_groups", "M_b_lever"]
PAGE_FACTS = {"J_flywheel": "flywheel-inertia", "M_b_groups": "Mb", "M_b_lever": "Mb-lever"}
VARIED = {"l_OA": ("0.08", "0.2", "0.01"), "P": ("1000", "5000", "500")}


def make_assignment(page) -> tuple[str, str]:
    page.goto("/scenes/course-project?lang=en")
    page.wait_for_selector("#project-variant-shaping_machine a")
    page.click("#make-assignment")
    page.wait_for_selector("#assignment-form")
    assert page.locator("#assignment-form").get_attribute("data-variant") == "shaping_machine"
    for slider, (low, high, step) in VARIED.items():
        row = page.locator(f'.slider-rule[data-slider="{slider}"]')
        row.locator('[name="vary"]').check()
        row.locator('[name="vary_min"]').fill(low)
        row.locator('[name="vary_max"]').fill(high)
        row.locator('[name="vary_step"]').fill(step)
    for pick in page.locator('.question-pick input[name="question"]').all():
        if (pick.get_attribute("value") in QUESTIONS) != pick.is_checked():
            pick.click()
    page.fill("#title", "Course project, group 1")
    screenshot(page, "course_project_assignment_builder")
    page.click("#create-assignment")
    page.wait_for_selector("#assignment-links:not([hidden])")
    turning = page.locator("#variants-turning")                   # |OA| up to 0.2 m: some variants stick
    turning.wait_for()
    assert re.search(r"of 64 variants checked, \d+ turn fully", turning.inner_text()), turning.inner_text()
    return page.locator("#student-link").get_attribute("href"), page.locator("#results-link").get_attribute("href")


def two_names_with_different_variants(assignment_id: str) -> tuple[str, str]:
    spec = AssignmentSpec.model_validate({
        "scene": "course-project", "variant": "shaping_machine",
        "sliders": {slider: {"vary": {"min": float(low), "max": float(high)}, "step": float(step)}
                    for slider, (low, high, step) in VARIED.items()},
        "questions": [{"id": q} for q in QUESTIONS]})
    resolved = plan(spec, scenes())
    first = "Olena Kovalenko"
    for k in range(100):
        second = f"Taras Shevchenko {k}"
        if resolved.number_for(assignment_id, normalise(second)) != resolved.number_for(assignment_id,
                                                                                         normalise(first)):
            return first, second
    raise AssertionError("no second name with another variant")


def project_facts(context, href: str) -> tuple[dict, dict]:
    """The student's variant opened on the course-project page (the link of their assignment page): the request
    the page sent and the numbers it shows for the questions."""
    page = context.new_page()
    problems = []
    page.on("pageerror", lambda error: problems.append(str(error)))
    with page.expect_request(lambda r: "/api/v1/course-project" in r.url and r.method == "POST") as sent:
        page.goto(href)
    settled(page, 0)
    assert page.get_attribute("#project-status", "data-state") == "ready", page.inner_text("#project-status")
    shown = {question: page_number(fact(page, name)) for question, name in PAGE_FACTS.items()}
    assert problems == []
    page.close()
    return sent.value.post_data_json, shown


def answer(page, question: str, value: float) -> str:
    page.fill(f"#answer-{question}", f"{value:.6g}")
    page.click(f"#question-{question} button")
    feedback = page.locator(f"#feedback-{question}")
    try:
        feedback.filter(has_text=re.compile("✓|✗")).wait_for()
    except Exception:
        origin = re.match(r"https?://[^/]+", page.url).group(0)
        raise AssertionError(f"no ✓ or ✗ for {question} = {value}: {feedback.inner_text()!r}; the server's log "
                             f"ends:\n{server_log_tail(origin)}") from None
    return feedback.inner_text()


def test_a_course_project_assignment_from_the_builder_to_the_results(chromium, app_url, browser_page):
    student_url, results_url = make_assignment(browser_page)
    assignment_id = re.search(r"/assignments/([\w-]+)", student_url).group(1)
    names = two_names_with_different_variants(assignment_id)
    shown_numbers = {}
    for name in names:
        context = chromium.new_context(base_url=app_url, viewport={"width": 1400, "height": 900})
        page = open_as_student(context, student_url, name)
        shown_numbers[name] = re.search(r"Variant (\d+) / (\d+)", page.inner_text(".assignment-who")).group(1)
        variant = own_variant(app_url, assignment_id, page.link)
        assert str(variant["variant"]) == shown_numbers[name]
        href = page.locator("#open-project").get_attribute("href")
        editor = page.locator("#open-editor").get_attribute("href")
        assert read_base64url(re.search(r"[?&]m=([\w-]+)", editor).group(1))["input"]["length"] == \
            pytest.approx(variant["values"]["l_OA"])
        body, shown = project_facts(context, href)
        assert body["linkage"]["input"]["length"] == pytest.approx(variant["values"]["l_OA"])
        assert body["masses"]["forces"][0]["working"] == pytest.approx(variant["values"]["P"])
        assert body["chosen"] == variant["values"]["chosen"]
        for question in QUESTIONS:
            assert "✓" in answer(page, question, shown[question]), (name, question)
        screenshot(page, f"course_project_assignment_student_{len(shown_numbers)}")
        assert page.problems == [], page.problems
        context.close()
    assert len(set(shown_numbers.values())) == 2, shown_numbers

    instructor = browser_page
    instructor.goto(results_url.replace("lang=ru", "lang=en"))
    rows = instructor.locator("#results tbody tr")
    rows.first.wait_for()
    assert rows.count() == 2
    table = {rows.nth(i).locator("td").nth(0).inner_text(): rows.nth(i).inner_text() for i in range(2)}
    for name in names:
        assert "3 / 3" in table[name], table[name]
    token = re.search(r"/results/([\w-]+)", results_url).group(1)
    results = httpx.get(f"{app_url}/api/v1/assignments/{assignment_id}/results/{token}").json()
    assert sorted(row["score"] for row in results["students"]) == [3, 3]
    screenshot(instructor, "course_project_assignment_results")


def test_the_editors_mechanism_becomes_a_course_project_assignment(chromium, app_url, browser_page):
    """From the editor (the shaping machine's preset), its link to the course-project scene shows the own
    mechanism; the button makes an assignment of it with per-student |OA|; a student's link opens /project with
    that very linkage (its frame and groups the editor's, |OA| the student's)."""
    from test_editor import act
    page = browser_page
    page.goto("/editor?lang=en")
    page.wait_for_function("() => document.querySelector('#editor-drawing')?.dataset.state !== undefined")
    act(page, lambda: page.select_option("#editor-preset", "shaping_machine"))
    page.wait_for_function("() => document.querySelector('#editor-open-dynamics a[data-scene=\"course-project\"]')")
    with page.expect_navigation(url=re.compile(r"/scenes/course-project")):    # not the editor rewriting its address
        page.click('#editor-open-dynamics a[data-scene="course-project"]')
    page.wait_for_selector("#project-variant-own a")
    editor_linkage = read_base64url(re.search(r"[?&]m=([\w-]+)", page.url).group(1))
    page.click("#make-assignment")
    page.wait_for_selector("#assignment-form")
    assert page.locator("#assignment-form").get_attribute("data-variant") == "own"
    row = page.locator('.slider-rule[data-slider="l_OA"]')
    row.locator('[name="vary"]').check()
    row.locator('[name="vary_min"]').fill("0.09")
    row.locator('[name="vary_max"]').fill("0.11")
    row.locator('[name="vary_step"]').fill("0.005")
    page.click("#create-assignment")
    page.wait_for_selector("#assignment-links:not([hidden])")
    page.locator("#variants-turning").wait_for()
    student_url = page.locator("#student-link").get_attribute("href")
    assignment_id = re.search(r"/assignments/([\w-]+)", student_url).group(1)
    context = chromium.new_context(base_url=app_url, viewport={"width": 1400, "height": 900})
    student = open_as_student(context, student_url, "Iryna Bondar")
    variant = own_variant(app_url, assignment_id, student.link)
    linkage = read_base64url(re.search(r"[?&]m=([\w-]+)", student.locator("#open-project").get_attribute("href"))
                             .group(1))
    assert linkage["input"]["length"] == pytest.approx(variant["values"]["l_OA"])
    assert linkage["groups"] == editor_linkage["groups"] and linkage["frame"] == editor_linkage["frame"]
    assert student.problems == []
    context.close()


PROJECT_BODY_JS = """async ({ scene, documents }) => {
  const entry = document.querySelector('script[type="module"][src*="project_scene.js"]').src;
  const { projectBody } = await import(entry);
  const { resolveAddressVariants } = await import(new URL("../common/model/address_mechanism.js", entry));
  resolveAddressVariants(scene, documents);
  return Object.fromEntries(scene.variants.map((variant) => [variant.id, projectBody(variant)]));
}"""


def test_the_scene_page_and_the_server_write_the_same_project_request(browser_page):
    """project_scene.js's projectBody against requests.project_body at the defaults, for every variant (the own
    one resolved with a hand-built six-bar and its estimate): the same request, exactly."""
    from server.core.structure.estimate import estimated_dynamics
    from server.lessons.requests import address_variant, defaults, project_body
    from test_dynamics_estimate import HAND_BUILT
    documents = {"m": HAND_BUILT, "d": estimated_dynamics(HAND_BUILT)}
    scene = scenes()["course-project"]
    page = browser_page
    page.goto("/scenes/course-project?lang=en")
    page.wait_for_selector("#project-variant-shaping_machine a")
    built = page.evaluate(PROJECT_BODY_JS, {"scene": json.loads(scene.model_dump_json()), "documents": documents})
    for variant in scene.variants:
        variant = address_variant(variant, documents)
        assert built[variant.id] == project_body(variant, defaults(variant)), variant.id
