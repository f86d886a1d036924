"""Long computations run in a process of their own: the answer, a refusal (422) and a dead child."""
from __future__ import annotations

import asyncio
import gc
import json
import os
import re
import signal
import subprocess
import sys
import threading
import time
from concurrent.futures import CancelledError
from concurrent.futures.process import BrokenProcessPool
from pathlib import Path

import pytest
from fastapi.testclient import TestClient

from server.runtime import heavy
from server.api.app import app
from server.lessons.scenes import scenes
from server.lessons.requests import scene_request
from server.core.mechanisms import GeometryError
from event_loop import run_to_end
from leftover_processes import alive, wait_gone

ROOT = Path(__file__).resolve().parents[1]
WAIT_S = 60             # a guard against a hang, never a measurement


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


def test_the_heavy_process_yields_the_cpu_to_the_worker():
    """Scheduling, not timing: the heavy processes run at a lower priority (a higher nice value) than the worker,
    the families' lower still, so a light answer does not wait behind an elastic run, nor an elastic one behind a
    family."""
    for lane, niceness in heavy.LANES.items():           # 19: the lowest priority there is
        assert heavy.run(os.nice, 0, lane=lane) == min(os.nice(0) + niceness, 19)
    assert heavy.LANES["answers"] <= heavy.LANES["previews"] < heavy.LANES["families"]


def test_a_heavy_process_freezes_what_it_holds_once_started():
    """gc.freeze after the warm-up: its modules and compiled kernels are out of every later full collection."""
    for lane in heavy.LANES:
        assert heavy.run(gc.get_freeze_count, lane=lane) > 10_000


def test_a_heavy_process_has_the_modules_of_its_work_loaded_before_its_first_job():
    """Unpickling a job imports its function's module; loaded at start, the first family does not wait ~0.4 s for
    it. (eval, a builtin, so that asking imports nothing itself.)"""
    heavy.shutdown()                                     # new processes: nothing run in them yet
    try:
        for lane in heavy.LANES:
            assert heavy.run(eval, "[name in __import__('sys').modules for name in ('server.api.routers.family', "
                                   "'server.api.endpoints', 'server.classroom.assignment_answers')]", lane=lane) == [True] * 3
    finally:
        heavy.shutdown()


def test_a_heavy_process_is_forked_from_a_forkserver_that_loaded_the_kernels():
    """The forkserver imports the lanes' modules and loads the compiled kernels once (forkserver_preload, a module
    that only the forkserver imports): a heavy process holds it as it was forked, and its own start then finds
    everything loaded. The worker never imports it."""
    heavy.shutdown()
    try:
        for lane in heavy.LANES:
            assert heavy.run(eval, "'server.runtime.forkserver_preload' in __import__('sys').modules", lane=lane)
        assert "server.runtime.forkserver_preload" not in sys.modules
    finally:
        heavy.shutdown()


def test_a_worker_freezes_what_it_holds_once_started():
    gc.unfreeze()
    assert gc.get_freeze_count() == 0
    with TestClient(app):
        assert gc.get_freeze_count() > 10_000


def test_without_nice_the_lanes_keep_the_workers_priority(monkeypatch):
    """MDL_HEAVY_NICE=0 (the browser tests' server, whose CPUs the other test processes keep busy): the lanes'
    new processes run at the worker's own priority."""
    heavy.shutdown()                                     # new pools, started with the switch off
    monkeypatch.setattr(heavy, "NICE", False)
    try:
        for lane in heavy.LANES:
            assert heavy.run(os.nice, 0, lane=lane) == os.nice(0)
    finally:
        heavy.shutdown()                                 # the next test's pools start with the default


def test_elastic_answers_and_refusals_through_the_process():
    client = TestClient(app)
    scene = scenes()["elastic-transmission"]
    body = scene_request(scene, scene.variants[0])
    answer = client.post("/api/v1/elastic", json=body)
    assert answer.status_code == 200 and answer.json()["numerics"]["method"] in ("DOP853", "Radau")
    refused = client.post("/api/v1/elastic", json=body | {"motor": {"kind": "indicator"}})
    assert refused.status_code == 422


def test_an_elastic_answer_tells_where_its_time_went_in_the_heavy_process():
    """Server-Timing of an answer computed in a heavy process: beside its wait for a place (lane) and the whole
    computation (compute), its wait in the heavy lane's queue, its run and its CPU there; each a part of compute."""
    client = TestClient(app)
    scene = scenes()["elastic-transmission"]
    body = scene_request(scene, scene.variants[0])
    body["t_end"] = body["t_end"] * 0.937                # not the warmed default answer: computed here
    answer = client.post("/api/v1/elastic", json=body)
    assert answer.status_code == 200 and answer.headers["x-cache"] == "miss"
    timing = dict(re.findall(r"([a-z]+);dur=([0-9.]+)", answer.headers["server-timing"]))
    assert set(timing) == {"lane", "compute", "queue", "run", "cpu"}
    parts = {name: float(value) for name, value in timing.items()}
    assert 0 < parts["cpu"] <= parts["run"] + 0.1 and parts["queue"] + parts["run"] <= parts["compute"]


