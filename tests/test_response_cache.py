"""The response cache: a repeated question is answered from memory with the same bytes, a different one is
computed; only 200 answers of the computing endpoints are kept, within the byte bound, least recently used
evicted first; the cached answer is the one the server computes afresh.
"""
from __future__ import annotations

import dataclasses
import functools
import gzip
import json
import re
import threading
import time

import orjson
import pytest
from fastapi.testclient import TestClient

from server.api import endpoints
from server.runtime import heavy
from server.api.app import create_app
from pydantic import BaseModel, ConfigDict

from server.api.routers.cache import CACHED_ENDPOINTS, request_models
from server.runtime.response_cache import (CachedAnswer, ResponseCache, ResponseCacheMiddleware, canonical_json,
                                           validated_body)
from server.api import answering
from server.core.dynamics import motion, report
from server.core.numerics import Numerics
from server.lessons.requests import scene_request
from server.lessons.scenes import interface_texts, scenes

API = "/api/v1"
SLIDER_CRANK = {"mechanism": "slider_crank", "params": {"l1": 0.1, "l2": 0.3, "e": 0.0}, "n": 361,
                "outputs": ["s", "u31", "du31", "joints"]}


def app_client(monkeypatch, max_bytes: int | None = None) -> TestClient:
    """A fresh app (its own cache) with MDL_CACHE_BYTES set, or unset for the default."""
    if max_bytes is None:
        monkeypatch.delenv("MDL_CACHE_BYTES", raising=False)
    else:
        monkeypatch.setenv("MDL_CACHE_BYTES", str(max_bytes))
    return TestClient(create_app())


@pytest.fixture
def client(monkeypatch) -> TestClient:
    return app_client(monkeypatch)


def kinematics(client, body=SLIDER_CRANK, lang="en"):
    return client.post(f"{API}/kinematics", params={"lang": lang}, json=body)


def stats(client) -> dict:
    response = client.get(f"{API}/cache")
    assert response.status_code == 200
    return response.json()


def without_runtime(value):
    """An answer without its run times: the cached one carries the first computation's."""
    if isinstance(value, dict):
        return {k: without_runtime(v) for k, v in value.items() if k != "runtime_ms"}
    if isinstance(value, list):
        return [without_runtime(v) for v in value]
    return value


def test_an_identical_request_is_a_hit_with_the_same_bytes(client):
    first, second = kinematics(client), kinematics(client)
    assert (first.status_code, second.status_code) == (200, 200)
    assert (first.headers["x-cache"], second.headers["x-cache"]) == ("miss", "hit")
    assert second.content == first.content
    assert second.headers["content-type"] == first.headers["content-type"]
    assert {k: stats(client)[k] for k in ("hits", "misses", "entries")} == {"hits": 1, "misses": 1, "entries": 1}


def test_a_computed_answer_tells_its_timing_and_a_hit_none(client):
    """Server-Timing (admission.with_timing) is the computation's: a miss carries it, a hit was not computed."""
    first, second = kinematics(client), kinematics(client)
    assert first.headers["x-cache"] == "miss" and re.fullmatch(r"lane;dur=[0-9.]+, compute;dur=[0-9.]+",
                                                                first.headers["server-timing"])
    assert second.headers["x-cache"] == "hit" and "server-timing" not in second.headers


def test_the_cache_keeps_both_encodings_and_each_client_gets_its_own(client):
    computed = kinematics(client)
    cached = client.post(f"{API}/kinematics", params={"lang": "en"}, json=SLIDER_CRANK,
                         headers={"accept-encoding": "identity"})
    zipped = client.post(f"{API}/kinematics", params={"lang": "en"}, json=SLIDER_CRANK,
                         headers={"accept-encoding": "gzip, deflate"})
    assert computed.headers["content-encoding"] == "gzip" and computed.headers["vary"] == "Accept-Encoding"
    assert cached.headers["x-cache"] == "hit" and "content-encoding" not in cached.headers
    assert zipped.headers["x-cache"] == "hit" and zipped.headers["content-encoding"] == "gzip"
    assert cached.content == computed.content == zipped.content          # httpx decodes the gzip bodies
    assert int(zipped.headers["content-length"]) < len(zipped.content) / 2    # sent compressed: curves shrink


