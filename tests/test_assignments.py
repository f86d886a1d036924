"""Assignments: the instructor's spec, per-student variants, answers computed on the server, submissions.
Students register by name and then identify themselves with their personal secret (here as
`Authorization: Bearer`; tests/test_identity.py covers the cookie, the personal link and the refusals).

The answers are checked against closed forms written here (the crank-slider's u₃₁ and u′₃₁ from the exact
geometry) and against the computing endpoints over HTTP for the same variant; the storage against a
fresh connection to the same file (a restart) and against concurrent submitters.
"""
from __future__ import annotations

import csv
import io
import json
import re
import subprocess
import sys
import threading
from datetime import datetime, timedelta, timezone

import numpy as np
import pytest
from fastapi.testclient import TestClient
from scipy.optimize import minimize_scalar

from server.lessons.markup import plain_label
from server.classroom import assignment_store
from server.classroom.answers import correct_answer
from server.api.app import app
from server.classroom.assignments import load
from server.api.routers import assignments as assignments_router
from server.classroom.store import SQLiteStore
from server.lessons.requests import scene_request
from server.lessons.scenes import Scene, scenes
from server.classroom.names import normalise

API = "/api/v1/assignments"
FLYWHEEL = {"scene": "flywheel", "variant": "rig", "title": "Lab 5",
            "sliders": {"delta": {"vary": {"min": 0.01, "max": 0.05}, "step": 0.001}, "omega_mean": {"value": 50}},
            "questions": [{"id": "flywheel_inertia"}], "attempts": 2, "reveal_answers": True}
CRANK = {"scene": "transfer-functions", "variant": "slider_crank",
         "sliders": {"lambda": {"vary": {"min": 2.5, "max": 5.0}}},
         "questions": [{"id": "u31_max"}, {"id": "du31_min", "tolerance": 0.005}], "reveal_answers": True}


@pytest.fixture()
def client(tmp_path, monkeypatch) -> TestClient:
    monkeypatch.setenv("MDL_DATA_DIR", str(tmp_path))
    monkeypatch.setenv("MDL_REGISTRATIONS_PER_HOUR", "100000")     # one test address registers whole classes
    assignment_store.store.cache_clear()
    yield TestClient(app)
    assignment_store.store.cache_clear()


def create(client, spec) -> dict:
    response = client.post(API, json=spec)
    assert response.status_code == 201, response.text
    return response.json()


def as_student(client, created, name) -> dict:
    """The headers of the student's requests (registered on first use; the secrets kept in `created`)."""
    secrets = created.setdefault("secrets", {})
    if name not in secrets:
        response = client.post(f"{API}/{created['id']}/students", json={"name": name})
        assert response.status_code == 201, response.text
        secrets[name] = response.json()["secret"]
    return {"Authorization": f"Bearer {secrets[name]}"}


def variant_of(client, created, name, lang="en") -> dict:
    response = client.get(f"{API}/{created['id']}/me", params={"lang": lang}, headers=as_student(client, created, name))
    assert response.status_code == 200, response.text
    return response.json()


def submit(client, created, name, question, answer):
    return client.post(f"{API}/{created['id']}/submissions", json={"question": question, "answer": answer},
                       headers=as_student(client, created, name))


def student_page(client, created, name, lang="en") -> str:
    """The student's page as their browser gets it: the cookie set by registering."""
    client.cookies.clear()
    client.get(f"/assignments/{created['id']}/me/{as_student(client, created, name)['Authorization'][7:]}")
    response = client.get(f"/assignments/{created['id']}", params={"lang": lang})
    assert response.status_code == 200 and 'id="assignment-data"' in response.text
    return response.text


def crank_slider_u31(phi, l1, l2):
    """u₃₁ = ds/dφ of the central crank-slider, φ = 0 at the inner dead centre (the scene's convention):
    s = x_B − (l₂ − l₁), x_B = −l₁cos φ + √(l₂² − l₁²sin²φ)."""
    s, c = np.sin(phi), np.cos(phi)
    root = np.sqrt(l2 ** 2 - (l1 * s) ** 2)
    return l1 * s - l1 ** 2 * s * c / root


def crank_slider_du31(phi, l1, l2):
    """u′₃₁ = d²s/dφ² of the same."""
    s, c = np.sin(phi), np.cos(phi)
    root = np.sqrt(l2 ** 2 - (l1 * s) ** 2)
    return l1 * c - l1 ** 2 * (c * c - s * s) / root - l1 ** 4 * s * s * c * c / root ** 3