def _sleep_until(marker: str, then_s: float) -> None:
    while not os.path.exists(marker):
        time.sleep(0.005)
    time.sleep(then_s)


def test_a_job_knows_its_wait_in_the_queue_its_run_and_its_cpu():
    """Causal bounds, not speed: a job queued behind one that runs until a marker appears waits at least as long
    as the marker is held back after it was queued; a job that sleeps runs at least its sleep and takes almost no
    CPU; one that computes takes CPU, never more than its run."""
    marker = f"/tmp/mdl-heavy-marker-{os.getpid()}-{time.monotonic_ns()}"
    heavy.run(os.getpid, lane="answers")                  # the process is up

    async def scenario():
        holding = asyncio.ensure_future(heavy.submit(_sleep_until, marker, 0.0))
        await asyncio.sleep(0)
        queued, computed = {}, {}
        heavy.TIMING.set(queued)
        behind = asyncio.ensure_future(heavy.submit(time.sleep, 0.1))
        await asyncio.sleep(0.2)                        # the marker held back 0.2 s after the job was queued
        open(marker, "w").close()
        await asyncio.gather(holding, behind)
        heavy.TIMING.set(computed)
        assert await heavy.submit(sum, range(3_000_000)) == 4_499_998_500_000
        return queued, computed

    try:
        queued, computed = run_to_end(scenario())
    finally:
        if os.path.exists(marker):
            os.remove(marker)
    assert queued["queue"] >= 0.2 and queued["run"] >= 0.1 and queued["cpu"] < 0.05
    assert 0 < computed["cpu"] <= computed["run"] + 1e-3 and computed["queue"] < 10


def test_a_slow_preview_holds_neither_the_next_preview_nor_an_answer():
    """Order, not timing: while one preview runs until a marker appears, another preview (the previews' second
    process) and an answer (the answers' own process) are computed, each in a process of its own."""
    marker = f"/tmp/mdl-heavy-marker-{os.getpid()}-{time.monotonic_ns()}"

    async def scenario():
        slow = asyncio.ensure_future(heavy.submit(_sleep_until, marker, 0.0, lane="previews"))
        await asyncio.sleep(0)
        beside = await asyncio.wait_for(heavy.submit(os.getpid, lane="previews"), WAIT_S)
        answer = await asyncio.wait_for(heavy.submit(os.getpid), WAIT_S)
        still_running = not slow.done()
        open(marker, "w").close()
        await asyncio.wait_for(slow, WAIT_S)
        return beside, answer, still_running

    try:
        beside, answer, still_running = run_to_end(scenario())
    finally:
        if os.path.exists(marker):
            os.remove(marker)
    assert still_running and heavy.processes("previews") == 2 * heavy.processes("answers")
    assert len({beside, answer, os.getpid()}) == 3


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
    assert not heavy._pools                       # no pool was started for the retry
    assert heavy.run(os.getpid) != os.getpid()


def test_a_server_started_again_after_shutdown_forks_from_the_same_forkserver():
    """shutdown() ends the heavy processes and leaves the forkserver, which has loaded the kernels: the next start
    in the same process (the tests start app after app) forks new heavy processes from it at once, start, stop,
    start again without a pause."""
    import multiprocessing.forkserver
    first = heavy.run(os.getpid)
    server = multiprocessing.forkserver._forkserver
    forkserver = server._forkserver_pid
    assert forkserver is not None
    heavy.shutdown()
    assert not alive({first})
    for _ in range(3):
        heavy.start()
        again = heavy.run(os.getpid)
        assert again not in (os.getpid(), first)
        heavy.shutdown()
        assert not alive({again})
    assert heavy.run(os.getpid) != os.getpid() and server._forkserver_pid == forkserver


def test_the_forkserver_ends_with_the_process_that_started_it():
    """Left running by shutdown(), the forkserver still never outlives its server: it ends when the process that
    started it does (whether it stops cleanly or is killed), as multiprocessing's forkserver reads the end of the
    pipe that process held open."""
    script = ("import os, sys; from server.runtime import heavy; pid = heavy.run(os.getpid); "
              "import multiprocessing.forkserver as f; print(f._forkserver._forkserver_pid, pid, flush=True); "
              "heavy.shutdown(); os._exit(0) if sys.argv[1] == 'exit' else os.kill(os.getpid(), 9)")
    for how in ("exit", "kill"):
        done = subprocess.run([sys.executable, "-c", script, how], capture_output=True, text=True, timeout=300,
                              cwd=ROOT)
        forkserver, child = map(int, done.stdout.split())
        wait_gone({forkserver, child}, f"the forkserver after its process's {how} ({done.stderr[-2000:]})")


