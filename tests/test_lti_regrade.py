"""An instructor's change that changes a score reaches the LMS gradebook too: the reset on the LTI results page
and the deletion of a student through the results token each post the LMS student's grade again (0). One app
server (`python3 -m server`), the test platform of tests/lti_platform.py; the gradebook is polled with a guard
against a hang only.
"""
from __future__ import annotations

import re

import httpx
import pytest

from lti_app import ADMIN_TOKEN, API, SPEC, app_servers, make_assignment, results, right_answer
from lti_platform import INSTRUCTOR, LEARNER, Browser, Platform, User

DANA = User("lms-dana-2", "Dana", "Petrenko")
EMIL = User("lms-emil-3", "Emil", "Horvat")
TEACHER = User("lms-teacher-9", "Tetiana", "Moroz")
QUESTION = SPEC["questions"][0]["id"]


@pytest.fixture(scope="module")
def lms(tmp_path_factory):
    with app_servers(tmp_path_factory.mktemp("lti-regrade"), count=1) as servers:
        platform = Platform()
        with platform.running():
            assert platform.register(servers[0].url, ADMIN_TOKEN).status_code == 201
            created = make_assignment(servers[0].url)
            link = platform.add_link("course-1", {"assignment": created["id"]}, SPEC["title"], {
                "label": SPEC["title"], "scoreMaximum": len(SPEC["questions"]), "resourceId": created["id"]})
            yield servers[0].url, platform, created, link


def right_on_first(base: str, platform: Platform, created: dict, link: str, user: User) -> Browser:
    """The learner launches and answers QUESTION right; their grade 1 arrives."""
    browser = Browser(platform)
    page = browser.launch(platform.launch(user, [LEARNER], resource_link_id=link))
    assert page.status_code == 200, page.text[:500]
    variant = browser.http.get(f"{base}{API}/assignments/{created['id']}/me").json()
    answered = browser.http.post(f"{base}{API}/assignments/{created['id']}/submissions",
                                 json={"question": QUESTION, "answer": right_answer(variant, QUESTION)},
                                 headers={"Origin": base})
    assert answered.status_code == 200 and answered.json()["right"], answered.text
    platform.wait_for_grade(user, lambda s: s.get("scoreGiven") == 1, platform.links[link]["lineitem"])
    return browser


def test_a_reset_on_the_lti_results_page_posts_the_grade_again(lms):
    base, platform, created, link = lms
    right_on_first(base, platform, created, link, DANA)
    teacher = Browser(platform)
    page = teacher.launch(platform.launch(TEACHER, [INSTRUCTOR], resource_link_id=link))
    assert page.status_code == 200 and DANA.name in page.text, page.text[:800]
    scroll_box = re.search(r'<div class="table-wrap"([^>]*)>', page.text).group(1)   # the wide table: reached, named
    assert 'tabindex="0"' in scroll_box and 'role="region"' in scroll_box
    assert re.search(r'aria-label="(Results|Результаты|Результати)"', scroll_box), scroll_box
    row = re.search(r'data-student="([0-9a-f]{16})" data-name="' + DANA.name, page.text)
    reset = teacher.http.post(f"{base}/lti/results/{created['id']}/students/{row.group(1)}/reset")
    assert reset.status_code == 303, reset.text[:500]
    score = platform.wait_for_grade(DANA, lambda s: s.get("scoreGiven") == 0, platform.links[link]["lineitem"])
    assert score["scoreMaximum"] == len(SPEC["questions"])
    anonymous = httpx.post(f"{base}/lti/results/{created['id']}/students/{row.group(1)}/reset")
    assert anonymous.status_code == 401                     # no instructor session: nothing reset


def test_deleting_a_student_by_the_results_token_posts_the_grade_again(lms):
    base, platform, created, link = lms
    right_on_first(base, platform, created, link, EMIL)
    row = next(r for r in results(base, created)["students"] if r["student"] == EMIL.name)
    deleted = httpx.delete(f"{base}{API}/assignments/{created['id']}/results/{created['results_token']}/students/"
                           f"{row['id']}")
    assert deleted.status_code == 204, deleted.text
    platform.wait_for_grade(EMIL, lambda s: s.get("scoreGiven") == 0, platform.links[link]["lineitem"])
