"""Wear of every pair of a general mechanism (/wear with mechanism 'general', Chaika–Vasylenko §4 on the pairs
of a structural-group kinetostatics): one pair recomputed by hand from /forces' reactions of the same machine,
the slider's two sides, and the refusals."""
import json

import numpy as np
import pytest
from fastapi.testclient import TestClient

from server.api.endpoints import compute
from server.api.app import app
from server.lessons.requests import scene_request
from server.lessons.scenes import scenes

client = TestClient(app)
from pathlib import Path  # noqa: E402
REPO = Path(__file__).parents[1]


@pytest.fixture(scope="module")
def shaping():
    scene = scenes()["forces-friction"]
    request = scene_request(scene, next(v for v in scene.variants if v.id == "shaping"))
    body = {"mechanism": "general", "linkage": request["linkage"], "masses": request["masses"], "rpm": 60.0,
            "hours": 1000.0, "n": 361, "outputs": ["wear"]}
    forces = compute("forces", {"mechanism": "general", "linkage": request["linkage"], "masses": request["masses"],
                                "loads": {"omega": 2 * np.pi}, "n": 361})
    return body, compute("wear", body), forces


def test_the_crank_pivot_by_hand_from_the_forces_answer(shaping):
    """Pair 01 (frame–crank): the frame's element (journal, pressed against the force it receives, R₀₁ on the
    crank being what the frame gives, −R₀₁ what it receives) over β on 5°: δ = 2·10⁶ k N_c/(π l) ∫ |R| |θ′₁|
    max(cos(β − γ − π), 0) dφ, θ′₁ = 1, k = I_pin/p_m, p_m = 4 mean|R|/(π l d) (rel 1e-9: the same floats
    summed by the same trapezoid); N_c = 60·60·1000."""
    body, wear, forces = shaping
    phi = np.asarray(forces["phi"])
    force = -np.asarray(forces["reactions"]["R01"])
    size = np.hypot(force[:, 0], force[:, 1])
    p_m = 4 * size.mean() / (np.pi * 0.025 * 0.02)
    k = 0.6e-10 / p_m
    gamma = np.arctan2(force[:, 1], force[:, 0]) + np.pi
    beta = np.radians(np.arange(0, 360, 5))
    delta = [2e6 * k * 3.6e6 / (np.pi * 0.025) * np.trapezoid(size * np.maximum(np.cos(b - gamma), 0), phi)
             for b in beta]
    row = next(r for r in wear["pairs_wear"] if r["pair"] == "01" and r["element"] == "journal")
    assert row["link"] == 0 and row["mean_pressure"] == pytest.approx(p_m, rel=1e-12)
    assert row["wear"] == pytest.approx(max(delta), rel=1e-9)
    assert row["beta"] == pytest.approx(float(np.degrees(beta[int(np.argmax(delta))])))
    assert wear["cycles"] == pytest.approx(3.6e6)


def test_every_pair_has_its_elements_and_the_sliders_sides_sum_to_the_whole(shaping):
    """Revolute pairs: a journal and a bush each; prismatic: the slider's two sides, whose sum is a ∫|N s′| dφ
    over the whole turn (the sides split the angles)."""
    body, wear, forces = shaping
    rows = wear["pairs_wear"]
    revolute = {r["pair"] for r in rows if r["kind"] == "R"}
    prismatic = {r["pair"] for r in rows if r["kind"] == "P"}
    assert revolute == {"12", "03", "34", "45", "01"} and prismatic == {"23", "05"}
    for name in revolute:
        assert sorted(r["element"] for r in rows if r["pair"] == name) == ["bush", "journal"]
    assert all(np.isfinite(r["wear"]) and r["wear"] >= 0 for r in rows)
    for name in prismatic:
        sides = [r for r in rows if r["pair"] == name]
        assert sorted(r["side"] for r in sides) == [-1, 1]


@pytest.mark.parametrize("change, field", [
    ({"reactions": "table_4_3"}, "reactions"),
    ({"linkage": None}, "linkage"),
])
def test_general_wear_refusals_name_the_field(shaping, change, field):
    body = {**shaping[0], **change}
    body = {key: value for key, value in body.items() if value is not None}
    response = client.post("/api/v1/wear?lang=en", json=body)
    assert response.status_code == 422
    assert field in response.text


def test_the_wear_scene_has_the_shaping_machines_pairs():
    """The wear scene's variant 'shaping': /wear of the general six-bar, a row for each element, their words in
    three languages."""
    scene = scenes()["wear"]
    variant = next(v for v in scene.variants if v.id == "shaping")
    assert "pairs_wear" in variant.panels
    rows = compute("wear", scene_request(scene, variant))["pairs_wear"]
    assert len(rows) == 14 and all(np.isfinite(r["wear"]) for r in rows)
    for lang in ("ru", "uk", "en"):
        words = json.loads((REPO / "content" / "i18n" / f"{lang}.json").read_text("utf-8"))
        assert {f"pair_element_{r['element']}" for r in rows} <= set(words)
