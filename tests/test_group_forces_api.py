"""POST /api/v1/forces with mechanism 'general': every preset answers (reactions by pair, the balancing moment,
the table of approximations, the crank check (3.2), η, free bodies of every group and the crank at the chosen
angle, numerics); the free bodies are in equilibrium as sent (the forces and couples of each link's entry sum to
zero to 1e-9 of the largest force, with the balancing moment on the crank); the answer for the crank-slider preset
equals the dedicated crank-slider's (1e-10, the core's agreement through the API); bad input answers 422 naming
the field."""
from __future__ import annotations

import numpy as np
import pytest
from fastapi.testclient import TestClient

from server.api.app import app
from server.core.structure.compose import compose
from server.core.structure.presets import presets
from server.core.structure.spec import parse
from group_force_checks import crank_driven


@pytest.fixture(scope="module")
def client() -> TestClient:
    with TestClient(app) as c:
        yield c


def body_of(name: str, friction: float = 0.1) -> dict:
    linkage = presets()[name]["linkage"]
    comp = compose(parse(linkage), np.zeros(1))
    slides = sorted(comp.slides)
    return {"mechanism": "general", "linkage": linkage, "n": 73, "free_body_phi": 1.0,
            "loads": {"omega": 12.0, "epsilon": 2.0},
            "masses": {"links": [{"link": k, "mass": 1.0 + k, "centre": [0.02, 0.01], "inertia": 0.01}
                                 for k in sorted(comp.links)],
                       "forces": [{"joint": slides[-1], "working": 500.0, "k": 0.3}] if slides else [],
                       "moments": [] if slides else [{"link": max(comp.links), "working": 20.0, "k": 0.5}],
                       "friction": friction, "pair_radius": 0.01}}


def cross(at, force):
    return at[0] * force[1] - at[1] * force[0]


@pytest.mark.parametrize("name", crank_driven())
def test_every_preset_answers_with_free_bodies_in_equilibrium(client, name):
    answer = client.post("/api/v1/forces?precision=full&lang=ru", json=body_of(name))
    assert answer.status_code == 200, answer.text[:400]
    body = answer.json()
    assert body["crank_check"]["frictionless"] <= 1e-12
    assert 0 < body["efficiency"] <= 1 and body["numerics"]["rtol"] == 1e-9
    assert len(body["iteration"]["table"]) == body["iteration"]["approximations"] >= 2
    groups = len(presets()[name]["linkage"]["groups"])
    bodies = body["free_body"]["bodies"]
    assert [b["group"] for b in bodies] == list(range(groups - 1, -1, -1)) + ["crank"]
    for entry in bodies:
        for link in entry["links"]:
            forces = [x for part in ("loads", "reactions", "friction") for x in entry[part] if x["link"] == link]
            total = np.sum([x["force"] for x in forces if "force" in x], axis=0)
            moment = sum(cross(x["at"], x["force"]) for x in forces if "force" in x) + sum(
                x["moment"] for x in forces if "moment" in x) + (entry.get("balancing_moment", 0.0))
            scale = max(np.hypot(*x["force"]) for x in forces if "force" in x)
            assert np.hypot(*total) <= 1e-9 * scale and abs(moment) <= 1e-9 * scale, (name, link)


def test_crank_slider_preset_matches_the_dedicated_answer(client):
    body = body_of("slider_crank", 0.0)
    body["masses"] = {"links": [{"link": 2, "mass": 2.0, "centre": [0.096, 0.0], "inertia": 0.03},
                                {"link": 3, "mass": 1.5}], "forces": [{"joint": "B", "working": 800.0, "k": 0.3}]}
    body["pair_friction"] = {"O": {"f": 0.1, "r": 0.02}, "A": {"f": 0.12, "r": 0.015}, "B": {"f": 0.15, "r": 0.01},
                             "x": {"f": 0.2}}
    body["n"] = 361
    general = client.post("/api/v1/forces?precision=full", json=body).json()
    dedicated = client.post("/api/v1/forces?precision=full", json={
        "n": 361, "loads": {"m2": 2.0, "J_S2": 0.03, "m3": 1.5, "omega": 12.0, "epsilon": 2.0, "force": 800.0,
                            "return_factor": 0.3},
        "pairs": {"f14": 0.1, "f12": 0.12, "f23": 0.15, "f34": 0.2}}).json()
    phi = np.asarray(dedicated["phi"])
    away = np.abs(np.sin(phi)) > 1e-6          # not at the dead centres nor where the rod's ω₂ = 0 (φ = 90°, 270°)
    away &= np.abs(np.cos(phi)) > 1e-6
    mb_g, mb_d = np.asarray(general["balancing_moment"]), np.asarray(dedicated["balancing_moment"])
    assert np.abs(mb_g - mb_d)[away].max() <= 1e-10 * np.abs(mb_d).max()
    r_g, r_d = np.asarray(general["reactions"]["R12"]), np.asarray(dedicated["reactions"]["R12"])
    assert np.abs(r_g - r_d)[away].max() <= 1e-10 * np.abs(r_d).max()


@pytest.mark.parametrize("change, field", [
    ({"pair_friction": {"Q": {"f": 0.1}}}, "pair_friction.Q"),
    ({"params": {"l1": 0.1}}, "body"),
    ({"outputs": ["wear"]}, "body"),
    ({"loads": {"m2": 1.0}}, "body"),
    ({"masses": {"links": [{"link": 9, "mass": 1.0}]}}, "masses.links.0.link"),
])
def test_bad_input_is_refused_naming_the_field(client, change, field):
    answer = client.post("/api/v1/forces", json={**body_of("four_bar"), **change})
    assert answer.status_code == 422, answer.text[:300]
    assert any(field in ".".join(map(str, item["loc"])) for item in answer.json()["detail"]), answer.text[:300]


@pytest.mark.parametrize("name", sorted(n for n, p in presets().items() if "dynamics" in p))
def test_every_preset_with_its_own_masses_and_loads(client, name):
    """The presets' own masses and loads (content/mechanisms/*.json 'dynamics'), with f = 0.1 in every pair:
    a finite answer, η between 0 and 1, and the frictionless crank check at round-off."""
    preset = presets()[name]
    masses = {**preset["dynamics"]["masses"], "friction": 0.1, "pair_radius": 0.01}
    answer = client.post("/api/v1/forces?precision=full", json={
        "mechanism": "general", "linkage": preset["linkage"], "masses": masses, "n": 181,
        "loads": {"omega": 2 * np.pi}})
    assert answer.status_code == 200, answer.text[:400]
    body = answer.json()
    assert body["crank_check"]["frictionless"] <= 1e-12
    assert body["efficiency"] is None or 0 <= body["efficiency"] <= 1
    assert not any(body["locked"]) or any("locking" in w or "торм" in w for w in body["warnings"])
