"""The LTI tables and pylti1p3's adapters to them, on every backend (SQLite in a temporary file; PostgreSQL on the
server tests/postgres.py starts, a fresh database per test). Two store instances stand for two app servers
(separate connections): what one keeps, the other finds, and what is single-use is used once across both.
The end-to-end launches against a real platform are tests/test_lti.py's.
"""
from __future__ import annotations

import threading
import time

import pytest
import requests

from server.api.access_log import cut
from server.classroom.lti import grades
from server.classroom.lti.launch_state import DatabaseSessionService
from server.classroom.lti.platforms import DatabaseToolConf, PlatformRefused, new_platform
from server.classroom.lti.tool_key import jwks, tool_key
from server.classroom.store import AssignmentRecord, SQLiteStore, StudentRecord
from server.classroom.store.lti_tables import LearnerRecord
from server.classroom.store.migrations import LATEST
from server.classroom.store.postgres import PostgresStore

from postgres import fresh_database, postgres_url  # noqa: F401 (the session's PostgreSQL server)

AGS = {"scope": ["https://purl.imsglobal.org/spec/lti-ags/scope/score"], "lineitem": "https://lms.example/li/1"}


@pytest.fixture(params=["sqlite", "postgresql"])
def database(request, tmp_path) -> str:
    if request.param == "sqlite":
        return str(tmp_path / "classroom.sqlite3")
    return fresh_database(request.getfixturevalue("postgres_url"))


@pytest.fixture()
def stores(database):
    """Two store instances on one database (two servers); closed at the end."""
    opened = [SQLiteStore(database) if not database.startswith("postgres") else PostgresStore(database)
              for _ in range(2)]
    opened[0].create(AssignmentRecord("a1", "hash", 100.0, {"title": "Lab", "questions": [{"id": "q1"}, {"id": "q2"}]},
                                      client="10.0.0.1"))
    yield opened
    for store in opened:
        if hasattr(store, "close"):
            store.close()


def moodle(**changes):
    fields = dict(issuer="https://moodle.example.edu", client_id="abc123", deployment_ids=["1"],
                  auth_login_url="https://moodle.example.edu/mod/lti/auth.php",
                  auth_token_url="https://moodle.example.edu/mod/lti/token.php",
                  key_set_url="https://moodle.example.edu/mod/lti/certs.php", name="Moodle") | changes
    return new_platform(**fields)


class FakeRequest:
    """What pylti1p3's session service asks of a request (nothing here: the state lives in the database)."""
    session: dict = {}

    def is_secure(self) -> bool:
        return True


def test_the_lti_tables_are_migration_6(stores):
    assert LATEST >= 6 and 6 in stores[0].applied_versions()


def test_a_platform_is_registered_once_per_issuer_and_client_id(stores):
    first, second = stores
    platform = moodle()
    assert first.lti_add_platform(platform)
    assert not second.lti_add_platform(moodle())                      # same issuer and client id: refused
    assert second.lti_add_platform(moodle(client_id="other"))         # another client id of the same issuer
    assert [p.client_id for p in second.lti_platforms(platform.issuer)] == ["abc123", "other"]
    assert second.lti_platform(platform.id) == platform


def test_a_registration_names_the_field_of_a_bad_url():
    for field in ("auth_login_url", "auth_token_url", "key_set_url"):
        with pytest.raises(PlatformRefused) as refused:
            moodle(**{field: "http://moodle.example.edu/x"})          # plain http only to this machine
        assert refused.value.field == field
    assert moodle(key_set_url="http://127.0.0.1:8080/jwks").key_set_url.startswith("http://127.0.0.1")
    with pytest.raises(PlatformRefused):
        moodle(deployment_ids=[])


