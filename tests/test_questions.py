"""Questions that are not one readout: a value at an angle the student chooses, a quantity
computed from named readouts, a prediction made before its plot opens; and where the public pages show an
answer. Answers are checked against the crank-slider's exact geometry written here (closed forms of u₃₁ and
u′₃₁, and central differences of the position s), never against the code under test.
"""
from __future__ import annotations

import json
import re

import numpy as np
import pytest
from fastapi.testclient import TestClient
from scipy.optimize import minimize_scalar

from server.classroom import assignment_store
from server.api.app import app
from server.classroom.visibility import public_views

from test_assignments import as_student
from server.lessons.scenes import Question, Scene, scenes

API = "/api/v1/assignments"
L1 = 0.1                                              # the scene's fixed crank, m
CRANK = {"scene": "transfer-functions", "variant": "slider_crank",
         "sliders": {"lambda": {"vary": {"min": 2.5, "max": 5.0}}}, "reveal_answers": True}


@pytest.fixture()
def client(tmp_path, monkeypatch) -> TestClient:
    monkeypatch.setenv("MDL_DATA_DIR", str(tmp_path))
    assignment_store.store.cache_clear()
    yield TestClient(app)
    assignment_store.store.cache_clear()


def create(client, questions, **more) -> dict:
    response = client.post(API, json=CRANK | {"questions": questions} | more)
    assert response.status_code == 201, response.text
    return response.json()


# How a test acts as a student: the only lines that know how a student is identified (registered by POST,
# test_assignments.as_student; their secret sent as `Authorization: Bearer`, or as their browser's cookie).

def state_of(client, created, name) -> dict:
    """The student's variant and the state of their questions, as their page reads it."""
    response = client.get(f"{API}/{created['id']}/me", params={"lang": "en"},
                          headers=as_student(client, created, name))
    assert response.status_code == 200, response.text
    return response.json()


def submit(client, created, name, question, answer, angle=None):
    body = {"question": question, "answer": answer} | ({} if angle is None else {"angle": angle})
    return client.post(f"{API}/{created['id']}/submissions", json=body, headers=as_student(client, created, name))


def student_page(client, created, name) -> str:
    """The student's page as their browser gets it: the cookie set by their personal link."""
    client.cookies.clear()
    client.get(f"/assignments/{created['id']}/me/{as_student(client, created, name)['Authorization'][7:]}")
    return client.get(f"/assignments/{created['id']}", params={"lang": "en"}).text


def lam_of(client, created, name) -> float:
    return state_of(client, created, name)["values"]["lambda"]


def u31(phi, l1, l2):
    """u₃₁ = ds/dφ of the central crank-slider, φ = 0 at the inner dead centre (the scene's convention):
    s = x_B − (l₂ − l₁), x_B = −l₁cos φ + √(l₂² − l₁²sin²φ)."""
    s, c = np.sin(phi), np.cos(phi)
    return l1 * s - l1 ** 2 * s * c / np.sqrt(l2 ** 2 - (l1 * s) ** 2)


def du31(phi, l1, l2):
    s, c = np.sin(phi), np.cos(phi)
    root = np.sqrt(l2 ** 2 - (l1 * s) ** 2)
    return l1 * c - l1 ** 2 * (c * c - s * s) / root - l1 ** 4 * s * s * c * c / root ** 3


def position(phi, l1, l2):
    return -l1 * np.cos(phi) + np.sqrt(l2 ** 2 - (l1 * np.sin(phi)) ** 2) - (l2 - l1)


def extremum(f, largest):
    """Global extremum over one turn: the best of 3600 nodes, polished by a bounded scalar search."""
    phi = np.linspace(0, 2 * np.pi, 3601)
    sign = 1 if largest else -1
    i = int(np.argmax(sign * f(phi)))
    best = minimize_scalar(lambda x: -sign * f(x), bounds=(phi[i] - 0.01, phi[i] + 0.01), method="bounded",
                           options={"xatol": 1e-12})
    return f(best.x)


def student_scene(client, created, name) -> dict:
    page = student_page(client, created, name)
    return json.loads(re.search(r'id="scene-data">(.*?)</script>', page, re.S).group(1).replace("<\\/", "</"))


def test_the_closed_form_is_the_derivative_of_the_position():
    """The reference itself: u₃₁ against central differences of s (h = 1e-5 rad: truncation ~h²·s‴ ≈ 1e-11 m,
    rounding ~1e-16/h ≈ 1e-11 m; 1e-9 m is safe)."""
    phi, h = np.radians(np.arange(10, 171, 5)), 1e-5
    for lam in (1.5, 3.0, 5.0):
        fd = (position(phi + h, L1, lam * L1) - position(phi - h, L1, lam * L1)) / (2 * h)
        assert np.allclose(u31(phi, L1, lam * L1), fd, rtol=0, atol=1e-9)


