"""Dry friction in the equation of motion of a general mechanism (kinetostatics/groups/dry_moment.py).

- The crank-slider as a general linkage with friction only in the slider's guide (the dedicated model: f in the
  prismatic pair, the friction of the useful load) reproduces the dedicated machine's M_c = k P|u₃₁|/(1 − f|tan ψ|)
  (Eremyants (3.24)–(3.28)): the tables, the reduction, the steady cycle and start-up, and the flywheel to 1e-10
  relative (both closed forms, or a Newton solve to ε_R = 1e-12, integrated by the same integrator: round-off and
  the solve's 1e-12 differ only), and the same angles lock; the mean M_c0, taken by different rules (trapezoid,
  Gauss–Legendre between the kinks), within the sum of their error estimates.
- The six-bar presets with friction in every pair: M_T at sample angles against scipy.optimize.fsolve of the full
  nonlinear equilibrium of every link (tests/group_force_checks.direct, written from the free-body sums, not the
  solver's matrices) to 1e-9 of the moment scale (fsolve's xtol 1e-14 on reactions of order 1e3 N, amplified by
  the groups' matrices); and by power equality M_T = Σ|z_p||rel_p| (the pairs' dissipated power) to 1e-10.
- A pair the linkage does not have answers 422 naming it; where friction locks the mechanism the motion says so
  in words (no number).
- The steady cycle with friction keeps the energy balance over the cycle ≤ 1e-8 of the driving work, and its
  error estimate holds against a run at 1/1000 of the tolerance (as tests/test_error_estimates.py).
"""
from __future__ import annotations

import numpy as np
import pytest

from server.api.endpoints import compute, machine
from server.api.schemas_dynamics import MassInput, MotionRequest
from server.core.kinetostatics.groups.analysis import analyse
from server.core.kinetostatics.groups.dry_moment import dry_moment
from server.core.mechanisms.general import GeneralMechanism
from server.core.structure.compose import compose
from server.core.structure.presets import presets

from group_force_checks import direct
from test_general_dynamics_machine import SIX_BARS, agree, means_agree, pair, preset_body, stall_curve_as_stated

F_GUIDE = 0.25


def with_friction(body: dict, general: bool) -> dict:
    if general:
        return body | {"pair_friction": {"x": {"f": F_GUIDE}}}
    return body | {"load": body["load"] | {"f": F_GUIDE}}


def test_tables_of_the_crank_slider_through_the_general_path():
    dedicated, general = pair("slider_crank", beta=0.0, motor={"kind": "constant", "M0": 40.0},
                              outputs=["steady"])
    a = machine(MotionRequest(**with_friction(dedicated, False)))
    b = machine(MotionRequest(**with_friction(general, True)))
    phi = np.linspace(0, 2 * np.pi, 997)
    ta, tb = a.tables(phi), b.tables(phi)
    scale = np.abs(ta.dry).max()
    assert scale > 0 and np.abs(ta.dry - tb.dry).max() <= 1e-10 * scale
    assert np.abs(ta.useful - tb.useful).max() <= 1e-10 * np.abs(ta.useful).max()


@pytest.mark.parametrize("name", ["slider_crank"])
def test_motion_with_friction_through_the_general_path(name):
    dedicated, general = pair(name, beta=2.0, motor={"kind": "linear", "M0": 60.0, "b": 1.0},
                              outputs=["steady", "startup"], omega0=1.0)
    a, b = compute("motion", with_friction(dedicated, False)), compute("motion", with_friction(general, True))
    assert a["works"]["dry_friction"] > 0
    agree(a, b)


def test_flywheel_with_friction_through_the_general_path():
    dedicated, general = pair("slider_crank", beta=0.0, motor={"kind": "constant", "M0": 30.0}, omega_mean=12.0,
                              delta=0.04)
    a, b = compute("flywheel", with_friction(dedicated, False)), compute("flywheel", with_friction(general, True))
    assert a["methods"] and a["warnings"] == b["warnings"]
    stall_curve_as_stated(a)
    stall_curve_as_stated(b)
    agree(a, b)


def test_reduction_with_friction_through_the_general_path():
    dedicated, general = pair("slider_crank", beta=0.5, outputs=["inertia", "resisting"], n=181, omega=3.0)
    a = compute("reduction", with_friction(dedicated, False))
    b = compute("reduction", with_friction(general, True))
    for key in ("total", "useful", "dry", "viscous"):
        agree(a["resisting"][key], b["resisting"][key])
    means_agree(a, b)


def six_bar(name: str):
    masses = presets()[name]["dynamics"]["masses"]
    model = MassInput(**masses | {"friction": 0.12, "pair_radius": 0.02}).model()
    return GeneralMechanism(presets()[name]["linkage"]), model


