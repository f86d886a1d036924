"""The answers of an assignment are computed in the heavy processes under a budget, kept per
variant in the store, and one address makes assignments at a bounded rate.

Reproductions: making an assignment computed 8 variants' answers in the request's own thread (19 s on an elastic
scene), and every first submission of a new name computed its variant again in the request (1–3 s), once per
worker process (an in-process lru_cache). Here the store is a small in-memory implementation of the three
methods of interface v2 that this module uses, so the tests read what was kept and count what was computed.
"""
from __future__ import annotations

from dataclasses import replace

import pytest
from server.classroom import assignment_answers
from server.classroom import answers
from server.classroom.refusals import Busy, TooOften
from server.runtime import heavy
from server.classroom.spec import AssignmentSpec
from server.classroom.variants import SpecError, plan
from server.lessons.scenes import scenes

CRANK = {"scene": "transfer-functions", "variant": "slider_crank",
         "sliders": {"lambda": {"vary": {"min": 2.5, "max": 5.0}}},
         "questions": [{"id": "u31_max"}, {"id": "du31_min", "tolerance": 0.005}], "reveal_answers": True}


class MemoryStore:
    """variant_answers / put_variant_answers / recent_assignments_by_client of interface v2, in memory."""

    def __init__(self):
        self.answers: dict = {}
        self.created: list[tuple[str, float]] = []

    def variant_answers(self, assignment_id, variant):
        return self.answers.get((assignment_id, variant))

    def put_variant_answers(self, assignment_id, variant, found):
        self.answers[(assignment_id, variant)] = dict(found)

    def recent_assignments_by_client(self, client, since):
        return sum(1 for who, at in self.created if who == client and at >= since)


@pytest.fixture
def memory(monkeypatch) -> MemoryStore:
    kept = MemoryStore()
    monkeypatch.setattr(assignment_answers, "store", lambda: kept)
    return kept


@pytest.fixture
def computed(monkeypatch) -> list:
    """Every correct answer computed, in this process (heavy.run runs the function here, as MDL_HEAVY_PROCESSES=0
    does), and which function heavy.run was given."""
    calls: list = []
    real = answers._readout.__wrapped__

    def counted(*args):
        calls.append(args)
        return real(*args)
    monkeypatch.setattr(answers, "_readout", counted)
    monkeypatch.setattr(heavy, "run", lambda function, *args, lane="answers": calls.append(function.__name__)
                        or function(*args))
    return calls


def crank_plan(**changes):
    return plan(AssignmentSpec.model_validate(CRANK | changes), scenes())


def test_making_an_assignment_computes_its_checked_variants_in_the_heavy_process(memory, computed):
    resolved = crank_plan()
    found = assignment_answers.check_new(resolved)
    assert computed[0] == "answers_of_variants"                  # handed to the heavy process, not run inline
    assert sorted(found) == assignment_answers.checked_numbers(resolved.count)
    assert all(set(a) == {"u31_max", "du31_min"} and all(isinstance(v, float) for v in a.values())
               for a in found.values())
    assignment_answers.keep("A1", found)
    assert memory.variant_answers("A1", 0) == found[0]


def test_a_question_without_an_answer_for_a_checked_variant_refuses_the_assignment(memory, monkeypatch, computed):
    def no_answer(resolved, values, question_id):
        raise SpecError("questions", f"'{question_id}' has no value for these parameters")
    monkeypatch.setattr(assignment_answers, "variant_answer", no_answer)
    with pytest.raises(SpecError, match="question 'u31_max' has no answer for the variant"):
        assignment_answers.check_new(crank_plan())


def test_a_variant_is_computed_once_then_read_from_the_store_by_every_student(memory, computed):
    resolved = crank_plan()
    first = assignment_answers.correct_value("A1", resolved, 3, "u31_max")
    computations = len([c for c in computed if isinstance(c, tuple)])
    assert computations == 2                                     # the variant's two questions, once
    again = [assignment_answers.correct_value("A1", resolved, 3, q) for q in ("u31_max", "du31_min")]
    assert again[0] == first and len([c for c in computed if isinstance(c, tuple)]) == computations
    assert memory.variant_answers("A1", 3) == {"u31_max": first, "du31_min": again[1]}


