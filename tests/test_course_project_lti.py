"""A course-project assignment launched from an LMS (the test platform of tests/lti_platform.py, over HTTP against
an app server as deployed): two learners with different variants of the shaping machine (per-student |OA| and
cutting force P) launch it from a resource link with a line item, answer J_fw, M_b by the groups and by
Zhukovsky's lever (computed independently by the course-project computation from their own values), and their
scores arrive in the platform's gradebook. No assertion depends on the machine's speed: the gradebook is polled
with a guard against a hang."""
from __future__ import annotations

import httpx
import pytest

from lti_app import ADMIN_TOKEN, API, app_servers, make_assignment, results
from lti_platform import LEARNER, Browser, Platform, User, page_text
from test_course_project_assignment import request_by_hand

QUESTIONS = ["J_flywheel", "M_b_groups", "M_b_lever"]
SPEC = {"scene": "course-project", "variant": "shaping_machine", "title": "Course project (LMS)",
        "sliders": {"l_OA": {"vary": {"min": 0.08, "max": 0.2}, "step": 0.01},
                    "P": {"vary": {"min": 1000, "max": 5000}, "step": 500}},
        "questions": [{"id": q} for q in QUESTIONS], "attempts": 3}
LEARNERS = [User("lms-iryna-1", "Iryna", "Bondar"), User("lms-petro-2", "Petro", "Hnatiuk"),
            User("lms-oksana-3", "Oksana", "Lysenko"), User("lms-dmytro-4", "Dmytro", "Savchuk")]


@pytest.fixture(scope="module")
def server(tmp_path_factory):
    with app_servers(tmp_path_factory.mktemp("lti-project")) as running:
        yield running[0]


@pytest.fixture(scope="module")
def platform(server):
    platform = Platform()
    with platform.running():
        response = platform.register(server.url, ADMIN_TOKEN)
        assert response.status_code == 201, response.text
        yield platform



def test_two_learners_launch_answer_and_their_scores_reach_the_gradebook(server, platform):
    created = make_assignment(server.url, SPEC)
    link = platform.add_link("course-1", {"assignment": created["id"]}, SPEC["title"], {
        "label": SPEC["title"], "scoreMaximum": len(QUESTIONS), "resourceId": created["id"]})
    lineitem = platform.links[link]["lineitem"]
    launched, entered = [], 0
    for user in LEARNERS:                         # until two learners have different variants
        entered += 1
        browser = Browser(platform)
        page = browser.launch(platform.launch(user, [LEARNER], resource_link_id=link))
        assert page.status_code == 200, f"{page.url}\n{page_text(page)[:800]}\n{server.log_tail(2500)}"
        assert 'id="open-project"' in page.text                     # the course-project page's link is there
        mine = browser.http.get(f"{server.url}{API}/assignments/{created['id']}/me").json()
        if all(mine["variant"] != other["variant"] for _, _, other in launched):
            launched.append((user, browser, mine))
        if len(launched) == 2:
            break
    assert len(launched) == 2, "four learners, one variant"
    for user, browser, mine in launched:
        project = httpx.post(f"{server.url}{API}/course-project", json=request_by_hand(mine["values"]), timeout=120)
        assert project.status_code == 200, project.text
        answer = project.json()
        expected = {"J_flywheel": answer["dynamics"]["flywheel"]["flywheel_inertia"],
                    "M_b_groups": answer["kinetostatics"]["balancing_moment"],
                    "M_b_lever": answer["kinetostatics"]["zhukovsky"]["moment"]}
        right = len(QUESTIONS) if user is launched[0][0] else len(QUESTIONS) - 1     # the second misses one
        for question, value in expected.items():
            sent = value if QUESTIONS.index(question) < right else value * 1.05
            outcome = browser.http.post(f"{server.url}{API}/assignments/{created['id']}/submissions",
                                        json={"question": question, "answer": sent},
                                        headers={"Origin": server.url})
            assert outcome.status_code == 200, outcome.text
            assert outcome.json()["right"] == (sent == value), (user.id, question, outcome.json())
        score = platform.wait_for_grade(user, lambda s, right=right: s.get("scoreGiven") == right, lineitem)
        assert score["scoreMaximum"] == len(QUESTIONS) and score["userId"] == user.id
    scores = [row["score"] for row in results(server.url, created)["students"]]
    # a learner who launched with a variant already taken is on the roster too, with nothing answered
    assert sorted(scores) == [0] * (entered - 2) + [len(QUESTIONS) - 1, len(QUESTIONS)]