def test_the_tool_conf_finds_a_registration_and_only_its_deployments(stores):
    first, second = stores
    platform = moodle(deployment_ids=["1", "7"])
    first.lti_add_platform(platform)
    conf = DatabaseToolConf(second)
    found = conf.find_registration_by_params(platform.issuer, "abc123")
    assert found.get_client_id() == "abc123" and found.get_auth_token_url() == platform.auth_token_url
    assert conf.find_registration_by_params(platform.issuer, "nobody") is None
    assert conf.find_registration_by_params("https://other.example", "abc123") is None
    assert conf.find_deployment_by_params(platform.issuer, "7", "abc123") is not None
    assert conf.find_deployment_by_params(platform.issuer, "99", "abc123") is None


def test_every_server_signs_with_one_tool_key_made_once(stores):
    keys = []
    threads = [threading.Thread(target=lambda s=s: keys.append(tool_key(s))) for s in stores]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join(timeout=60)
    assert len(keys) == 2 and keys[0] == keys[1]
    public = jwks(stores[1])["keys"][0]
    assert public["kid"] == keys[0].kid and public["kty"] == "RSA" and "d" not in public
    assert "PRIVATE" not in repr(keys[0]) and "PRIVATE" not in str(jwks(stores[0]))


def test_a_launch_state_is_taken_once_across_servers(stores):
    first, second = stores
    first.lti_put("ticket:x", {"kind": "student"}, time.time() + 60)
    taken = []
    threads = [threading.Thread(target=lambda s=s: taken.append(s.lti_take("ticket:x", time.time()))) for s in stores]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join(timeout=60)
    assert sorted(taken, key=str) == [None, {"kind": "student"}]
    second.lti_put("ticket:old", {"kind": "student"}, time.time() - 1)      # expired: never given
    assert first.lti_get("ticket:old", time.time()) is None and first.lti_take("ticket:old", time.time()) is None
    second.lti_put("state:never-used", {"nonce": "n"}, time.time() - 1)      # a login never launched
    assert first.lti_forget_expired(time.time()) == 1 and second.lti_forget_expired(time.time()) == 0


def login(store, state: str, nonce: str) -> None:
    """What pylti1p3's OIDC login does with the session service: the nonce, then the state with its params."""
    session = DatabaseSessionService(FakeRequest(), store)
    session.save_nonce(nonce)
    session.save_state_params(state, {"target": "https://tool/lti/launch"})


def test_the_state_of_a_login_on_one_server_is_checked_on_the_other_with_its_nonce(stores):
    first, second = stores
    login(first, "state-1", "nonce-1")
    launch = DatabaseSessionService(FakeRequest(), second)
    assert launch.check_state_is_valid("state-1", "hash") and launch.check_nonce("nonce-1")
    assert launch.get_state_params("state-1") == {"target": "https://tool/lti/launch"}
    replay = DatabaseSessionService(FakeRequest(), first)
    assert not replay.check_state_is_valid("state-1", "hash") and not replay.check_nonce("nonce-1")


def test_a_nonce_is_valid_only_with_the_state_it_was_issued_with(stores):
    first, second = stores
    login(first, "state-a", "nonce-a")
    login(first, "state-b", "nonce-b")
    launch = DatabaseSessionService(FakeRequest(), second)
    assert launch.check_state_is_valid("state-b", "hash")
    assert not launch.check_nonce("nonce-a")                 # an old id_token under a fresh state
    unknown = DatabaseSessionService(FakeRequest(), second)
    assert not unknown.check_state_is_valid("state-forged", "hash") and not unknown.check_nonce("nonce-a")


def test_a_learner_link_keeps_the_grade_service_of_an_earlier_launch(stores):
    first, second = stores
    platform = moodle()
    first.lti_add_platform(platform)
    first.lti_link_learner(LearnerRecord(platform.id, "u1", "a1", "lti:k1", "course-1", AGS))
    second.lti_link_learner(LearnerRecord(platform.id, "u1", "a1", "lti:k1", "course-1", None))   # an NRPS fill
    assert second.lti_learner(platform.id, "u1", "a1").ags == AGS
    assert [learner.sub for learner in first.lti_learners_of("a1", "lti:k1")] == ["u1"]
    assert first.lti_learners_of("a1", "someone") == []


