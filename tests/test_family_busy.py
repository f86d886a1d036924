"""A busy server's families (server/runtime/heavy.py busy and crowded, server/api/routers/family.py) and the
families the workers share (server/runtime/shared_cache.py): behaviour only, no timing.

- heavy.busy says whether answers or previews wait for their lane or a refinement holds the families' lane;
  heavy.crowded whether more previews wait than their lane has processes. An answer runs beside a preview, never
  behind it.
- Under a busy signal a full family is not refined: the answer is the coarse family (from the cache when it holds
  it), nothing is handed to the families' lane, and the answer is not kept as the full family.
- While previews queue, a coarse family takes the lean start: every other one of the 9 start members, each the
  endpoint's own answer at its value.
- The same family asked twice while it is computed is computed once.
- A family computed by one worker is served to another from the shared layer without computing it again.
"""
from __future__ import annotations

import asyncio
import gzip
import json
import sqlite3
import threading
import time

import pytest
from fastapi.testclient import TestClient

from server.api.app import create_app
from server.api.routers import family as route
from server.families import family
from server.lessons.requests import path_value, scene_request
from server.lessons.scenes import scenes
from server.runtime import heavy
from event_loop import run_to_end

API = "/api/v1"
WAIT_S = 60             # a guard against a hang, never a measurement


def family_request(stage: str = "coarse") -> dict:
    """The reduced-inertia scene's slider-crank λ family at the defaults (light: a few ms per member)."""
    scene = scenes()["reduced-inertia"]
    variant = next(v for v in scene.variants if v.id == "slider_crank")
    slider = next(s for s in variant.sliders if s.id == "lambda")
    request = scene_request(scene, variant, None)
    scale = path_value(request, slider.scale) if slider.scale else 1.0
    vary = [{"path": path, "factor": float(slider.to_si * scale)} for path in (slider.param, *slider.also)]
    return {"endpoint": scene.endpoint, "request": request, "vary": vary, "min": slider.min, "max": slider.max,
            "log": slider.log, "stage": stage}


@pytest.fixture
def in_worker(monkeypatch):
    """Heavy work in the worker's own heavy thread; every family computed counted by its stage and leanness."""
    monkeypatch.setattr(heavy, "HEAVY_PROCESSES", 0)
    monkeypatch.setattr(family, "TIME_BUDGET_S", 1e9)
    monkeypatch.delenv("MDL_SHARED_CACHE", raising=False)
    computed = []
    real = route.family_body

    def counted(body, lang, gzip_accepted, lean=False):
        computed.append((body["stage"], lean))
        return real(body, lang, gzip_accepted, lean)

    monkeypatch.setattr(route, "family_body", counted)
    return computed


def post(client: TestClient, body: dict):
    response = client.post(f"{API}/family", json=body)
    assert response.status_code == 200, response.text[:300]
    return response, response.json()


def test_the_busy_signal_reads_the_lanes_queues(monkeypatch):
    monkeypatch.setattr(heavy, "HEAVY_PROCESSES", 0)
    release = threading.Event()

    async def scenario():
        assert not heavy.busy() and not heavy.crowded()
        held = asyncio.ensure_future(heavy.submit(release.wait, WAIT_S, lane="families"))
        await asyncio.sleep(0)
        assert heavy.busy() and not heavy.crowded()             # a refinement holds the families' lane
        release.set()
        await asyncio.wait_for(held, WAIT_S)
        assert not heavy.busy()
        release.clear()
        running = asyncio.ensure_future(heavy.submit(release.wait, WAIT_S, lane="previews", newest_first=True))
        await asyncio.sleep(0)
        assert not heavy.busy()                                 # one preview running, none waiting
        waiting = asyncio.ensure_future(heavy.submit(release.wait, WAIT_S, lane="previews", newest_first=True))
        await asyncio.sleep(0)
        assert heavy.busy() and heavy.crowded()                 # a preview waits behind it
        answer = await asyncio.wait_for(heavy.submit(sum, (1, 2)), WAIT_S)   # beside them, not behind them
        assert answer == 3 and not release.is_set() and heavy.crowded()
        release.set()
        await asyncio.wait_for(asyncio.gather(running, waiting), WAIT_S)
        assert not heavy.busy() and not heavy.crowded()
        release.clear()
        answering = asyncio.ensure_future(heavy.submit(release.wait, WAIT_S))
        queued = asyncio.ensure_future(heavy.submit(release.wait, WAIT_S))
        await asyncio.sleep(0)
        assert heavy.busy() and not heavy.crowded()             # an answer waits for the answers' process
        release.set()
        await asyncio.wait_for(asyncio.gather(answering, queued), WAIT_S)
        assert not heavy.busy()

    run_to_end(scenario())


