"""The reduced moments over the cycle (server/core/dynamics/cycle_moments.py; Chaika–Vasylenko §3.2, §3.4 steps
8–10, Fig. 3.7), each checked against something that is not the code under test: the work of a constant
pressure (p A_p H, analytic), a quadrature 240 times finer, finite differences of the links' potential energy
over the exact joint positions, finite differences of the piston's exact position (power equality), the
midpoint rule's closed form for a cosine, and the printed columns of Chaika–Vasylenko's Table 4.3."""
from __future__ import annotations

import math

import numpy as np
import pytest

from server.api.endpoints import compute
from server.core.dynamics.cycle_moments import (Cylinder, Drawing, Masses, cycle_moments, drawing_scale,
                                                graphical_integration, gravity_moment, piston_moment)
from server.core.dynamics.motors import gas_force
from server.core.mechanisms import MECHANISMS

# The example engine of Chaika–Vasylenko §4.3: l₁ = 0.045 m, λ₂ = l₂/l₁ = 4, λ_S2 = 0.38, D = 0.075 m, masses
# m₁ = 14.8, m₂ = 1.8, m₃ = 1.33 kg, p_max = 3.0 MPa, 2400 rpm; the cylinder stands above the crank (α = 90°).
BOOK = {"l1": 0.045, "l2": 0.18, "e": 0.0, "a2": 0.38}
MASSES = Masses(m1=14.8, crank_centre=0.1, m2=1.8, m3=1.33, guide_angle=math.pi / 2)
OMEGA = 2400 * 2 * math.pi / 60
STROKE = 2 * BOOK["l1"]
AREA = math.pi * 0.075**2 / 4
FLAT = tuple([1.0] * 11), tuple([0.0] * 11)     # p = p_max on expansion, 0 on compression


def engine(mode="two_stroke", diagram=(None, None), p_max=3e6) -> Cylinder:
    return Cylinder(mode, p_max, 0.075, *diagram)


def run(cylinder, masses=MASSES, params=BOOK, drawing=Drawing(), efficiency=0.85):
    result, notices = cycle_moments(params, masses, cylinder, OMEGA, efficiency, drawing)
    return result, notices


@pytest.mark.parametrize("mode, turns", [("two_stroke", 1), ("four_stroke", 2)])
def test_a_constant_pressure_does_the_work_p_a_h_and_the_useful_moment_spreads_it_over_the_cycle(mode, turns):
    """p constant on the expansion stroke: A_P|Φ = p A_p H exactly and A_P(φ) = p A_p (s(π) − s(φ)) on π…2π, so
    M_kO = −p A_p H/(τπ) (3.32). Tolerance 1e-10 relative: Simpson's error on the smooth u₃₁ with 4320
    intervals per turn is ~1e-14; the rest is rounding."""
    result, notices = run(engine(mode, FLAT, 2e6), Masses())
    work = 2e6 * AREA * STROKE
    assert notices == []
    assert result["cycle_work"] == pytest.approx(work, rel=1e-10)
    assert result["balancing_moment"] == pytest.approx(-work / (2 * turns * math.pi), rel=1e-10)
    phi = result["phi"]
    expanding = (phi > math.pi) & (phi <= 2 * math.pi)
    s = MECHANISMS["slider_crank"].evaluate(BOOK, phi, set()).values["s"]
    assert np.allclose(result["works"]["P"][expanding], 2e6 * AREA * (STROKE - s[expanding]), rtol=0, atol=1e-9 * work)
    assert np.allclose(result["works"]["P"][phi <= math.pi], 0.0, atol=1e-12 * work)


@pytest.mark.parametrize("mode", ["two_stroke", "four_stroke", "compressor"])
def test_the_works_agree_with_a_quadrature_170_times_finer_within_their_error_estimate(mode):
    """A(φ) of the gas and of gravity against the trapezoid rule on 360·2¹¹ intervals per turn of the same moments
    (the shown nodes among its nodes; its error, h²|M″|/12 per unit angle, is ~1e-10 of the work); the estimate
    the answer carries must hold."""
    cylinder = engine(mode, p_max=0.7e6 if mode == "compressor" else 3e6)
    result, _ = run(cylinder)
    turns = cylinder.strokes // 2
    phi = np.linspace(0.0, cylinder.cycle, 360 * 2**11 * turns + 1)
    kinematics = MECHANISMS["slider_crank"].evaluate(BOOK, phi, set())
    force = gas_force(cylinder.indicator(), MECHANISMS["slider_crank"], BOOK, phi, kinematics)
    gas = piston_moment(force, kinematics.values["u31"])
    gravity = gravity_moment(BOOK, MASSES, kinematics)
    step = phi[1] - phi[0]
    at = np.arange(0, phi.size, 2**11)
    reference = {name: np.concatenate([[0.0], np.cumsum((m[1:] + m[:-1]) / 2) * step])[at]
                 for name, m in (("gas", gas), ("gravity", gravity))}
    gas_work = result["works"]["P" if mode != "compressor" else "kO"]
    estimate = result["numerics"]["error_estimate"]
    for name, ours in (("gas", gas_work), ("gravity", result["works"]["G"])):
        error = np.max(np.abs(ours - reference[name])) / np.max(np.abs(reference[name]))
        assert error <= max(estimate, 1e-10), (name, error, estimate)


