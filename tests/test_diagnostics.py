"""Edge values and the one result type: the slotted link's viscous moment at λ = 1, one sign convention
for the coupler, the declared Numerics, the parabola-vertex extremum and Simpson's rule — each against something
that is not the code under test (closed forms, finite differences of the drawn geometry, analytic integrals)."""
import dataclasses
import json
import math

import numpy as np
import pytest
from fastapi.testclient import TestClient
from hypothesis import given, settings, strategies as st

from server.api.app import app
from server.api.schemas import NumericsModel
from server.core.angular_acceleration import CrankLaw, crank_slider, trammel
from server.core.dynamics.compiled import mean_of_extremes
from server.core.dynamics.resistance import Load, resisting_moment
from server.core.mechanisms import MECHANISMS
from server.core.numerics import Numerics, cumulative_simpson, parabola_extremum, simpson

client = TestClient(app)


def strict(response):
    assert response.status_code == 200, response.text
    return json.loads(response.text, parse_constant=lambda name: pytest.fail(f"{name} in the response"))


# --- defect 5: the slotted link's viscous moment at λ = 1 ---------------------------------------------------------

BETA, OMEGA, L1 = 2.5, 7.0, 0.13


def viscous(l0, phi):
    return resisting_moment("slotted_link", {"l0": l0, "l1": L1}, Load(beta=BETA), np.asarray(phi, float), OMEGA).viscous


def test_viscous_moment_at_lambda_one_is_the_closed_form_limit_at_pi():
    """Eremyants (3.53*): M_T = βω l₁² sin²(φ/2), so β ω l₁² at φ = π where u₂₁ itself jumps (+l₁ → −l₁)."""
    at_pi = viscous(L1, [np.pi])[0]
    assert at_pi == pytest.approx(BETA * OMEGA * L1**2, rel=1e-15)       # the limit, to rounding


@pytest.mark.parametrize("distance", [1e-1, 1e-3, 1e-6, 1e-9])
def test_viscous_moment_at_lambda_one_approaches_pi_continuously(distance):
    """(3.53*) in its printed form at angles approaching π from both sides: relative rounding only (1e-14)."""
    phi = np.array([np.pi - distance, np.pi + distance, 3.0, 0.5])
    assert viscous(L1, phi) == pytest.approx(BETA * OMEGA * L1**2 * np.sin(phi / 2) ** 2, rel=1e-14)


@settings(max_examples=60, deadline=None)
@given(lam=st.floats(0.05, 5.0), phi=st.floats(0.0, 2 * np.pi))
def test_viscous_moment_is_beta_omega_times_the_squared_sliding_speed_of_the_drawn_block(lam, phi):
    """S(φ) = u₂₁² against central differences of |BC| from the coordinates (B on the crank circle, C the lever
    pivot): h = 1e-5, truncation ~h²·|BC|‴ and round-off ~ε|BC|/h, both below 1e-6 away from λ = 1, φ = π."""
    l0 = lam * L1
    distance = lambda a: np.hypot(L1 * np.sin(a), L1 * np.cos(a) + l0)
    if distance(phi) < 0.05 * L1:
        return                                                     # near the pivot: the limit test above
    h = 1e-5
    speed = (distance(phi + h) - distance(phi - h)) / (2 * h)
    assert viscous(l0, [phi])[0] == pytest.approx(BETA * OMEGA * speed**2, rel=1e-6, abs=1e-9 * BETA * OMEGA * L1**2)


def test_reduction_answer_carries_the_finite_viscous_moment_at_pi():
    body = {"mechanism": "slotted_link", "params": {"l0": 0.1, "l1": 0.1}, "load": {"force": 0, "beta": BETA},
            "omega": OMEGA, "n": 361, "outputs": ["resisting"]}
    data = strict(client.post("/api/v1/reduction", json=body))
    assert data["resisting"]["viscous"][180] == pytest.approx(BETA * OMEGA * 0.01, rel=1e-12)   # φ = π is node 180
    assert None not in data["resisting"]["viscous"]


# --- defect 5: one sign convention for the coupler, both scenes ----------------------------------------------------

def crank_sense(A: np.ndarray) -> np.ndarray:
    """+1 where the crank turns counter-clockwise between neighbouring samples, −1 clockwise (from the drawing)."""
    return np.sign(A[:-1, 0] * A[1:, 1] - A[:-1, 1] * A[1:, 0])