# --- a value at an angle the student chooses -----------------------------------------------------------

def test_the_value_at_the_chosen_angle_is_the_exact_u31_there(client):
    """The server evaluates the mechanism at exactly the student's φ: equal to the closed form to rounding
    (rel 1e-9 leaves room for the solver of the positions, which meets machine precision)."""
    created = create(client, [{"id": "u31_at_angle"}], attempts=1)
    for name, angle in (("Ivanov", 35), ("Petrenko", 90), ("Shevchenko", 165), ("Bondar", 10)):
        lam = lam_of(client, created, name)
        exact = u31(np.radians(angle), L1, lam * L1)
        outcome = submit(client, created, name, "u31_at_angle", exact * (1 + 1e-3), angle)
        assert outcome.status_code == 200, outcome.text
        assert outcome.json()["right"] and outcome.json()["correct_value"] == pytest.approx(exact, rel=1e-9)


def test_the_value_at_another_angle_is_wrong(client):
    created = create(client, [{"id": "u31_at_angle"}], attempts=2)
    lam = lam_of(client, created, "Ivanov")
    at_40 = u31(np.radians(40), L1, lam * L1)
    assert not submit(client, created, "Ivanov", "u31_at_angle", at_40, 45).json()["right"]
    assert submit(client, created, "Ivanov", "u31_at_angle", at_40, 40).json()["right"]


def test_the_offset_crank_slider_at_an_angle_matches_differences_of_its_position(client):
    """With an offset e the closed form above does not hold: the reference is the five-point difference of the
    position s that the kinematics endpoint returns at φ ± h, ± 2h (h = 1e-3 rad). The endpoint sends 7
    significant digits (s ≈ 0.06 m: ±5e-9 m), so the difference is good to ~1e-5 m / 0.08 m; truncation
    h⁴·s⁽⁵⁾/30 ≈ 1e-14 m. Hence rel 2e-4."""
    created = create(client, [{"id": "u31_at_angle"}],
                     sliders={"lambda": {"value": 3.2}, "offset": {"value": 0.4}}, attempts=1)
    angle, h = 65.0, 1e-3
    phi = [np.radians(angle) + k * h for k in (-2, -1, 1, 2)]
    body = {"mechanism": "slider_crank", "params": {"l1": L1, "l2": 3.2 * L1, "e": 0.4 * L1}, "phi": phi,
            "outputs": ["s"]}
    s = client.post("/api/v1/kinematics", json=body).json()["outputs"]["s"]
    reference = (s[0] - 8 * s[1] + 8 * s[2] - s[3]) / (12 * h)
    outcome = submit(client, created, "Any", "u31_at_angle", reference, angle).json()
    assert outcome["right"] and outcome["correct_value"] == pytest.approx(reference, rel=2e-4)


@pytest.mark.parametrize("angle, reason", [(None, "needs the crank angle"), (12, "in steps of 5"),
                                           (5, "from 10° to 170°"), (175, "from 10° to 170°")])
def test_a_missing_or_off_grid_angle_is_refused_naming_the_angle_and_costs_no_attempt(client, angle, reason):
    created = create(client, [{"id": "u31_at_angle"}], attempts=1)
    refused = submit(client, created, "Ivanov", "u31_at_angle", 0.05, angle)
    assert refused.status_code == 422 and refused.json()["detail"][0]["loc"] == ["body", "angle"]
    assert reason in refused.json()["detail"][0]["msg"]
    assert submit(client, created, "Ivanov", "u31_at_angle", 0.05, 30).status_code == 200


def test_the_instructor_may_narrow_the_angles(client):
    created = create(client, [{"id": "u31_at_angle", "angle": {"min": 100, "max": 160, "step": 20}}])
    state = state_of(client, created, "Ivanov")["questions"][0]
    assert state["kind"] == "at_angle" and state["angle"] == {"min": 100, "max": 160, "step": 20}
    assert submit(client, created, "Ivanov", "u31_at_angle", 0.05, 30).status_code == 422
    assert submit(client, created, "Ivanov", "u31_at_angle", 0.05, 140).status_code == 200


