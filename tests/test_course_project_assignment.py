"""Course-project assignments (content/scenes/course_project.json): the shaping machine with per-student link
lengths and loads. Two students get different variants; every variant handed out turns fully (checked here by
the course project's own full-turn check), and a number whose crank sticks is replaced by the next one that
turns; ranges whose crank never turns are refused by name. The right answers, computed independently by posting
the course-project computation with the student's values written into the preset by hand, are accepted and a
5 %-off answer refused; the student's links open their very variant on /project and in /editor."""
from __future__ import annotations

import copy
import hashlib
import json
import math
import re
from html import unescape
from pathlib import Path
from urllib.parse import parse_qs, urlsplit

import pytest
from fastapi.testclient import TestClient

from server.classroom import assignment_store
from server.classroom import answers
from server.api.app import app
from server.classroom.assignments import load
from server.classroom import turning
from server.classroom.names import normalise
from server.core.course_project.positions import full_turn, stroke_positions
from server.core.mechanisms import GeometryError
from server.core.mechanisms.general import GeneralMechanism
from server.lessons.project_links import read_base64url

API = "/api/v1/assignments"
PRESET = json.loads((Path(__file__).resolve().parents[1] / "content" / "mechanisms" / "shaping_machine.json")
                    .read_text(encoding="utf-8"))
SPEC = {"scene": "course-project", "variant": "shaping_machine", "title": "Course project", "lang": "en",
        "sliders": {"l_OA": {"vary": {"min": 0.08, "max": 0.25}, "step": 0.01},     # above ≈ 0.2 m it sticks
                    "l_DE": {"vary": {"min": 0.12, "max": 0.2}, "step": 0.02},
                    "m5": {"vary": {"min": 20, "max": 60}, "step": 10},
                    "P": {"vary": {"min": 1000, "max": 5000}, "step": 500},
                    "n1": {"value": 80}, "delta": {"value": 0.04}, "chosen": {"value": 4}},
        "questions": [{"id": "v_E"}, {"id": "omega_max"}, {"id": "J_flywheel"}, {"id": "M_b_lever"},
                      {"id": "efficiency"}],
        "attempts": 3}
NAMES = ["Ann Petrenko", "Bohdan Shevchenko", "Olena Koval", "Taras Melnyk"]


@pytest.fixture()
def client(tmp_path, monkeypatch) -> TestClient:
    monkeypatch.setenv("MDL_DATA_DIR", str(tmp_path))
    assignment_store.store.cache_clear()
    yield TestClient(app)
    assignment_store.store.cache_clear()


@pytest.fixture()
def created(client) -> dict:
    response = client.post(API, json=SPEC)
    assert response.status_code == 201, response.text
    return response.json()


def register(client, created, name) -> dict:
    response = client.post(f"{API}/{created['id']}/students", json={"name": name})
    assert response.status_code == 201, response.text
    return {"Authorization": f"Bearer {response.json()['secret']}"}


def my_variant(client, created, headers) -> dict:
    response = client.get(f"{API}/{created['id']}/me", params={"lang": "en"}, headers=headers)
    assert response.status_code == 200, response.text
    return response.json()


def request_by_hand(values: dict) -> dict:
    """The course-project request of the student's values, written into the preset here (not by the lesson
    model): |OA|, |DE|, m₅, P, n₁ (rpm), [δ], f and the chosen position."""
    dynamics = copy.deepcopy(PRESET["dynamics"])
    linkage = copy.deepcopy(PRESET["linkage"])
    linkage["input"]["length"] = values["l_OA"]
    linkage["frame"]["joints"]["C"][1] = -values["l_OC"]
    linkage["groups"][1]["length"] = values["l_DE"]
    masses = dynamics["masses"]
    masses["links"][3]["mass"] = values["m5"]
    masses["forces"][0]["working"] = values["P"]
    masses |= {"friction": values["friction"], "pair_radius": 0.02}
    return {"linkage": linkage, "masses": masses, "inertias": dynamics["inertias"],
            "omega_mean": values["n1"] * math.pi / 30, "delta": values["delta"], "positions": 12,
            "chosen": int(values["chosen"])}


def turns(values: dict) -> bool:
    """The crank turns fully (the course project's own check)."""
    try:
        full_turn(GeneralMechanism(request_by_hand(values)["linkage"]))
    except GeometryError:
        return False
    return True


def usable(values: dict) -> bool:
    """The crank turns fully and the ram has one working and one idle stroke."""
    try:
        stroke_positions(GeneralMechanism(request_by_hand(values)["linkage"]), None, 12)
    except GeometryError:
        return False
    return True


