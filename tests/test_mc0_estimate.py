"""M_c0 of the resisting-moment scene and its error estimate, as /reduction answers them, against an independent
integral of the same M_c(φ): scipy.integrate.quad (QUADPACK's adaptive Gauss–Kronrod) at relative 1e-13, run
between each two zeros of the load's switching functions (the output's reversal u₃₁ = 0, where the stroke factor
switches, and the friction terms' own arguments), each zero found by brentq on the function itself.

The estimate must hold: |M_c0 − quad| ≤ estimate × (cycle mean of |M_c|), at the scene's three defaults and over
its sliders: λ across the range, f = 0 and f > 0, the return-stroke factor, viscous friction, both conventions.
The slotted link with λ = l₀/l₁ > 1 (an oscillating lever) turns back between the trapezoid rule's nodes; there
the difference of the grid and its half was up to three times below the true error. The estimate is also not
vague: at most 100 times the true error, or, where the rule is exact to rounding (M_c smooth and periodic), at
most 1e-8 (the bound then carries only the O(h³) remainder of the second differences' smooth part).
"""
from __future__ import annotations

import json

import numpy as np
import pytest
from fastapi.testclient import TestClient
from scipy.integrate import quad
from scipy.optimize import brentq

from server.api.app import app
from server.core.dynamics.resistance import Load, resisting_moment
from server.core.mechanisms import MECHANISMS
from server.paths import CHECKOUT as ROOT

QUAD_RTOL = 1e-13
SCAN = 4096           # samples per cycle on which the switching functions are scanned for sign changes
VAGUE_FLOOR = 1e-8    # an estimate below this is never called vague


def scene_defaults() -> dict[str, dict]:
    """Each variant's request with its sliders and toggles at their defaults, as the page first sends it."""
    scene = json.loads((ROOT / "content/scenes/resisting_moment.json").read_text())
    sliders = json.loads((ROOT / "content/sliders.json").read_text())
    bodies = {}
    for variant in scene["variants"][:3]:
        body = json.loads(json.dumps(variant["request"]))
        body["mechanism"] = variant["mechanism"]
        controls = [{**sliders.get(s.get("use"), {}), **s} for s in variant.get("sliders", [])]
        for control in controls + variant.get("toggles", []):
            group, _, name = control["param"].partition(".")
            if group not in ("params", "load"):           # the iteration's angle: not the mean's business
                continue
            value = control["default"]
            if "scale" in control:
                scale_group, scale_name = control["scale"].split(".")
                value *= body[scale_group][scale_name]
            body.setdefault(group, {})[name] = value
        bodies[variant["id"]] = body
    return bodies


DEFAULTS = scene_defaults()


def case(mechanism: str, ratio: float | None = None, **load) -> dict:
    """A request of the scene's variant ``mechanism`` with λ and load values changed."""
    body = json.loads(json.dumps(DEFAULTS[mechanism]))
    if ratio is not None:
        body["params"]["l2" if mechanism == "slider_crank" else "l0"] = ratio * body["params"]["l1"]
    body["load"].update(load)
    return body


CASES = {
    "sine default": DEFAULTS["sine"],
    "slider-crank default": DEFAULTS["slider_crank"],
    "slotted link default": DEFAULTS["slotted_link"],
    "sine f=0": case("sine", f=0.0, convention="consistent"),
    "sine f=0.5": case("sine", f=0.5, convention="consistent"),
    "crank-slider f=0 λ=1.3": case("slider_crank", 1.3, f=0.0),
    "crank-slider f=0 λ=3": case("slider_crank", 3.0, f=0.0),
    "crank-slider f=0 λ=6 kp=1": case("slider_crank", 6.0, f=0.0, return_factor=1.0),
    "crank-slider f=0.5 λ=2 consistent": case("slider_crank", 2.0, f=0.5, convention="consistent"),
    "crank-slider f=0.2 βω=0.2": {**case("slider_crank", 3.0, f=0.2, beta=0.2, convention="consistent"), "omega": 1.0},
    "slotted λ=1.5 f=0": case("slotted_link", 1.5, f=0.0),
    "slotted λ=3 f=0": case("slotted_link", 3.0, f=0.0, return_factor=0.2),
    "slotted λ=3 f=0.5 kM=0": case("slotted_link", 3.0, f=0.5, return_factor=0.0),
    "slotted λ=5 f=0.1 kM=1": case("slotted_link", 5.0, f=0.1, return_factor=1.0),
    "slotted λ=2 f=0.2 textbook": case("slotted_link", 2.0, f=0.2, convention="textbook"),
}


def reference(body: dict) -> tuple[float, float, float]:
    """(M_c0 by quad, quad's error bound, the cycle mean of |M_c|), all in N·m."""
    mechanism = MECHANISMS[body["mechanism"]]
    p = mechanism.check(body["params"])
    load = Load(**body["load"])
    cycle = mechanism.cycle(p)

    def moment(phi):
        return resisting_moment(body["mechanism"], p, load, np.atleast_1d(phi), body.get("omega", 1.0)).total

    phi = np.linspace(0.0, cycle, SCAN + 1)
    zeros = []
    for row, values in enumerate(resisting_moment(body["mechanism"], p, load, phi, 0.0).switches):
        values = np.asarray(values, float)
        zeros += list(phi[values == 0])

        def switch(x, row=row):
            return float(resisting_moment(body["mechanism"], p, load, np.array([x]), 0.0).switches[row][0])

        for i in np.nonzero(values[:-1] * values[1:] < 0)[0]:
            zeros.append(brentq(switch, phi[i], phi[i + 1], xtol=1e-15, rtol=1e-15))
    edges = np.unique(np.concatenate([[0.0], [z for z in zeros if 0 < z < cycle], [cycle]]))
    parts = [quad(lambda x: moment(x)[0], a, b, epsabs=0.0, epsrel=QUAD_RTOL, limit=500)
             for a, b in zip(edges[:-1], edges[1:])]
    fine = np.linspace(0.0, cycle, 2**16 + 1)
    scale = float(np.mean(np.abs(moment(fine)[:-1])))
    return sum(v for v, _ in parts) / cycle, sum(e for _, e in parts) / cycle, scale


@pytest.fixture(scope="module")
def client():
    return TestClient(app)


@pytest.mark.parametrize("name", list(CASES))
def test_mc0_within_its_error_estimate(client, name):
    body = {**CASES[name], "outputs": ["resisting"]}
    response = client.post("/api/v1/reduction", json=body)
    assert response.status_code == 200, response.text
    answer = response.json()
    mean, estimate = answer["resisting"]["mean"], answer["numerics"]["error_estimate"]
    exact, quad_error, scale = reference(body)
    true_error = abs(mean - exact) / scale
    slack = (quad_error + 64 * np.finfo(float).eps * scale) / scale      # the reference's and the sum's rounding
    assert true_error <= estimate + slack, (name, mean, exact, true_error, estimate)
    assert estimate <= max(100 * true_error, VAGUE_FLOOR), (name, true_error, estimate)