def test_the_stored_answer_is_the_answer_computed_directly(memory, computed):
    resolved = crank_plan()
    stored = assignment_answers.correct_value("A1", resolved, 5, "du31_min")
    assert stored == answers.correct_answer(resolved, resolved.values(5), "du31_min")


def test_a_variant_whose_budget_runs_out_answers_503_and_keeps_nothing(memory, computed, monkeypatch):
    monkeypatch.setattr(assignment_answers, "VARIANT_BUDGET_S", -1.0)     # already spent when it starts
    with pytest.raises(Busy) as refused:
        assignment_answers.correct_value("A1", crank_plan(), 2, "u31_max")
    assert refused.value.code == "answers_not_ready" and refused.value.retry_after > 0
    assert memory.answers == {} and not [c for c in computed if isinstance(c, tuple)]


def test_a_budget_cut_inside_a_variant_leaves_the_whole_variant_out(monkeypatch):
    ticks = iter([0.0, 0.0, 10.0])          # the deadline (5 s), the first question, past it at the second
    monkeypatch.setattr(assignment_answers.time, "perf_counter", lambda: next(ticks))
    found = assignment_answers.answers_of_variants(crank_plan(), [0, 1], 5.0)
    assert found == {}


def test_an_answer_cut_short_by_its_endpoints_bound_is_never_kept_as_correct(memory, computed, monkeypatch):
    real = answers.compute_answer
    monkeypatch.setattr(answers, "compute_answer", lambda *args: replace(real(*args), partial=True))
    assert assignment_answers.answers_of_variants(crank_plan(), [4], 60.0) == {}
    with pytest.raises(Busy) as refused:
        assignment_answers.correct_value("A1", crank_plan(), 4, "u31_max")
    assert refused.value.code == "answers_not_ready" and memory.answers == {}


def test_an_answer_the_variant_has_not_is_a_422_in_words(memory):
    resolved = crank_plan()
    memory.put_variant_answers("A1", 0, {"u31_max": "undefined at a singular position", "du31_min": 1.0})
    with pytest.raises(SpecError, match="singular position"):
        assignment_answers.correct_value("A1", resolved, 0, "u31_max")


def test_one_address_makes_a_bounded_number_of_assignments_an_hour(memory, monkeypatch):
    monkeypatch.setattr(assignment_answers, "ASSIGNMENTS_PER_HOUR", 3)
    now = 100_000.0
    memory.created = [("10.0.0.1", now - 3000), ("10.0.0.1", now - 1200), ("10.0.0.2", now - 10)]
    assignment_answers.limit_creation("10.0.0.1", now)          # two in the hour: a third is allowed
    memory.created.append(("10.0.0.1", now - 5))
    with pytest.raises(TooOften) as refused:
        assignment_answers.limit_creation("10.0.0.1", now)
    assert refused.value.code == "rate_limited" and refused.value.limit == 3
    wait = refused.value.retry_after
    assert 600 <= wait <= 600 + assignment_answers.RETRY_STEP_S   # the oldest (now − 3000 s) leaves after 600 s
    assignment_answers.limit_creation("10.0.0.2", now)          # another address is not affected
    assignment_answers.limit_creation("10.0.0.1", now + wait)     # and after Retry-After, a place is free


# --- over HTTP, on the real store (SQLite in a tmp directory) ---------------------------------------------------

from fastapi.testclient import TestClient                      # noqa: E402

from server.classroom import assignment_store  # noqa: E402
from server.api.app import create_app                           # noqa: E402
from server.api.security import SECURITY_HEADERS               # noqa: E402

API = "/api/v1/assignments"


@pytest.fixture
def client(tmp_path, monkeypatch) -> TestClient:
    monkeypatch.setenv("MDL_DATA_DIR", str(tmp_path))
    monkeypatch.setenv("MDL_REGISTRATIONS_PER_HOUR", "100000")     # one test address registers many students
    monkeypatch.setattr(heavy, "HEAVY_PROCESSES", 0)
    assignment_store.store.cache_clear()
    yield TestClient(create_app())
    assignment_store.store.cache_clear()


def test_the_assignment_rate_is_limited_per_address_with_retry_after(client, monkeypatch):
    monkeypatch.setattr(assignment_answers, "ASSIGNMENTS_PER_HOUR", 2)
    made = [client.post(API, json=CRANK) for _ in range(3)]
    assert [r.status_code for r in made] == [201, 201, 429]
    refused = made[2]
    assert 3540 <= int(refused.headers["retry-after"]) <= 3600 + assignment_answers.RETRY_STEP_S
    assert refused.json()["detail"][0]["type"] == "rate_limited"
    assert all(refused.headers[name] == value for name, value in SECURITY_HEADERS.items())
    record = assignment_store.store().assignment(made[0].json()["id"])
    assert record.client == "testclient"                         # the address is kept with the assignment


