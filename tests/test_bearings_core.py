"""The plain-bearing designer (Chaika–Vasylenko §2) against independent computations: hand-computed sizes,
the book's own units for (2.12), Petroff's law for (2.17), the limits of (2.13) and of the Stribeck curve, the
printed tables, and the pair's relative angular speed against finite differences of the joints' geometry.
The book prints no worked bearing example; its recommended journal diameters (§2.1) and clearances (§2.2) are
checked as printed."""
from __future__ import annotations

import math

import numpy as np
import pytest

from server.core.bearings import dry, film
from server.core.bearings.tables import DRY, LUBRICATED, MPA
from server.core.kinematics import compute_kinematics

RPM = 2 * math.pi / 60


def test_tables_hold_the_printed_rows():
    """Tables 2.1 and 2.2 as printed (Chaika–Vasylenko), in SI; exact: they are typed data."""
    bronze = DRY["bronze_brof"]
    assert (bronze.pressure, bronze.speed, bronze.pv, bronze.temperature, bronze.friction) == (
        (5 * MPA, 20 * MPA), (1.1, 1.1), (25 * MPA, 35 * MPA), (70, 80), (0.12, 0.20))
    assert DRY["nylon"].friction is None                      # printed blank
    babbit = LUBRICATED["babbit_b83"]
    assert (babbit.pressure, babbit.speed, babbit.pv, babbit.temperature) == (
        (10 * MPA, 15 * MPA), (50, 50), (50 * MPA, 75 * MPA), (115, 115))
    assert LUBRICATED["ptfe"].pv is None and LUBRICATED["bronze_brs30"].temperature is None
    assert len(DRY) == 11 and len(LUBRICATED) == 14
    assert bronze.allowable() == {"pressure": 5 * MPA, "speed": 1.1, "pv": 25 * MPA, "temperature": 70,
                                  "friction": 0.20}


@pytest.mark.parametrize("load, pressure, ratio, d", [(8000.0, 5e6, 1.0, 0.04), (8000.0, 5e6, 2.0, math.sqrt(8e-4)),
                                                       (500.0, 0.5e6, 0.8, math.sqrt(500 / 0.4e6))])
def test_sizing_by_2_4_and_2_5_by_hand(load, pressure, ratio, d):
    """(2.5) d = √(F/([p]·l̄)), (2.4) l_z = √(F·l̄/[p]) = l̄·d, and at that size p_m of (2.3) is exactly [p_m]
    (1e-12: round-off of a square root and a division)."""
    sized = dry.size(load, pressure, ratio)
    assert sized["diameter"] == pytest.approx(d, rel=1e-12)
    assert sized["length"] == pytest.approx(math.sqrt(load * ratio / pressure), rel=1e-12)
    assert dry.mean_pressure(load, sized["length"], sized["diameter"]) == pytest.approx(pressure, rel=1e-12)


def test_speed_and_friction_power_as_the_book_writes_them():
    """V_s = π·d·n/60 (2.6) and P_f = ω₁·T₁ with T₁ = l_z·(d²/2)·f·p_m (2.7); 1e-13 relative: round-off."""
    d, n, length, f, load = 0.05, 1450.0, 0.06, 0.15, 3000.0
    assert dry.sliding_speed(n * RPM, d) == pytest.approx(math.pi * d * n / 60, rel=1e-13)
    p = dry.mean_pressure(load, length, d)
    torque = length * d**2 / 2 * f * p
    assert dry.friction_power(f, load, dry.sliding_speed(n * RPM, d)) == pytest.approx(n * RPM * torque, rel=1e-13)


def test_heat_balance_2_12_in_si_equals_the_book_units():
    """(2.12) with the printed 8.43, p_m in kgf/m², k′ in kcal/(m²·h·°C): the SI form agrees to the rounding of
    8.43 (the exact factor is 9.80665 W ÷ 1.163 W per kcal/h = 8.4322, so 3·10⁻⁴ of the rise; tolerance 5·10⁻⁴)."""
    length = d = 0.04
    f, p, v, k_book, area, ambient = 0.2, 2e6, 1.0, 11.0, 0.1, 20.0
    book = ambient + 8.43 * length * d / (k_book * area) * f * (p / 9.80665) * v
    si = dry.bushing_temperature(dry.friction_power(f, p * length * d, v), ambient, k_book * dry.KCAL_PER_HOUR, area)
    assert si - ambient == pytest.approx(book - ambient, rel=5e-4)


def test_shaft_heat_2_13_limits():
    """(2.13) T_n = T_B + P·t/(G·c′ + 0.5·A·k′·t): a short shift heats the shaft's mass adiabatically (P·t/(G·c′)),
    a long one tends to T_B + 2P/(A·k′); both limits analytic, tolerances from the neglected term's size."""
    part = dry.shaft(0.04, 3.5)
    assert part["mass"] == pytest.approx(7850 * math.pi * 0.04**2 / 4 * 0.28, rel=1e-13)
    power, k = 50.0, 12.0
    short = dry.shaft_temperature(power, 20.0, k, part["mass"], part["area"], 1e-4)
    assert short - 20 == pytest.approx(power * 0.36 / (part["mass"] * dry.STEEL_HEAT), rel=1e-4)
    long = dry.shaft_temperature(power, 20.0, k, part["mass"], part["area"], 1e6)
    assert long - 20 == pytest.approx(2 * power / (part["area"] * k), rel=1e-3)