def rate_in_crank_sense(first: np.ndarray, second: np.ndarray, crank: np.ndarray, t: np.ndarray) -> np.ndarray:
    """Angular speed of the segment first→second by central differences of the drawn points, counted positive in
    the sense the crank turns (its drawn sense, not a formula)."""
    angle = np.unwrap(np.arctan2(second[:, 1] - first[:, 1], second[:, 0] - first[:, 0]))
    sense = crank_sense(crank)
    assert np.all(sense == sense[0])                                # the crank keeps one sense in the drawing
    return sense[0] * (angle[2:] - angle[:-2]) / (t[2:] - t[:-2])


@pytest.mark.parametrize("lam", [0.2, 0.5, 0.9])
def test_crank_slider_coupler_speed_sign_from_finite_differences_of_its_drawing(lam):
    law = CrankLaw("harmonic", 1.3, amplitude=0.4, frequency=1.7)
    t = np.linspace(0.0, 6.0, 6001)
    result = crank_slider(lam, 0.4, law, t)
    A, B = result["points"]["A"], result["points"]["B"]
    fd = rate_in_crank_sense(A, B, A, t)
    # central differences, h = 1 ms: error ~h²ω³ < 1e-4 here (ω ≲ 2 rad/s, λ ≤ 0.9: ω_AB' bounded by ~20)
    assert fd == pytest.approx(result["omega_coupler"][1:-1], abs=1e-4)


def test_trammel_coupler_speed_sign_from_finite_differences_of_its_drawing():
    law = CrankLaw("harmonic", 1.3, amplitude=0.4, frequency=1.7)
    t = np.linspace(0.0, 6.0, 6001)
    result = trammel(0.4, law, t)
    B, D, A = result["points"]["B"], result["points"]["D"], result["points"]["A"]
    fd = rate_in_crank_sense(B, D, A, t)
    assert fd == pytest.approx(result["omega_coupler"][1:-1], abs=1e-5)     # here exactly −ω: error ~h²ω‴
    assert np.all(np.sign(result["omega_coupler"]) == -1)                   # BD turns against the crank


def test_the_same_convention_in_the_transfer_functions():
    """The crank-slider of the transfer-function scene: u₂₁ = ω_AB/ω₁ against differences of its drawn rod angle,
    counted in its crank's drawn sense, and equal to the angular-acceleration scene's ω_AB/ω at the same φ."""
    mech = MECHANISMS["slider_crank"]
    lam = 0.4
    p = mech.check({"l1": lam, "l2": 1.0, "e": 0.0})
    phi = np.linspace(0.0, 2 * np.pi, 4001)
    ev = mech.evaluate(p, phi, {"joints"})
    A, B = ev.joints["A"], ev.joints["B"]
    fd = rate_in_crank_sense(A, B, A, phi)
    assert fd == pytest.approx(ev.values["u21"][1:-1], abs=1e-5)            # h = 1.6e-3 rad: error ~h²u‴ ≲ 1e-5
    scene = crank_slider(lam, lam, CrankLaw("constant", 1.0), phi)          # ω = 1: t = φ
    assert scene["omega_coupler"] == pytest.approx(ev.values["u21"], abs=1e-14)


def test_phi_zero_is_the_same_position_in_both_scenes():
    """φ = 0: the crank lies along the slider's line pointing away from the slider, and it turns the same way."""
    mech = MECHANISMS["slider_crank"]
    p = mech.check({"l1": 0.1, "l2": 0.25, "e": 0.0})
    phi = np.array([0.0, 1e-3])
    ev = mech.evaluate(p, phi, {"joints"})
    scene = crank_slider(0.4, 0.1, CrankLaw("constant", 1.0), phi)
    for A, B in ((ev.joints["A"] - ev.joints["O"], ev.joints["B"] - ev.joints["O"]),
                 (scene["points"]["A"], scene["points"]["B"])):
        assert A[0] == pytest.approx([-0.1, 0.0], abs=1e-15)               # along the guide, away from the slider
        assert B[0, 0] > 0 and B[0, 1] == pytest.approx(0.0, abs=1e-15)     # the slider on the other side of O
    assert crank_sense(ev.joints["A"] - ev.joints["O"]) == crank_sense(scene["points"]["A"])
    assert scene["points"]["B"][0] == pytest.approx(ev.joints["B"][0] - ev.joints["O"][0], abs=1e-15)


def test_instantaneous_centre_lies_where_the_signed_ap_puts_it():
    """P from the drawing (line OA meets the normal to the guide at B) against A − AP·(unit OA), AP = 1/inv_AP
    counted from A towards O; and ω_AB = V_A/AP with V_A = ω·OA."""
    t = np.array([0.3, 1.0, 2.5, 4.0, 5.5])
    law = CrankLaw("constant", 1.0)
    for result in (crank_slider(0.5, 0.2, law, t), trammel(0.2, law, t)):
        A, P = result["points"]["A"], result["points"]["P"]
        unit = A / np.linalg.norm(A, axis=1)[:, None]
        assert P == pytest.approx(A - unit / result["inv_AP"][:, None], abs=1e-12)
        assert result["omega_coupler"] == pytest.approx(0.2 * result["omega"] * result["inv_AP"], abs=1e-14)