def test_a_stored_answer_is_compressed_once_kept_once_and_reads_back_as_its_body():
    body = orjson.dumps({"phi": [k / 7 for k in range(500)]})
    answer = CachedAnswer.of(((b"content-type", b"application/json"),), body)
    assert gzip.decompress(answer.gzipped) == body
    assert CachedAnswer.of((), body).gzipped == answer.gzipped               # mtime 0: the same bytes each time
    assert CachedAnswer.of((), b"{}").gzipped is None                         # too small to gain from it
    start = answer.message_start(True, b"hit")
    headers = dict(start["headers"])
    assert headers[b"content-encoding"] == b"gzip" and headers[b"content-length"] == str(len(answer.gzipped)).encode()
    assert answer.body_for(True) is answer.gzipped and answer.body_for(False) == body
    assert answer.plain is None and answer.size < len(body) / 2           # kept once: compressed
    assert CachedAnswer.of((), b"{}").plain == b"{}"                          # small: kept as it is


class Question(BaseModel):
    """Any JSON object: the middleware's tests below are about which paths and answers it keeps."""
    model_config = ConfigDict(extra="allow")


ANY_BODY = {name: Question for name in CACHED_ENDPOINTS}


def test_the_key_is_the_validated_request_in_canonical_json_exactly():
    assert 0.1 * 3 != 0.3
    assert canonical_json({"l2": 0.1 * 3}) != canonical_json({"l2": 0.3})          # two questions
    assert canonical_json({"b": 1, "a": [2.5, {"d": 0.1, "c": "x"}]}) == \
        canonical_json({"a": [2.5, {"c": "x", "d": 0.1}], "b": 1})
    assert len({canonical_json({"x": v}) for v in (float("nan"), None, float("inf"), -float("inf"))}) == 4
    assert validated_body(b"{not json", Question) is None
    assert validated_body(b'{"mechanism": "sine", "n": 0}', request_models()["kinematics"]) is None


def test_every_cached_endpoint_has_its_request_model():
    assert set(request_models()) == set(CACHED_ENDPOINTS)


def test_point_one_times_three_and_point_three_are_two_entries_each_echoing_its_value(client):
    computed = kinematics(client, {**SLIDER_CRANK, "params": {"l1": 0.1, "l2": 0.1 * 3, "e": 0.0}})
    typed = kinematics(client, {**SLIDER_CRANK, "params": {"l2": 0.3, "e": 0.0, "l1": 0.1}})
    assert (computed.headers["x-cache"], typed.headers["x-cache"]) == ("miss", "miss")
    assert (computed.json()["params"]["l2"], typed.json()["params"]["l2"]) == (0.1 * 3, 0.3)
    reordered = kinematics(client, {**SLIDER_CRANK, "params": {"e": 0.0, "l1": 0.1, "l2": 0.3}})
    assert reordered.headers["x-cache"] == "hit" and reordered.content == typed.content


def test_different_parameters_language_or_endpoint_miss(client):
    kinematics(client)
    other_l2 = kinematics(client, {**SLIDER_CRANK, "params": {"l1": 0.1, "l2": 0.31, "e": 0.0}})
    other_outputs = kinematics(client, {**SLIDER_CRANK, "outputs": ["s"]})
    other_lang = kinematics(client, lang="ru")
    assert [r.headers["x-cache"] for r in (other_l2, other_outputs, other_lang)] == ["miss"] * 3
    assert other_l2.json()["outputs"]["s"] != other_lang.json()["outputs"]["s"]
    assert stats(client)["entries"] == 4


def test_a_422_answer_is_computed_every_time_and_never_stored(client):
    crossed = {**SLIDER_CRANK, "params": {"l1": 0.3, "l2": 0.1, "e": 0.0}}     # the rod shorter than the crank
    answers = [kinematics(client, crossed) for _ in range(2)]
    assert [a.status_code for a in answers] == [422, 422]
    assert [a.headers["x-cache"] for a in answers] == ["miss", "miss"]
    assert stats(client)["entries"] == 0