def potential(params, masses, phi):
    """Π = −Σ m_j g⃗·r_Sj from the exact joint positions (S₁ on the crank at ρ₁l₁)."""
    joints = MECHANISMS["slider_crank"].evaluate(params, phi, {"joints"}).joints
    g = masses.g * np.array([-math.sin(masses.guide_angle), -math.cos(masses.guide_angle)])
    s1 = masses.crank_centre * params["l1"] * np.stack([-np.cos(phi), np.sin(phi)], 1)
    return -(masses.m1 * s1 @ g + masses.m2 * joints["S2"] @ g + masses.m3 * joints["B"] @ g)


@pytest.mark.parametrize("alpha", [0.0, 0.7, math.pi / 2])
def test_the_gravity_moment_is_minus_the_derivative_of_the_links_potential_energy(alpha):
    """M_G = −dΠ/dφ by central differences (h = 1e-5: error h²|Π‴|/6 ~ 1e-11 of max|M_G|; tolerance 1e-8), and
    its work A_G(φ) = Π(0) − Π(φ) (Simpson, tolerance 1e-9 of the largest |ΔΠ|), zero over the turn."""
    masses = Masses(m1=14.8, crank_centre=0.3, m2=1.8, m3=1.33, guide_angle=alpha)
    params = {**BOOK, "e": 0.01}
    result, _ = run(engine(p_max=1e6), masses, params)
    phi, h = result["phi"], 1e-5
    derivative = -(potential(params, masses, phi + h) - potential(params, masses, phi - h)) / (2 * h)
    scale = np.max(np.abs(derivative))
    assert np.max(np.abs(result["moments"]["G"] - derivative)) <= 1e-8 * scale
    drop = potential(params, masses, np.zeros(1)) - potential(params, masses, phi)
    assert np.max(np.abs(result["works"]["G"] - drop)) <= 1e-9 * np.max(np.abs(drop))
    assert abs(result["works"]["G"][-1]) <= 1e-12 * np.max(np.abs(drop))


@pytest.mark.parametrize("mode", ["two_stroke", "compressor"])
def test_power_equality_and_the_steady_state(mode):
    """M_P·ω (engine) or M_kO·ω (compressor) equals the gas force's power F·v_B with v_B from central differences
    of the piston's exact position (tolerance 1e-7 of the largest power: the differences' h² error); the cycle's
    mean gas power is the indicated (engine) or effective (compressor) power; A_Σ(Φ) = 0 (3.32)."""
    cylinder = engine(mode, p_max=0.7e6 if mode == "compressor" else 3e6)
    result, _ = run(cylinder)
    phi, h = result["phi"], 1e-6
    evaluate = lambda angle: MECHANISMS["slider_crank"].evaluate(BOOK, angle, {"joints"}).joints["B"][:, 0]  # noqa: E731
    velocity = OMEGA * (evaluate(phi + h) - evaluate(phi - h)) / (2 * h)
    force = gas_force(cylinder.indicator(), MECHANISMS["slider_crank"], BOOK, phi)
    power = -force * velocity                                 # the gas pushes towards the crank (−x)
    gas = result["moments"]["P" if mode != "compressor" else "kO"]
    assert np.max(np.abs(gas * OMEGA - power)) <= 1e-7 * np.max(np.abs(power))
    mean = np.mean((gas * OMEGA)[:-1])                        # a uniform closed grid: the trapezoid's mean
    key = "indicated" if mode != "compressor" else "effective"
    assert abs(result["powers"][key] - abs(mean)) <= 1e-3 * abs(mean)     # the 361-point mean's own error
    total = result["works"]
    assert abs(total["sum"][-1]) <= 1e-12 * result["cycle_work"]
    if mode == "compressor":
        assert result["powers"]["motor"] == pytest.approx(result["powers"]["effective"] / 0.85, rel=1e-15)
        assert result["moments"]["P"][0] * OMEGA == pytest.approx(result["powers"]["effective"], rel=1e-12)
    else:       # N_e = η_m N_i; the book prints N_e = N_i/η_m
        assert result["powers"]["effective"] == pytest.approx(0.85 * result["powers"]["indicated"], rel=1e-15)
        assert result["powers"]["effective_printed"] == pytest.approx(result["powers"]["indicated"] / 0.85, rel=1e-15)