# --- one result type -----------------------------------------------------------------------------------------------

def test_numerics_is_declared_once_with_the_same_fields_in_core_and_api():
    core = {f.name for f in dataclasses.fields(Numerics)}
    assert core == set(NumericsModel.model_fields)
    assert {"method", "why", "rtol", "steps", "rejected", "nfev", "njev", "nlu", "iterations", "converged",
            "runtime_ms", "error_estimate", "energy_residual", "message"} <= core


def test_numerics_never_carries_a_non_finite_number_and_says_so():
    numerics = Numerics("m", error_estimate=float("nan"), energy_residual=np.float64(np.inf), steps=np.int64(4))
    out = numerics.as_dict()
    assert out["error_estimate"] is None and out["energy_residual"] is None and out["steps"] == 4
    assert "error_estimate" in out["message"] and "energy_residual" in out["message"]
    NumericsModel.model_validate(out)


ENGINE = {"mechanism": "slider_crank", "params": {"l1": 0.12, "l2": 0.528, "a2": 0.32},
          "inertias": {"J1": 2.72, "m2": 24.2, "J_S2": 1.21, "m3": 36.2},
          "motor": {"kind": "indicator", "p_max": 4.4e6, "piston_diameter": 0.1}, "omega_mean": 47.124}
OWN_ANSWERS = [
    ("flywheel", ENGINE | {"delta": 0.0125}),
    ("reduction", {"mechanism": "sine", "params": {"l1": 1}, "load": {"force": 1, "f": 0.15}, "outputs": ["resisting"]}),
    ("reduction", {"mechanism": "slider_crank", "params": {"l1": 1, "l2": 1.02}, "load": {"force": 1, "f": 1.5},
                   "outputs": ["resisting"]}),
    ("angular-acceleration", {"lam": 0.5}),
    ("angular-acceleration", {"mechanism": "trammel", "law": "harmonic", "amplitude": 0.5}),
]


@pytest.mark.parametrize("lang", ["en", "uk"])
@pytest.mark.parametrize("endpoint, body", OWN_ANSWERS, ids=[f"{e}-{i}" for i, (e, _) in enumerate(OWN_ANSWERS)])
def test_answers_of_this_workstream_carry_the_declared_numerics(endpoint, body, lang):
    data = strict(client.post(f"/api/v1/{endpoint}?lang={lang}", json=body))
    numerics = NumericsModel.model_validate(data["numerics"])            # extra keys are refused
    assert numerics.method and numerics.runtime_ms >= 0
    assert numerics.error_estimate is not None or numerics.message       # no estimate: said in words


def test_self_locking_reduction_says_why_it_has_no_error_estimate():
    body = {"mechanism": "slider_crank", "params": {"l1": 1, "l2": 1.02}, "load": {"force": 1, "f": 1.5},
            "outputs": ["resisting"]}
    numerics = strict(client.post("/api/v1/reduction", json=body))["numerics"]
    assert numerics["error_estimate"] is None and "M_c0" in numerics["message"]


# --- the parabola-vertex extremum and Simpson's rule ---------------------------------------------------------------

@pytest.mark.parametrize("n", [64, 256, 1024])
def test_parabola_vertex_extremum_of_a_shifted_cosine_is_third_order(n):
    """max and min of a + b cos(φ − c) over a closed grid against a ± |b|: the vertex errs by O(h³) or better
    (here h⁴/… since the cosine is even about its peak), the best node by O(h²)."""
    phi = np.linspace(0, 2 * np.pi, n + 1)
    y = 0.3 + 2.0 * np.cos(phi - 0.123)
    h = 2 * np.pi / n
    assert abs(parabola_extremum(y, +1) - 2.3) <= 2.0 * h**3
    assert abs(parabola_extremum(y, -1) + 1.7) <= 2.0 * h**3
    assert abs(y.max() - 2.3) > 10 * abs(parabola_extremum(y, +1) - 2.3) or abs(y.max() - 2.3) < 1e-15


