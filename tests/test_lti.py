"""The app as an LTI 1.3 tool, launched from a real test platform (tests/lti_platform.py) over HTTP.

Two app servers (`python3 -m server`, as deployed) share one SQLite file; the platform (its own keys, /auth,
/token, AGS, NRPS, deep linking return) runs in this process. Most tests talk to the first server; the last
logs in on one server and launches on the other, without the state cookie, so the state kept in the database is
what carries the launch. The module's story, in order: registration (and its refusals); the instructor's deep
linking picks an assignment (a signed content item with the assignment and a line item arrives); a learner's
launch lands on the student page under the LMS name; a right answer's score arrives in the gradebook, a wrong then
right answer updates it; the instructor's launch shows the results with the NRPS roster; bad launches are refused
with a reason and register nobody.
No assertion depends on the machine's speed: the gradebook is polled with a guard against a hang.
"""
from __future__ import annotations

import time
from urllib.parse import urlsplit

import httpx
import pytest

from lti_app import ADMIN_TOKEN, API, SPEC, app_servers, make_assignment, results, right_answer
from lti_platform import DL, INSTRUCTOR, LEARNER, LTI, Browser, Platform, User, forms_of, page_text

ANNA = User("lms-anna-7", "Anna", "Kovalenko")
BORIS = User("lms-boris-8", "Boris", "Lebedev")
CLARA = User("lms-clara-9", "Clara", "Novak")          # on the course roster only: never launches
TEACHER = User("lms-teacher-1", "Tamara", "Sidorova")
MALLORY = User("lms-mallory-0", "Mallory", "Forger")    # every launch of hers is bad
RAY = User("lms-ray-5", "Ray", "Replay")                 # launches once, then replays it
GLEB = User("lms-gleb-2", "Gleb", "Orlov")
HANA = User("lms-hana-12", "Hana", "Sato")
GUARD_SECONDS = 120          # waits are guards against a hang, never timings
QUESTIONS = [q["id"] for q in SPEC["questions"]]


@pytest.fixture(scope="module")
def servers(tmp_path_factory):
    with app_servers(tmp_path_factory.mktemp("lti-app"), count=2) as running:
        yield running


@pytest.fixture(scope="module")
def platform(servers):
    platform = Platform()
    with platform.running():
        response = platform.register(servers[0].url, ADMIN_TOKEN)
        assert response.status_code == 201, response.text
        yield platform


@pytest.fixture(scope="module")
def story(servers, platform):
    """What the tests share: the assignment, and the resource link the instructor's deep linking made."""
    return {"assignment": make_assignment(servers[0].url)}


def fail_message(servers, response: httpx.Response | None = None) -> str:
    shown = f"{response.status_code} {response.url}\n{page_text(response)[:800]}\n" if response is not None else ""
    return shown + "server log:\n" + servers[0].log_tail(2500)


# --- registration ---------------------------------------------------------------------------------------------

def test_registration_needs_the_admin_token_and_real_urls(servers, platform):
    other = Platform()                                      # not running: only its registration body is sent
    url = f"{servers[0].url}{API}/lti/platforms"
    anonymous = httpx.post(url, json=other.registration())
    assert anonymous.status_code in (401, 403) and anonymous.text, anonymous.text
    wrong = httpx.post(url, json=other.registration(), headers={"Authorization": "Bearer not-the-token"})
    assert wrong.status_code in (401, 403), wrong.text
    for field in ("auth_login_url", "key_set_url", "auth_token_url"):
        bad = httpx.post(url, json=other.registration() | {field: "not a url"},
                         headers={"Authorization": f"Bearer {ADMIN_TOKEN}"})
        assert bad.status_code == 422 and field in bad.text, (field, bad.text)
    listed = httpx.get(url, headers={"Authorization": f"Bearer {ADMIN_TOKEN}"})
    assert listed.status_code == 200, listed.text
    issuers = [p["issuer"] for p in listed.json()] if isinstance(listed.json(), list) else \
        [p["issuer"] for p in listed.json()["platforms"]]
    assert issuers == [platform.issuer]                     # the refused ones are not there
    assert httpx.get(url).status_code in (401, 403)
    tool = httpx.get(f"{servers[0].url}{API}/lti/tool")
    assert tool.status_code == 200 and tool.json()["jwks_url"] == platform.tool.jwks_url
    keys = httpx.get(platform.tool.jwks_url).json()["keys"]
    assert keys and all(k["kty"] == "RSA" and k.get("kid") and "d" not in k for k in keys)


