"""The loads slider of the own-mechanism variants ("load factor on P and M₀", masses.load_factor).

- Linearity (the physics, not the code): the reduced moment of the useful loads is M_c = −Σ F·V_q − Σ M u_k1
  (Eremyants (1.1)–(1.5)), linear in the loads, and the weights' share does not depend on them; so without
  friction M_c(c) − M_c(0) = c·(M_c(1) − M_c(0)) at every angle. Tolerance 1e-12 of the moment's scale: the same
  arithmetic on numbers of one magnitude, round-off only.
- In each of the four scenes that offer it (resisting moment, flywheel, equation of motion, forces), a factor
  gives the same answer as the table with every P and M₀ multiplied by hand, to 1e-12 relative: the slider means
  what its label says, through every endpoint's own path (the steady cycle, the flywheel's solve, kinetostatics).
- Out of range: 422 naming masses.load_factor.
"""
from __future__ import annotations

import copy

import numpy as np
import pytest
from fastapi.testclient import TestClient

from server.api.app import app
from server.api.endpoints import compute
from server.lessons.requests import scene_request
from server.lessons.scenes import scenes

SCENES = ("resisting-moment", "flywheel", "equation-of-motion", "forces-friction")


def own_body(scene_id: str, **values) -> tuple[str, dict]:
    scene = scenes()[scene_id]
    variant = next(v for v in scene.variants if v.id == "own")
    assert "load_factor" in {s.id for s in variant.sliders}
    return scene.endpoint, scene_request(scene, variant, values)


def by_hand(body: dict, factor: float) -> dict:
    """The body with every useful load's working value multiplied, and no load_factor."""
    out = copy.deepcopy(body)
    masses = out["masses"]
    masses.pop("load_factor", None)
    for load in [*masses.get("forces", []), *masses.get("moments", [])]:
        load["working"] *= factor
    return out


def numbers(tree) -> np.ndarray:
    """Every number of an answer in walk order (None as NaN); texts, flags and the numerics' run time (which
    differs from run to run) are left out."""
    found = []

    def walk(x):
        if isinstance(x, dict):
            for key, value in x.items():
                if key != "runtime_ms":
                    walk(value)
        elif isinstance(x, (list, tuple)):
            for value in x:
                walk(value)
        elif isinstance(x, np.ndarray):
            found.extend(np.asarray(x, float).ravel().tolist())
        elif isinstance(x, (int, float)) and not isinstance(x, bool) or x is None:
            found.append(np.nan if x is None else float(x))
    walk(tree)
    return np.array(found)


def test_the_reduced_moment_is_linear_in_the_loads_and_the_weights_share_stays():
    endpoint, body = own_body("resisting-moment", f=0.0)
    answers = {c: compute(endpoint, body | {"masses": body["masses"] | {"load_factor": c}}) for c in (0.0, 1.0, 2.5)}
    moment = {c: np.asarray(a["resisting"]["total"], float) for c, a in answers.items()}
    loads = moment[1.0] - moment[0.0]
    scale = np.abs(moment[2.5]).max()
    assert np.abs(loads).max() > 0.1 * scale                       # the loads matter beside the weights
    assert np.abs(moment[2.5] - moment[0.0] - 2.5 * loads).max() <= 1e-12 * scale


@pytest.mark.parametrize("scene_id", SCENES)
def test_a_factor_is_the_table_with_its_loads_multiplied(scene_id):
    endpoint, body = own_body(scene_id, load_factor=1.7)
    assert body["masses"]["load_factor"] == 1.7 and body["masses"].get("forces")
    slider, hand = numbers(compute(endpoint, body)), numbers(compute(endpoint, by_hand(body, 1.7)))
    assert slider.shape == hand.shape
    finite = np.isfinite(hand)
    assert np.array_equal(finite, np.isfinite(slider))
    assert np.allclose(slider[finite], hand[finite], rtol=1e-12, atol=1e-12 * np.abs(hand[finite]).max())
    table = numbers(compute(endpoint, by_hand(body, 1.0)))         # the table as it is: no factor, 1
    assert table.shape != hand.shape or not np.allclose(table[finite], hand[finite])     # 1.7 changed it


@pytest.mark.parametrize("value", [-0.1, 10.5, "much"])
def test_a_factor_out_of_range_is_refused_naming_it(value):
    endpoint, body = own_body("resisting-moment")
    with TestClient(app) as client:
        answer = client.post(f"/api/v1/{endpoint}", json=body | {"masses": body["masses"] | {"load_factor": value}})
    assert answer.status_code == 422
    assert any(item["loc"][-2:] == ["masses", "load_factor"] for item in answer.json()["detail"])


def test_without_useful_loads_the_machine_runs_at_the_motors_no_load_speed_on_average():
    """Factor 0, no friction: the weights' work over a cycle is zero, so the linear motor's must be too,
    ∮ i(M₀ − b·i·ω) dφ = 0, and the crank's φ-mean speed is the no-load speed M₀/(b·i) (it used to be called a
    stall: the balance was searched for only below the no-load speed, where the weights' mean moment, 1e-16 of
    round-off, left no root). Tolerance 1e-7: the steady cycle's rtol 1e-8 and the trapezoid over its nodes
    (2.8e-9 here)."""
    endpoint, body = own_body("equation-of-motion", load_factor=0.0, f=0.0)
    answer = compute(endpoint, body | {"outputs": ["steady"]})
    assert answer["warnings"] == []
    phi, omega = np.asarray(answer["phi"], float), np.asarray(answer["omega"], float)
    motor, gear = body["motor"], body["inertias"]["gear_ratio"]
    assert motor["kind"] == "linear"
    mean = np.trapezoid(omega, phi) / (phi[-1] - phi[0])
    assert mean == pytest.approx(motor["M0"] / (motor["b"] * gear), rel=1e-7)