@pytest.mark.parametrize("name", SIX_BARS)
def test_dry_moment_against_fsolve_and_power(name):
    mechanism, model = six_bar(name)
    phi = np.linspace(0, 2 * np.pi, 24, endpoint=False) + 0.037
    found = dry_moment(mechanism, compose(mechanism.linkage, phi), model)
    assert not found.locked.any() and np.isfinite(found.moment).all()
    result = analyse(mechanism, model, phi, 0.0, 0.0, 1e-12)       # the same statics, with its table and loads
    scale = np.abs(result.reduced_moment).max() + np.abs(found.moment).max()
    # power equality: the pairs' dissipated power per unit crank speed
    lost = sum(np.abs(result.solution.friction[p] * pair.relative) for p, pair in enumerate(result.pairs))
    assert np.abs(found.moment - lost).max() <= 1e-10 * scale
    # the full nonlinear equilibrium, solved by fsolve from the answer perturbed by 1 %
    for k in range(phi.size):
        row = result.solution
        start = np.concatenate([*(x[k] for x in row.unknowns), [row.R01[k].real, row.R01[k].imag],
                                [result.sense * row.balancing[k]]])
        (_, _, balancing), residual = direct(result, k, start * 1.01)
        assert residual <= 1e-8 * np.abs(start).max()
        moment = result.sense * balancing[0] - result.reduced_moment[k]
        assert abs(moment - found.moment[k]) <= 1e-9 * scale, (k, moment, found.moment[k])


@pytest.mark.parametrize("name", SIX_BARS)
def test_preset_steady_cycle_with_friction(name):
    dynamics = presets()[name]["dynamics"]
    body = preset_body(name, motor=dynamics["motor"], outputs=["steady"], rtol=1e-10)
    body["masses"] = body["masses"] | {"friction": 0.1, "pair_radius": 0.02}
    steady = compute("motion", body)
    works = steady["works"]
    assert works["dry_friction"] > 0
    balance = works["driving"] - works["useful"] - works["dry_friction"] - works["viscous_friction"]
    assert abs(balance) <= 1e-8 * works["driving"], works
    # η = A_useful/A_driving (Chaika–Vasylenko (3.38)) against the motor's work integrated on its own: equal to the
    # energy balance's residual (1e-8); below 1 with friction in the pairs (it read 1 when only the load's f counted)
    assert steady["efficiency"] < 1
    assert steady["efficiency"] == pytest.approx(works["useful"] / works["driving"], rel=1e-8)


def test_unknown_pair_and_self_locking():
    from fastapi.testclient import TestClient
    from server.api.app import app
    dynamics = presets()["shaping_machine"]["dynamics"]
    body = preset_body("shaping_machine", motor=dynamics["motor"], outputs=["steady"])
    with TestClient(app) as client:
        answer = client.post("/api/v1/motion", json=body | {"pair_friction": {"Q": {"f": 0.1}}})
        assert answer.status_code == 422
        detail = answer.json()["detail"][0]
        assert detail["loc"][:3] == ["body", "pair_friction", "Q"] and "no pair 'Q'" in detail["msg"]
        locked = client.post("/api/v1/motion", json=body | {"masses": body["masses"] | {"friction": 2.0,
                                                                                        "pair_radius": 0.2}})
        assert locked.status_code == 200
        said = locked.json()
        assert said.get("steady") is None and any("Self-locking" in w for w in said["warnings"]), said["warnings"]


@pytest.mark.parametrize("name", SIX_BARS)
def test_the_steady_cycles_estimate_holds_with_friction(name):
    """As tests/test_error_estimates.py for the four mechanisms: the steady cycle with dry friction in every
    pair (its moment jumps where a friction or a load changes sense, has corners where a normal force or a
    relative motion passes zero: all kinks on the nodes; the knuckle press's joint of three links is two pairs
    of one name, and both are rough) against our run at 1/1000 of the tolerance and of the
    estimate, on nested nodes: the true error of ω and t is at most 3× the estimate and 2× rtol."""
    from server.core.dynamics.motion import steady_cycle
    from test_error_estimates import ROUNDING, true_error
    dynamics = presets()[name]["dynamics"]
    body = preset_body(name, motor=dynamics["motor"], outputs=["steady"], rtol=1e-7)
    body["masses"] = body["masses"] | {"friction": 0.1, "pair_radius": 0.02}
    built = machine(MotionRequest(**body))
    result = steady_cycle(built, 1e-7)
    estimate = result.numerics.error_estimate
    reference = steady_cycle(built, max(min(1e-7, estimate) / 1000, 3e-13))
    assert reference.numerics.steps >= 4 * result.numerics.steps
    error = true_error(result.steady, reference.steady)
    assert error <= 3 * estimate + ROUNDING and error <= 2e-7, (error, estimate)