def test_students_get_different_variants_and_every_one_turns(client, created):
    """The spec varies |OA| into the range where the crank sticks; no student gets such a variant."""
    got = [my_variant(client, created, register(client, created, name)) for name in NAMES]
    assert len({g["variant"] for g in got}) >= 2
    assert len({json.dumps(g["values"], sort_keys=True) for g in got}) >= 2
    for g in got:
        assert 0.08 - 1e-9 <= g["values"]["l_OA"] <= 0.25 + 1e-9 and 1000 <= g["values"]["P"] <= 5000
        assert turns(g["values"]) and usable(g["values"]), g["values"]
    info = got[0]["assignment"]
    assert 0 < info["turning"]["turn"] < info["turning"]["checked"]           # some variants stick, some turn


def test_a_number_that_sticks_is_replaced_by_the_next_that_turns(client, created):
    """SHA-256 of the assignment and the name gives the number; where that variant's crank sticks, the next
    number (+1, +2, …) that turns is handed out: the rule, computed here from the digest."""
    _, resolved = load(created["id"])
    replaced = 0
    for k in range(60):
        name = f"Student {k}"
        digest = hashlib.sha256(f"{created['id']}\n{normalise(name)}".encode()).digest()
        number = int.from_bytes(digest, "big") % resolved.count
        expected = number
        while not usable(resolved.values(expected)):
            expected = (expected + 1) % resolved.count
        replaced += expected != number
        assert resolved.number_for(created["id"], normalise(name)) == expected
    assert replaced > 0                     # the spec's range makes some names' own numbers stick


def test_ranges_whose_crank_never_turns_are_refused_by_name(client):
    """|OA| ≥ 0.22 m with |DE| ≤ 0.15 m: the RRP group of the ram cannot be assembled over the whole turn."""
    spec = SPEC | {"sliders": SPEC["sliders"] | {"l_OA": {"vary": {"min": 0.22, "max": 0.25}, "step": 0.01},
                                                 "l_DE": {"vary": {"min": 0.1, "max": 0.15}, "step": 0.01}}}
    response = client.post(API, json=spec)
    assert response.status_code == 422, response.text
    detail = response.json()["detail"][0]
    assert detail["loc"] == ["body", "sliders", "l_OA", "vary"]
    assert "turns fully" in detail["msg"] and "l_OA 0.22 … 0.25" in detail["msg"], detail["msg"]


def independent_answers(client, values: dict) -> dict:
    """The questions' values read from POST /api/v1/course-project with the student's values."""
    response = client.post("/api/v1/course-project", json=request_by_hand(values))
    assert response.status_code == 200, response.text
    project = response.json()
    at = project["kinematics"][int(values["chosen"]) - 1]
    assert at["number"] == values["chosen"]
    return {"v_E": at["points"]["E"]["v"]["value"], "omega_max": project["dynamics"]["omega_max"]["omega"],
            "J_flywheel": next(m for m in project["dynamics"]["flywheel"]["methods"]
                               if m["method"] == "exact")["additional"],
            "M_b_lever": project["kinetostatics"]["zhukovsky"]["moment"],
            "efficiency": project["kinetostatics"]["friction"]["efficiency"]}


def test_right_answers_are_accepted_and_five_percent_off_refused(client, created):
    headers = register(client, created, NAMES[0])
    mine = my_variant(client, created, headers)
    for question, value in independent_answers(client, mine["values"]).items():
        wrong = client.post(f"{API}/{created['id']}/submissions", headers=headers,
                            json={"question": question, "answer": value * 1.05})
        assert wrong.status_code == 200 and not wrong.json()["right"], (question, wrong.text)
        right = client.post(f"{API}/{created['id']}/submissions", headers=headers,
                            json={"question": question, "answer": value})
        assert right.status_code == 200 and right.json()["right"], (question, value, right.text)
    rows = client.get(f"{API}/{created['id']}/results/{created['results_token']}").json()["students"]
    assert [r["score"] for r in rows] == [len(SPEC["questions"])]


def test_a_variant_is_computed_once_for_all_its_questions(created, monkeypatch):
    """The five questions of one variant read one course-project answer (a few hundred ms), not five."""
    _, resolved = load(created["id"])
    calls, real = [], answers.compute
    monkeypatch.setattr(answers, "compute", lambda endpoint, body: calls.append(endpoint) or real(endpoint, body))
    answers._project.cache_clear()
    answers._readout.cache_clear()
    values = resolved.values(turning.handed_out(resolved, 1))
    for pick in resolved.spec.questions:
        answers.variant_answer(resolved, values, pick.id)
    assert calls == ["course-project"]


def link_documents(href: str) -> dict:
    query = parse_qs(urlsplit(unescape(href)).query)
    return {key: read_base64url(query[key][0]) for key in ("m", "d", "p") if key in query} | {
        "path": urlsplit(unescape(href)).path}


