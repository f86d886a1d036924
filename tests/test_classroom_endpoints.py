"""The classroom computes an assignment's answers through the endpoints server/api gives it (answers.use_endpoints,
when the app is made): in the worker, and in a heavy process, which is handed the same function with its work
(the classroom imports nothing of server/api: tests/test_layers.py)."""
from __future__ import annotations

import pytest

from server.api import endpoints
from server.api.app import create_app
from server.classroom import answers, assignment_answers
from server.classroom.spec import AssignmentSpec
from server.classroom.variants import plan
from server.lessons.scenes import scenes
from server.runtime import heavy

CRANK = {"scene": "transfer-functions", "variant": "slider_crank",
         "sliders": {"lambda": {"vary": {"min": 2.5, "max": 5.0}}}, "questions": [{"id": "u31_max"}]}


def crank_plan():
    return plan(AssignmentSpec.model_validate(CRANK), scenes())


def test_without_endpoints_the_classroom_says_where_they_come_from(monkeypatch):
    monkeypatch.setattr(answers, "compute_answer", answers._no_endpoints)
    with pytest.raises(answers.NoEndpoints, match="use_endpoints"):
        answers.compute("kinematics", {"mechanism": "sine", "params": {"l1": 0.1}})


def test_making_the_app_gives_the_classroom_the_endpoints(monkeypatch):
    monkeypatch.setattr(answers, "compute_answer", answers._no_endpoints)
    create_app()
    assert answers.compute_answer is endpoints.parsed_answer
    body = {"mechanism": "slider_crank", "params": {"l1": 0.1, "l2": 0.3, "e": 0.0}, "n": 5, "outputs": ["u31"]}
    answer = endpoints.parsed_answer("kinematics", body)
    assert answer.payload == endpoints.compute("kinematics", body)          # as a client parses it
    assert not answer.partial and isinstance(answer.payload["outputs"]["u31"], list)


def test_a_heavy_process_computes_with_the_endpoints_it_is_handed(monkeypatch):
    """A new heavy process (forkserver) has not made the app: the endpoints come with the job, and its answers are
    those computed here."""
    monkeypatch.setattr(heavy, "HEAVY_PROCESSES", 1)
    monkeypatch.setattr(answers, "compute_answer", endpoints.parsed_answer)
    resolved = crank_plan()
    heavy.shutdown()                                     # a new process: nothing given to it before
    try:
        found = heavy.run(assignment_answers.answers_of_variants, resolved, [3], 60.0, endpoints.parsed_answer)
    finally:
        heavy.shutdown()
    assert found == {3: {"u31_max": answers.correct_answer(resolved, resolved.values(3), "u31_max")}}