@pytest.mark.parametrize("pick, field, reason", [
    ({"id": "u31_at_angle", "angle": {"min": 0, "max": 90, "step": 5}}, ["questions", "0", "angle"], "within 10°"),
    ({"id": "u31_at_angle", "angle": {"min": 20, "max": 90, "step": 0}}, ["questions", "0", "angle", "step"], ""),
    ({"id": "u31_at_angle", "angle": {"min": 20, "max": 90, "step": 30}}, ["questions", "0", "angle"], "whole"),
    ({"id": "u31_at_angle", "angle": {"min": 90, "max": 20, "step": 5}}, ["questions", "0", "angle"], "below"),
    ({"id": "u31_max", "angle": {"min": 20, "max": 90, "step": 5}}, ["questions", "0", "angle"], "does not ask"),
    ({"id": "u31_max", "expression": "1 + 1"}, ["questions", "0", "expression"], "not computed from readouts"),
    ({"id": "du31_ratio", "expression": "du_max / x"}, ["questions", "0", "expression"], "'x' is not a readout"),
    ({"id": "du31_ratio", "expression": "du_max +"}, ["questions", "0", "expression"], "ends too early"),
    ({"id": "du31_ratio", "expression": "__import__('os')"}, ["questions", "0", "expression"], "cannot read"),
    ({"id": "du31_ratio", "expression": "(" * 13 + "1" + ")" * 13}, ["questions", "0", "expression"], "deeper"),
    ({"id": "du31_ratio", "expression": "1" * 201}, ["questions", "0", "expression"], "at most 200"),
])
def test_a_malformed_question_spec_is_refused_naming_the_field(client, pick, field, reason):
    refused = client.post(API, json=CRANK | {"questions": [pick]})
    assert refused.status_code == 422, refused.text
    detail = refused.json()["detail"][0]
    assert [str(part) for part in detail["loc"]] == ["body", *field] and reason in detail["msg"], detail


# --- a quantity computed from two readouts --------------------------------------------------------------

def test_the_ratio_of_two_readouts_matches_the_closed_form(client):
    """u′₃₁max / u′₃₁min from the exact geometry; the server's extrema are O(h³) ≈ 1e-9 on its 0.1° grid,
    so rel 1e-7 is tight and safe."""
    created = create(client, [{"id": "du31_ratio"}], attempts=1)
    for name in ("Ivanov", "Petrenko"):
        lam = lam_of(client, created, name)
        f = lambda p: du31(p, L1, lam * L1)
        exact = extremum(f, True) / extremum(f, False)
        outcome = submit(client, created, name, "du31_ratio", exact).json()
        assert outcome["right"] and outcome["correct_value"] == pytest.approx(exact, rel=1e-7)


def test_the_instructor_may_write_another_expression_over_the_readouts(client):
    created = create(client, [{"id": "du31_ratio", "expression": "(du_max − du_min) ÷ 2"}], attempts=1)
    lam = lam_of(client, created, "Ivanov")
    f = lambda p: du31(p, L1, lam * L1)
    exact = (extremum(f, True) - extremum(f, False)) / 2
    outcome = submit(client, created, "Ivanov", "du31_ratio", exact).json()
    assert outcome["right"] and outcome["correct_value"] == pytest.approx(exact, rel=1e-7)


def test_content_with_a_wrong_expression_or_an_angle_on_a_dynamics_scene_does_not_load():
    base = {"id": "q", "label": {"ru": "q", "uk": "q", "en": "q"}, "hides": []}
    with pytest.raises(ValueError, match="not a readout"):
        Question.model_validate(base | {"kind": "combination", "expression": "a / b",
                                        "readouts": {"a": {"outputs": ["u31"], "path": "outputs.u31"}}})
    with pytest.raises(ValueError, match="angle grid"):
        Question.model_validate(base | {"outputs": ["u31"], "path": "outputs.u31", "kind": "at_angle"})
    flywheel = scenes()["flywheel"].model_dump()
    flywheel["questions"].append(base | {"kind": "at_angle", "outputs": ["flywheel"], "path": "x",
                                         "angle": {"min": 0, "max": 90, "step": 5}})
    with pytest.raises(ValueError, match="needs a kinematics scene"):
        Scene.model_validate(flywheel)


# --- a prediction before its plot opens -----------------------------------------------------------------

def panels_showing(scene: dict, output: str) -> set[str]:
    return {k for k, p in scene["panels"].items() if output in p.get("outputs", []) + p.get("needs", [])}