def test_the_chord_method_read_exactly_is_the_midpoint_rule_in_closed_form():
    """M = a + b cos φ over 12 intervals of h = π/6: each chord adds M(φ_mid) h, and ∫ over an interval is
    a h + 2b sin(h/2) cos φ_mid, so the graphical cos part is the exact one times (h/2)/sin(h/2). Exact to
    rounding (1e-12). The scales: μ_φ = 2π/L, μ_A = μ_M μ_φ K, μ_M a standard scale fitting the height."""
    a, b, h = 3.0, 40.0, math.pi / 6
    mid = (np.arange(12) + 0.5) * h
    drawing = Drawing(pole=40, width=180, height=60, reading=0)
    result = graphical_integration(a + b * np.cos(mid), a + b, 2 * math.pi, 1, drawing)
    nodes = np.arange(13) * h
    exact_cos = b * np.sin(nodes)
    expected = a * nodes + exact_cos * (h / 2) / math.sin(h / 2)
    assert np.allclose(result["work"], expected, rtol=0, atol=1e-12 * b)
    assert result["mu_phi"] == pytest.approx(2 * math.pi / 180, rel=1e-15)
    assert result["mu_M"] == 1.0 and (a + b) / result["mu_M"] <= 60            # 43/60 = 0.72 → 1 N·m/mm
    assert result["mu_A"] == pytest.approx(result["mu_M"] * result["mu_phi"] * 40, rel=1e-15)
    assert result["step"] * result["mu_phi"] == pytest.approx(2 * math.pi / 12, rel=1e-15)  # 0.5236: printed "0.432"


def test_reading_the_drawing_to_half_a_millimetre_moves_the_integral_at_most_by_its_bound():
    """Each ordinate read to 0.5 mm is off by ≤ 0.25 mm, so y_A after k chords by ≤ k·0.25·Δx/K mm."""
    rng = np.random.default_rng(5)
    moments = rng.uniform(-300, 300, 24)
    exact = graphical_integration(moments, 300, 4 * math.pi, 2, Drawing(per_turn=12, reading=0))
    read = graphical_integration(moments, 300, 4 * math.pi, 2, Drawing(per_turn=12, reading=0.5))
    bound = np.arange(25) * 0.25 * read["step"] / read["pole"] * read["mu_A"]
    assert np.all(np.abs(read["work"] - exact["work"]) <= bound + 1e-12)
    assert np.any(read["work"] != exact["work"])


@pytest.mark.parametrize("value, scale", [(0.7, 1.0), (4.2, 5.0), (3.7e-3, 4e-3), (22.0, 25.0), (51.0, 100.0)])
def test_drawing_scales_are_the_standard_ones(value, scale):
    assert drawing_scale(value) == pytest.approx(scale, rel=1e-15)


# Chaika–Vasylenko Table 4.3 (the 2-stroke engine of §4.3): φ₁ from top dead centre (the app's φ = φ₁ + 180°),
# V_qB (m/rad, 4 decimals printed; ±0.2187 of u₂₁ is a misprint, V_qB is right) and F₃ (N, < 0 towards the crank).
TABLE_PHI = np.radians(np.arange(0, 361, 30))
TABLE_VQB = np.array([0, -0.0274, -0.0440, -0.0450, -0.0340, -0.0176, 0, 0.0176, 0.0340, 0.0450, 0.0440, 0.0274, 0])
TABLE_F3 = np.array([-6097, -11930, -5587, -2651, -1723, -1325, 0, -133, -133, -398, -1060, -2651, -6097.0])


def test_the_moments_at_the_books_positions_match_table_4_3():
    """M_G of the piston alone with the cylinder above the crank is −m₃ g V_qB, and the gas moment of the printed
    F₃ is F₃ V_qB (3.24): the core's analogs match the printed V_qB to its last digit (±5e-5 m/rad, so the
    moments within m₃ g·5e-5 and |F₃|·5e-5 N·m)."""
    phi = TABLE_PHI + math.pi
    kinematics = MECHANISMS["slider_crank"].evaluate(BOOK, phi, set())
    piston_only = Masses(m3=1.33, guide_angle=math.pi / 2)
    assert np.allclose(gravity_moment(BOOK, piston_only, kinematics), -1.33 * 9.81 * TABLE_VQB, rtol=0,
                       atol=1.33 * 9.81 * 5e-5)
    moment = piston_moment(-TABLE_F3, kinematics.values["u31"])
    assert np.all(np.abs(moment - TABLE_F3 * TABLE_VQB) <= np.abs(TABLE_F3) * 5e-5 + 1e-9)