def test_under_a_busy_signal_a_full_family_is_answered_coarse_and_nothing_is_refined(in_worker, monkeypatch):
    client = TestClient(create_app())
    body = family_request("full")
    monkeypatch.setattr(heavy, "busy", lambda: True)
    submitted = []
    real_submit = heavy.submit

    async def spied(function, *args, lane="answers", newest_first=False):
        submitted.append((lane, newest_first))
        return await real_submit(function, *args, lane=lane, newest_first=newest_first)

    monkeypatch.setattr(heavy, "submit", spied)
    response, answer = post(client, body)
    assert answer["numerics"]["stage"] == "coarse" and len(answer["values"]) == family.START_MEMBERS
    assert response.headers["cache-control"] == "no-store"
    assert submitted == [("previews", False)] and in_worker == [("coarse", False)]  # the families' lane: nothing

    _, coarse = post(client, body | {"stage": "coarse"})     # the page's coarse request, computed and kept
    response, again = post(client, body)                     # busy still: the kept coarse family, not computed
    assert again == coarse and response.headers["cache-control"] == "no-store"
    assert len(in_worker) == 2 and submitted == [("previews", False)] * 2     # previews: in the order asked

    monkeypatch.setattr(heavy, "busy", lambda: False)        # spare CPU: refined, not the coarse answer kept
    response, full = post(client, body)
    assert full["numerics"]["stage"] == "full" and response.headers["x-cache"] == "miss"
    assert in_worker[-1] == ("full", False) and submitted[-1] == ("families", True)   # refinements: newest first


def test_while_previews_queue_a_coarse_family_takes_every_other_start_member(in_worker, monkeypatch):
    monkeypatch.setattr(heavy, "crowded", lambda: True)
    client = TestClient(create_app())
    body = family_request("coarse")
    _, lean = post(client, body)
    nine = family.spaced(body["min"], body["max"], family.START_MEMBERS, body["log"])
    assert lean["values"] == [family.rounded(v) for v in nine[::2]] and len(lean["values"]) == family.LEAN_MEMBERS
    assert lean["numerics"]["stage"] == "coarse" and lean["numerics"]["points"] == family.LEAN_MEMBERS
    assert str(family.LEAN_MEMBERS) in lean["numerics"]["method"] and in_worker == [("coarse", True)]
    assert lean["interpolation_error"] is not None and lean["interpolation_error"] >= 0
    monkeypatch.setattr(heavy, "crowded", lambda: False)
    _, nine = post(TestClient(create_app()), body)           # another worker's cache: the 9 start members
    assert len(nine["values"]) == family.START_MEMBERS
    for value, member in zip(lean["values"], lean["answers"]):   # the same members: each the answer at its value
        assert nine["answers"][nine["values"].index(value)] == member


