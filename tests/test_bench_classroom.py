"""Smoke test of the classroom load test (bench/classroom.py): a class of 3 students for 3 seconds against the
servers it starts (1 and 2 workers) writes its tables, with requests answered and no errors (the old page
pattern); the new pattern's family requests are built per the POST /api/v1/family contract from the scene
JSON, and a family the server cannot give is reported as an error, never hidden."""
from __future__ import annotations

import importlib.util
import json
import math
import random
import re
import subprocess
import sys
from pathlib import Path

from typing import get_args

from server.api.routers.family import WITHOUT_FAMILY, Endpoint, FamilyRequest
from server.lessons.scenes import scene_documents

REPO = Path(__file__).resolve().parents[1]
SPEC = importlib.util.spec_from_file_location("classroom", REPO / "bench" / "classroom.py")
classroom = importlib.util.module_from_spec(SPEC)
SPEC.loader.exec_module(classroom)


def test_the_class_is_spread_over_the_scenes_by_the_stated_shares():
    scenes = classroom.apportion(60, classroom.SCENE_MIX)
    assert len(scenes) == 60
    assert {s: scenes.count(s) for s in ("transfer-functions", "equation-of-motion", "flywheel", "angular-acceleration")} \
        == {"transfer-functions": 18, "equation-of-motion": 9, "flywheel": 9, "angular-acceleration": 3}
    assert len(classroom.apportion(3, classroom.SCENE_MIX)) == 3


def test_a_student_walks_over_the_values_the_slider_can_express():
    student = classroom.Student(classroom.scenes()["transfer-functions"], random.Random(1))
    for _ in range(500):
        student.move()
        value = student.values[student.variant.id][student.slider.id]
        assert value in student.positions
    assert student.body().startswith(b"{")