def test_a_body_that_is_not_json_bypasses_the_cache(client):
    for _ in range(2):
        broken = client.post(f"{API}/kinematics", content=b'{"mechanism": ', headers={"content-type": "application/json"})
        assert broken.status_code == 422 and "x-cache" not in broken.headers
    as_text = client.post(f"{API}/kinematics", content=json.dumps(SLIDER_CRANK), headers={"content-type": "text/plain"})
    assert "x-cache" not in as_text.headers
    assert stats(client)["bypassed"] == 3 and stats(client)["entries"] == 0


def test_the_byte_bound_holds_and_the_least_recently_used_answer_goes_first(monkeypatch):
    bodies = [{**SLIDER_CRANK, "params": {"l1": 0.1, "l2": 0.3 + 0.01 * k, "e": 0.0}} for k in range(4)]
    sizing = app_client(monkeypatch, 10**8)
    sizes = []                                                          # each entry: its gzip body and headers
    for body in bodies:
        before = stats(sizing)["bytes"]
        kinematics(sizing, body)
        sizes.append(stats(sizing)["bytes"] - before)
    room = 2 * max(sizes) + min(sizes) // 4                             # room for any two answers, not three
    assert room < 3 * min(sizes), sizes
    client = app_client(monkeypatch, room)
    kinematics(client, bodies[0])
    kinematics(client, bodies[1])
    assert kinematics(client, bodies[0]).headers["x-cache"] == "hit"     # 0 is now the most recently used
    kinematics(client, bodies[2])                                        # evicts 1, keeps 0
    state = stats(client)
    assert state["entries"] == 2 and state["evictions"] == 1 and state["bytes"] <= state["max_bytes"]
    assert kinematics(client, bodies[0]).headers["x-cache"] == "hit"
    assert kinematics(client, bodies[1]).headers["x-cache"] == "miss"
    for body in bodies:
        kinematics(client, body)
        assert stats(client)["bytes"] <= room


def test_an_answer_larger_than_the_whole_cache_is_not_stored():
    cache = ResponseCache(max_bytes=1000)
    cache.put(b"k", CachedAnswer(((b"content-type", b"application/json"),), b"x" * 2000))
    assert cache.stats()["entries"] == 0 and cache.bytes == 0


def test_zero_bytes_turns_the_cache_off(monkeypatch):
    client = app_client(monkeypatch, 0)
    answers = [kinematics(client) for _ in range(2)]
    assert all(a.status_code == 200 and "x-cache" not in a.headers for a in answers)
    assert stats(client)["enabled"] is False


def test_a_size_that_is_not_a_number_is_refused(monkeypatch):
    monkeypatch.setenv("MDL_CACHE_BYTES", "64MB")
    with pytest.raises(ValueError, match="MDL_CACHE_BYTES"):
        ResponseCache.from_env()


class CountingApp:
    """An inner app that answers 200 to every request and counts how often it is asked."""

    def __init__(self):
        self.calls = 0

    async def __call__(self, scope, receive, send):
        self.calls += 1
        while (await receive()).get("more_body"):
            pass
        await send({"type": "http.response.start", "status": 200, "headers": [(b"content-type", b"application/json")]})
        await send({"type": "http.response.body", "body": b'{"answer": %d}' % self.calls})


@pytest.mark.parametrize("path,cached", [
    *((f"{API}/{name}", True) for name in CACHED_ENDPOINTS),
    (f"{API}/work-precision/motion", False),       # the answer is a timing measurement
    (f"{API}/work-precision/elastic", False),
    (f"{API}/assignments", False),
    (f"{API}/assignments/abc123/answers", False),
    (f"{API}/kinematics/extra", False),
    ("/scenes/transfer-functions", False),
])
def test_only_the_computing_endpoints_are_cached(path, cached):
    inner = CountingApp()
    client = TestClient(ResponseCacheMiddleware(inner, ResponseCache(), models=ANY_BODY))
    answers = [client.post(path, json={"same": "question"}) for _ in range(3)]
    assert inner.calls == (1 if cached else 3)
    assert [a.headers.get("x-cache") for a in answers] == (["miss", "hit", "hit"] if cached else [None] * 3)
    assert len({a.content for a in answers}) == (1 if cached else 3)


