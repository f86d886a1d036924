"""Long computations run in a process of their own: the answer, a refusal (422) and a dead child."""
from __future__ import annotations

import os
import signal
import threading
import time
from concurrent.futures import CancelledError
from concurrent.futures.process import BrokenProcessPool

from fastapi.testclient import TestClient

from server.api import heavy
from server.api.app import app
from server.lessons.scenes import scenes
from server.lessons.requests import scene_request
from server.core.mechanisms import GeometryError


def test_it_runs_elsewhere_and_a_refusal_comes_back_whole():
    assert heavy.run(os.getpid) != os.getpid()
    error = GeometryError("params.l2", "too short", "crank_cannot_turn", ratio=1.5)
    try:
        heavy.run(_raise, error)
    except GeometryError as back:
        assert (back.field, back.reason, back.code, back.context) == ("params.l2", "too short",
                                                                      "crank_cannot_turn", {"ratio": 1.5})
    else:
        raise AssertionError("the refusal was lost")


def _raise(error):
    raise error


def test_elastic_answers_and_refusals_through_the_process():
    client = TestClient(app)
    scene = scenes()["elastic-transmission"]
    body = scene_request(scene, scene.variants[0])
    answer = client.post("/api/v1/elastic", json=body)
    assert answer.status_code == 200 and answer.json()["numerics"]["method"] in ("DOP853", "Radau")
    refused = client.post("/api/v1/elastic", json=body | {"motor": {"kind": "indicator"}})
    assert refused.status_code == 422


def test_a_dead_child_is_replaced():
    first = heavy.run(os.getpid)
    os.kill(first, signal.SIGKILL)
    second = heavy.run(os.getpid)
    assert second not in (first, os.getpid())


def test_a_computation_waiting_at_shutdown_starts_no_new_process():
    """A request still waiting when the worker stops fails: a new pool started for it would outlive the server.
    A later call (another app in the same process, as in the tests) gets a new pool."""
    heavy.run(os.getpid)
    outcome = []

    def waiting():
        try:
            outcome.append(heavy.run(time.sleep, 5))
        except (BrokenProcessPool, CancelledError) as error:    # running, or still queued on a slow machine
            outcome.append(error)
    thread = threading.Thread(target=waiting)
    thread.start()
    time.sleep(0.5)                               # the sleep is running in the heavy process
    heavy.shutdown()
    thread.join(10)
    assert len(outcome) == 1 and isinstance(outcome[0], (BrokenProcessPool, CancelledError))
    assert heavy._pool is None                    # no pool was started for the retry
    assert heavy.run(os.getpid) != os.getpid()
