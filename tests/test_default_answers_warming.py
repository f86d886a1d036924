"""MDL_WARM_DEFAULTS: after the start each worker computes every scene's default answers on spare CPU, so that a
page's first request is a cache hit; off by default; the warming ends with the app. Waits are guards against a
hang, never timed assertions."""
from __future__ import annotations

import asyncio
import threading
import time

import pytest
from fastapi.testclient import TestClient

from server.api.app import create_app
from server.lessons.requests import scene_request
from server.lessons.scenes import scenes
from server.runtime import default_answers

GUARD_S = 600
LIGHT = {"reduction", "wear", "angular-acceleration"}      # a few light endpoints: the warming of the test is short


def _page_request(client, scene_id: str, lang: str = "ru"):
    scene = scenes()[scene_id]
    return client.post(f"/api/v1/{scene.endpoint}?lang={lang}", json=scene_request(scene, scene.variants[0]),
                       headers={"Accept-Encoding": "gzip"})


def _wait_warmed(client, app) -> default_answers.Warming:
    warming = app.state.default_answers
    assert warming is not None, "the warming did not start"
    deadline = time.monotonic() + GUARD_S
    while not warming.done.is_set():
        assert time.monotonic() < deadline, f"the warming did not end: {warming.answered} answered"
        time.sleep(0.2)
    return warming


def test_languages_from_the_environment(monkeypatch):
    monkeypatch.delenv("MDL_WARM_DEFAULTS", raising=False)
    assert default_answers.languages_from_env() == ("ru", "uk", "en")        # unset: on, every language
    assert default_answers.languages_from_env("") == ()
    assert default_answers.languages_from_env("0") == ()
    assert default_answers.languages_from_env("1") == ("ru", "uk", "en")
    assert default_answers.languages_from_env("en, ru") == ("en", "ru")
    with pytest.raises(ValueError, match="MDL_WARM_DEFAULTS names de"):
        default_answers.languages_from_env("ru,de")


def test_every_scene_and_variant_of_a_cached_endpoint_is_asked_first_variants_first():
    requests = default_answers.default_requests({"reduction", "wear"}, ("ru",))
    paths = [path for path, _, _ in requests]
    assert set(paths) == {"/api/v1/reduction", "/api/v1/wear"}
    expected = sum(len(s.variants) for s in scenes().values() if s.endpoint in ("reduction", "wear"))
    assert len(requests) <= expected and len(requests) >= expected - 2     # 'own' variants may need documents
    firsts = sum(1 for s in scenes().values() if s.endpoint in ("reduction", "wear"))
    first_bodies = {body for _, _, body in requests[:firsts]}
    import orjson
    for scene in (s for s in scenes().values() if s.endpoint in ("reduction", "wear")):
        assert orjson.dumps(scene_request(scene, scene.variants[0])) in first_bodies
    assert all(query == "lang=ru" for _, query, _ in requests)


def test_a_scenes_default_answer_is_a_cache_hit_after_warming(monkeypatch):
    monkeypatch.setenv("MDL_WARM_DEFAULTS", "ru")
    monkeypatch.setattr(default_answers, "QUIET_S", 0.05)
    app = create_app()
    original = default_answers.start
    monkeypatch.setattr(default_answers, "start", lambda a, cached: original(a, cached=LIGHT))
    with TestClient(app) as client:
        warming = _wait_warmed(client, app)
        assert warming.refused == 0 and warming.answered == len(warming.requests) > 0
        for scene_id in ("resisting-moment", "reduced-inertia", "wear", "angular-acceleration"):
            answer = _page_request(client, scene_id)
            assert answer.status_code == 200
            assert answer.headers["x-cache"] == "hit", scene_id
        assert _page_request(client, "wear", "en").headers["x-cache"] == "miss"    # only the languages named
        assert _page_request(client, "bearings").headers["x-cache"] == "miss"      # only the endpoints given


