"""The LTI tool as a university deploys it: two app servers on one PostgreSQL behind nginx (the shipped
deploy/nginx/mdl.conf, tests/nginx.py), launched from the test platform (tests/lti_platform.py) through nginx.

nginx hands requests to the servers in turn, so the login initiation and the launch that follows it land on
different servers (read from nginx's access log, which names the upstream of each request); the launch must still
find its state and nonce (kept in the database), and the student's right answer must reach the platform's
gradebook (the score posted by whichever server took the submission, with a token from the platform's token
endpoint). The gradebook is polled with a guard against a hang, never timed.
"""
from __future__ import annotations

import re
from urllib.parse import urlsplit

import pytest

from lti_app import ADMIN_TOKEN, API, SPEC, app_servers, make_assignment, right_answer
from lti_platform import LEARNER, Browser, Platform, User, page_text
from nginx import nginx_proxy
from postgres import fresh_database, postgres_url  # noqa: F401 (postgres_url is a fixture)

DANA = User("lms-dana-3", "Dana", "Horvat")
LAUNCH_TRIES = 4               # nginx's round robin alternates; a stray request in between only delays it


@pytest.fixture(scope="module")
def deployment(tmp_path_factory, postgres_url):
    directory = tmp_path_factory.mktemp("lti-deployment")
    env = {"MDL_DATABASE_URL": fresh_database(postgres_url), "MDL_FORWARDED_ALLOW_IPS": "127.0.0.1"}
    with app_servers(directory, count=2, env=env) as servers, \
            nginx_proxy(directory / "nginx", [s.port for s in servers]) as proxy:
        yield servers, proxy


def upstream_of(proxy, path: str, after: int) -> list[str]:
    """The upstream servers of the requests for `path` in nginx's access log since line `after`."""
    return [re.search(r"upstream=(\S+)", line).group(1) for line in proxy.access_log()[after:]
            if f" {path}" in line and "upstream=" in line]


def test_a_launch_through_nginx_across_both_servers_passes_a_grade_back(deployment):
    servers, proxy = deployment
    platform = Platform()
    with platform.running():
        registered = platform.register(proxy.url, ADMIN_TOKEN)
        assert registered.status_code == 201, registered.text
        assert platform.tool.launch_url.startswith(proxy.url), platform.tool     # the tool's URLs are nginx's
        assignment = make_assignment(proxy.url)
        link = platform.add_link("course-1", {"assignment": assignment["id"]}, SPEC["title"],
                                 {"label": SPEC["title"], "scoreMaximum": len(SPEC["questions"]),
                                  "resourceId": assignment["id"]})
        for _ in range(LAUNCH_TRIES):
            browser = Browser(platform)
            seen = len(proxy.access_log())
            page = browser.launch(platform.launch(DANA, [LEARNER], resource_link_id=link))
            assert page.status_code == 200, (page.status_code, page_text(page)[:800], servers[0].log_tail(1500),
                                              servers[1].log_tail(1500))
            logins, launches = upstream_of(proxy, "/lti/login", seen), upstream_of(proxy, "/lti/launch", seen)
            assert len(logins) == 1 and len(launches) == 1, proxy.access_log()[seen:]
            if logins != launches:
                break
        else:
            pytest.fail(f"in {LAUNCH_TRIES} launches nginx never sent the login and the launch to different "
                        f"servers:\n" + "\n".join(proxy.access_log()))
        assert urlsplit(str(page.url)).path == f"/assignments/{assignment['id']}" and DANA.name in page.text

        me = browser.http.get(f"{proxy.url}{API}/assignments/{assignment['id']}/me")
        assert me.status_code == 200 and me.json()["student"] == DANA.name, me.text
        question = SPEC["questions"][0]["id"]
        outcome = browser.http.post(f"{proxy.url}{API}/assignments/{assignment['id']}/submissions",
                                    json={"question": question, "answer": right_answer(me.json(), question)},
                                    headers={"Origin": proxy.url})
        assert outcome.status_code == 200 and outcome.json()["right"], outcome.text
        score = platform.wait_for_grade(DANA, lambda s: s.get("scoreGiven") == 1, platform.links[link]["lineitem"])
        assert score["scoreMaximum"] == len(SPEC["questions"]) and score["userId"] == DANA.id