def extremum(f, largest):
    """Global extremum over one turn: the best of 3600 nodes, polished by a bounded scalar search."""
    phi = np.linspace(0, 2 * np.pi, 3601)
    values = f(phi) if largest else -f(phi)
    i = int(np.argmax(values))
    best = minimize_scalar(lambda x: -(f(x) if largest else -f(x)), bounds=(phi[i] - 0.01, phi[i] + 0.01),
                           method="bounded", options={"xatol": 1e-12})
    return f(best.x)


# --- the answers ---------------------------------------------------------------------------------------

def test_crank_slider_answers_match_the_closed_forms(client):
    """u₃₁max and u′₃₁min of the student's λ against the exact geometry: the server's parabolic refinement
    on a 0.1° grid is O(h³) ≈ 1e-9, so rel 1e-7 is tight and safe."""
    created = create(client, CRANK | {"attempts": 1})
    for name in ("Ivanov", "Petrenko", "Shevchenko"):
        variant = variant_of(client, created, name)
        lam = variant["values"]["lambda"]
        l1 = 0.1                                      # the scene's fixed crank
        u31 = extremum(lambda p: crank_slider_u31(p, l1, lam * l1), True)
        du31 = extremum(lambda p: crank_slider_du31(p, l1, lam * l1), False)
        for question, exact in (("u31_max", u31), ("du31_min", du31)):
            outcome = submit(client, created, name, question, exact * (1 + 1e-7)).json()
            assert outcome["right"], (name, lam, question)
            assert outcome["correct_value"] == pytest.approx(exact, rel=1e-7)


def test_flywheel_answer_is_what_the_flywheel_endpoint_computes_for_the_variant(client):
    """The question reads flywheel_inertia from POST /api/v1/flywheel for the student's values (the
    method itself is tested in test_flywheel.py against the analytic case and a time integration)."""
    created = create(client, FLYWHEEL)
    variant = variant_of(client, created, "Kovalenko")
    scene = scenes()["flywheel"]
    body = scene_request(scene, scene.variants[0], variant["values"])
    assert body["delta"] == variant["values"]["delta"]
    direct = client.post("/api/v1/flywheel?precision=full", json=body).json()["flywheel_inertia"]
    wrong = submit(client, created, "Kovalenko", "flywheel_inertia", direct * 1.05).json()
    assert not wrong["right"] and wrong["correct_value"] is None and wrong["attempts_left"] == 1
    right = submit(client, created, "Kovalenko", "flywheel_inertia", direct * 1.019).json()
    assert right["right"] and right["closed"] and right["correct_value"] == pytest.approx(direct, rel=1e-12)


# --- variants ------------------------------------------------------------------------------------------

def test_the_variant_follows_from_the_name_alone(client):
    created = create(client, FLYWHEEL)
    first = variant_of(client, created, "Иванов  Иван")
    _, resolved = load(created["id"])
    assert first["variant"] == resolved.number_for(created["id"], normalise(" иванов иван ")) + 1
    assert first["values"] == resolved.values(first["variant"] - 1)
    other = create(client, FLYWHEEL)                                 # another assignment: independent draw
    numbers = {variant_of(client, other, f"student {k}")["variant"] for k in range(40)}
    assert len(numbers) > 18                                         # 40 draws from 41 values: ≈ 26 distinct expected
    assert first["assignment"]["variants"] == 41


def test_variants_spread_over_the_grid_and_stay_in_range(client):
    created = create(client, FLYWHEEL)
    deltas = [variant_of(client, created, f"s{k}")["values"]["delta"] for k in range(120)]
    grid = np.arange(0.01, 0.05 + 1e-9, 0.001)       # the [δ] slider is logarithmic: 1000 positions over
    assert all(np.isclose(grid, d, rtol=6e-3).any() for d in deltas)   # 2.3 decades: a step is 0.53 %
    assert len(set(deltas)) > 30                                     # 120 draws from 41: ≈ 39 distinct expected
    assert min(deltas) >= 0.01 and max(deltas) <= 0.05


# --- what the student's page holds before answering -----------------------------------------------------

NUMBER = re.compile(r"-?\d+(?:[.,]\d+)?(?:[eE][-+]?\d+)?")


def numbers_in(text: str) -> np.ndarray:
    return np.array([float(m.replace(",", ".")) for m in NUMBER.findall(text)] or [np.nan])