def test_a_score_waits_once_per_student_and_is_posted_by_one_server(stores):
    first, second = stores
    first.lti_queue_score("a1", "lti:k1", 10.0)
    second.lti_queue_score("a1", "lti:k1", 11.0)                           # queued again: still one row
    due = first.lti_due_scores(20.0)
    assert len(due) == 1 and due[0].queued_at == 11.0
    assert first.lti_claim_score(due[0], 200.0) and not second.lti_claim_score(due[0], 200.0)
    second.lti_queue_score("a1", "lti:k1", 12.0)                           # a new submission while posting
    first.lti_score_posted(due[0])
    assert [p.queued_at for p in second.lti_pending_scores()] == [12.0]    # posted once more later
    again = second.lti_due_scores(20.0)[0]
    second.lti_score_failed(again, "HTTP 503 from https://lms/scores", 500.0)
    pending = first.lti_pending_scores()[0]
    assert pending.tries == 1 and pending.retry_at == 500.0 and "503" in pending.last_error
    assert first.lti_due_scores(20.0) == []


def test_a_failed_passback_is_kept_to_retry_and_raises_nothing(stores):
    first, second = stores
    platform = moodle()
    first.lti_add_platform(platform)
    first.register("a1", StudentRecord("lti:k1", "Anna", 0, {}, 100.0))
    first.submit("a1", "lti:k1", "q1", 1.0, True, 3, 101.0, "10.0.0.1", 1.0)
    first.lti_link_learner(LearnerRecord(platform.id, "u1", "a1", "lti:k1", "course-1", AGS))
    assert grades.standing(first, "a1", "lti:k1") == (1, 2, "InProgress")
    first.lti_queue_score("a1", "lti:k1", time.time())

    class Down(requests.Session):
        def request(self, *args, **kwargs):
            raise requests.ConnectionError("the LMS is down")

    assert grades.post_due(second, session=Down()) == {"posted": 0, "failed": 1}
    pending = first.lti_pending_scores()[0]
    assert pending.tries == 1 and "the LMS is down" in pending.last_error and pending.retry_at > time.time()


def test_a_reset_student_stands_at_zero():
    class Nobody:
        def assignment(self, assignment_id):
            return AssignmentRecord("a1", "h", 1.0, {"questions": [{"id": "q1"}]})

        def student(self, assignment_id, key):
            return None

    assert grades.standing(Nobody(), "a1", "gone") == (0, 1, "Initialized")


def test_the_access_log_cuts_a_ticket():
    assert cut("/lti/continue/AbC-123_xyz?lang=ru") == "/lti/continue/(ticket)?lang=ru"


def test_a_grade_that_could_not_be_posted_is_tried_again_on_a_timer(stores, monkeypatch):
    from server.classroom import lti_classroom
    first, _ = stores
    platform = moodle(auth_token_url="http://127.0.0.1:9/token")          # nothing listens there
    first.lti_add_platform(platform)
    first.register("a1", StudentRecord("lti:k1", "Anna", 0, {}, 100.0))
    first.lti_link_learner(LearnerRecord(platform.id, "u1", "a1", "lti:k1", "course-1", AGS))
    first.lti_queue_score("a1", "lti:k1", time.time())
    monkeypatch.setattr(lti_classroom, "store", lambda: first)
    monkeypatch.setattr(lti_classroom, "_retry", {"timer": None})
    lti_classroom._post_due()
    timer = lti_classroom._retry["timer"]
    try:
        assert first.lti_pending_scores()[0].tries == 1
        assert timer is not None and timer.is_alive() and timer.daemon
        assert lti_classroom.RETRY_FLOOR_S <= timer.interval <= grades.MAX_DELAY_SECONDS
    finally:
        if timer is not None:
            timer.cancel()
