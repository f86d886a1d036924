"""Lecture 10 §10.9–§10.10: the induction motor's static characteristic, the stability of its operating point
(Fig. 10.14) and the successive approximations, each against something that is not the code under test:
finite differences of the characteristic, the sign of the restoring moment after a small speed change, the
closed form (L30), and the joint solution of the equation of motion (motion.steady_cycle, Newton shooting)."""
from __future__ import annotations

import json

import numpy as np
import pytest
from fastapi.testclient import TestClient

from server.api.app import create_app
from server.core.dynamics import motion as mo
from server.core.dynamics import motor_characteristic as mc
from server.core.dynamics.machine import Inertias, Load, Machine
from server.core.dynamics.motors import Motor
from server.core.dynamics.successive_approximations import cycle_mean, successive_approximations

KLOSS = Motor(kind="kloss", M_max=70.0, s_critical=0.2, omega_sync=157.0)
I = 5.0                                     # the gear ratio of the equation-of-motion scene


def machine(J1: float, motor: Motor = KLOSS) -> Machine:
    return Machine("slider_crank", {"l1": 0.1, "l2": 0.3, "e": 0.0, "a2": 0.5},
                   Inertias(J1=J1, m2=5, J_S2=0.05, m3=10, J_rotor=0.01, gear_ratio=I),
                   Load(force=2000, return_factor=0.2, f=0.1), motor)


def test_the_characteristic_peaks_at_the_critical_speed_and_splits_there():
    """b of Fig. 10.14: the torque's finite-difference slope changes sign at ω₁к (central differences, h =
    1e-4 of ω₁с: truncation ~h²·M‴ ≪ the slope 1e-2 N·m·s away from the peak)."""
    curve = mc.characteristic(KLOSS, I)
    knee, h = curve["maximum"]["omega"], 1e-4 * 157 / I
    def torque(w):
        return float(mc.reduced_torque(KLOSS, I, w)[0])
    assert torque(knee) == pytest.approx(I * 70.0, rel=1e-12)                       # M_дmax = i·M_к
    assert (torque(knee + h) - torque(knee - h)) / (2 * h) == pytest.approx(0.0, abs=1e-6 * I * 70)
    stable = ~np.isnan(curve["stable"])
    assert np.all(curve["omega"][stable] >= knee) and np.all(curve["omega"][~stable] < knee)
    assert curve["synchronous"]["moment"] == 0.0 and torque(157 / I) == pytest.approx(0.0, abs=1e-12)


@pytest.mark.parametrize("load", [150.0, 200.0, 340.0])
def test_the_stability_criterion_holds_by_finite_differences_and_by_the_restoring_moment(load):
    """Two crossings between the starting torque (i·2M_к s_к/(1 + s_к²) = 134.6 N·m) and M_дmax: the one on bd
    stable, the one on ab not. The slopes against central
    differences (rel 1e-6: h = 1e-5 ω₁с, truncation h² M‴/6); stability against the physics: a speed raised
    by h must meet a net braking moment (M_д − M_с < 0) at a stable point and a driving one at an unstable one."""
    points = mc.operating_points(KLOSS, I, load)
    assert [p.branch for p in points] == ["stable", "unstable"] and [p.stable for p in points] == [True, False]
    h = 1e-5 * 157 / I
    for p in points:
        def excess(w):
            return float(mc.reduced_torque(KLOSS, I, w)[0]) - load
        assert excess(p.omega) == pytest.approx(0.0, abs=1e-9 * load)
        assert p.drive_slope == pytest.approx((excess(p.omega + h) - excess(p.omega - h)) / (2 * h), rel=1e-6)
        assert (excess(p.omega + h) < 0) == p.stable and (excess(p.omega - h) > 0) == p.stable


def test_no_operating_point_above_the_maximum_torque_the_motor_stalls():
    assert [p.branch for p in mc.operating_points(KLOSS, I, 50.0)] == ["stable"]     # below the starting torque
    assert mc.operating_points(KLOSS, I, I * 70.0 * 1.001) == []
    assert len(mc.operating_points(KLOSS, I, I * 70.0 * 0.999)) == 2