@pytest.mark.parametrize("spec", [FLYWHEEL, CRANK], ids=["flywheel", "crank"])
def test_no_answer_reaches_the_student_before_submission(client, spec):
    created = create(client, spec)
    page = student_page(client, created, "Bondarenko")
    variant = variant_of(client, created, "Bondarenko")
    scene = json.loads(re.search(r'id="scene-data">(.*?)</script>', page, re.S).group(1).replace("<\\/", "</"))
    hidden = {"flywheel"} if spec is FLYWHEEL else {"u31", "du31"}
    assert not hidden & set(scene["outputs"]) and all(
        not hidden & set(p.get("needs", []) + p.get("outputs", [])) for p in scene["panels"].values())
    assert "questions" not in scene or scene["questions"] == []
    seen = np.concatenate([numbers_in(page), numbers_in(json.dumps(variant))])
    for question in spec["questions"]:
        # what the server will accept as right: learnt only by submitting a (wrong) answer to the last attempt
        outcome = None
        for _ in range(spec.get("attempts", 3)):
            outcome = submit(client, created, "Bondarenko", question["id"], 1e9).json()
        correct = outcome["correct_value"]
        assert not np.any(np.isclose(seen, correct, rtol=1e-4, atol=0)), (question["id"], correct)


# --- submissions and storage ----------------------------------------------------------------------------

def test_attempts_are_counted_and_a_closed_question_refuses(client):
    created = create(client, FLYWHEEL)
    assert submit(client, created, "A", "flywheel_inertia", 1.0).json()["attempts_left"] == 1
    last = submit(client, created, "A", "flywheel_inertia", 1.0).json()
    assert last["closed"] and last["attempts_left"] == 0 and last["correct_value"] > 0
    refused = submit(client, created, "A", "flywheel_inertia", last["correct_value"])
    assert refused.status_code == 409 and refused.json()["detail"][0]["type"] == "no_attempts_left"
    right = submit(client, created, "B", "flywheel_inertia", variant_answer(client, created, "B"))
    assert right.json()["right"]
    again = submit(client, created, "B", "flywheel_inertia", 1.0)
    assert again.status_code == 409 and again.json()["detail"][0]["type"] == "already_right"


def variant_answer(client, created, name) -> float:
    """The server's answer for the student's variant, to submit a right one."""
    values = variant_of(client, created, name)["values"]
    _, resolved = load(created["id"])
    return correct_answer(resolved, values, "flywheel_inertia")


def test_answers_stay_hidden_unless_the_assignment_reveals_them(client):
    created = create(client, FLYWHEEL | {"reveal_answers": False})
    outcomes = [submit(client, created, "Quiet", "flywheel_inertia", 1.0).json() for _ in range(2)]
    assert outcomes[-1]["closed"] and all(o["correct_value"] is None for o in outcomes)
    assert variant_of(client, created, "Quiet")["questions"][0]["correct_value"] is None
    right = submit(client, created, "Loud", "flywheel_inertia", variant_answer(client, created, "Loud")).json()
    assert right["right"] and right["correct_value"] is None