def test_submit_answers_brings_refusals_back_and_replaces_a_dead_child():
    async def scenario():
        pid = await heavy.submit(os.getpid)
        try:
            await heavy.submit(_raise, GeometryError("params.l2", "too short", "crank_cannot_turn"))
        except GeometryError as back:
            assert back.code == "crank_cannot_turn"
        else:
            raise AssertionError("the refusal was lost")
        os.kill(pid, signal.SIGKILL)
        return pid, await heavy.submit(os.getpid)

    first, second = run_to_end(scenario())
    assert first != os.getpid() and second not in (first, os.getpid())


def test_a_submit_cancelled_while_queued_is_never_computed():
    """A request cancelled while it waits (its client gone) leaves the queue. The pool hands a process the
    call it runs plus up to two more already marked running (one process): those two are fillers."""
    marker = f"/tmp/mdl-heavy-{os.getpid()}-{time.monotonic_ns()}"

    async def scenario():
        started = [asyncio.ensure_future(heavy.submit(time.sleep, 0.5)),
                   *(asyncio.ensure_future(heavy.submit(os.getpid)) for _ in range(2))]
        queued = [asyncio.ensure_future(heavy.submit(_touch, marker)) for _ in range(3)]
        await asyncio.sleep(0.1)
        for task in queued:
            task.cancel()
        await asyncio.gather(*started)
        return [task.cancelled() for task in queued]

    heavy.run(os.getpid)                                   # the process is up
    assert all(run_to_end(scenario()))
    heavy.run(os.getpid)                                   # whatever was still queued has run by now
    assert not os.path.exists(marker)


def _touch(path):
    open(path, "w").close()


def test_with_no_heavy_processes_submit_runs_in_a_thread_of_its_own(monkeypatch):
    """MDL_HEAVY_PROCESSES=0: the computation runs in the worker, in a thread that is neither the event loop's
    nor one of the pool that serves the light routes."""
    monkeypatch.setattr(heavy, "HEAVY_PROCESSES", 0)

    async def scenario():
        return await heavy.submit(threading.current_thread), threading.current_thread()

    worker, loop_thread = run_to_end(scenario())
    assert worker is not loop_thread and worker.name.startswith("mdl-heavy")


def _append(path, text):
    with open(path, "a") as file:
        file.write(text)


def _until_stopped(started, limit_s):
    """A family's stand-in in the families' lane: works in chunks (here: waits) until `heavy.stopped` says its
    client has given it up, or `limit_s` has passed; says which, and writes it after `started` in its file."""
    with open(started, "a") as file:
        file.write("started ")
    end, outcome = time.monotonic() + limit_s, "not stopped"
    while time.monotonic() < end:
        if heavy.stopped():
            outcome = "stopped"
            break
        time.sleep(0.01)
    with open(started, "a") as file:
        file.write(outcome + "; ")
    return outcome


def _lane_scenario(lane, first, then):
    """`lane` held by `first` (a job already handed to the pool); `then`, pairs of (job, newest_first), submitted
    while it runs."""
    async def scenario():
        holding = asyncio.ensure_future(heavy.submit(*first, lane=lane))
        await asyncio.sleep(0)
        queued = [asyncio.ensure_future(heavy.submit(*job, lane=lane, newest_first=newest)) for job, newest in then]
        return await asyncio.gather(holding, *queued)
    return scenario()


@pytest.mark.parametrize("lane, previews, order", [("families", "abcd", "dcba"), ("answers", "bd", "acdb"),
                                                   ("answers", "", "abcd")])
def test_the_answers_waiting_go_first_oldest_first_then_the_newest_preview(lane, previews, order):
    """Order, not timing: while a job holds the lane's one process, the jobs asked meanwhile wait in the worker.
    Next goes the oldest job, else the newest refinement (a slider's full family, submitted newest_first): in a
    class past its CPUs the newest family is the slider still held."""
    log = f"/tmp/mdl-heavy-order-{os.getpid()}-{time.monotonic_ns()}"
    heavy.run(os.getpid, lane=lane)                       # the process is up
    try:
        run_to_end(_lane_scenario(lane, (time.sleep, 0.3),
                                  [((_append, log, text), text in previews) for text in "abcd"]))
        with open(log) as file:
            assert file.read() == order
    finally:
        if os.path.exists(log):
            os.remove(log)
    assert not heavy._queues[lane].waiting and heavy._queues[lane].running == 0