def register(client, assignment_id: str, name: str) -> tuple[int, dict]:
    """Register by POST (identity's flow): the variant number (from 0) and the headers of the student's requests."""
    response = client.post(f"{API}/{assignment_id}/students", json={"name": name})
    assert response.status_code == 201, response.text
    return response.json()["variant"] - 1, {"Authorization": f"Bearer {response.json()['secret']}"}


def a_student_of_a_fresh_variant(client, assignment_id: str, kept) -> tuple[int, dict]:
    """A newly registered student whose variant was not computed when the assignment was made."""
    for k in range(200):
        number, headers = register(client, assignment_id, f"student {k}")
        if number not in kept:
            return number, headers
    raise AssertionError("every student fell on a checked variant")


def test_a_new_assignment_keeps_its_checked_answers_and_a_new_variant_is_computed_once(client, monkeypatch):
    created = client.post(API, json=CRANK).json()
    store = assignment_store.store()
    resolved = crank_plan()
    kept = [n for n in range(resolved.count) if store.variant_answers(created["id"], n) is not None]
    assert kept == assignment_answers.checked_numbers(resolved.count)
    runs = []
    real_run = heavy.run
    monkeypatch.setattr(heavy, "run", lambda function, *args, **kw: runs.append(args[1]) or real_run(function, *args))
    number, headers = a_student_of_a_fresh_variant(client, created["id"], kept)
    answer = client.post(f"{API}/{created['id']}/submissions", json={"question": "u31_max", "answer": 0.1},
                         headers=headers)
    assert answer.status_code == 200 and runs == [[number]]
    assert store.variant_answers(created["id"], number) is not None
    again = client.post(f"{API}/{created['id']}/submissions", json={"question": "du31_min", "answer": 0.1},
                        headers=headers)
    assert again.status_code == 200 and runs == [[number]]       # read from the store, not computed again


def test_a_variant_out_of_budget_answers_503_and_spends_no_attempt(client, monkeypatch):
    fine = CRANK | {"sliders": {"lambda": {"vary": {"min": 2.5, "max": 5.0}, "step": 0.001}}}
    created = client.post(API, json=fine).json()
    kept = set(assignment_answers.checked_numbers(plan(AssignmentSpec.model_validate(fine), scenes()).count))
    _, headers = a_student_of_a_fresh_variant(client, created["id"], kept)
    monkeypatch.setattr(assignment_answers, "VARIANT_BUDGET_S", -1.0)
    late = client.post(f"{API}/{created['id']}/submissions", json={"question": "u31_max", "answer": 0.1},
                       headers=headers)
    assert late.status_code == 503 and int(late.headers["retry-after"]) > 0
    assert late.json()["detail"][0]["type"] == "answers_not_ready"
    monkeypatch.setattr(assignment_answers, "VARIANT_BUDGET_S", 15.0)
    state = client.get(f"{API}/{created['id']}/me", headers=headers).json()
    assert state["questions"][0]["attempts_used"] == 0


def test_answers_wait_in_a_bounded_number_of_threads_and_refuse_at_once_past_it(memory, computed):
    """With every place taken (other requests waiting for the heavy process), a variant not kept yet is refused
    at once with 503 and Retry-After instead of holding another thread; a kept one is read as ever."""
    resolved = crank_plan()
    kept = assignment_answers.correct_value("A1", resolved, 1, "u31_max")
    places = [assignment_answers._computing.acquire(blocking=False) for _ in range(assignment_answers.ANSWER_COMPUTATIONS)]
    try:
        assert all(places)
        with pytest.raises(Busy) as busy:
            assignment_answers.correct_value("A1", resolved, 2, "u31_max")
        assert busy.value.code == "answers_busy" and busy.value.retry_after == 2
        assert assignment_answers.correct_value("A1", resolved, 1, "u31_max") == kept
    finally:
        for _ in places:
            assignment_answers._computing.release()
    assert assignment_answers.correct_value("A1", resolved, 2, "u31_max") > 0