def test_a_prediction_keeps_its_plots_locked_until_it_is_closed(client):
    created = create(client, [{"id": "u31_max_prediction"}], attempts=2)
    state = state_of(client, created, "Ivanov")["questions"][0]
    assert state["kind"] == "prediction" and set(state["locks"]) == {"u31", "approximations", "harmonics"}
    before = student_scene(client, created, "Ivanov")
    assert "u31" not in before["outputs"] and not panels_showing(before, "u31")
    assert "u31" not in before["variants"][0]["panels"]
    lam = lam_of(client, created, "Ivanov")
    exact = extremum(lambda p: u31(p, L1, lam * L1), True)
    assert not submit(client, created, "Ivanov", "u31_max_prediction", 2 * exact).json()["right"]
    still = student_scene(client, created, "Ivanov")            # wrong, one attempt left: still locked
    assert "u31" not in still["outputs"] and "u31" not in still["variants"][0]["panels"]
    outcome = submit(client, created, "Ivanov", "u31_max_prediction", exact * 1.01).json()
    assert outcome["right"] and outcome["correct_value"] == pytest.approx(exact, rel=1e-7)
    after = student_scene(client, created, "Ivanov")
    assert "u31" in after["outputs"] and {"u31", "approximations", "harmonics"} <= set(after["variants"][0]["panels"])
    other = student_scene(client, created, "Petrenko")           # another student's page stays locked
    assert "u31" not in other["outputs"]


def test_a_prediction_opens_after_the_last_wrong_attempt_too(client):
    created = create(client, [{"id": "u31_max_prediction"}], attempts=1)
    submit(client, created, "Ivanov", "u31_max_prediction", 1.0)
    assert "u31" in student_scene(client, created, "Ivanov")["outputs"]


def test_a_readout_of_the_same_plot_keeps_it_hidden_after_the_prediction(client):
    created = create(client, [{"id": "u31_max_prediction"}, {"id": "u31_max"}], attempts=1)
    submit(client, created, "Ivanov", "u31_max_prediction", 1.0)
    assert "u31" not in student_scene(client, created, "Ivanov")["outputs"]


# --- where the public pages show an answer --------------------------------------------------------------

def test_the_public_scene_shows_the_u31_questions_in_its_plots():
    scene = scenes()["transfer-functions"]
    variant = next(v for v in scene.variants if v.id == "slider_crank")
    for question in scene.questions:
        shown = {panel for _, panel, _ in public_views(scene, variant, question)}
        assert "u31" in scene.panels and ("u31" in shown or "du31" in shown), question.id
        assert "linkage" not in shown and "position" not in shown       # s and the drawing give no u₃₁ value


def test_a_question_whose_outputs_no_panel_draws_is_not_shown():
    scene = scenes()["transfer-functions"]
    variant = next(v for v in scene.variants if v.id == "slider_crank")
    hidden_only = scene.questions[0].model_copy(update={"hides": ["special"]})
    assert public_views(scene, variant, hidden_only) == []


def test_every_question_of_every_scene_is_shown_somewhere_or_says_why_not():
    """Every question shipped today is drawn by a panel of its own public scene: the builder must say so."""
    for scene in scenes().values():
        if scene.kind == "project":          # computed by the student on /project: the builder says so
            continue
        for question in scene.questions:
            variant = next(v for v in scene.variants if not question.variants or v.id in question.variants)
            views = public_views(scene, variant, question)
            assert any(s.id == scene.id and direct for s, _, direct in views), (scene.id, question.id)


@pytest.mark.parametrize("lang, words", [("ru", "открытой странице"), ("uk", "відкритій сторінці"),
                                         ("en", "public page")])
def test_the_builder_tells_per_question_where_its_answer_shows(client, lang, words):
    page = client.get("/scenes/transfer-functions/assign", params={"lang": lang, "variant": "slider_crank"}).text
    notices = re.findall(r'<p class="leak-notice[^"]*" id="leak-([^"]+)"[^>]*>(.*?)</p>', page, re.S)
    assert {q for q, _ in notices} == {q.id for q in scenes()["transfer-functions"].questions}
    assert all(words in text for _, text in notices)


# --- decimal comma in the API ---------------------------------------------------------------------------

@pytest.mark.parametrize("text", ["2,5", "1,234.5", "1.234,5", "2,5,1"])
def test_the_api_refuses_a_number_written_with_a_comma_naming_the_field(client, text):
    """JSON numbers carry no locale; a string the API would read as a number must not lose its comma."""
    refused = client.post(API, json=CRANK | {"questions": [{"id": "u31_max"}],
                                             "sliders": {"lambda": {"value": text}}})
    assert refused.status_code == 422
    assert refused.json()["detail"][0]["loc"] == ["body", "sliders", "lambda", "value"]


