"""The steady cycle's efficiency η = A_useful/A_driving (Chaika–Vasylenko (3.38)) within its meaning (never absurd).

Over a periodic cycle the kinetic energy returns to its value, so A_driving = A_useful + A_friction: without
friction η is 1 by construction, exactly (no quadrature can make it 1.0000005); with friction whose work is
≥ 0 (the consistent convention: friction always resists) 0 ≤ η ≤ 1. The driving work integrated directly
agrees with that balance to the reported energy residual; where η has no meaning (the textbook's printed
formulas let friction help on the return stroke) it is null, with a sentence why.
"""
import json

import pytest
from fastapi.testclient import TestClient
from test_error_estimates import random_body
from test_stability import RIG

from server.api import endpoints
from server.api.app import app
from server.api.schemas_dynamics import MotionRequest
from server.core.dynamics.motion import steady_cycle

client = TestClient(app)


def motion(body):
    response = client.post("/api/v1/motion?lang=en", json=body)
    assert response.status_code == 200, response.text
    return json.loads(response.text)


def check(efficiency, works, residual, frictionless, warnings):
    """η within [0, 1], exactly 1 without friction, and the direct driving work within the residual."""
    if frictionless:
        assert efficiency == 1.0
        return
    if efficiency is None:
        assert works["dry_friction"] + works["viscous_friction"] < 0 or works["useful"] < 0
        assert any("η is not given" in w for w in warnings)
        return
    assert 0.0 <= efficiency <= 1.0
    turnover = abs(works["driving"]) + abs(works["useful"]) + abs(works["dry_friction"]) + abs(works["viscous_friction"])
    assert abs(works["useful"] - efficiency * works["driving"]) <= residual * turnover + 1e-12 * turnover


@pytest.mark.parametrize("seed", range(0, 64, 3))
@pytest.mark.parametrize("friction", [True, False])
def test_efficiency_on_random_machines(seed, friction):
    body = random_body(seed)
    if not friction:
        body["load"] |= {"f": 0.0, "beta": 0.0, "convention": "consistent"}
    machine = endpoints.machine(MotionRequest(**body))
    result = steady_cycle(machine, body["rtol"], body.get("omega_mean"), body.get("balance", False))
    if result.steady is None:
        assert result.notices
        return
    frictionless = body["load"]["f"] == 0 and body["load"]["beta"] == 0 and body["load"]["convention"] == "consistent"
    check(result.steady.efficiency, result.steady.works, result.numerics.energy_residual, frictionless,
          [n.text for n in result.notices])
    assert 0.0 <= result.numerics.energy_residual <= 1.0


@pytest.mark.parametrize("masses", [1e-6, 1.0, 1e3])
@pytest.mark.parametrize("speed", [0.05, 300.0])
@pytest.mark.parametrize("f", [0.0, 0.1])
def test_efficiency_over_the_stability_grid(masses, speed, f):
    """tests/test_stability.py's machines over nine decades of masses and slow and fast cranks."""
    body = RIG | {"inertias": {"J1": 0.5 * masses, "m2": 5 * masses, "J_S2": 0.05 * masses, "m3": 10 * masses,
                               "J_rotor": 0.01, "gear_ratio": 5},
                  "load": RIG["load"] | {"f": f},
                  "motor": {"kind": "linear", "M0": 60 * speed / 40, "b": 0.3}, "outputs": ["steady"]}
    data = motion(body)
    if "omega" not in data:
        assert data["warnings"]
        return
    check(data["efficiency"], data["works"], data["numerics"]["energy_residual"], f == 0.0, data["warnings"])
    assert 0.0 <= data["numerics"]["energy_residual"] <= 1.0


def test_the_textbook_formulas_that_let_friction_help_leave_eta_unset_in_words():
    """The slotted link's printed (3.44)–(3.49) are negative on the idle stroke: the 'friction' work over the
    cycle is below zero and A_useful/A_driving > 1 would be no efficiency."""
    body = {"mechanism": "slotted_link", "params": {"l0": 0.2, "l1": 0.1}, "inertias": {"J1": 0.5, "J3": 0.1},
            "load": {"force": 20, "return_factor": 1.0, "f": 0.0, "convention": "textbook"},
            "motor": {"kind": "linear", "M0": 60, "b": 0.3}, "outputs": ["steady"]}
    data = motion(body)
    assert data["works"]["dry_friction"] < 0 and data["efficiency"] is None
    assert any("η is not given" in w for w in data["warnings"])


def test_the_constant_torque_default_says_its_stall_concerns_the_start_up_beside_its_steady_cycle():
    """The scene's constant-torque machine has a steady cycle and stalls only when started
    from rest; the answer says which. Bound, independent of the integrator: viscous friction only takes energy,
    so from rest T(φ) ≤ W(φ) = ∫₀^φ (i·M₀ − M_c,φ) dφ (the φ-dependent moments, by the trapezoid rule on a
    fine grid), and the start-up must stop no later than W's first zero (0.5° of grid and refinement)."""
    import numpy as np

    from server.api.endpoints import compute
    from server.core.dynamics.resistance import Load, resisting_moment
    from server.lessons.requests import scene_request
    from server.lessons.scenes import scenes
    scene = scenes()["equation-of-motion"]
    body = scene_request(scene, next(v for v in scene.variants if v.id == "constant"), None)
    answer = compute("motion", body, "en")
    assert len(answer["omega"]) > 10 and np.isfinite(answer["omega_mean"])          # the steady cycle is shown
    numerics = answer["startup"]["numerics"]
    assert numerics["message_code"] == "stall_startup_from"
    assert any("concerns the start-up only" in w for w in answer["warnings"])
    assert not any(w.startswith("Stall") and "start-up" not in w for w in answer["warnings"])
    phi = np.linspace(0.0, 2 * np.pi, 20001)
    load = Load(**{**body["load"], "beta": 0.0})
    from server.core.mechanisms import MECHANISMS
    params = {**MECHANISMS["slider_crank"].defaults(), **body["params"]}
    moment = resisting_moment("slider_crank", params, load, phi).total
    net = body["inertias"]["gear_ratio"] * body["motor"]["M0"] - moment
    work = np.concatenate([[0.0], np.cumsum(0.5 * (net[1:] + net[:-1]) * np.diff(phi))])
    first_zero = np.degrees(phi[np.argmax(work[1:] < 0) + 1])
    assert (work[1:] < 0).any() and numerics["message_context"]["phi"] <= first_zero + 0.5


def test_every_ending_of_a_start_up_is_said_in_the_readers_language():
    """A start-up cut at max_cycles before it settles ends "not yet periodic": a routine message with its own
    key (and its estimate's sentence when above rtol), so ru and uk pages never show the English text."""
    from server.api.endpoints import compute
    from server.lessons.requests import scene_request
    from server.lessons.scenes import interface_texts, scenes
    scene = scenes()["equation-of-motion"]
    body = {**scene_request(scene, next(v for v in scene.variants if v.id == "linear"), None), "max_cycles": 1}
    english = compute("motion", body, "en")["startup"]["numerics"]
    assert english["message_code"].startswith("startup_not_periodic")
    for lang in ("ru", "uk"):
        local = compute("motion", body, lang)["startup"]["numerics"]
        template = interface_texts(lang)["num_message_" + english["message_code"]]
        assert local["message"] != english["message"] and local["message"].startswith(template.split("{")[0])