# --- deep linking, the learner's launch, grades --------------------------------------------------------------

def pick(page: httpx.Response, wanted: str) -> dict:
    """The picker's form with the button that chooses `wanted` (its value, e.g. "scene:<id>", or an assignment's
    id within it), that button's name and value as `extra`."""
    for form in forms_of(page.text):
        buttons = [b for b in form["buttons"] if b[0] and b[1] == wanted] or \
                  [b for b in form["buttons"] if b[0] and wanted in str(b[1])]
        if buttons:
            return form | {"extra": {buttons[0][0]: buttons[0][1]}}
        if wanted in str(form["fields"]):
            return form | {"extra": {}}
    raise AssertionError(f"no form of the picker chooses {wanted}:\n{page.text[:3000]}")


def deep_link(servers, platform, wanted: str) -> dict:
    """The instructor's deep linking launch choosing `wanted`: the content item the platform received."""
    browser = Browser(platform)
    picker = browser.launch(platform.launch(TEACHER, [INSTRUCTOR], message_type="LtiDeepLinkingRequest"))
    assert picker.status_code == 200, fail_message(servers, picker)
    form = pick(picker, wanted)
    kept = len(platform.deep_links)
    returned = browser.post_form(str(picker.url), form, form["extra"])
    assert returned.status_code == 200 and str(returned.url) == platform.deep_link_return_url, \
        fail_message(servers, returned) + f"\nplatform refused: {platform.refusals}"
    assert len(platform.deep_links) == kept + 1
    items = platform.deep_links[-1][DL + "content_items"]
    assert len(items) == 1 and items[0]["type"] == "ltiResourceLink"
    assert items[0]["url"] == platform.tool.launch_url
    return items[0]


def test_deep_linking_returns_a_signed_item_with_the_assignment_and_a_line_item(servers, platform, story):
    assignment = story["assignment"]["id"]
    item = deep_link(servers, platform, assignment)
    assert item["custom"] == {"assignment": assignment}
    assert item["lineItem"]["scoreMaximum"] == len(QUESTIONS) and item["lineItem"]["resourceId"] == assignment
    story["link"] = item["resource_link_id"]
    story["lineitem"] = platform.links[story["link"]]["lineitem"]


def test_deep_linking_a_scene_or_a_new_assignment(servers, platform, story):
    scene = deep_link(servers, platform, "scene:transfer-functions")
    assert scene["custom"] == {"scene": "transfer-functions"} and "lineItem" not in scene
    made = deep_link(servers, platform, "new:transfer-functions")
    new_id = made["custom"]["assignment"]
    assert new_id != story["assignment"]["id"]
    info = httpx.get(f"{servers[0].url}{API}/assignments/{new_id}").json()
    assert info["scene"] == "transfer-functions" and info["questions"]
    assert made["lineItem"]["scoreMaximum"] == len(info["questions"]) and made["lineItem"]["resourceId"] == new_id


def test_a_learner_cannot_choose_content(servers, platform):
    page = Browser(platform).launch(platform.launch(User("lms-lena-11", "Lena", "Curious"), [LEARNER],
                                                    message_type="LtiDeepLinkingRequest", context="course-2"))
    assert_refused(servers, page, "not_instructor")


def link_of(platform, story) -> str:
    """The resource link the deep linking made; when that failed, one set up by hand in the LMS (custom
    assignment=<id> and a line item), so that the later tests still say what they test."""
    if "link" not in story:
        assignment = story["assignment"]["id"]
        story["link"] = platform.add_link("course-1", {"assignment": assignment}, SPEC["title"], {
            "label": SPEC["title"], "scoreMaximum": len(QUESTIONS), "resourceId": assignment})
        story["lineitem"] = platform.links[story["link"]]["lineitem"]
    return story["link"]


def learner_launch(platform, story, user: User, browser: Browser | None = None) -> tuple[Browser, httpx.Response]:
    browser = browser or Browser(platform)
    page = browser.launch(platform.launch(user, [LEARNER], resource_link_id=link_of(platform, story)))
    return browser, page