def test_the_linearised_branch_corrected_passes_through_both_points_the_printed_one_does_not():
    """(L30): M = b₁* + k₁*ω must give M_дн at ω₁н and 0 at ω₁с; the print's b₁* (ω₁ for ω₁с) misses ω₁с by
    exactly M_дн (worked by hand: (ω₁н − ω₁с)·M_дн/(ω₁с − ω₁н) = −M_дн)."""
    point = mc.operating_points(KLOSS, I, 100.0)[0]
    line = mc.linearised(KLOSS, I, point)
    assert line["b"] + line["k"] * point.omega == pytest.approx(100.0, rel=1e-12)
    assert line["at_sync"] == pytest.approx(0.0, abs=1e-10)
    assert line["at_sync_printed"] == pytest.approx(-100.0, rel=1e-12)


def test_the_successive_approximations_reach_the_joint_solution():
    """The limit of §10.10 against the equation of motion solved with the characteristic (Newton shooting,
    RK4, rtol 1e-10): max|Δω|/ω̄ ≤ 1e-6 (the trapezoid rule on 2048 steps per turn: ~3e-8 measured, the
    iteration's tolerance 1e-9·ρ/(1 − ρ)); the step-to-step change shrinks by ρ = |k₁*|/(Ī ω̄), the linearised
    contraction, within 10 % (the harmonics beyond the first and the φ-dependence of I and ω are neglected)."""
    built = machine(5.0)
    tables = mo.cycle_tables(built, built.kinks(), 2048)
    load = -cycle_mean(tables.net_phi, tables.phi)
    working = mc.operating_points(KLOSS, I, load)[0]
    steps = successive_approximations(built, tables, working.omega, mc.critical_speed(KLOSS, I), tol=1e-9)
    assert steps.converged and steps.ratio < 1
    joint = mo.steady_cycle(built, 1e-10).steady
    last = np.interp(joint.phi, tables.phi, steps.omega[-1])
    assert np.max(np.abs(last - joint.omega)) / joint.omega_mean < 1e-6
    changes = np.array([row["change"] for row in steps.rows[-10:]])
    assert np.exp(np.mean(np.log(changes[1:] / changes[:-1]))) == pytest.approx(steps.ratio, rel=0.10)
    assert steps.numerics.error_estimate < 1e-8


def test_the_approximations_diverge_when_rho_exceeds_one_though_the_joint_solution_exists():
    """ρ ≥ 1 (small flywheel): the changes grow and a sentence says so, while the equation of motion with the
    characteristic still has its steady cycle."""
    built = machine(1.0)
    tables = mo.cycle_tables(built, built.kinks(), 2048)
    working = mc.operating_points(KLOSS, I, -cycle_mean(tables.net_phi, tables.phi))[0]
    steps = successive_approximations(built, tables, working.omega, mc.critical_speed(KLOSS, I))
    assert steps.ratio > 1 and not steps.converged
    assert "motor_approximations_diverge" in [n.code for n in steps.notices]
    assert mo.steady_cycle(built, 1e-8).steady is not None



def steps_both_ways(built: Machine, tol: float = 1e-8):
    tables = mo.cycle_tables(built, built.kinks(), 2048)
    working = mc.operating_points(built.motor, I, -cycle_mean(tables.net_phi, tables.phi))
    knee = mc.critical_speed(built.motor, I)
    return [successive_approximations(built, tables, working[0].omega, knee, tol, compiled=compiled)
            for compiled in (False, True)]


LINEARISED = Motor(kind="induction", M_nominal=40.0, omega_nominal=150.0, omega_sync=157.0)


@pytest.mark.parametrize("built", [machine(5.0), machine(1.0), machine(2.0, LINEARISED),
                                   Machine("slider_crank", {"l1": 0.1, "l2": 0.3, "e": 0.02, "a2": 0.5},
                                           Inertias(J1=3.0, m2=5, J_S2=0.05, m3=10, J_rotor=0.01, gear_ratio=I),
                                           Load(force=2000, return_factor=0.2, f=0.1, beta=5.0), KLOSS)],
                         ids=["kloss", "kloss diverging", "linearised", "kloss with viscous load"])