# --- nothing of the answer reaches the student's page ----------------------------------------------------

NUMBER = re.compile(r"-?\d+(?:[.,]\d+)?(?:[eE][-+]?\d+)?")


@pytest.mark.parametrize("question, angle", [("u31_at_angle", 40), ("du31_ratio", None),
                                             ("u31_max_prediction", None)])
def test_the_new_kinds_send_no_answer_to_the_page_before_it_is_closed(client, question, angle):
    """The page and the student's state are searched for the value the server checks against (learnt by
    spending the last attempt): rel 1e-4 would catch any rounding of it."""
    created = create(client, [{"id": question}], attempts=1)
    page = student_page(client, created, "Koval")
    state = json.dumps(state_of(client, created, "Koval"))
    seen = np.array([float(m.replace(",", ".")) for m in NUMBER.findall(page + state)])
    correct = submit(client, created, "Koval", question, 1e9, angle).json()["correct_value"]
    assert not np.any(np.isclose(seen, correct, rtol=1e-4, atol=0)), (question, correct)


def test_a_combination_on_a_dynamics_scene_is_the_swing_of_the_steady_speed(client):
    """Δω = δ·ω_mean by the definition of δ; the reference is ω_max − ω_min of the steady ω(φ) the motion
    endpoint returns, interpolated by a periodic cubic spline (129 nodes: error ~h⁴ ≈ 1e-6 of Δω; rel 1e-4)."""
    from scipy.interpolate import CubicSpline
    from server.lessons.requests import scene_request
    created = client.post(API, json={"scene": "equation-of-motion", "variant": "linear",
                                     "questions": [{"id": "omega_swing"}], "attempts": 1, "reveal_answers": True})
    assert created.status_code == 201, created.text
    scene = scenes()["equation-of-motion"]
    steady = client.post("/api/v1/motion", json=scene_request(scene, scene.variants[0], outputs=["steady"])).json()
    spline = CubicSpline(steady["phi"], steady["omega"], bc_type="periodic")
    fine = spline(np.linspace(steady["phi"][0], steady["phi"][-1], 200_001))
    reference = fine.max() - fine.min()
    outcome = submit(client, created.json(), "Any", "omega_swing", reference).json()
    assert outcome["right"] and outcome["correct_value"] == pytest.approx(reference, rel=1e-4)


@pytest.mark.parametrize("scene_id", [s.id for s in scenes().values() if s.questions])
def test_every_builder_page_has_a_notice_for_each_of_its_questions(client, scene_id):
    scene = scenes()[scene_id]
    for variant in scene.variants:
        asked = {q.id for q in scene.questions if not q.variants or variant.id in q.variants}
        if not asked or variant.address:   # one's own mechanism: the builder opens it from an address only
            continue
        for lang in ("ru", "uk", "en"):
            page = client.get(f"/scenes/{scene_id}/assign", params={"lang": lang, "variant": variant.id}).text
            assert set(re.findall(r'class="leak-notice[^"]*" id="leak-([^"]+)"', page)) == asked, (variant.id, lang)


def test_what_a_per_variant_cache_keeps_gives_the_same_answers_after_a_json_round_trip(client):
    """variant_answer / answer_from are the interface of the store's per-variant answers (JSON): an at_angle
    question keeps its value at every angle offered, and reading the student's angle from it after JSON is
    the exact u₃₁ there."""
    from server.classroom.answers import answer_from, variant_answer
    from server.classroom.assignments import load
    created = create(client, [{"id": "u31_at_angle", "angle": {"min": 20, "max": 160, "step": 0.5}},
                              {"id": "du31_ratio"}])
    _, resolved = load(created["id"])
    values = resolved.values(3)
    kept = json.loads(json.dumps({q.id: variant_answer(resolved, values, q.id) for q in resolved.spec.questions}))
    assert len(kept["u31_at_angle"]) == 281
    lam = values["lambda"]
    for angle in (20, 37.5, 160):
        assert answer_from(resolved, "u31_at_angle", kept["u31_at_angle"], angle) == pytest.approx(
            u31(np.radians(angle), L1, lam * L1), rel=1e-9)
    with pytest.raises(ValueError, match="steps of 0.5"):
        answer_from(resolved, "u31_at_angle", kept["u31_at_angle"], 37.2)
    f = lambda p: du31(p, L1, lam * L1)
    assert answer_from(resolved, "du31_ratio", kept["du31_ratio"]) == pytest.approx(
        extremum(f, True) / extremum(f, False), rel=1e-7)