def test_printed_2_13_barely_warms_the_bearing():
    """The printed (2.13) lacks p_m·V_s: for a bearing the corrected form heats by tens of degrees it gives
    a rise of hundredths (the number the scene shows beside the corrected one)."""
    part = dry.shaft(0.04, 3.5)
    k = 11 * dry.KCAL_PER_HOUR
    printed = dry.shaft_temperature_as_printed(0.04, 0.04, 0.2, 20.0, k, part["mass"], part["area"], 8.0)
    corrected = dry.shaft_temperature(0.2 * 2000 * 0.1, 20.0, k, part["mass"], part["area"], 8.0)
    assert 0 < printed - 20 < 0.1 and corrected - 20 > 10


def test_film_power_is_petroffs_law():
    """(2.17) with α = 2π is Petroff's T = 2π·μ·ω·r³·l/h₀ times ω (1e-13: round-off); a half wrap halves it."""
    omega, r, length, h0, mu = 300.0, 0.02, 0.04, 2e-5, 0.02
    power, re = film.film_power(omega, r, length, h0, mu, 2 * math.pi, mu / 880)
    assert re < 1000
    assert power == pytest.approx(2 * math.pi * mu * omega * r**3 * length / h0 * omega, rel=1e-13)
    half, _ = film.film_power(omega, r, length, h0, mu, math.pi, mu / 880)
    assert half == pytest.approx(power / 2, rel=1e-13)


def test_reynolds_switch_2_18_2_19_is_a_jump():
    """Re_ω = ω·r·h₀/(2ν) (2.18); at Re_ω = 1000, k_τ = 1 + 0.0525·40^0.75 = 1.835034 (40^0.75 = 15.9054 by hand; 7 digits)."""
    assert film.reynolds(100.0, 0.05, 1e-4, 1e-6) == pytest.approx(250.0, rel=1e-13)
    assert float(film.turbulence_factor(999.999)) == 1.0
    assert float(film.turbulence_factor(1000.0)) == pytest.approx(1.835034, abs=5e-7)
    nu, r, h0, length, mu = 1e-6, 0.05, 1e-4, 0.05, 8.8e-4
    omega = np.array([0.9999, 1.0]) * 1000 * 2 * nu / (r * h0)        # Re just below and at 1000
    power, re = film.film_power(omega, r, length, h0, mu, 2 * math.pi, nu)
    assert re[1] == pytest.approx(1000, rel=1e-12)
    assert power[1] / power[0] == pytest.approx(1.835034 / 0.9999**2, rel=1e-6)


def test_stribeck_curve_limits_and_zones():
    """f → f_b = 0.3 as λ → 0 (exp(−10⁻⁶) off by 3·10⁻⁷); f → Petroff πλr/h₀ for λ ≫ λ_t (exp(−100) ≈ 4·10⁻⁴⁴);
    at the zone limits the contact term is f_b/2 and the film carries 90 % of f (1e-9: the root's tolerance)."""
    psi = 1e-3
    assert float(film.stribeck(1e-6 * film.TRANSITION, psi)) == pytest.approx(0.3, rel=1e-6)
    lam = 100 * film.TRANSITION
    assert float(film.stribeck(lam, psi)) == pytest.approx(math.pi * lam / psi, rel=1e-12)
    first, second = film.regime_limits(psi)
    assert 0.3 * math.exp(-first / film.TRANSITION) == pytest.approx(0.15, rel=1e-12)
    assert film.petroff(second, psi) / float(film.stribeck(second, psi)) == pytest.approx(0.9, rel=1e-9)
    assert [film.regime(x, (first, second)) for x in (first / 2, (first + second) / 2, 2 * second)] == \
        ["boundary", "mixed", "fluid"]


def test_relative_angular_speed_of_each_pair_by_finite_differences(engine_analysis):
    """|ω₁| at O, |ω₂ − ω₁| at A, |ω₂| at B against central differences of the link angles from the joints
    (h = 2π/4000: the difference's error h²/6·θ‴ ≈ 10⁻⁷ of ω₁; tolerance 10⁻⁵·ω₁)."""
    from server.core.bearings.loads import pair_load
    analysis, omega1 = engine_analysis
    h = 2 * math.pi / 4000
    ahead, behind = (compute_kinematics("slider_crank", ENGINE_PARAMS, ["joints"], phi=analysis.phi + step)
                     .outputs["joints"] for step in (h, -h))
    angle = lambda joints, a, b: np.arctan2(*(joints[b] - joints[a]).T[::-1])
    rate = lambda a, b: np.angle(np.exp(1j * (angle(ahead, a, b) - angle(behind, a, b)))) / (2 * h) * omega1
    crank, rod = rate("O", "A"), rate("A", "B")
    expected = {"O": np.abs(crank), "A": np.abs(rod - crank), "B": np.abs(rod)}
    for pair in "OAB":
        load = pair_load(analysis, pair, omega1)
        assert np.max(np.abs(load.omega - expected[pair])) < 1e-5 * omega1, pair


ENGINE_PARAMS = {"l1": 0.045, "l2": 0.18, "a2": 0.38}


@pytest.fixture(scope="module")
def engine_analysis():
    from server.core.dynamics.motors import Motor
    from server.core.kinetostatics.crank_slider import Loads, Pairs, analyse
    from server.core.mechanisms import MECHANISMS
    omega = 2400 * RPM
    loads = Loads(m2=1.8, m3=1.33, J1=0.09, omega=omega,
                  gas=Motor(kind="indicator", p_max=3e6, piston_diameter=0.075))
    params = MECHANISMS["slider_crank"].check(ENGINE_PARAMS)
    return analyse(params, loads, Pairs(), np.linspace(0, 2 * np.pi, 181)), omega