def test_concurrent_submitters_never_exceed_the_attempts(client):
    """Twelve threads submit wrong answers for one student at once: exactly `attempts` land (BEGIN IMMEDIATE).
    The first wrong answer goes alone: it makes the variant's correct answers kept, so that none of the twelve
    waits for them (at most MDL_ANSWER_COMPUTATIONS wait; the rest would get 503, no attempt counted)."""
    created = create(client, FLYWHEEL | {"attempts": 3})
    variant_of(client, created, "Racer")
    assert submit(client, created, "Racer", "flywheel_inertia", 1.0).status_code == 200
    codes = []

    def one():
        codes.append(submit(client, created, "Racer", "flywheel_inertia", 1.0).status_code)

    threads = [threading.Thread(target=one) for _ in range(12)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert sorted(codes) == [200] * 2 + [409] * 10
    row = client.get(f"{API}/{created['id']}/results/{created['results_token']}").json()["students"][0]
    assert row["attempts"] == 3 and row["questions"]["flywheel_inertia"]["attempts"] == 3


def test_a_restart_loses_nothing(client, tmp_path):
    created = create(client, FLYWHEEL)
    submit(client, created, "Melnyk", "flywheel_inertia", 3.0)
    reopened = SQLiteStore(tmp_path / assignment_store.DATABASE_FILE)       # a new process would do this
    assert reopened.assignment(created["id"]).spec["title"] == "Lab 5"
    assert [(s.student_key, s.answer, s.attempt) for s in reopened.submissions(created["id"])] == [("melnyk", 3.0, 1)]


def test_the_deadline_closes_submissions(client):
    past = (datetime.now(timezone.utc) - timedelta(minutes=1)).isoformat()
    created = create(client, FLYWHEEL | {"deadline": past})
    assert client.get(f"{API}/{created['id']}").json()["open"] is False
    refused = submit(client, created, "Late", "flywheel_inertia", 1.0)
    assert refused.status_code == 403 and refused.json()["detail"][0]["type"] == "deadline_passed"


def test_submissions_are_rate_limited_per_address(client, monkeypatch):
    monkeypatch.setattr(assignments_router, "SUBMISSIONS_PER_MINUTE", 2)
    created = create(client, FLYWHEEL | {"attempts": 5})
    assert [submit(client, created, n, "flywheel_inertia", 1.0).status_code for n in "ab"] == [200, 200]
    limited = submit(client, created, "c", "flywheel_inertia", 1.0)
    assert limited.status_code == 429 and limited.headers["retry-after"] == "60"


def test_results_and_csv_agree(client):
    created = create(client, FLYWHEEL)
    submit(client, created, "Ткаченко", "flywheel_inertia", 2.5)
    submit(client, created, "Lysenko", "flywheel_inertia", variant_answer(client, created, "Lysenko"))
    results = client.get(f"{API}/{created['id']}/results/{created['results_token']}").json()
    table = client.get(f"{API}/{created['id']}/results/{created['results_token']}/csv")
    assert table.headers["content-type"].startswith("text/csv")
    rows = list(csv.DictReader(io.StringIO(table.text.lstrip("\ufeff")), delimiter=";"))   # ru: ";", "0,5"
    plan = load(created["id"])[1]                       # the columns in words of the assignment's language (ru)
    delta = plain_label(next(s.label["ru"] for s in plan.variant.sliders if s.id == "delta"))      # headers: plain
    inertia = plain_label(next(q.label["ru"] for q in plan.scene.questions if q.id == "flywheel_inertia"))
    number = lambda cell: float(cell.replace(",", "."))                    # noqa: E731
    assert [r["Студент"] for r in rows] == [s["student"] for s in results["students"]] == ["Ткаченко", "Lysenko"]
    for row, student in zip(rows, results["students"]):
        assert int(row["Вариант"]) == student["variant"] and number(row[delta]) == student["values"]["delta"]
        assert int(row["Верно"]) == student["score"] and int(row[f"{inertia}: верно"]) == student["score"]
        checked_against = student["questions"]["flywheel_inertia"]["correct"]
        assert checked_against == variant_answer(client, created, student["student"])
        assert number(row[f"{inertia}: Правильный ответ"]) == checked_against     # repr: every digit
    assert client.get(f"{API}/{created['id']}/results/wrong-token").status_code == 404
    assert client.get(f"/assignments/{created['id']}/results/wrong-token").status_code == 404


@pytest.mark.parametrize("change, field", [
    ({"scene": "nowhere"}, ["body", "scene"]),
    ({"variant": "tricycle"}, ["body", "variant"]),
    ({"sliders": {"warp": {"value": 1}}}, ["body", "sliders", "warp"]),
    ({"sliders": {"delta": {"vary": {"min": 0.01, "max": 0.5}}}}, ["body", "sliders", "delta", "vary"]),
    ({"sliders": {"delta": {"value": 0.9}}}, ["body", "sliders", "delta", "value"]),
    ({"sliders": {"delta": {"vary": {"min": 0.05, "max": 0.01}}}}, ["body", "sliders", "delta", "vary"]),
    ({"questions": [{"id": "u31_max"}]}, ["body", "questions", "0", "id"]),
    ({"questions": []}, ["body", "questions"]),
    ({"attempts": 0}, ["body", "attempts"]),
    ({"toggles": {"strokes": 3}}, ["body", "toggles", "strokes"]),
])
def test_a_wrong_spec_is_refused_with_the_field(client, change, field):
    response = client.post(API, json=FLYWHEEL | change)
    assert response.status_code == 422
    detail = response.json()["detail"][0]
    assert [str(part) for part in detail["loc"][:len(field)]] == field and detail["msg"]


def test_a_variant_without_an_answer_is_refused_when_the_assignment_is_made(client):
    """λ down to 1.05 with an offset that makes the crank unable to turn: the server says so at creation."""
    spec = CRANK | {"sliders": {"lambda": {"vary": {"min": 1.05, "max": 1.5}}, "offset": {"value": 0.5}}}
    response = client.post(API, json=spec)
    assert response.status_code == 422 and "no answer" in response.json()["detail"][0]["msg"]


def test_bad_submissions_are_refused(client):
    created = create(client, FLYWHEEL)
    url = f"{API}/{created['id']}/submissions"
    mine = as_student(client, created, "x")
    assert client.post(url, json={"question": "nope", "answer": 1}, headers=mine).status_code == 422
    assert client.post(url, content='{"question": "flywheel_inertia", "answer": NaN}',
                       headers=mine | {"content-type": "application/json"}).status_code == 422
    assert client.post(url, json={"student": "x" * 81, "question": "flywheel_inertia", "answer": 1},
                       headers=mine).status_code == 422
    assert client.post(url, json={"question": "flywheel_inertia", "answer": 1, "extra": 1}, headers=mine).status_code == 422
    assert client.post(f"{API}/unknown/submissions",
                       json={"question": "flywheel_inertia", "answer": 1}, headers=mine).status_code == 404


def test_assignment_pages_render(client):
    created = create(client, FLYWHEEL)
    start = client.get(f"/assignments/{created['id']}", params={"lang": "uk"})
    assert start.status_code == 200 and 'name="student"' in start.text
    assert client.get("/scenes/flywheel/assign", params={"lang": "en", "delta": "0.02"}).status_code == 200
    assert client.get("/scenes/nowhere/assign").status_code == 404
    page = client.get(f"/assignments/{created['id']}/results/{created['results_token']}", params={"lang": "ru"})
    assert page.status_code == 200 and "results-empty" in page.text


def test_coupler_acceleration_answer_matches_the_closed_form(client):
    """ε_AB of the crank-slider at constant ω: sin ψ = λ sin φ gives ψ″ = λ(λ² − 1) sin φ / (1 − λ²sin²φ)^{3/2},
    ε = ω²ψ″; its largest value over a turn, rel 1e-5 (the answer is refined from 361 nodes, O(h³))."""
    created = create(client, {"scene": "angular-acceleration", "variant": "crank_slider",
                              "sliders": {"lam": {"vary": {"min": 0.2, "max": 0.8}}}, "questions": [{"id": "epsilon_max"}],
                              "reveal_answers": True})
    variant = variant_of(client, created, "Lesya Ukrainka")
    lam, omega = variant["values"]["lam"], variant["values"]["omega0"]
    psi_dd = lambda phi: lam * (lam ** 2 - 1) * np.sin(phi) / (1 - (lam * np.sin(phi)) ** 2) ** 1.5
    exact = omega ** 2 * extremum(psi_dd, True)
    outcome = submit(client, created, "Lesya Ukrainka", "epsilon_max", exact * (1 + 1e-6)).json()
    assert outcome["right"] and outcome["correct_value"] == pytest.approx(exact, rel=1e-5)


@pytest.mark.parametrize("scene_id, question_id", [(s.id, q.id) for s in scenes().values() for q in s.questions])
def test_every_question_has_an_answer_and_its_page_hides_it(client, scene_id, question_id):
    """At the defaults of the first variant it applies to: a finite answer, and a student's page whose
    requests hold none of the outputs the question hides."""
    scene = scenes()[scene_id]
    asked = next(q for q in scene.questions if q.id == question_id)
    variant = next(v for v in scene.variants if not asked.variants or v.id in asked.variants)
    created = create(client, {"scene": scene_id, "variant": variant.id, "questions": [{"id": question_id}]})
    page = student_page(client, created, "Default")
    shown = json.loads(re.search(r'id="scene-data">(.*?)</script>', page, re.S).group(1).replace("<\\/", "</"))
    shown_scene = Scene.model_validate(shown)
    request = scene_request(shown_scene, shown_scene.variants[0])
    assert not set(asked.hides) & set(request.get("outputs", []))      # a course project asks for no outputs
    _, resolved = load(created["id"])
    angle = asked.angle.min if asked.kind == "at_angle" else None       # a question at the student's angle
    assert np.isfinite(correct_answer(resolved, resolved.values(0), question_id, angle))


def test_the_classroom_and_the_lessons_do_not_import_the_http_layer():
    """server/classroom and server/lessons build on the lesson model alone: importing them loads no module of
    server/api (a fresh interpreter, so nothing else has imported it)."""
    code = ("import sys, server.classroom.spec, server.classroom.store, server.classroom.variants, "
            "server.classroom.names, server.classroom.identity, "
            "server.lessons.requests, server.lessons.scenes; "
            "print(sorted(m for m in sys.modules if m.startswith('server.api')))")
    loaded = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert loaded.strip() == "[]"
