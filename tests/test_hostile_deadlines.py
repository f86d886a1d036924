"""One deadline per request, kept by every stage, and said in words when it is reached.

Before, /elastic gave its run 4 s, the check run 2 s more, and the bearing iteration a fresh 8 s of its own
(9.9–18.4 s measured); /work-precision/elastic gave its reference up to 12 s and then the runs 6 s more. Now one
deadline is made per request and handed to every stage. Tested by behaviour, never by time: a deadline already
in the past (or a budget of 0 s) must stop each stage with a partial result that says so (numerics message,
warnings, X-Partial: 1), and every stage must receive the one deadline of its request.
"""
from __future__ import annotations

import math

import pytest
from fastapi.testclient import TestClient

from server.api import endpoints
from server.runtime import heavy
from server.api.app import create_app
from server.api.schemas_elastic import ElasticRequest
from server.core import work_precision
from server.core.elastic import report
from server.lessons.requests import scene_request
from server.lessons.scenes import scenes

API = "/api/v1"
PAST = -math.inf        # a deadline that has already passed, whatever the clock reads


def linkage_body(outputs: list[str]) -> dict:
    scene = scenes()["elastic-linkage"]
    return scene_request(scene, scene.variants[0]) | {"outputs": outputs}


def linkage_machine():
    return endpoints.elastic_machine(ElasticRequest.model_validate(linkage_body(["histories"])))


@pytest.fixture
def client(monkeypatch, tmp_path) -> TestClient:
    monkeypatch.setenv("MDL_DATA_DIR", str(tmp_path))
    monkeypatch.setattr(heavy, "HEAVY_PROCESSES", 0)            # in this process, where the budgets are patched
    return TestClient(create_app())


def test_every_stage_of_an_elastic_request_gets_the_one_deadline_of_the_request(monkeypatch):
    seen = []
    real_simulate, real_bearings = endpoints.simulate, endpoints.bearing_iteration
    monkeypatch.setattr(endpoints, "simulate",
                        lambda *a, **k: seen.append(("run", k["deadline"])) or real_simulate(*a, **k))
    monkeypatch.setattr(endpoints, "bearing_iteration",
                        lambda *a, **k: seen.append(("bearings", k["deadline"])) or real_bearings(*a, **k))
    monkeypatch.setattr(report, "REQUEST_BUDGET_S", 0.0)
    endpoints.elastic(ElasticRequest.model_validate(linkage_body(["histories", "bearings"])), "en")
    assert [stage for stage, _ in seen] == ["run", "bearings"]
    assert seen[0][1] == seen[1][1]                              # one instant, not a budget per stage


def test_a_run_and_its_check_stop_at_a_deadline_already_past_and_say_so():
    result, notices = report.simulate(linkage_machine(), 0.3, 151, 1e-6, with_rigid=False, deadline=PAST)
    codes = [notice.code for notice in notices]
    assert codes == ["elastic_partial", "elastic_check_partial"]
    assert result["numerics"]["message"].startswith("stopped at t = ")                     # the run, then its check
    assert result["numerics"]["message"].endswith("covers the run up to there only.")
    assert result["t"].size < 151                               # the samples it reached, no more


def test_a_check_run_cut_short_says_its_estimate_covers_part_of_the_run(monkeypatch):
    """The run completes; only the check run meets the deadline (the second integration is given one past)."""
    calls = []

    def integrate(*args):
        calls.append(args)
        args = list(args)
        if len(calls) == 2:
            args[6] = PAST
        return real(*args)
    real = report.integrate
    monkeypatch.setattr(report, "integrate", integrate)
    result, notices = report.simulate(linkage_machine(), 0.3, 151, 1e-6, with_rigid=False)
    assert [n.code for n in notices] == ["elastic_check_partial"]
    assert result["t"].size == 151 and result["numerics"]["error_estimate"] is not None
    assert "covers the run up to there only" in result["numerics"]["message"]


def test_the_bearing_iteration_stops_at_the_deadline_and_counts_no_cut_round():
    outcome = report.bearing_iteration(linkage_machine(), report.Bearing(), 0.3, 151, 1e-6, deadline=PAST)
    assert outcome["rounds"] == [] and outcome["converged"] is False
    assert outcome["message_code"] == "bearings_time_budget" and "time budget" in outcome["message"]


def test_the_bearing_iteration_still_converges_when_time_allows():
    outcome = report.bearing_iteration(linkage_machine(), report.Bearing(), 0.3, 151, 1e-6)
    assert outcome["converged"] is True and outcome["message_code"] == ""


@pytest.mark.parametrize("lang", ["en", "ru", "uk"])
def test_an_elastic_request_out_of_time_answers_partial_in_words_and_is_not_cached(client, monkeypatch, lang):
    monkeypatch.setattr(report, "REQUEST_BUDGET_S", 0.0)
    body = linkage_body(["histories", "rigid", "bearings"])
    answers = [client.post(f"{API}/elastic?lang={lang}", json=body) for _ in range(2)]
    assert [a.status_code for a in answers] == [200, 200]
    assert all(a.headers["x-partial"] == "1" and a.headers["x-cache"] == "miss" for a in answers)
    data = answers[0].json()
    assert data["bearings"]["rounds"] == [] and data["bearings"]["message_code"] == "bearings_time_budget"
    assert len(data["warnings"]) >= 3                            # the run, its check, the bearings: each in words
    if lang == "en":
        assert sum("work bound" in w for w in data["warnings"]) == 2 and "time budget" in data["warnings"][-1]


def test_an_elastic_study_stops_at_its_one_deadline_and_says_so(client, monkeypatch):
    monkeypatch.setattr(work_precision, "BUDGET_S", 0.0)
    response = client.post(f"{API}/work-precision/elastic?lang=en", json=linkage_body(["histories"]))
    assert response.status_code == 200 and response.headers["x-partial"] == "1"
    data = response.json()
    assert data["study"]["rows"] == [] and len(data["study"]["skipped"]) == 12
    assert any("time budget" in w for w in data["warnings"])


def test_an_elastic_study_given_a_past_deadline_runs_nothing_after_the_reference():
    study = work_precision.elastic_study(linkage_machine(), 0.3, deadline=PAST)
    assert study["rows"] == [] and study["out_of_time"] and work_precision.study_notices(study)


def test_a_motion_study_given_a_past_deadline_stops_and_says_so():
    scene = scenes()["equation-of-motion"]
    from server.api.schemas_dynamics import MotionRequest
    machine = endpoints.machine(MotionRequest.model_validate(scene_request(scene, scene.variants[0])))
    study = work_precision.motion_study(machine, deadline=PAST)
    assert study["rows"] == [] and study["out_of_time"]
    assert "time budget" in work_precision.study_notices(study)[0].text
    complete = work_precision.motion_study(machine, deadline=math.inf)
    assert not complete["out_of_time"] and not work_precision.study_notices(complete)