def test_the_endpoint_answers_the_variant_and_refuses_what_it_cannot_compute():
    body = {"mechanism": "slider_crank", "params": BOOK, "inertias": {"m2": 1.8, "m3": 1.33}, "omega": OMEGA,
            "cycle": {"mode": "compressor", "p_max": 7e5, "bore": 0.075, "efficiency": 0.9},
            "outputs": ["cycle_moments"]}
    answer = compute("reduction", body, "ru")["cycle_moments"]
    assert answer["graphical"]["integrated"] == "O" and answer["balancing_moment"] > 0
    assert "Симпсон" in answer["numerics"]["method"]
    from server.core.mechanisms import GeometryError
    with pytest.raises(GeometryError, match="cycle"):
        compute("reduction", {**body, "cycle": None})
    from pydantic import ValidationError
    with pytest.raises(ValidationError, match="compressor"):
        compute("reduction", {**body, "cycle": {**body["cycle"], "expansion": [0.5] * 11}})


def test_no_work_is_said_in_words():
    result, notices = run(engine(diagram=(tuple([0.0] * 11), tuple([0.0] * 11))))
    assert result["graphical"]["epsilon"] is None and [n.code for n in notices] == ["cycle_no_work"]


def test_a_compressor_past_its_delivery_limit_is_said_in_words():
    """π = p_d/p_s ≥ ((1 + c)/c)ⁿ = 21^1.3 ≈ 52.4 (c = 0.05, n = 1.3): the volumetric efficiency 1 − c(π^(1/n) − 1)
    is zero there (checked here in its closed form), and the answer says the compressor delivers nothing."""
    limit = Cylinder("compressor", 1e6, 0.075).delivery_limit
    assert 1 - 0.05 * (limit ** (1 / 1.3) - 1) == pytest.approx(0.0, abs=1e-12)
    below, quiet = run(Cylinder("compressor", (limit - 1.5) * 1e5, 0.075))
    beyond, said = run(Cylinder("compressor", (limit - 0.5) * 1e5, 0.075))
    assert quiet == [] and below["cycle_work"] > 0
    assert [n.code for n in said] == ["compressor_no_delivery"]


def test_on_the_sheet_each_chord_is_parallel_to_its_ray_and_starts_where_the_last_ended():
    """Fig. 3.7 in mm: chord k (between the integral curve's nodes) has the slope of the ray from P(−K, 0) to
    (0, y_k), and y_k is the diagram's ordinate at the interval's midpoint (read exactly). Tolerance 1e-12 mm."""
    result, _ = run(engine(), drawing=Drawing(pole=55, reading=0))
    sheet = result["graphical"]["sheet"]
    x = sheet["x"]
    rays = ~np.isnan(sheet["rays"])
    ray_x, ray_y = x[rays].reshape(-1, 2), sheet["rays"][rays].reshape(-1, 2)
    assert np.all(ray_x[:, 0] == -55) and np.all(ray_x[:, 1] == 0) and np.all(ray_y[:, 0] == 0)
    slope = ray_y[:, 1] / 55
    curve = ~np.isnan(sheet["integral"])
    chord = np.diff(sheet["integral"][curve]) / np.diff(x[curve])
    assert np.allclose(chord, slope, rtol=0, atol=1e-12)
    diagram = ~np.isnan(sheet["diagram"])
    carried = ~np.isnan(sheet["carried"])
    mid_x = x[carried].reshape(-1, 2)[:, 0]
    assert np.allclose(np.interp(mid_x, x[diagram], sheet["diagram"][diagram]), ray_y[:, 1], rtol=0, atol=1e-9)


@pytest.mark.parametrize("field, value", [("p_max", 0.0), ("bore", 0.0), ("efficiency", 0.0), ("mode", "diesel")])
def test_a_cylinder_that_cannot_be_drawn_is_refused_naming_its_field(field, value):
    """p_max below 1 kPa or a bore below 1 mm would make the diagram's scale underflow; η = 0 divides N_e."""
    from fastapi.testclient import TestClient
    from server.api.app import app
    cycle = {"mode": "two_stroke", "p_max": 3e6, "bore": 0.075, "efficiency": 0.85, field: value}
    response = TestClient(app).post("/api/v1/reduction", json={
        "mechanism": "slider_crank", "params": BOOK, "cycle": cycle, "outputs": ["cycle_moments"]})
    assert response.status_code == 422
    assert response.json()["detail"][0]["loc"][-2:] == ["cycle", field]



def test_another_mechanism_asking_for_the_cycle_moments_is_refused_before_anything_is_computed():
    """The check comes first in /reduction, before its general-mechanism branch (which would leave it out)."""
    from server.core.mechanisms import GeometryError
    with pytest.raises(GeometryError, match="crank-slider"):
        compute("reduction", {"mechanism": "four_bar", "outputs": ["inertia", "cycle_moments"]})
