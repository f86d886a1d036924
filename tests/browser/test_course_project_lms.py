"""A course-project assignment placed in an LMS, in Chromium: the instructor makes an assignment for the shaping
machine with per-student |OA| and cutting force P in the builder (clicking and typing), places it in the course by
the test platform's deep linking (tests/lti_platform.py: the launch in the course page's frame, the tool's picker,
the signed content item back to the platform, which makes the resource link and its line item); two students
launch it from the course page, each in a browser of their own, see different variant numbers, open their variant
on the course-project page, read J_fw and M_b (by the groups and by Zhukovsky's lever) off it and type them in,
one all right, the other one wrong; both scores arrive in the platform's gradebook (polled, with a guard against a
hang only). One app server (`python3 -m server`, tests/lti_app.py) and one platform for the module; no console
errors; screenshots in test-artifacts/ (course-project-lms-*.png).
"""
from __future__ import annotations

import re

import pytest

from conftest import ARTIFACTS
from lti_app import ADMIN_TOKEN, API, app_servers
from lti_platform import DL, INSTRUCTOR, LEARNER, Platform, User
from test_project_assignment_flow import QUESTIONS, answer, make_assignment, project_facts

pytestmark = pytest.mark.browser
TEACHER = User("lms-teacher-21", "Tamara", "Sidorova")
LEARNERS = [User("lms-iryna-21", "Iryna", "Bondar"), User("lms-petro-22", "Petro", "Hnatiuk"),
            User("lms-oksana-23", "Oksana", "Lysenko"), User("lms-dmytro-24", "Dmytro", "Savchuk")]
VIEWPORT = {"width": 1400, "height": 1000}


@pytest.fixture(scope="module")
def tool(tmp_path_factory):
    with app_servers(tmp_path_factory.mktemp("lti-course-project")) as servers:
        yield servers[0]


@pytest.fixture(scope="module")
def platform(tool):
    platform = Platform()
    with platform.running():
        response = platform.register(tool.url, ADMIN_TOKEN)
        assert response.status_code == 201, response.text
        yield platform


def watched_context(chromium, tool):
    """A browser of its own whose every page keeps its console errors and uncaught exceptions in `problems`."""
    context = chromium.new_context(base_url=tool.url, viewport=VIEWPORT)
    context.problems = []

    def watch(page):
        page.on("console", lambda message: message.type == "error" and context.problems.append(
            f"{page.url}: {message.text}"))
        page.on("pageerror", lambda error: context.problems.append(f"{page.url}: {error}"))
    context.on("page", watch)
    return context


def place_in_course(page, platform, assignment_id: str) -> str:
    """The instructor's deep linking from the course page: the picker in the frame, the assignment chosen; the
    resource link the platform made of the content item."""
    kept = len(platform.deep_links)
    page.goto(platform.course_page_url(platform.launch(TEACHER, [INSTRUCTOR], message_type="LtiDeepLinkingRequest")))
    frame = page.frame(name="tool")
    choice = frame.locator(f'#lti-picker button[value="assignment:{assignment_id}"]')
    choice.wait_for()
    page.screenshot(path=ARTIFACTS / "course-project-lms-picker.png", full_page=True)
    choice.click()
    frame.locator("h1", has_text="Content added").wait_for()
    assert len(platform.deep_links) == kept + 1, platform.refusals
    item, = platform.deep_links[-1][DL + "content_items"]
    assert item["custom"] == {"assignment": assignment_id}
    assert item["lineItem"]["scoreMaximum"] == len(QUESTIONS) and item["lineItem"]["resourceId"] == assignment_id
    return item["resource_link_id"]


def launch_student(chromium, tool, platform, user: User, link: str, assignment_id: str):
    """The student's launch from the course page: the frame on the assignment page, and the variant the API
    gives this student's session (fetched inside the frame, with its cookie)."""
    context = watched_context(chromium, tool)
    page = context.new_page()
    page.goto(platform.course_page_url(platform.launch(user, [LEARNER], resource_link_id=link)))
    frame = page.frame(name="tool")
    frame.wait_for_url(re.compile(rf"/assignments/{assignment_id}(\?|$)"))
    frame.locator("#questions .question").first.wait_for()
    variant = frame.evaluate(f"() => fetch('{API}/assignments/{assignment_id}/me').then(r => r.json())")
    return context, page, frame, variant


def test_a_course_project_from_the_builder_through_the_lms_to_its_gradebook(chromium, tool, platform):
    instructor = watched_context(chromium, tool)
    page = instructor.new_page()
    student_url, _ = make_assignment(page)
    assignment_id = re.search(r"/assignments/([\w-]+)", student_url).group(1)
    link = place_in_course(page, platform, assignment_id)
    lineitem = platform.links[link]["lineitem"]
    assert platform.lineitems[lineitem]["resourceLinkId"] == link
    assert instructor.problems == [], instructor.problems
    instructor.close()

    students = []
    for user in LEARNERS:                                 # until two students have different variants
        context, page, frame, variant = launch_student(chromium, tool, platform, user, link, assignment_id)
        if any(variant["variant"] == other[4]["variant"] for other in students):
            context.close()
            continue
        students.append((user, context, page, frame, variant))
        if len(students) == 2:
            break
    assert len(students) == 2, "four students, one variant"

    for number, (user, context, page, frame, variant) in enumerate(students):
        who = frame.locator(".assignment-who").inner_text()
        assert user.name in who, who
        assert re.search(r"Variant (\d+) / \d+", who).group(1) == str(variant["variant"]), who
        body, shown = project_facts(context, frame.locator("#open-project").get_attribute("href"))
        assert body["linkage"]["input"]["length"] == pytest.approx(variant["values"]["l_OA"])
        assert body["masses"]["forces"][0]["working"] == pytest.approx(variant["values"]["P"])
        right = len(QUESTIONS) - number                  # the second student misses the last question
        for index, question in enumerate(QUESTIONS):
            typed = shown[question] if index < right else shown[question] * 1.05
            assert ("✓" if index < right else "✗") in answer(frame, question, typed), (user.id, question)
        page.screenshot(path=ARTIFACTS / f"course-project-lms-student-{number + 1}.png", full_page=True)
        score = platform.wait_for_grade(user, lambda s, right=right: s.get("scoreGiven") == right, lineitem)
        assert score["userId"] == user.id and score["scoreMaximum"] == len(QUESTIONS)
        assert context.problems == [], context.problems
        context.close()
    assert {user.id: platform.gradebook[(lineitem, user.id)]["scoreGiven"] for user, *_ in students} == {
        students[0][0].id: len(QUESTIONS), students[1][0].id: len(QUESTIONS) - 1}