def test_get_requests_are_never_cached():
    inner = CountingApp()
    client = TestClient(ResponseCacheMiddleware(inner, ResponseCache(), models=ANY_BODY))
    for _ in range(2):
        client.get(f"{API}/kinematics")
    assert inner.calls == 2


class PartialApp(CountingApp):
    """Answers 200 saying the answer is partial (a bound cut the computation short)."""

    async def __call__(self, scope, receive, send):
        self.calls += 1
        while (await receive()).get("more_body"):
            pass
        await send({"type": "http.response.start", "status": 200,
                    "headers": [(b"content-type", b"application/json"), (b"x-partial", b"1")]})
        await send({"type": "http.response.body", "body": b'{"answer": %d}' % self.calls})


def test_an_answer_that_says_it_is_partial_is_computed_every_time():
    inner = PartialApp()
    client = TestClient(ResponseCacheMiddleware(inner, ResponseCache(), models=ANY_BODY))
    answers = [client.post(f"{API}/elastic", json={}) for _ in range(2)]
    assert inner.calls == 2 and [a.headers["x-cache"] for a in answers] == ["miss", "miss"]
    assert all(a.headers["x-partial"] == "1" for a in answers)


def test_a_complete_answer_is_stored_whatever_the_clock_says(monkeypatch):
    """The rule reads the answer, not the time: a clock that jumps an hour per reading changes nothing."""
    hours = iter(range(0, 10**9, 3600))
    monkeypatch.setattr(time, "perf_counter", lambda: float(next(hours)))
    inner = CountingApp()
    client = TestClient(ResponseCacheMiddleware(inner, ResponseCache(), models=ANY_BODY))
    answers = [client.post(f"{API}/elastic", json={}) for _ in range(2)]
    assert inner.calls == 1 and [a.headers["x-cache"] for a in answers] == ["miss", "hit"]


def test_a_motion_answer_cut_short_by_its_time_budget_says_so_and_is_not_stored(client, monkeypatch):
    monkeypatch.setattr(report, "TIME_BUDGET_S", 0.0)          # the steady cycle stops after its first level
    scene = scenes()["equation-of-motion"]
    body = scene_request(scene, scene.variants[0]) | {"outputs": ["steady"]}
    answers = [client.post(f"{API}/motion?lang=ru", json=body) for _ in range(2)]
    assert [a.status_code for a in answers] == [200, 200]
    assert [a.headers["x-cache"] for a in answers] == ["miss", "miss"]
    assert all(a.headers["x-partial"] == "1" for a in answers)
    assert "по лимиту времени" in answers[0].json()["numerics"]["message"]     # said in the reader's language
    assert stats(client)["entries"] == 0


def test_a_start_up_above_rtol_at_the_finest_level_is_whole_and_stored(client):
    """A start-up refined to the finest level (STARTUP_MAX_PER_2PI) whose estimate is still above rtol is a full
    answer, said so: no X-Partial, kept by the cache (its words named 'the time budget' too, and a busy class's
    every such answer was computed again and counted as cut short)."""
    scene = scenes()["equation-of-motion"]
    variant = next(v for v in scene.variants if v.id == "linear")
    body = scene_request(scene, variant, {"M0": 60.0, "b": 0.05, "omega0": 0.5, "f": 0.1})
    answers = [client.post(f"{API}/motion?lang=ru", json=body) for _ in range(2)]
    assert [a.status_code for a in answers] == [200, 200]
    numerics = answers[0].json()["startup"]["numerics"]
    assert numerics["message"].endswith(f"при {motion.STARTUP_MAX_PER_2PI} шагах на 2π (самый мелкий уровень)")
    assert "лимит" not in numerics["message"]
    assert ["x-partial" in a.headers for a in answers] == [False, False]
    assert [a.headers["x-cache"] for a in answers] == ["miss", "hit"]