def test_the_links_open_the_students_variant_on_the_project_page_and_in_the_editor(client, created):
    name = NAMES[1]
    headers = register(client, created, name)
    mine = my_variant(client, created, headers)
    client.cookies.clear()
    client.get(f"/assignments/{created['id']}/me/{headers['Authorization'][7:]}")
    page = client.get(f"/assignments/{created['id']}", params={"lang": "en"}).text
    hrefs = {key: re.search(rf'id="open-{key}" href="([^"]+)"', page).group(1) for key in ("project", "editor")}
    project, editor = link_documents(hrefs["project"]), link_documents(hrefs["editor"])
    expected = request_by_hand(mine["values"])
    assert project["path"] == "/project" and editor["path"] == "/editor"
    for documents in (project, editor):
        assert documents["m"] == expected["linkage"]
        assert documents["d"]["masses"] == expected["masses"]
        assert documents["d"]["flywheel"]["omega_mean"] == pytest.approx(expected["omega_mean"], rel=1e-12)
        assert documents["d"]["flywheel"]["delta"] == expected["delta"]
    assert project["p"]["positions"] == 12 and project["p"]["chosen"] == expected["chosen"]
    assert project["p"]["title"]["student"] == name and project["p"]["title"]["variant"] == str(mine["variant"])
    for key in ("project", "editor"):
        assert client.get(hrefs[key].replace("&amp;", "&")).status_code == 200


def test_an_own_mechanism_from_the_editor_is_assigned_with_per_student_crank_and_speed(client):
    """The editor's six-bar (no preset) with its estimated masses: per-student |OA| and ω₁ₘ; the answers computed
    independently from the mechanism sent are accepted, the links carry the student's own linkage."""
    from server.core.structure.estimate import estimated_dynamics
    from test_dynamics_estimate import HAND_BUILT
    dynamics = estimated_dynamics(HAND_BUILT)
    length = HAND_BUILT["input"]["length"]
    spec = {"scene": "course-project", "variant": "own", "lang": "en", "mechanism": {"m": HAND_BUILT, "d": dynamics},
            "sliders": {"l_OA": {"vary": {"min": 0.8 * length, "max": 1.2 * length}, "step": 0.05 * length},
                        "omega": {"vary": {"min": 8, "max": 12}, "step": 1}},
            "questions": [{"id": "J_flywheel"}, {"id": "M_b_groups"}]}
    assert client.post(API, json=spec | {"mechanism": None}).json()["detail"][0]["loc"] == ["body", "variant"]
    wrong = client.post(API, json=spec | {"variant": "shaping_machine", "sliders": {}})
    assert wrong.status_code == 422 and wrong.json()["detail"][0]["loc"] == ["body", "mechanism"]
    response = client.post(API, json=spec)
    assert response.status_code == 201, response.text
    created = response.json()
    seen = set()
    for name in NAMES[:3]:
        headers = register(client, created, name)
        mine = my_variant(client, created, headers)
        values = mine["values"]
        seen.add(mine["variant"])
        linkage = copy.deepcopy(HAND_BUILT)
        linkage["input"]["length"] = values["l_OA"]
        body = {"linkage": linkage, "masses": dynamics["masses"] | {"friction": values["friction"], "pair_radius": 0.02},
                "inertias": dynamics["inertias"], "omega_mean": values["omega"], "delta": values["delta"],
                "positions": 12, "chosen": int(values["chosen"])}
        project = client.post("/api/v1/course-project", json=body).json()
        expected = {"J_flywheel": project["dynamics"]["flywheel"]["flywheel_inertia"],
                    "M_b_groups": project["kinetostatics"]["balancing_moment"]}
        for question, value in expected.items():
            outcome = client.post(f"{API}/{created['id']}/submissions", headers=headers,
                                  json={"question": question, "answer": value}).json()
            assert outcome["right"], (name, question, outcome)
        client.cookies.clear()
        client.get(f"/assignments/{created['id']}/me/{headers['Authorization'][7:]}")
        page = client.get(f"/assignments/{created['id']}", params={"lang": "en"}).text
        project_link = link_documents(re.search(r'id="open-project" href="([^"]+)"', page).group(1))
        assert project_link["m"] == linkage and project_link["d"]["flywheel"]["omega_mean"] == values["omega"]
    assert len(seen) >= 2


def test_the_builder_offers_the_presets_and_with_an_editor_address_the_own_mechanism(client):
    from server.core.structure.estimate import estimated_dynamics
    from server.lessons.project_links import base64url
    from test_dynamics_estimate import HAND_BUILT
    page = client.get("/scenes/course-project/assign", params={"lang": "ru"}).text
    assert 'data-variant="shaping_machine"' in page and "variant=jaw_crusher" in page and "variant=own" not in page
    assert 'data-slider="l_OA"' in page and 'data-slider="P"' in page and 'value="0,1"' in page     # decimal comma
    address = {"lang": "en", "variant": "own", "m": base64url(HAND_BUILT), "d": base64url(estimated_dynamics(HAND_BUILT))}
    page = client.get("/scenes/course-project/assign", params=address).text
    assert 'data-variant="own"' in page and 'id="own-mechanism"' in page
    own = json.loads(unescape(re.search(r'id="own-mechanism">(.*?)</script>', page, re.S).group(1)))
    assert own["m"] == HAND_BUILT
    assert client.get("/scenes/course-project", params={"lang": "uk"}).status_code == 200