def test_the_same_family_asked_twice_while_it_is_computed_is_computed_once(in_worker, monkeypatch):
    app = create_app()
    app.state.response_cache.max_bytes = 0          # the cache off: only the route's own sharing can help
    started, release = threading.Event(), threading.Event()
    real = route.family_body
    calls = []

    def held(body, lang, gzip_accepted, lean=False):
        calls.append(body["stage"])
        started.set()
        release.wait(WAIT_S)
        return real(body, lang, gzip_accepted, lean)

    monkeypatch.setattr(route, "family_body", held)
    answers = []
    with TestClient(app) as client:                 # one event loop, as in one worker
        students = [threading.Thread(target=lambda: answers.append(post(client, family_request("coarse"))[1]))
                    for _ in range(2)]
        students[0].start()
        assert started.wait(WAIT_S)
        students[1].start()
        time.sleep(0.5)          # not a measurement: the second student's request reaches the route meanwhile
        release.set()
        for student in students:
            student.join(WAIT_S)
    assert len(answers) == 2 and answers[0] == answers[1]
    assert calls == ["coarse"]


def test_a_family_one_worker_computed_is_served_by_another_from_the_shared_layer(in_worker, monkeypatch, tmp_path):
    path = tmp_path / "shared.sqlite"
    monkeypatch.setenv("MDL_SHARED_CACHE", str(path))
    one, other = TestClient(create_app()), TestClient(create_app())     # two workers: a cache each, one layer
    body = family_request("coarse")
    first, answer = post(one, body)
    assert first.headers["x-cache"] == "miss" and in_worker == [("coarse", False)]
    deadline = time.monotonic() + WAIT_S             # the shared write is not awaited by the answer
    while time.monotonic() < deadline:
        with sqlite3.connect(path) as connection:
            if connection.execute("SELECT COUNT(*) FROM answers").fetchone()[0]:
                break
        time.sleep(0.05)
    second, same = post(other, body)
    assert second.headers["x-cache"] == "hit" and same == answer
    assert in_worker == [("coarse", False)]           # computed once, by the first worker
    with other.stream("POST", f"{API}/family", json=body, headers={"Accept-Encoding": "gzip"}) as third:
        assert json.loads(gzip.decompress(b"".join(third.iter_raw()))) == answer   # kept compressed, served so


@pytest.mark.parametrize("lean", [False, True], ids=["nine", "lean"])
@pytest.mark.parametrize("scene_id, variant_id, slider_id", [("transfer-functions", "slider_crank", "lambda"),
                                                             ("reduced-inertia", "slider_crank", "lambda"),
                                                             ("reduced-inertia", "slider_crank", "J1")])
def test_a_coarse_preview_is_a_member_or_within_the_tolerance(in_worker, monkeypatch, scene_id, variant_id,
                                                              slider_id, lean):
    """A coarse family (as the page asks for it: its drawn fields, packed) interpolates only the intervals whose
    bound is within the tolerance, and there the drawn preview is within it of the exact answer; every other
    interval (orders 0) draws its nearer member: a true answer of a nearby value. The error it states covers
    both (the change across a nearest interval)."""
    from server.lessons.family_requests import family_request as grab_request
    from test_family_bound import assert_drawn_within
    from test_family_fields import whole_members

    monkeypatch.setattr(heavy, "crowded", lambda: lean)
    scene = scenes()[scene_id]
    variant = next(v for v in scene.variants if v.id == variant_id)
    slider = next(s for s in variant.sliders if s.id == slider_id)
    body = grab_request(scene, variant, slider, None) | {"stage": "coarse"}
    _, answer = post(TestClient(create_app()), body)
    values, log, orders = answer["values"], body["log"], answer["orders"]
    assert len(values) == (family.LEAN_MEMBERS if lean else family.START_MEMBERS)
    assert set(orders) <= {0, 1, 3}
    members = whole_members(answer)
    allowed = family.TOLERANCE + family.PACK_QUANTUM / 2
    for k in range(len(values) - 1):
        a, b = family.coordinate(values[k], log), family.coordinate(values[k + 1], log)
        for w in (0.3, 0.7):
            value = family.from_coordinate(a + w * (b - a), log)
            if orders[k] == 0:
                drawn = family.interpolate_family(values, members, value, log, orders)
                assert drawn is members[k if w < 0.5 else k + 1]
            else:
                assert_drawn_within(body, answer, members, value, allowed)
    assert answer["interpolation_error"] is not None