def test_parabola_vertex_keeps_an_end_node_of_an_open_history_and_respects_the_mask():
    t = np.linspace(0, 1, 101)
    assert parabola_extremum(t**2, +1, periodic=False) == 1.0               # rising to the end: the end node
    phi = np.linspace(0, 2 * np.pi, 201)
    y = np.sin(phi)
    allowed = phi > np.pi                                                    # only the lower half: the minimum −1
    assert parabola_extremum(y, +1, allowed=allowed) <= 1e-12
    assert parabola_extremum(y, -1, allowed=allowed) == pytest.approx(-1.0, abs=(2 * np.pi / 200) ** 3)


@settings(max_examples=40, deadline=None)
@given(T0=st.floats(5.0, 50.0), amplitude=st.floats(0.1, 3.5), shift=st.floats(0, 6.28), n=st.integers(32, 600))
def test_compiled_twin_of_the_extremum_matches_the_helper_exactly(T0, amplitude, shift, n):
    """compiled.mean_of_extremes is the numba twin of ½(max ω + min ω) by the helper: the same arithmetic. The
    kinetic energy T₀ + A stays positive (|A| < 1.3 × 3.5 < 5 ≤ T₀): a machine in motion; with amplitude 4 and
    T₀ = 5, ω would be √ of a negative number at some angle, NaN in both."""
    phi = np.linspace(0, 2 * np.pi, n + 1)
    work = amplitude * (np.sin(phi + shift) + 0.3 * np.sin(2 * phi))
    total = 1.0 + 0.2 * np.cos(phi) ** 2
    omega = np.sqrt(2 * (T0 + work) / total)
    expected = 0.5 * (parabola_extremum(omega, +1) + parabola_extremum(omega, -1))
    assert mean_of_extremes(work, total, T0) == pytest.approx(expected, rel=1e-15, abs=0)


def test_simpson_against_analytic_integrals():
    """∫₀^π sin = 2, ∫₀¹ x³ = 1/4 (exact for cubics); the odd tail by the trapezoid still converges."""
    x = np.linspace(0, np.pi, 101)
    assert simpson(np.sin(x), x[1] - x[0]) == pytest.approx(2.0, abs=(np.pi / 100) ** 4)     # h⁴·π/180·max|f⁗|
    x = np.linspace(0, 1, 11)
    assert simpson(x**3, 0.1) == pytest.approx(0.25, abs=1e-15)
    x = np.linspace(0, np.pi, 102)                                          # 101 intervals: odd tail
    assert simpson(np.sin(x), x[1] - x[0]) == pytest.approx(2.0, abs=(np.pi / 101) ** 3)


def test_cumulative_simpson_follows_the_antiderivative():
    x = np.linspace(0, 3, 2 * 150 + 1)                                       # step nodes and half-step nodes
    running = cumulative_simpson(np.exp(x), 2 * (x[1] - x[0]))
    bound = 3 * (x[1] - x[0]) ** 4 / 180 * np.exp(3)                        # (b − a)h⁴/180·max|f⁗|, h the node spacing
    assert running == pytest.approx(np.exp(x[::2]) - 1, abs=bound)
    assert math.isclose(running[-1], simpson(np.exp(x), x[1] - x[0]), rel_tol=1e-14)


# --- the reduction's words about the friction iteration come from the series' ratio, not from a step cap ------------

def iteration_answer(f):
    body = {"mechanism": "slider_crank", "params": {"l1": 1.0, "l2": 1.03}, "load": {"force": 100.0, "f": f},
            "iteration_phi": math.pi / 2, "outputs": ["friction_iteration"]}
    return strict(client.post("/api/v1/reduction", json=body))


def test_a_slowly_converging_series_is_not_called_diverging():
    """λ = 1.03, f = 0.2 at φ = 90°: tan ψ = (1/1.03)/√(1 − 1/1.03²) = 4.05, ratio f·tan ψ = 0.81 < 1 (geometry by
    hand, not the code): the series converges, however many steps the table shows."""
    tan_psi = (1 / 1.03) / math.sqrt(1 - 1 / 1.03**2)
    data = iteration_answer(0.2)
    assert data["friction_iteration"]["ratio"] == pytest.approx(0.2 * tan_psi, rel=1e-12)
    assert not any("diverge" in w for w in data["warnings"])
    assert data["friction_iteration"]["limit"]["F_T"] == pytest.approx(100 * 0.2 * tan_psi / (1 - 0.2 * tan_psi), rel=1e-12)
    assert data["friction_iteration"]["converged"] or any("limit" in w for w in data["warnings"])


def test_a_series_with_ratio_above_one_is_self_locking():
    data = iteration_answer(0.3)                                            # ratio 0.3 · 4.05 = 1.22
    assert any("Self-locking" in w and "diverge" in w for w in data["warnings"])