@pytest.mark.parametrize("lane", heavy.LANES)
def test_a_running_family_given_up_by_its_client_stops(lane):
    """A family (full, or coarse in the previews' lane) whose client goes away while it runs sees heavy.stopped()
    turn true (between its chunks of members) and ends, so that the lane's process is free for the next; one not
    given up never sees it. (A lane of two processes would start the next beside the first: there the next is
    asked once the first has ended.)"""
    started = f"/tmp/mdl-heavy-started-{os.getpid()}-{time.monotonic_ns()}"

    async def scenario():
        running = asyncio.ensure_future(heavy.submit(_until_stopped, started, 120, lane=lane))
        while not os.path.exists(started):
            await asyncio.sleep(0.01)
        running.cancel()
        while heavy.processes(lane) > 1 and not Path(started).read_text().endswith("; "):
            await asyncio.sleep(0.01)
        after = await heavy.submit(_until_stopped, started, 0.2, lane=lane)   # runs once the first has ended
        return running.cancelled(), after

    try:
        assert run_to_end(scenario()) == (True, "not stopped")
        with open(started) as file:             # the first job saw its stop; the second ran after it had ended
            assert file.read() == "started stopped; started not stopped; "
    finally:
        os.remove(started)
    assert heavy.run(os.getpid, lane=lane) != os.getpid()


def test_a_family_stops_in_the_workers_own_thread_too(monkeypatch):
    """MDL_HEAVY_PROCESSES=0: the families' lane runs in the worker's heavy thread, and a given-up family stops
    there as it does in a process."""
    monkeypatch.setattr(heavy, "HEAVY_PROCESSES", 0)
    started = f"/tmp/mdl-heavy-started-{os.getpid()}-{time.monotonic_ns()}"

    async def scenario():
        running = asyncio.ensure_future(heavy.submit(_until_stopped, started, 120, lane="families"))
        while not os.path.exists(started):
            await asyncio.sleep(0.01)
        running.cancel()
        return running, await heavy.submit(_until_stopped, started, 0.2, lane="families")

    try:
        running, after = run_to_end(scenario())
        assert running.cancelled() and after == "not stopped"
        with open(started) as file:
            assert file.read() == "started stopped; started not stopped; "
    finally:
        os.remove(started)


def test_a_family_whose_client_disconnects_stops_before_its_next_chunk(monkeypatch):
    """End to end through the app (admission, cache, route, lane, member batches; MDL_HEAVY_PROCESSES=0 so that
    the chunks can be counted here): the client of a full family disconnects while its first chunk of members
    is computed; the route is cancelled, and the family computes no further chunk (a whole family takes several:
    the 2 end members, then the 7 others, then its refinements)."""
    from server.api import family_batch
    from server.api.app import create_app

    monkeypatch.setattr(heavy, "HEAVY_PROCESSES", 0)
    family_batch.MEMO.store.clear()
    family_batch.MEMO.held = 0
    computing, go_on, chunks = threading.Event(), threading.Event(), []
    real = family_batch.compute_answers

    def held_chunk(*args):
        chunks.append(len(args[1]))
        computing.set()
        go_on.wait(120)
        return real(*args)

    monkeypatch.setattr(family_batch, "compute_answers", held_chunk)
    scene = scenes()["transfer-functions"]
    variant = next(v for v in scene.variants if v.id == "slider_crank")
    request = scene_request(scene, variant, {})
    body = json.dumps({"endpoint": "kinematics", "request": request, "min": 1.05, "max": 8,
                       "vary": [{"path": "params.l2", "factor": request["params"]["l1"]}]}).encode()
    scope = {"type": "http", "asgi": {"version": "3.0"}, "http_version": "1.1", "method": "POST", "scheme": "http",
             "path": "/api/v1/family", "raw_path": b"/api/v1/family", "query_string": b"lang=en", "root_path": "",
             "headers": [(b"content-type", b"application/json"), (b"content-length", str(len(body)).encode())],
             "client": ("127.0.0.1", 50000), "server": ("127.0.0.1", 8000)}
    sent = []

    async def scenario():
        gone = asyncio.Event()
        messages = [{"type": "http.request", "body": body, "more_body": False}]

        async def receive():
            if messages:
                return messages.pop(0)
            await gone.wait()
            return {"type": "http.disconnect"}

        async def send(message):
            sent.append(message)

        answering = asyncio.ensure_future(create_app()(scope, receive, send))
        while not computing.is_set():
            await asyncio.sleep(0.01)
        gone.set()                                         # the client goes while the first chunk is computed
        await answering
        go_on.set()
        while heavy._queues["families"].running:           # the family ends in the worker's heavy thread
            await asyncio.sleep(0.01)

    run_to_end(scenario())
    assert chunks == [2] and not [m for m in sent if m["type"] == "http.response.start"]