def my_variant(servers, story, browser: Browser) -> dict:
    response = browser.http.get(f"{servers[0].url}{API}/assignments/{story['assignment']['id']}/me")
    assert response.status_code == 200, fail_message(servers, response)
    return response.json()


def submit(servers, story, browser: Browser, question: str, answer: float) -> dict:
    response = browser.http.post(f"{servers[0].url}{API}/assignments/{story['assignment']['id']}/submissions",
                                 json={"question": question, "answer": answer},
                                 headers={"Origin": servers[0].url})
    assert response.status_code == 200, fail_message(servers, response)
    return response.json()


def test_a_learners_launch_opens_the_student_page_under_the_lms_name(servers, platform, story):
    browser, page = learner_launch(platform, story, ANNA)
    assignment = story["assignment"]["id"]
    assert page.status_code == 200, fail_message(servers, page)
    assert urlsplit(str(page.url)).path == f"/assignments/{assignment}", page.url
    assert 'id="assignment-data"' in page.text and ANNA.name in page.text
    assert my_variant(servers, story, browser)["student"] == ANNA.name
    again = Browser(platform)                                        # another device, the login by GET: the same
    again.launch(platform.launch(ANNA, [LEARNER], resource_link_id=link_of(platform, story)), method="GET")
    assert my_variant(servers, story, again)["variant"] == my_variant(servers, story, browser)["variant"]
    rows = [row for row in results(servers[0].url, story["assignment"])["students"] if row["student"] == ANNA.name]
    assert len(rows) == 1
    story["anna"] = browser


def test_a_right_answer_arrives_in_the_gradebook(servers, platform, story):
    browser = story["anna"]
    variant = my_variant(servers, story, browser)
    assert submit(servers, story, browser, QUESTIONS[0], right_answer(variant, QUESTIONS[0]))["right"]
    score = platform.wait_for_grade(ANNA, lambda s: s.get("scoreGiven") == 1, story["lineitem"])
    assert score["scoreMaximum"] == len(QUESTIONS) and score["userId"] == ANNA.id
    assert score["activityProgress"] in ("Started", "InProgress", "Submitted", "Completed")
    assert score["gradingProgress"] in ("FullyGraded", "Pending", "PendingManual")
    assert platform.token_requests and all(r["client_assertion_type"].endswith("jwt-bearer")
                                           for r in platform.token_requests)


def test_a_wrong_then_right_answer_updates_the_grade(servers, platform, story):
    browser, page = learner_launch(platform, story, BORIS)
    assert page.status_code == 200, fail_message(servers, page)
    variant = my_variant(servers, story, browser)
    answer = right_answer(variant, QUESTIONS[1])
    assert not submit(servers, story, browser, QUESTIONS[1], answer * 1.5 + 1)["right"]
    wrong = platform.wait_for_grade(BORIS, lambda s: s.get("scoreGiven") == 0, story["lineitem"])
    assert submit(servers, story, browser, QUESTIONS[1], answer)["right"]
    right = platform.wait_for_grade(BORIS, lambda s: s.get("scoreGiven") == 1, story["lineitem"])
    assert right["timestamp"] >= wrong["timestamp"] and right["scoreMaximum"] == len(QUESTIONS)


def test_the_instructors_launch_shows_the_results_with_the_nrps_roster(servers, platform, story):
    platform.enrol("course-1", CLARA, [LEARNER])
    browser = Browser(platform)
    page = browser.launch(platform.launch(TEACHER, [INSTRUCTOR], resource_link_id=link_of(platform, story)))
    assert page.status_code == 200, fail_message(servers, page)
    text = page_text(page)
    for user in (ANNA, BORIS, CLARA):
        assert user.name in page.text or user.name in text, (user.name, text[:2000])
    assert TEACHER.name not in [row["student"] for row in results(servers[0].url, story["assignment"])["students"]]