def test_the_compiled_steps_are_the_plain_steps(built):
    """The compiled loop (Newton's method for both roots, Brent's as the fallback) against the numpy loop with
    scipy's brentq: the same number of steps, the same ending, every law ω^(k)(φ) and moment M_д^(k)(φ) within
    1e-12 (both roots to ~1e-14; the sums differ from numpy's only in rounding), the table's figures likewise
    (the change, a difference of nearly equal laws, to 1e-6 of itself or 1e-15), the same words."""
    plain, compiled = steps_both_ways(built)
    assert len(plain.rows) == len(compiled.rows) > 1 and plain.converged == compiled.converged
    assert plain.ratio == compiled.ratio
    for a, b in zip(plain.omega + plain.moment, compiled.omega + compiled.moment):
        assert np.max(np.abs(a - b)) <= 1e-12 * np.max(np.abs(a))
    for a, b in zip(plain.rows, compiled.rows):
        for key in a:
            assert b[key] == pytest.approx(a[key], rel=1e-6 if key == "change" else 1e-12, abs=1e-15)
    assert [n.code for n in plain.notices] == [n.code for n in compiled.notices]
    if plain.converged:
        assert compiled.numerics.error_estimate == pytest.approx(plain.numerics.error_estimate, rel=1e-6)



def test_after_warm_up_no_approximation_compiles_anything():
    """warm_up compiles the loop's one signature: the steps of every machine above (kloss, linearised, a viscous
    load) add none, so no request waits for the compiler."""
    from server.core.dynamics import approximations_compiled
    approximations_compiled.warm_up()
    before = len(approximations_compiled.approximation_steps.signatures)
    steps_both_ways(machine(5.0))
    steps_both_ways(machine(2.0, LINEARISED))
    assert len(approximations_compiled.approximation_steps.signatures) == before == 1

BODY = {"mechanism": "slider_crank", "params": {"l1": 0.1, "l2": 0.3, "e": 0, "a2": 0.5},
        "inertias": {"J1": 5, "m2": 5, "J_S2": 0.05, "m3": 10, "J_rotor": 0.01, "gear_ratio": 5},
        "load": {"force": 2000, "return_factor": 0.2, "f": 0.1},
        "motor": {"kind": "kloss", "M_max": 70, "s_critical": 0.2, "omega_sync": 157},
        "outputs": ["characteristic", "operating_point", "approximations", "joint"]}


@pytest.fixture(scope="module")
def client():
    return TestClient(create_app())


def test_the_endpoint_answers_by_name_without_nan_and_with_numerics(client):
    answer = client.post("/api/v1/motor-characteristic?precision=full", json=BODY)
    assert answer.status_code == 200 and "NaN" not in answer.text and "Infinity" not in answer.text
    data = answer.json()
    assert set(data) >= set(BODY["outputs"])
    assert data["approximations"]["numerics"]["converged"] and data["joint"]["numerics"]["error_estimate"] < 1e-6
    assert data["joint"]["difference"] < 1e-6
    assert data["figures"]["margin"] > 0
    assert data["numerics"]["error_estimate"] < 1e-12                # the operating point's residual
    only = client.post("/api/v1/motor-characteristic", json={**BODY, "outputs": ["characteristic"]}).json()
    assert set(only) == {"characteristic", "warnings"}


def test_a_stalling_load_is_said_in_words(client):
    data = client.post("/api/v1/motor-characteristic?lang=ru",
                       json={**BODY, "load": {"force": 20000, "return_factor": 0.2, "f": 0.1}}).json()
    assert "approximations" not in data and any("опрокидывается" in w for w in data["warnings"])


@pytest.mark.parametrize("change, field", [
    ({"motor": {"kind": "linear", "M0": 30, "b": 0.3}}, "motor"),
    ({"tol": 0}, "tol"),
    ({"outputs": ["speed"]}, "outputs"),
])
def test_bad_input_is_refused_naming_the_field(client, change, field):
    answer = client.post("/api/v1/motor-characteristic", json={**BODY, **change})
    assert answer.status_code == 422
    assert field in json.dumps([d["loc"] for d in answer.json()["detail"]])


def test_diverging_approximations_are_said_in_russian_beside_the_joint_solution(client):
    body = {**BODY, "inertias": {**BODY["inertias"], "J1": 0.3}}
    answer = client.post("/api/v1/motor-characteristic?lang=ru", json=body)
    assert answer.status_code == 200
    data = answer.json()
    assert not data["approximations"]["converged"] and data["approximations"]["contraction"] > 1
    assert "расходятся" in data["approximations"]["numerics"]["message"]
    assert any("расходятся" in w for w in data["warnings"]) and data["joint"]["delta"] > 0