@pytest.mark.parametrize("code", ["settled", "startup_not_periodic", "startup_time_budget"])
@pytest.mark.parametrize("bound_stopped", [False, True])
def test_a_start_up_is_partial_exactly_when_a_bound_stopped_it(code, bound_stopped):
    """The estimate above rtol: a bound that stopped the next level (or the cycles) makes the answer partial in
    its words, the finest level does not; each ending has its words in every language."""
    said = {"settled": "settled after 3 cycles", "startup_not_periodic": "not yet periodic after 3 cycles",
            "startup_time_budget": "stopped at the time budget after 3 cycles, not yet periodic"}[code]
    numerics = Numerics(method="RK4", rtol=1e-8, message=said, message_code=code, message_context={"cycles": 3})
    motion.above_rtol(numerics, 2e-5, 1024, bound_stopped)
    partial = answering.cut_short({"startup": {"numerics": dataclasses.asdict(numerics)}}, [])
    assert partial == (bound_stopped or code == "startup_time_budget")
    for lang in ("en", "ru", "uk"):
        assert interface_texts(lang)[f"num_message_{numerics.message_code}"].format(
            **numerics.message_context).count("1024") == 1


def test_an_elastic_answer_cut_short_by_its_work_bound_says_so_and_is_not_stored(client, monkeypatch):
    monkeypatch.setattr(heavy, "HEAVY_PROCESSES", 0)            # in this process, where the bound is patched
    monkeypatch.setattr(endpoints, "simulate", functools.partial(endpoints.simulate, max_evaluations=50))
    scene = scenes()["elastic-transmission"]
    body = scene_request(scene, scene.variants[0]) | {"outputs": ["histories"], "t_end": 0.3, "n": 61}
    answers = [client.post(f"{API}/elastic?lang=en", json=body) for _ in range(2)]
    assert [a.status_code for a in answers] == [200, 200]
    assert [a.headers["x-cache"] for a in answers] == ["miss", "miss"]
    assert all(a.headers["x-partial"] == "1" for a in answers)
    assert any("work bound" in w for w in answers[0].json()["warnings"])
    monkeypatch.undo()
    complete = [client.post(f"{API}/elastic?lang=en", json=body) for _ in range(2)]
    assert "x-partial" not in complete[0].headers
    assert [a.headers["x-cache"] for a in complete] == ["miss", "hit"]


def test_the_work_precision_study_of_the_real_app_is_computed_every_time(client):
    scene = scenes()["equation-of-motion"]
    body = scene_request(scene, scene.variants[0])
    for _ in range(2):
        study = client.post(f"{API}/work-precision/motion", params={"lang": "en"}, json=body)
        assert study.status_code == 200 and "x-cache" not in study.headers
    assert stats(client)["hits"] == 0 and stats(client)["entries"] == 0


@pytest.mark.parametrize("scene_id", list(scenes()))
def test_the_cached_answer_is_the_answer_computed_afresh(monkeypatch, scene_id):
    """Every scene's default request: the second answer comes from the cache, and equals (run times aside,
    byte for byte for kinematics) what a server without a cache computes."""
    scene = scenes()[scene_id]
    body = scene_request(scene, scene.variants[0])
    url = f"{API}/{scene.endpoint}?lang=en"
    cached_client, fresh_client = app_client(monkeypatch), app_client(monkeypatch, 0)
    assert cached_client.post(url, json=body).headers["x-cache"] == "miss"
    cached = cached_client.post(url, json=body)
    fresh = fresh_client.post(url, json=body)
    assert cached.status_code == fresh.status_code == 200
    assert cached.headers["x-cache"] == "hit"
    if scene.endpoint == "kinematics":
        assert cached.content == fresh.content
    assert without_runtime(cached.json()) == without_runtime(fresh.json())