def test_the_instructor_resets_a_student_and_the_gradebook_is_told(servers, platform, story):
    """The results page's reset removes Anna's answers; her grade in the LMS goes back to 0."""
    browser = Browser(platform)
    page = browser.launch(platform.launch(TEACHER, [INSTRUCTOR], resource_link_id=link_of(platform, story)))
    assert page.status_code == 200, fail_message(servers, page)
    platform.wait_for_grade(ANNA, lambda s: s.get("scoreGiven") == 1, story["lineitem"])
    anna = next(row for row in results(servers[0].url, story["assignment"])["students"] if row["student"] == ANNA.name)
    form = next(f for f in forms_of(page.text) if f"/students/{anna['id']}/reset" in f["action"])
    after = browser.post_form(str(page.url), form)
    assert after.status_code == 200, fail_message(servers, after)
    score = platform.wait_for_grade(ANNA, lambda s: s.get("scoreGiven") == 0, story["lineitem"])
    assert score["scoreMaximum"] == len(QUESTIONS)


def test_a_link_without_a_line_item_gets_one_from_the_tool(servers, platform, story):
    """A link typed in by hand with the assignment but no grade column: the tool finds or makes its line item
    in the course's line items container (AGS lineitems), and the score goes there."""
    assignment = story["assignment"]["id"]
    link = platform.add_link("course-1", {"assignment": assignment}, "Typed in by hand")
    before = set(platform.lineitems)
    browser = Browser(platform)
    page = browser.launch(platform.launch(GLEB, [LEARNER], resource_link_id=link))
    assert page.status_code == 200, fail_message(servers, page)
    variant = my_variant(servers, story, browser)
    assert submit(servers, story, browser, QUESTIONS[0], right_answer(variant, QUESTIONS[0]))["right"]
    score = platform.wait_for_grade(GLEB, lambda s: s.get("scoreGiven") == 1,
                                    lineitem=lambda: next(iter(set(platform.lineitems) - before), None))
    made = platform.lineitems[score["lineitem"]]
    assert made["scoreMaximum"] == len(QUESTIONS) and assignment in (made.get("tag"), made.get("resourceId"))


def test_a_grade_the_lms_could_not_take_is_posted_when_it_is_back(servers, platform, story):
    """The platform's token endpoint down: the student's answer is accepted all the same, the score waits with
    the reason (the administrator's list), and reaches the gradebook on the tool's own retry once the LMS is back."""
    browser, page = learner_launch(platform, story, HANA)
    assert page.status_code == 200, fail_message(servers, page)
    variant = my_variant(servers, story, browser)
    refused_before = platform.refusals.count("the token endpoint is down (an outage the test made)")
    platform.token_outage = True
    try:
        assert submit(servers, story, browser, QUESTIONS[0], right_answer(variant, QUESTIONS[0]))["right"]
        admin = {"Authorization": f"Bearer {ADMIN_TOKEN}"}
        deadline = time.monotonic() + GUARD_SECONDS
        while not any("503" in (p.get("last_error") or "") for p in httpx.get(
                f"{servers[0].url}{API}/lti/platforms", headers=admin).json().get("pending_scores", [])):
            assert time.monotonic() < deadline, f"no failed passback listed; platform refused {platform.refusals}"
            time.sleep(0.2)
        assert platform.refusals.count("the token endpoint is down (an outage the test made)") > refused_before
        assert platform.grade(HANA, story["lineitem"]) is None
    finally:
        platform.token_outage = False
    score = platform.wait_for_grade(HANA, lambda s: s.get("scoreGiven") == 1, story["lineitem"])
    assert score["userId"] == HANA.id


def test_a_scene_link_opens_the_scene(servers, platform):
    page = Browser(platform).launch(platform.launch(GLEB, [LEARNER], custom={"scene": "transfer-functions"}))
    assert page.status_code == 200 and urlsplit(str(page.url)).path == "/scenes/transfer-functions", \
        fail_message(servers, page)


def test_registration_is_closed_without_an_admin_token(monkeypatch):
    """A server without MDL_ADMIN_TOKEN refuses every registration, saying why (the app in this process)."""
    from fastapi.testclient import TestClient
    from server.api.app import app
    monkeypatch.delenv("MDL_ADMIN_TOKEN", raising=False)
    refused = TestClient(app).post(f"{API}/lti/platforms", json=Platform().registration(),
                                   headers={"Authorization": "Bearer anything"})
    assert refused.status_code == 403 and "MDL_ADMIN_TOKEN" in refused.text, refused.text


