"""The tool inside an LMS page, in Chromium: a course page of the test platform (tests/lti_platform.py) holds the
launch in an `<iframe>`; the login initiation, the platform's authentication answer and the launch all happen in
the frame, as in Moodle.

- Same site (platform and tool both on 127.0.0.1, other ports): the student lands on the assignment's page in the
  frame, answers there, and the score arrives in the platform's gradebook.
- Different sites (platform on `localhost`, tool on `127.0.0.1`), in a Chromium started with its third-party
  cookie phase-out switch (`--test-third-party-cookie-phaseout`; over plain http a cookie set inside a
  cross-site frame is refused in any case: SameSite=Lax is not kept there, SameSite=None needs Secure): the
  frame offers "Open in a new window" (the tool tells a cross-site frame by Sec-Fetch-Dest/Site); the new
  window holds the session first-party, the student answers there, and the window's ticket works once.
No console errors on either page; screenshots in test-artifacts/ (lti-frame-*.png).
"""
from __future__ import annotations

import re

import httpx
import pytest

from conftest import ARTIFACTS, CHROMIUM_ARGS, WAIT_MS
from lti_app import ADMIN_TOKEN, SPEC, app_servers, make_assignment, right_answer
from lti_platform import LEARNER, Platform, User

QUESTION = SPEC["questions"][0]["id"]
ERIK = User("lms-erik-4", "Erik", "Johansson")
FARIDA = User("lms-farida-6", "Farida", "Aliyeva")


@pytest.fixture(scope="module")
def tool(tmp_path_factory):
    with app_servers(tmp_path_factory.mktemp("lti-frames"), count=1) as servers:
        yield servers[0]


@pytest.fixture(scope="module")
def assignment(tool):
    return make_assignment(tool.url)


@pytest.fixture(scope="module")
def platforms(tool, assignment):
    """Two LMSs registered in the app: one on the tool's site (127.0.0.1), one on another site (localhost)."""
    same, cross = Platform(host="127.0.0.1", name="Moodle on 127.0.0.1"), Platform(host="localhost",
                                                                                  name="Moodle on localhost")
    with same.running(), cross.running():
        for platform in (same, cross):
            response = platform.register(tool.url, ADMIN_TOKEN)
            assert response.status_code == 201, response.text
            platform.link = platform.add_link("course-1", {"assignment": assignment["id"]}, SPEC["title"], {
                "label": SPEC["title"], "scoreMaximum": len(SPEC["questions"]), "resourceId": assignment["id"]})
        yield same, cross


def watched(context):
    page = context.new_page()
    page.problems = []
    page.on("console", lambda message: message.type == "error" and page.problems.append(message.text))
    page.on("pageerror", lambda error: page.problems.append(str(error)))
    return page


def answer_right(where, assignment: dict) -> None:
    """Answer QUESTION right on the student page in `where` (a frame or a page) and wait for its ✓."""
    where.locator(f"#answer-{QUESTION}").wait_for()
    variant = where.evaluate(f"() => fetch('/api/v1/assignments/{assignment['id']}/me').then(r => r.json())")
    feedback = where.locator(f"#feedback-{QUESTION}")
    before = feedback.inner_text()
    where.fill(f"#answer-{QUESTION}", f"{right_answer(variant, QUESTION):.6g}")
    where.click(f"#question-{QUESTION} button")
    where.wait_for_function("([id, before]) => document.getElementById(id).textContent !== before",
                            arg=[f"feedback-{QUESTION}", before])
    assert "✓" in feedback.inner_text(), feedback.inner_text()


def test_a_student_answers_inside_the_lms_frame(chromium, tool, assignment, platforms):
    platform = platforms[0]
    context = chromium.new_context(viewport={"width": 1400, "height": 1000})
    try:
        page = watched(context)
        page.goto(platform.course_page_url(platform.launch(ERIK, [LEARNER], resource_link_id=platform.link)))
        inner = page.frame(name="tool")                 # one frame, navigated by the launch's forms
        inner.wait_for_url(re.compile(rf"/assignments/{assignment['id']}(\?|$)"))
        inner.locator(f"#answer-{QUESTION}").wait_for()
        assert ERIK.name in inner.locator("body").inner_text()
        answer_right(inner, assignment)
        page.screenshot(path=ARTIFACTS / "lti-frame-same-site.png", full_page=True)
        score = platform.wait_for_grade(ERIK, lambda s: s.get("scoreGiven") == 1, platform.links[platform.link]
                                        ["lineitem"])
        assert score["userId"] == ERIK.id and score["scoreMaximum"] == len(SPEC["questions"])
        assert page.problems == [], page.problems
    finally:
        context.close()


@pytest.fixture(scope="module")
def no_third_party_cookies(chromium):
    """A Chromium of its own that blocks third-party cookies."""
    browser = chromium.browser_type.launch(executable_path="/usr/bin/chromium", headless=True,
                                           args=CHROMIUM_ARGS + ["--test-third-party-cookie-phaseout"])
    yield browser
    browser.close()


def test_from_another_site_the_frame_opens_the_assignment_in_a_new_window(no_third_party_cookies, tool, assignment,
                                                                          platforms):
    platform = platforms[1]
    context = no_third_party_cookies.new_context(viewport={"width": 1400, "height": 1000})
    context.set_default_timeout(WAIT_MS)
    context.set_default_navigation_timeout(WAIT_MS)
    try:
        page = watched(context)
        page.goto(platform.course_page_url(platform.launch(FARIDA, [LEARNER], resource_link_id=platform.link)))
        opener = page.frame_locator("#tool").get_by_role("link", name=re.compile("new window", re.I))
        opener.wait_for()
        ticket = opener.evaluate("a => a.href")
        page.screenshot(path=ARTIFACTS / "lti-frame-cross-site.png", full_page=True)
        with context.expect_page() as opened:
            opener.click()
        window = opened.value
        window.problems = []
        window.on("console", lambda message: message.type == "error" and window.problems.append(message.text))
        window.on("pageerror", lambda error: window.problems.append(str(error)))
        window.wait_for_url(re.compile(rf"/assignments/{assignment['id']}(\?|$)"))
        assert FARIDA.name in window.locator("body").inner_text()
        answer_right(window, assignment)
        window.screenshot(path=ARTIFACTS / "lti-frame-new-window.png", full_page=True)
        score = platform.wait_for_grade(FARIDA, lambda s: s.get("scoreGiven") == 1, platform.links[platform.link]
                                        ["lineitem"])
        assert score["userId"] == FARIDA.id
        with httpx.Client(follow_redirects=True) as thief:          # the ticket was single-use
            reused = thief.get(ticket)
            assert 400 <= reused.status_code < 500, (ticket, reused.status_code)
            me = thief.get(f"{tool.url}/api/v1/assignments/{assignment['id']}/me")
            assert me.status_code == 401, (me.status_code, reused.headers.get_list("set-cookie"))
        assert page.problems == [] and window.problems == [], (page.problems, window.problems)
    finally:
        context.close()