def test_three_students_for_three_seconds_write_the_tables_without_errors(tmp_path):
    output = tmp_path / "classroom.md"
    run = subprocess.run([sys.executable, "bench/classroom.py", "--students", "3", "--seconds", "3",
                          "--compare-clients", "0", "--pattern", "old", "--output", str(output)],
                         cwd=REPO, capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr[-3000:]
    text = output.read_text(encoding="utf-8")
    assert "## 1 worker" in text and "## 2 workers" in text
    totals = re.findall(r"^\| \*\*all\*\* \| (\d+) \|.*\| (\d+) \((\d+) / (\d+) / (\d+)\) \|", text, re.MULTILINE)
    assert len(totals) == 2, text
    for requests, errors, *_ in totals:
        assert int(requests) > 0 and int(errors) == 0, text
    for workers in (1, 2):    # every worker logged its cache counters as it stopped; they count what the clients saw
        counted = re.search(rf"logs as it stops \({workers} of {workers}\): (\d+) hits, .* the clients saw (\d+) "
                            r"answers with X-Cache: hit", text)
        assert counted and counted[1] == counted[2], text
    assert text.count("s after it stopped (SIGTERM, 15 s): 0.") == 2, text       # no process outlives it


FAMILY_ENDPOINTS = set(get_args(Endpoint))          # the contract's choice of endpoint (all but WITHOUT_FAMILY)


def substituted(request: dict, vary: list[dict], value: float) -> dict:
    """What the family server does for one member: each path in the request set to value × factor."""
    body = json.loads(json.dumps(request))
    for item in vary:
        *keys, last = item["path"].split(".")
        node = body
        index = lambda node, key: int(key) if isinstance(node, list) else key      # "masses.forces.0.working"
        for key in keys:
            node = node[index(node, key)]
        last = index(node, last)
        assert last in (range(len(node)) if isinstance(node, list) else node), item["path"]   # not a new field
        node[last] = value * item["factor"]
    return body


def close(a, b) -> bool:
    """Equal structures, numbers to 1e-12 relative (value × factor against the page's own product)."""
    if isinstance(a, dict):
        return isinstance(b, dict) and a.keys() == b.keys() and all(close(a[k], b[k]) for k in a)
    if isinstance(a, list):
        return isinstance(b, list) and len(a) == len(b) and all(close(x, y) for x, y in zip(a, b))
    if isinstance(a, float) or isinstance(b, float):
        return math.isclose(a, b, rel_tol=1e-12, abs_tol=1e-300)
    return a == b


def test_the_family_request_of_every_slider_follows_the_contract():
    """For every scene with families, variant and slider, with the other sliders at random positions: the body is
    a valid FamilyRequest (the contract) with packed and, where the variant's panels draw any in a preview, the
    fields; its request is the page's request; setting the vary paths to v × factor reproduces the
    page's request at any other slider value v (checked at the slider's ends and a random position, against
    scene_request, which is independent of the factors); min, max and log are the slider's, as in the scene JSON."""
    rng = random.Random(13)
    scene_request, slider_values = classroom.scene_request, classroom.slider_values
    previews = sys.modules["family_request"].all_preview_fields(REPO)
    checked = with_fields = 0
    for scene in (s for s in classroom.scenes().values() if s.endpoint not in WITHOUT_FAMILY):
        raw = scene_documents()[scene.id.replace("-", "_")]
        for variant, raw_variant in zip(scene.variants, raw["variants"]):
            for slider, raw_slider in zip(variant.sliders, raw_variant.get("sliders", [])):
                values = {s.id: rng.choice(slider_values(s)) for s in variant.sliders}
                body = classroom.page_family_body(scene, variant, slider, REPO, values)
                fields = previews[f"{scene.id}/{variant.id}"]
                assert set(body) == {"endpoint", "request", "vary", "min", "max", "log", "packed"} | \
                    ({"fields"} if fields else set())
                FamilyRequest.model_validate(body)
                assert body["packed"] is True and body.get("fields", []) == fields
                with_fields += bool(fields)
                assert body["endpoint"] == scene.endpoint and body["endpoint"] in FAMILY_ENDPOINTS
                assert body["request"] == scene_request(scene, variant, values)
                assert (body["min"], body["max"], body["log"]) == \
                    (raw_slider["min"], raw_slider["max"], raw_slider.get("log", False))
                assert body["min"] < body["max"] and (not body["log"] or body["min"] > 0)
                paths = [item["path"] for item in body["vary"]]
                expected = [f"params.{raw_slider['param']}"] if scene.kind == "kinematics" else \
                    [raw_slider["param"], *raw_slider.get("also", [])]
                assert paths == expected
                assert all(math.isfinite(item["factor"]) and item["factor"] > 0 for item in body["vary"])
                for value in (slider.min, slider.max, rng.choice(slider_values(slider))):
                    assert close(substituted(body["request"], body["vary"], value),
                                 scene_request(scene, variant, values | {slider.id: value})), (scene.id, slider.id)
                json.dumps(body, allow_nan=False)
                checked += 1
    assert checked > 50 and with_fields > 50


def test_the_new_page_pattern_asks_families_and_exact_answers_without_errors(tmp_path):
    """Three students on the new pattern against one worker: each grab asks a family (answered, or given up by
    the student's next grab as the page does), the drags exact answers; none of either is an error."""
    output = tmp_path / "classroom_new.md"
    for seconds in ("3", "20"):     # a loaded machine may answer no exact request within 3 s: the class works longer
        run = subprocess.run([sys.executable, "bench/classroom.py", "--students", "3", "--seconds", seconds,
                              "--workers", "1", "--compare-clients", "0", "--pattern", "new", "--output", str(output)],
                             cwd=REPO, capture_output=True, text=True, timeout=240)
        assert run.returncode == 0, run.stderr[-3000:]
        text = output.read_text(encoding="utf-8")
        assert "## 1 worker, new page pattern" in text
        rows = re.findall(r"^\| `(family \([a-z-]+\)|coarse family \([a-z-]+\)|[a-z-]+)` \| (\d+) \|.*\| (\d+) \((\d+) / (\d+) / (\d+)\) \|",
                          text, re.MULTILINE)
        families = [(int(n), int(e)) for name, n, e, *_ in rows if "family" in name]
        exact = [(int(n), int(e)) for name, n, e, *_ in rows if "family" not in name]
        given_up = re.search(r"Families given up by the student's next grab[^:]*: (\d+)", text)
        if exact:
            break
    asked = sum(n for n, _ in families) + (int(given_up.group(1)) if given_up else 0)
    assert asked >= 1, text
    assert exact and all(e == 0 for _, e in exact), text
    assert all(e == 0 for _, e in families), text


def test_a_request_on_a_connection_the_server_closed_while_idle_is_sent_again_once(tmp_path):
    """uvicorn closes a keep-alive connection idle for 5 s; a browser then sends the request again on a new
    one, and so does the benchmark (counted as resent, not as a network error). A request that fails on the new
    connection too is a network error: it is sent again only once."""
    import http.server
    import threading

    answered = []

    class ClosingAfterEachAnswer(http.server.BaseHTTPRequestHandler):
        protocol_version = "HTTP/1.1"

        def do_POST(self):
            self.rfile.read(int(self.headers["Content-Length"]))
            if self.path == "/drop":            # no answer at all
                self.close_connection = True
                return
            answered.append(self.path)
            body = b"{}"
            self.send_response(200)
            self.send_header("Content-Length", str(len(body)))
            self.end_headers()
            self.wfile.write(body)
            self.close_connection = True        # as an idle keep-alive connection timed out after the answer

        def log_message(self, *args):
            pass

    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), ClosingAfterEachAnswer)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    try:
        student = classroom.Student(classroom.scenes()["transfer-functions"], random.Random(1))
        record = classroom.Record()
        connection = classroom.Connection(server.server_address[1], student, record, math.inf)
        assert [connection.post("/x", b"{}") for _ in range(3)] == [200, 200, 200]
        assert record.resent == 2 and len(answered) == 3
        assert [row[2] for row in record.rows] == [200, 200, 200]
        assert connection.post("/drop", b"{}") == 0 and record.resent == 3          # once more, then the error
    finally:
        server.shutdown()
        server.server_close()


class _Server:
    """What classroom.warmed reads of a running server: its log's path and whether it has exited."""

    def __init__(self, log_path: Path, exited: bool = False):
        self.log_path, self.exited = log_path, exited

    def poll(self):
        return 1 if self.exited else None


def test_a_warm_run_waits_for_every_workers_warming_and_gives_up_on_a_server_that_exited(tmp_path):
    """--warm: the class starts once each worker has logged the end of its warming
    (server/runtime/default_answers.py's line); a server that has stopped before is an error, not a wait."""
    log = tmp_path / "server.log"
    line = "INFO:     default answers in the cache: 535 of 535 requests (230.1 s, 21.4 CPU-s)\n"
    log.write_text(line + line)
    assert classroom.warmed(_Server(log), 2) >= 0
    log.write_text(line)                                  # one worker of two has warmed; the server has exited
    try:
        classroom.warmed(_Server(log, exited=True), 2)
    except RuntimeError as error:
        assert "warming did not end" in str(error)
    else:
        raise AssertionError("a server that exited before warming was waited for")