# --- refused launches ---------------------------------------------------------------------------------------------

def assert_refused(servers, response: httpx.Response, *codes: str) -> None:
    """A 4xx page giving the reason in words and its code (one of `codes`)."""
    assert 400 <= response.status_code < 500, fail_message(servers, response)
    text = page_text(response).lower() if "html" in response.headers.get("content-type", "") else response.text.lower()
    assert any(code in text for code in codes), (codes, response.status_code, text[:600])


def nobody_named(servers, story, user: User) -> None:
    names = [row["student"] for row in results(servers[0].url, story["assignment"])["students"]]
    assert user.name not in names, names


def mallory_launch(platform, story, **options):
    return platform.launch(MALLORY, [LEARNER], resource_link_id=link_of(platform, story),
                           custom={"assignment": story["assignment"]["id"]}, **options)


def test_a_forged_launch_is_refused(servers, platform, story):
    response = Browser(platform).launch(mallory_launch(platform, story, forged=True))
    assert_refused(servers, response, "bad_signature")
    nobody_named(servers, story, MALLORY)


def test_an_expired_launch_is_refused(servers, platform, story):
    response = Browser(platform).launch(mallory_launch(platform, story, expired=True))
    assert_refused(servers, response, "expired")
    nobody_named(servers, story, MALLORY)


def test_a_replayed_launch_is_refused(servers, platform, story):
    browser = Browser(platform)
    launch = platform.launch(RAY, [LEARNER], resource_link_id=link_of(platform, story))
    first = browser.launch(launch)
    assert first.status_code == 200, fail_message(servers, first)
    same = browser.replay(launch.id_token, launch.state, launch.redirect_uri)
    assert_refused(servers, same, "replayed_nonce", "replayed_state", "unknown_state")
    # the nonce again under a fresh state: a new login, then the old id_token with the new state
    fresh = platform.launch(RAY, [LEARNER], resource_link_id=link_of(platform, story))
    auth_page = browser.login_only(fresh)
    new_state = forms_of(auth_page.text)[0]["fields"]["state"]
    again = browser.replay(launch.id_token, new_state, launch.redirect_uri)
    assert_refused(servers, again, "replayed_nonce")


@pytest.mark.parametrize("case, options, codes", [
    ("unknown issuer at login", {"iss": "http://unknown.example"}, ("unknown_issuer",)),
    ("unknown issuer in the token", {"claims": {"iss": "http://unknown.example"}}, ("unknown_issuer",)),
    # pylti1p3 finds the registration by (iss, aud): another audience is no registration of this tool
    ("wrong audience", {"claims": {"aud": "someone-else", "azp": "someone-else"}},
     ("unknown_issuer", "wrong_audience")),
    ("unregistered deployment", {"deployment_id": "99", "claims": {LTI + "deployment_id": "99"}},
     ("unknown_deployment",)),
])
def test_a_launch_from_nowhere_is_refused(servers, platform, story, case, options, codes):
    response = Browser(platform).launch(mallory_launch(platform, story, **options))
    assert_refused(servers, response, *codes)
    nobody_named(servers, story, MALLORY)


# --- several servers: the login state in the database -----------------------------------------------------------

def test_login_on_one_server_and_launch_on_the_other_without_the_state_cookie(servers, platform, story):
    first, second = servers
    browser = Browser(platform)
    launch = platform.launch(CLARA, [LEARNER], resource_link_id=link_of(platform, story))
    auth_page = browser.login_only(launch)                           # the login on the first server
    assert auth_page.status_code == 200, auth_page.text
    form = forms_of(auth_page.text)[0]
    assert form["action"].startswith(first.url)
    browser.http.cookies.clear()                                     # the state cookie does not come back (a frame)
    page = browser.post_form(form["action"], form | {"action": form["action"].replace(first.url, second.url)})
    assert page.status_code == 200, fail_message(servers, page)
    assert urlsplit(str(page.url)).path == f"/assignments/{story['assignment']['id']}"
    variant = browser.http.get(f"{second.url}{API}/assignments/{story['assignment']['id']}/me")
    assert variant.status_code == 200 and variant.json()["student"] == CLARA.name, variant.text