def test_off_when_set_to_0_nothing_is_warmed(monkeypatch):
    monkeypatch.setenv("MDL_WARM_DEFAULTS", "0")
    app = create_app()
    with TestClient(app) as client:
        assert app.state.default_answers is None
        assert _page_request(client, "wear").headers["x-cache"] == "miss"


def test_the_warming_stops_with_the_app(monkeypatch):
    """Stopped in the middle: its task ends, no thread is left. Still warming when stopped on any machine: each of
    the ~180 requests (three languages) waits for a quiet window of its own (QUIET_S), seconds in all."""
    monkeypatch.setenv("MDL_WARM_DEFAULTS", "1")
    monkeypatch.setattr(default_answers, "QUIET_S", 0.05)
    before = set(threading.enumerate())
    app = create_app()
    with TestClient(app) as client:
        warming = app.state.default_answers
        deadline = time.monotonic() + GUARD_S
        while warming.answered < 1:                    # one answer computed: it is running
            assert time.monotonic() < deadline, "the warming answered nothing"
            time.sleep(0.05)
        assert not warming.done.is_set()
        assert client.get("/api/v1/cache").status_code == 200       # the server answers while warming
    assert warming.task.done() and (warming.task.cancelled() or warming.done.is_set())
    deadline = time.monotonic() + 30
    while (left := [t for t in threading.enumerate() if t not in before and t.is_alive()]) and \
            time.monotonic() < deadline:
        time.sleep(0.1)
    assert left == [], left


def test_the_variants_families_are_cache_hits_after_warming_wherever_the_slider_stands(monkeypatch):
    """With the families cached, the warming asks each variant's slider families as the page does on a grab
    (server/lessons/family_requests.py, the page's body: tests/browser/test_request_body_parity.py), the coarse
    stage and the full one: a student's first grab, the slider anywhere and the others at their defaults, is a
    hit in both stages; a grab after another slider has moved is not (another question). The families are
    computed in this process with their time budgets lifted (as test_family_engine.unbudgeted_client does): a
    family cut short by its budget on a loaded machine would not be kept, and the test would depend on its speed."""
    from server.core.dynamics import report
    from server.families import family
    from server.lessons.family_requests import family_request
    from server.lessons.requests import defaults
    from server.runtime import heavy

    monkeypatch.setattr(heavy, "HEAVY_PROCESSES", 0)
    monkeypatch.setattr(family, "TIME_BUDGET_S", 1e9)
    monkeypatch.setattr(report, "TIME_BUDGET_S", 1e9)
    monkeypatch.setenv("MDL_WARM_DEFAULTS", "ru")
    monkeypatch.setattr(default_answers, "QUIET_S", 0.05)
    app = create_app()
    original = default_answers.start
    # the wear scene's endpoint only (its variants' families are the cheapest: a fraction of a CPU-second in all)
    monkeypatch.setattr(default_answers, "start", lambda a, cached: original(a, cached={"wear", "family"}))
    scene = scenes()["wear"]
    variant = scene.variants[0]
    with TestClient(app) as client:
        warming = _wait_warmed(client, app)
        families = [body for path, _, body in warming.requests if path.endswith("/family")]
        assert warming.refused == 0 and len(families) >= 2 * len(variant.sliders)
        first, second = variant.sliders[:2]
        moved = {first.id: first.max}                        # the grabbed slider at its end: the same family
        for stage in ({"stage": "coarse"}, {}):
            answer = client.post("/api/v1/family?lang=ru", json=family_request(scene, variant, first, moved) | stage,
                                 headers={"Accept-Encoding": "gzip"})
            assert answer.status_code == 200 and answer.headers["x-cache"] == "hit", stage
            assert answer.json()["numerics"]["stage"] == (stage.get("stage") or "full")
        other = family_request(scene, variant, second, moved) | {"stage": "coarse"}   # another slider moved first
        assert defaults(variant)[first.id] != first.max
        assert client.post("/api/v1/family?lang=ru", json=other).headers["x-cache"] == "miss"