def test_the_store_keeps_its_byte_count_right_under_concurrent_use():
    cache = ResponseCache(max_bytes=50_000)
    answers = [CachedAnswer(((b"content-type", b"application/json"),), bytes(100 + 37 * k)) for k in range(64)]

    def work(offset: int):
        for n in range(2000):
            key = bytes([(offset + n * 7) % 64])
            if cache.get(key) is None:
                cache.put(key, answers[key[0]])

    threads = [threading.Thread(target=work, args=(k,)) for k in range(8)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    state = cache.stats()
    assert state["hits"] + state["misses"] == 8 * 2000
    assert cache.bytes == sum(a.size for a in cache._entries.values()) <= cache.max_bytes


def test_the_statistics_are_documented_in_openapi(client):
    schema = client.get(f"{API}/openapi.json").json()
    answer = schema["paths"][f"{API}/cache"]["get"]["responses"]["200"]["content"]["application/json"]["schema"]
    assert answer["$ref"].endswith("/CacheStats")
    fields = schema["components"]["schemas"]["CacheStats"]["properties"]
    assert {"hits", "misses", "entries", "bytes", "max_bytes"} <= set(fields)
    assert all(field.get("description") for field in fields.values())


def test_a_family_compressed_in_the_heavy_process_is_kept_and_served_in_either_encoding(monkeypatch):
    """A family comes from the heavy process gzip-compressed when the client takes gzip (routers/family.py: its
    serialising and compressing stay off the worker's event loop). The cache keeps it as it came and serves a
    client without gzip the same JSON decompressed, and a client with gzip the very bytes computed; a family
    asked first without gzip is compressed by the cache as any answer."""
    client = app_client(monkeypatch)
    scene = scenes()["transfer-functions"]
    variant = next(v for v in scene.variants if v.id == "slider_crank")
    request = scene_request(scene, variant, {})
    body = {"endpoint": "kinematics", "request": request, "min": 1.05, "max": 8, "stage": "coarse",
            "vary": [{"path": "params.l2", "factor": request["params"]["l1"]}]}
    raw_headers = {"Accept-Encoding": "gzip"}
    with client.stream("POST", f"{API}/family", json=body, headers=raw_headers) as first:
        compressed_bytes = b"".join(first.iter_raw())
    assert (first.status_code, first.headers["content-encoding"], first.headers["x-cache"]) == (200, "gzip", "miss")
    plain = gzip.decompress(compressed_bytes)
    assert json.loads(plain)["numerics"]["stage"] == "coarse" and len(json.loads(plain)["values"]) == 9
    second = client.post(f"{API}/family", json=body, headers={"Accept-Encoding": "identity"})
    assert second.headers["x-cache"] == "hit" and "content-encoding" not in second.headers
    assert second.content == plain and int(second.headers["content-length"]) == len(plain)
    with client.stream("POST", f"{API}/family", json=body, headers=raw_headers) as third:
        assert b"".join(third.iter_raw()) == compressed_bytes and third.headers["x-cache"] == "hit"

    other = body | {"min": 1.1}                                  # another family, asked first without gzip
    plain_first = client.post(f"{API}/family", json=other, headers={"Accept-Encoding": "identity"})
    assert "content-encoding" not in plain_first.headers and plain_first.headers["x-cache"] == "miss"
    with client.stream("POST", f"{API}/family", json=other, headers=raw_headers) as again:
        assert gzip.decompress(b"".join(again.iter_raw())) == plain_first.content
        assert again.headers["content-encoding"] == "gzip" and again.headers["x-cache"] == "hit"


def test_a_whole_number_is_one_key_however_it_is_spelled():
    """A browser's JSON.stringify writes 2 where Python writes 2.0: in a field the models leave untyped (a family's
    ``request``) both reach the key as they came, and must be one question. Whole floats are keyed as ints below
    2**53 (exact there); other floats, booleans and non-finite numbers are kept apart as before."""
    page = {"request": {"m": 2, "l": 0.25, "on": True, "n": [1, 3]}, "far": 2.0 ** 60}
    script = {"request": {"m": 2.0, "l": 0.25, "on": True, "n": [1.0, 3.0]}, "far": 2.0 ** 60}
    assert canonical_json(page) == canonical_json(script) == \
        b'{"far":1.152921504606847e18,"request":{"l":0.25,"m":2,"n":[1,3],"on":true}}'
    assert canonical_json({"x": 1.0}) != canonical_json({"x": True})
    assert canonical_json({"x": float("nan")}) != canonical_json({"x": None})
