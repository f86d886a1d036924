"""Reference values from the sources reproduce: tables, worked examples and claims of the texts.

Sources (README, "Sources"): Eremyants §2.3–§2.5, its formulas evaluated (crank-slider, slotted
link, four-bar, change-point four-bars, approximations (2.16)/(2.17*), harmonic claims),
Chaika–Vasylenko Table 4.3 (ICE crank-slider), Drakunov–Tuleshova (3)–(8) (the
four-bar oracle).  Each printed number is compared to half a unit in its last
printed digit, the precision the text gives; where a printed value is wrong the test says so.

Converting the sources to the app's conventions (each conversion is itself checked here):
* Crank-slider, Eremyants = ours: φ from the inner dead centre, clockwise; s = x; s2 = ψ.
* Crank-slider, Chaika–Vasylenko: φ₁ from the crank pointing at the slider, counter-clockwise, so
  φ₁ = π − φ, V_qB(φ₁) = dx_B/dφ₁ = −u₃₁(φ), φ₂ = −ψ (mod 360°), u₂₁ = dφ₂/dφ₁ = dψ/dφ = u₂₁.
* Four-bar: A origin, D = (l₀, 0), φ counter-clockwise from AD; assembly = +1 is Eremyants'
  (2.41) branch and Drakunov–Tuleshova's "+".
* Change-point four-bars (Eremyants §2.5): φ from the special position.  Schemes 1, 2: our φ,
  scheme 2's textbook branch is our assembly = −1.  Scheme 3: our φ = φ_textbook + π and its
  rocker angle is counted the other way, u₃₁(textbook) = −u₃₁(ours).
"""
from __future__ import annotations

from functools import partial

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

from linkage_geometry import measured_positions
from server.core.harmonics import harmonics
from server.core.kinematics import compute_kinematics
from server.core.mechanisms import MECHANISMS

assert_allclose = partial(np.testing.assert_allclose, equal_nan=False)   # a NaN on either side fails

SLIDER, SLOTTED, FOUR_BAR = MECHANISMS["slider_crank"], MECHANISMS["slotted_link"], MECHANISMS["four_bar"]
ROUNDING_SLACK = 1e-12   # on top of half a unit in the last digit: binary rounding of the reference itself


def half_unit(decimals: int) -> float:
    """The printed precision: a value printed with d decimals is exact to ±0.5·10⁻ᵈ."""
    return 0.5 * 10.0 ** -decimals + ROUNDING_SLACK


def values_at(mech, params: dict, phi, outputs=("s", "u31", "du31", "s2", "u21", "du21")) -> dict[str, np.ndarray]:
    p = mech.check(params)
    ev = mech.evaluate(p, np.atleast_1d(np.asarray(phi, float)), set())
    return {k: ev.values[k] for k in outputs}


# --- Eremyants §2.3, (2.7)–(2.15) evaluated: crank-slider, l₁ = 1 --------------------------------------------------------

# λ = l₂/l₁, φ (deg), x, u₃₁, u′₃₁ (6 decimals), ψ (deg, 4 decimals), u₂₁, u′₂₁ (6 decimals)
CRANK_SLIDER_000 = [
    (3, 0, 0.0, 0.0, 0.666667, 0.0, 0.333333, 0.0),
    (3, 30, 0.092014, 0.353615, 0.689750, 9.5941, 0.292770, -0.154542),
    (3, 60, 0.372281, 0.715270, 0.666165, 16.7787, 0.174078, -0.292375),
    (3, 90, 0.828427, 1.000000, 0.353553, 19.4712, 0.0, -0.353553),
    (3, 120, 1.372281, 1.016781, -0.333835, 16.7787, -0.174078, -0.292375),
    (3, 150, 1.824065, 0.646385, -1.042300, 9.5941, -0.292770, -0.154542),
    (3, 180, 2.0, 0.0, -1.333333, 0.0, -0.333333, 0.0),
    (1.5, 90, 0.618034, 1.000000, 0.894427, 41.8103, 0.0, -0.894427),
    (5, 90, 0.898979, 1.000000, 0.204124, 11.5370, 0.0, -0.204124),
]


@pytest.mark.parametrize("row", CRANK_SLIDER_000, ids=lambda r: f"λ={r[0]} φ={r[1]}°")
def test_crank_slider_positions_and_transfer_functions_match_eremyants(row):
    lam, phi_deg, x, u31, du31, psi_deg, u21, du21 = row
    v = values_at(SLIDER, {"l1": 1.0, "l2": lam}, np.radians(phi_deg))
    for name, got, printed in (("x", v["s"], x), ("u31", v["u31"], u31), ("du31", v["du31"], du31),
                               ("u21", v["u21"], u21), ("du21", v["du21"], du21)):
        assert abs(got[0] - printed) <= half_unit(6), name
    assert abs(np.degrees(v["s2"][0]) - psi_deg) <= half_unit(4)


@pytest.mark.parametrize("lam, u_max, phi_deg", [(1.5, 1.22693, 115.70), (3, 1.05464, 106.80), (5, 1.01983, 100.90)])
def test_fastest_slider_speed_and_its_crank_angle_match_eremyants(lam, u_max, phi_deg):
    p = SLIDER.check({"l1": 1.0, "l2": lam})
    best = minimize_scalar(lambda x: -SLIDER.evaluate(p, np.array([x]), set()).values["u31"][0],
                           bounds=(np.pi / 2, np.pi), method="bounded", options={"xatol": 1e-10})
    assert abs(-best.fun - u_max) <= half_unit(5)
    # The angles are printed with two decimals but come from a 0.1° search: exact 115.656°, 106.825°,
    # 100.900°.  They reproduce to the 0.1° grid (±0.05°), not to ±0.005°.
    assert abs(np.degrees(best.x) - phi_deg) <= 0.05


@pytest.mark.parametrize("lam", [1.5, 3, 5])
def test_slider_acceleration_analog_at_the_dead_centres_is_one_minus_and_one_plus_one_over_lambda(lam):
    v = values_at(SLIDER, {"l1": 1.0, "l2": lam}, [0.0, np.pi])
    assert v["du31"][0] == pytest.approx(1 - 1 / lam, abs=1e-14)
    assert v["du31"][1] == pytest.approx(-(1 + 1 / lam), abs=1e-14)


@pytest.mark.parametrize("lam", [1.5, 3, 5])
def test_central_crank_slider_stroke_is_twice_the_crank(lam):
    outer = [sp for sp in SLIDER.special_positions(SLIDER.check({"l1": 1.0, "l2": lam})) if sp.kind == "dead_centre"]
    assert [sp.phi for sp in outer] == [0.0, pytest.approx(np.pi, abs=1e-15)]
    assert outer[1].value == pytest.approx(2.0, abs=1e-14)


@pytest.mark.parametrize("lam", [1.5, 3, 5])
def test_rod_inclination_never_exceeds_arctan_of_one_over_root_lambda_squared_minus_one(lam):
    """000 §7.1 P8: max tan ψ = 1/√(λ² − 1), hence tan ψ < 1 whenever λ² > 2."""
    psi = values_at(SLIDER, {"l1": 1.0, "l2": lam}, np.linspace(0, 2 * np.pi, 20001))["s2"]
    assert np.max(np.tan(np.abs(psi))) == pytest.approx(1 / np.sqrt(lam**2 - 1), rel=1e-9)
    assert (np.max(np.tan(np.abs(psi))) < 1) == (lam**2 > 2)


# --- Eremyants §2.3: approximations (2.16), (2.17*) -----------------------------------------------

@pytest.mark.parametrize("lam, err_u31, err_u21, decimals", [(1.5, 0.066, 0.075, 3), (3, 0.0064, 0.0076, 4),
                                                             (5, 0.0013, 0.0016, 4)])
def test_largest_errors_of_the_approximations_2_16_match_eremyants(lam, err_u31, err_u21, decimals):
    result = compute_kinematics("slider_crank", {"l1": 1.0, "l2": lam}, ["approx_error"], n=10001)
    errors = result.outputs["approx_error"]
    # a 0.036° grid finds the maximum to ≈ (Δφ)²·|u‴| < 1e-6, far inside the printed precision
    assert abs(errors["u31"] - err_u31) <= half_unit(decimals)
    assert abs(errors["u21"] - err_u21) <= half_unit(decimals)


def test_approximations_2_17_star_are_2_13_and_2_15_with_the_root_replaced_by_lambda():
    lam, phi = 3.0, np.linspace(0, 2 * np.pi, 73)
    p = SLIDER.check({"l1": 1.0, "l2": lam})
    v = SLIDER.evaluate(p, phi, {"du31_approx", "du21_approx"}).values
    root = lam   # √(λ² − sin²φ) → λ
    du31 = np.cos(phi) - np.cos(2 * phi) / root - np.sin(2 * phi) ** 2 / (4 * root**3)      # (2.13)
    du21 = (1 - lam**2) * np.sin(phi) / root**3                                              # (2.15)
    assert_allclose(v["du31_approx"], du31, atol=1e-15)
    assert_allclose(v["du21_approx"], du21, atol=1e-15)


def test_corrected_sign_of_the_rod_acceleration_approximation_at_lambda_3_phi_1_rad():
    """000 §4.3: exact u′₂₁ = −0.282, printed (2.17) gives +0.249, the corrected (2.17*) −0.249."""
    p = SLIDER.check({"l1": 1.0, "l2": 3.0})
    v = SLIDER.evaluate(p, np.array([1.0]), {"du21_approx"}).values
    assert abs(v["du21"][0] - (-0.282)) <= half_unit(3)
    assert abs(v["du21_approx"][0] - (-0.249)) <= half_unit(3)


# --- Eremyants §2.3, (2.17): harmonic content of the crank-slider ----------------------------------------

def amplitudes(params: dict, output: str) -> np.ndarray:
    return np.array(harmonics(SLIDER, SLIDER.check(params), output)["amplitude"])


@pytest.mark.parametrize("lam", [3, 5, 10])
def test_second_harmonic_of_slider_velocity_is_about_1_over_2_lambda_of_the_first(lam):
    a = amplitudes({"l1": 1.0, "l2": lam}, "u31")
    assert a[0] == pytest.approx(1.0, abs=1e-12)   # the first harmonic is exactly the crank's l₁ sin φ
    # u₃₁ = l₁[sin φ − (1/(2λ) + 1/(8λ³) + …) sin 2φ + …]: the claim neglects 1/(8λ³) < 1/(4λ³)
    assert abs(a[1] / a[0] - 1 / (2 * lam)) <= 1 / (4 * lam**3)
    assert np.all(a[2::2] < 1e-12)   # odd harmonics beyond the first vanish (u₃₁ − l₁ sin φ is π-periodic)


@pytest.mark.parametrize("lam", [3, 5, 10])
def test_fourth_harmonic_of_slider_acceleration_analog_is_1_over_4_lambda_cubed_twice_the_textbook_estimate(lam):
    """000 §4.3 claims the third (4φ) harmonic of u′₃₁ has amplitude 1/(8λ³) of the first, < 0.5 % for λ > 3.

    Expanding x = l₁(1 − λ − cos φ + √(λ² − sin²φ)) to O(λ⁻³) gives u′₃₁ ∋ cos 4φ/(4λ³): the 4φ
    amplitude is 1/(4λ³) (1 + O(λ⁻²)), twice the textbook's.  At λ = 3 it is 1.0 %, not 0.46 %; the
    "< 0.5 %" claim holds only from λ ≈ 3.75 on.
    """
    a = amplitudes({"l1": 1.0, "l2": lam}, "du31")
    ratio = a[3] / a[0]
    assert ratio == pytest.approx(1 / (4 * lam**3), rel=1 / lam**2)
    assert ratio > 1.9 / (8 * lam**3)
    if lam == 3:
        assert ratio > 0.005


@pytest.mark.parametrize("lam", [3, 5, 10])
def test_rod_velocity_and_acceleration_analogs_are_one_harmonic_of_amplitude_about_1_over_lambda(lam):
    for output in ("u21", "du21"):
        a = amplitudes({"l1": 1.0, "l2": lam}, output)
        # u₂₁ = cos φ/√(λ² − sin²φ) = cos φ/λ + cos φ sin²φ/(2λ³) + …: first harmonic 1/λ + 1/(8λ³)
        assert abs(a[0] - 1 / lam) <= 1 / (4 * lam**3)
        assert np.all(a[1:] <= 1 / (4 * lam**3) * 9)   # the rest is O(λ⁻³) (3φ harmonic of u′₂₁ is 3× that of u₂₁)


def test_sine_mechanism_transfer_functions_are_single_harmonics_of_amplitude_l1():
    mech = MECHANISMS["sine"]
    p = mech.check({"l1": 0.1})
    for output in ("u31", "du31", "u21", "du21"):
        h = harmonics(mech, p, output)
        assert h["amplitude"][0] == pytest.approx(0.1, abs=1e-15)
        assert max(h["amplitude"][1:]) < 1e-15 and abs(h["mean"]) < 1e-15


# --- Eremyants §2.4, its formulas evaluated: slotted link, l₁ = 1 ----------------------------------------------------------

# λ = l₀/l₁, φ (deg), ψ (deg, 4 decimals), y, u₃₁, u′₃₁, u₂₁, u′₂₁ (6 decimals)
SLOTTED_000 = [
    (0.5, 0, 0.0, 0.0, 0.666667, 0.0, 0.0, 0.333333),
    (0.5, 90, 63.4349, 0.381966, 0.800000, 0.240000, 0.447214, 0.178885),
    (0.5, 135, 106.3249, 0.763187, 1.190744, 0.899679, 0.479841, -0.167350),
    (0.5, 180, 180.0, 1.0, 2.000000, 0.0, 0.0, -1.000000),
    (1.0, 90, 45.0, 0.585786, 0.5, 0.0, 0.707107, 0.353553),
    (2.0, 0, 0.0, 0.0, 0.333333, 0.0, 0.0, 0.666667),
    (2.0, 90, 26.5651, 0.763932, 0.200000, -0.240000, 0.894427, 0.357771),
    (2.0, 135, 28.6751, 1.526374, -0.190744, -0.899679, 0.959683, -0.334700),
    (2.0, 180, 0.0, 2.0, -1.000000, 0.0, 0.0, -2.000000),
]


@pytest.mark.parametrize("row", SLOTTED_000, ids=lambda r: f"λ={r[0]} φ={r[1]}°")
def test_slotted_link_positions_and_transfer_functions_match_eremyants(row):
    lam, phi_deg, psi_deg, y, u31, du31, u21, du21 = row
    v = values_at(SLOTTED, {"l0": lam, "l1": 1.0}, np.radians(phi_deg))
    assert abs(np.degrees(v["s"][0]) - psi_deg) <= half_unit(4)
    for name, got, printed in (("y", v["s2"], y), ("u31", v["u31"], u31), ("du31", v["du31"], du31),
                               ("u21", v["u21"], u21), ("du21", v["du21"], du21)):
        assert abs(got[0] - printed) <= half_unit(6), name


@pytest.mark.parametrize("lam", [0.2, 0.5, 0.9, 0.98])
def test_rotating_lever_speed_ratio_spans_1_over_1_plus_lambda_to_1_over_1_minus_lambda(lam):
    u31 = values_at(SLOTTED, {"l0": lam, "l1": 1.0}, np.linspace(0, 2 * np.pi, 36001), ("u31",))["u31"]
    # the grid contains φ = 0 and π, where the extremes lie: exact up to rounding
    assert u31.min() == pytest.approx(1 / (1 + lam), rel=1e-12)
    assert u31.max() == pytest.approx(1 / (1 - lam), rel=1e-12)


def test_lever_turns_at_half_the_crank_speed_when_lambda_is_one_and_is_undefined_at_180_degrees():
    phi = np.linspace(0, 2 * np.pi, 721)
    u31 = values_at(SLOTTED, {"l0": 1.0, "l1": 1.0}, phi, ("u31",))["u31"]
    regular = ~np.isclose(phi, np.pi)
    assert_allclose(u31[regular], 0.5, atol=1e-15)
    assert np.isnan(u31[~regular]).all()


@pytest.mark.parametrize("lam", [1.02, 1.5, 2.0, 5.0])
def test_oscillating_lever_swings_through_two_arcsin_one_over_lambda(lam):
    p = SLOTTED.check({"l0": lam, "l1": 1.0})
    lever, _ = measured_positions("slotted_link", p, np.linspace(0, 2 * np.pi, 200001))
    gamma = 2 * np.arcsin(1 / lam)
    # a 0.0018° grid misses the extreme by ≤ ½|u′₃₁|Δφ² < 1e-9 rad
    assert np.ptp(lever) == pytest.approx(gamma, abs=1e-8)
    extremes = [sp for sp in SLOTTED.special_positions(p) if sp.kind == "rocker_extreme"]
    assert sorted(sp.value for sp in extremes) == pytest.approx([-gamma / 2, gamma / 2], abs=1e-14)
    u31_there = SLOTTED.evaluate(p, np.array([sp.phi for sp in extremes]), set()).values["u31"]
    assert_allclose(u31_there, 0.0, atol=1e-15)
    if lam == 2.0:
        assert np.degrees(gamma) == pytest.approx(60.0, abs=1e-12)


# --- Eremyants (2.42*), (2.44*): general four-bar check case ---------------------------------------------------

def test_four_bar_check_case_of_eremyants_gives_the_corrected_2_42_and_2_44():
    """λ₀ = 4, λ₂ = 3.5, λ₃ = 3, φ = 1 rad: u₃₁ = 0.128989 (2.42*), u₂₁ = −0.222160 (2.44*); printed (2.42) −0.356."""
    v = values_at(FOUR_BAR, {"l0": 4.0, "l1": 1.0, "l2": 3.5, "l3": 3.0, "assembly": 1}, 1.0)
    assert abs(v["u31"][0] - 0.128989) <= half_unit(6)
    assert abs(v["u21"][0] - (-0.222160)) <= half_unit(6)
    lam0, lam2, lam3, phi = 4.0, 3.5, 3.0, 1.0
    d = np.sqrt(1 + lam0**2 - 2 * lam0 * np.cos(phi))
    printed_2_42 = ((1 - lam0 * np.cos(phi)) / (d * (lam0 - np.cos(phi)))
                    - lam0 * (d**2 - lam3**2 + lam2**2) / (d**2 * np.sqrt(4 * lam3**2 * d**2
                                                                          - (lam3**2 - lam2**2 + d**2) ** 2)))
    assert abs(printed_2_42 - (-0.356)) <= half_unit(3)   # the misprint the corrected form replaces


# --- Eremyants §2.5: change-point ("special") four-bars ------------------------------------

# (λ₂, λ₃, λ₀), our assembly, our φ at the textbook's φ = 0, sign of u₃₁(textbook)/u₃₁(ours)
SCHEMES = {1: ((4, 3, 2), 1, 0.0, 1), 2: ((3, 4, 2), -1, 0.0, 1), 3: ((3, 2, 4), 1, np.pi, -1)}


def scheme_params(scheme: int, limiter: int) -> dict:
    (l2, l3, l0), assembly, _, _ = SCHEMES[scheme]
    return {"l0": l0, "l1": 1.0, "l2": l2, "l3": l3, "assembly": assembly, "limiter": limiter}


def textbook_u31(scheme: int, phi_textbook, limiter: int = 0) -> np.ndarray:
    """u₃₁ as the textbook counts it, computed by the app: φ and sign converted (module docstring)."""
    _, _, shift, sign = SCHEMES[scheme]
    return sign * values_at(FOUR_BAR, scheme_params(scheme, limiter), np.asarray(phi_textbook) + shift, ("u31",))["u31"]


def textbook_2_52_2_53(scheme: int, phi: np.ndarray) -> np.ndarray:
    """(2.52) scheme 1, (2.52*) scheme 2 (reconstructed), (2.53) scheme 3, half-angle forms, 4π-periodic."""
    (l2, l3, l0), _, _, _ = SCHEMES[scheme]
    s2, c = np.sin(phi / 2) ** 2, np.cos(phi / 2)
    root = np.sqrt(l2 * l3 / l0 - s2)
    if scheme == 3:
        d2 = 1 + l0**2 + 2 * l0 * np.cos(phi)
        return -(1 + l0 - 2 * l0 * s2 + (2 * l0 * s2 - l2 * (l0 + 1)) * c / root) / d2
    d1 = 1 + l0**2 - 2 * l0 * np.cos(phi)
    bracket = 2 * l0 * s2 + l2 * (l0 - 1) if scheme == 1 else l2 * (l0 - 1) - 2 * l0 * s2
    return (1 - l0 + 2 * l0 * s2 + bracket * c / root) / d1


def textbook_2_54_2_55(scheme: int, phi: np.ndarray) -> np.ndarray:
    """u′₃₁ by (2.54) (scheme 1) and (2.55) (scheme 3)."""
    (l2, l3, l0), _, _, _ = SCHEMES[scheme]
    y, b, g = np.cos(phi / 2), (1 - l0**2) / (2 * l0), l2 * l3 / l0 - 1
    if scheme == 1:
        a, c = (l0 + 1) ** 2 / (4 * l0), l2 * (l0 - 1) / (2 * l0) + 1
        bracket = b * y + ((g + 2 * (c - a)) * y**4 + g * (c - 3 * a) * y**2 + a * c * g) / np.sqrt((g + y**2) ** 3)
        return -np.sin(phi / 2) / (4 * (a - y**2) ** 2) * bracket
    a, c = (l0 - 1) ** 2 / (4 * l0), l2 * (l0 + 1) / (2 * l0) - 1
    bracket = b * y + ((g - 2 * (c - a)) * y**4 - g * (c - 3 * a) * y**2 + a * c * g) / np.sqrt((g + y**2) ** 3)
    return -np.sin(phi / 2) / (4 * (a + y**2) ** 2) * bracket


# u₃₁ (textbook sign) leaving the special position (φ = 0), arriving (φ = 2π), at 90°, 180°, 270°; 5 decimals
SPECIAL_000 = {1: (0.63299, -2.63299, 0.56181, 0.33333, -0.16181),
               2: (0.22474, -2.22474, 0.26030, 0.33333, 0.13970),
               3: (0.28990, -0.68990, 0.39872, 0.33333, -0.51636)}


@pytest.mark.parametrize("scheme", SCHEMES)
def test_change_point_four_bar_u31_matches_eremyants_values(scheme):
    leaving, arriving, *quarters = SPECIAL_000[scheme]
    u = textbook_u31(scheme, np.radians([0.0, 360.0, 90.0, 180.0, 270.0]))
    assert_allclose(u, [leaving, arriving, *quarters], rtol=0, atol=half_unit(5))


@pytest.mark.parametrize("scheme", SCHEMES)
def test_rocker_speed_at_the_special_position_follows_the_closed_forms_of_eremyants(scheme):
    (l2, l3, l0), _, _, _ = SCHEMES[scheme]
    root = np.sqrt(l0 * l2 / l3)
    if scheme == 3:
        expected = [(root - 1) / (1 + l0), -(root + 1) / (1 + l0)]
    else:
        expected = [(-1 + root) / (l0 - 1), (-1 - root) / (l0 - 1)]
    assert_allclose(textbook_u31(scheme, np.array([0.0, 2 * np.pi])), expected, atol=1e-12)


@pytest.mark.parametrize("scheme", SCHEMES)
def test_change_point_four_bar_without_limiter_follows_2_52_and_2_53_over_the_whole_4pi_cycle(scheme):
    """The textbook's half-angle formulas are the no-limiter motion: one branch on 0…2π, the other on 2π…4π."""
    phi = np.linspace(0, 4 * np.pi, 1441)
    assert_allclose(textbook_u31(scheme, phi), textbook_2_52_2_53(scheme, phi), rtol=0, atol=1e-12)


@pytest.mark.parametrize("scheme", [1, 3])
def test_change_point_four_bar_acceleration_analog_follows_2_54_and_2_55(scheme):
    phi = np.linspace(0, 4 * np.pi, 1441)
    _, _, shift, sign = SCHEMES[scheme]
    du31 = sign * values_at(FOUR_BAR, scheme_params(scheme, 0), phi + shift, ("du31",))["du31"]
    assert_allclose(du31, textbook_2_54_2_55(scheme, phi), rtol=0, atol=1e-12)


def test_scheme_2_as_printed_2_52_would_give_wrong_values():
    """000 §7.2: the text's claim that scheme 2 has the same u₃₁ as scheme 1 gives 0.50151, 0.33333, −0.10151."""
    (l2, l3, l0), _, _, _ = SCHEMES[2]
    phi = np.radians([90.0, 180.0, 270.0])
    s2, c = np.sin(phi / 2) ** 2, np.cos(phi / 2)
    printed = (1 - l0 + 2 * l0 * s2 + (2 * l0 * s2 + l2 * (l0 - 1)) * c / np.sqrt(l2 * l3 / l0 - s2)) \
        / (1 + l0**2 - 2 * l0 * np.cos(phi))
    assert_allclose(printed, [0.50151, 0.33333, -0.10151], atol=half_unit(5))
    assert abs(textbook_u31(2, phi[0]) - printed[0]) > 0.2


@pytest.mark.parametrize("scheme", SCHEMES)
def test_stroke_limiter_makes_u31_jump_from_the_arriving_to_the_leaving_value(scheme):
    leaving, arriving, *_ = SPECIAL_000[scheme]
    _, _, shift, sign = SCHEMES[scheme]
    p = FOUR_BAR.check(scheme_params(scheme, 1))
    assert FOUR_BAR.cycle(p) == pytest.approx(2 * np.pi)
    u = sign * FOUR_BAR.evaluate(p, shift + 2 * np.pi + np.array([-1e-9, 0.0]), set()).values["u31"]
    # 1e-9 rad before the impact u₃₁ is within |u′₃₁|·1e-9 < 1e-6 of its arriving value
    assert u == pytest.approx([arriving, leaving], abs=half_unit(5) + 1e-6)
    assert FOUR_BAR.jumps(p) == [pytest.approx(shift)]


@pytest.mark.parametrize("scheme, swing_deg", [(1, 109.47), (2, 75.52), (3, 75.52)])
def test_rocker_swing_from_the_special_position_matches_eremyants(scheme, swing_deg):
    """With limiter the rocker swings to one side and back; without, to both sides over the 4π cycle."""
    _, _, shift, _ = SCHEMES[scheme]
    exact = {1: 180 - np.degrees(np.arccos(1 / 3)), 2: np.degrees(np.arccos(1 / 4)), 3: np.degrees(np.arccos(1 / 4))}
    assert exact[scheme] == pytest.approx(swing_deg, abs=half_unit(2))
    for limiter, cycle in ((1, 2 * np.pi), (0, 4 * np.pi)):
        p = FOUR_BAR.check(scheme_params(scheme, limiter))
        rocker, _ = measured_positions("four_bar", p, shift + np.linspace(0, cycle, 100001))
        turn = np.degrees(np.angle(np.exp(1j * (rocker - rocker[0]))))
        # a 0.0036° (0.0072°) grid misses the extreme by ≤ ½|u′₃₁|Δφ² < 1e-6°
        if limiter:
            assert max(abs(turn.min()), abs(turn.max())) == pytest.approx(exact[scheme], abs=1e-5)
            assert min(abs(turn.min()), abs(turn.max())) < 1e-9   # one side only: it rebounds at the limiter
        else:
            assert [turn.min(), turn.max()] == pytest.approx([-exact[scheme], exact[scheme]], abs=1e-5)


def test_impact_speed_of_schemes_1_and_2_is_several_times_that_of_scheme_3():
    """000 §2.5: |u₃₁| at the limiter ≈ 2.6 and 2.2 for schemes 1, 2 against 0.69 for scheme 3."""
    impact = {s: abs(textbook_u31(s, np.array([2 * np.pi]))[0]) for s in SCHEMES}
    assert impact[1] > 3 * impact[3] and impact[2] > 3 * impact[3]


# --- Chaika–Vasylenko Table 4.3: ICE crank-slider, l₁ = 0.045 m, l₂ = 0.18 m, e = 0 ------------------

# φ₁ (deg), V_qB (m/rad), u₂₁, φ₂ (deg, 1 decimal), x_B (m, derived from l₁, l₂, not printed) — as printed (4 decimals)
TABLE_4_3 = [
    (0, 0.0, -0.2500, 360.0, 0.2250), (30, -0.0274, -0.2187, 352.8, 0.2176), (60, -0.0440, -0.1280, 347.5, 0.1982),
    (90, -0.0450, 0.0, 345.5, 0.1743), (120, -0.0340, 0.1280, 347.5, 0.1532), (150, -0.0176, 0.2187, 352.8, 0.1396),
    (180, 0.0, 0.2500, 0.0, 0.1350), (210, 0.0176, 0.2182, 7.2, 0.1396), (240, 0.0340, 0.1280, 12.5, 0.1532),
    (270, 0.0450, 0.0, 14.5, 0.1743), (300, 0.0440, -0.1280, 12.5, 0.1982), (330, 0.0274, -0.2182, 7.2, 0.2176),
    (360, 0.0, -0.2500, 360.0, 0.2250),
]
MISPRINTS_4_3 = {30: -0.2182, 150: 0.2182}   # printed ∓0.2187: a print/OCR slip (210° and 330° print 0.2182)
ICE = {"l1": 0.045, "l2": 0.18, "e": 0.0}


def ice_kinematics(phi1_deg) -> dict[str, np.ndarray]:
    """Chaika–Vasylenko's quantities from the app's: φ = π − φ₁, V_qB = −u₃₁, φ₂ = −ψ mod 360°, x_B from the joints."""
    p = SLIDER.check(ICE)
    phi = np.pi - np.radians(np.atleast_1d(phi1_deg))
    ev = SLIDER.evaluate(p, phi, {"joints"})
    return {"V_qB": -ev.values["u31"], "u21": ev.values["u21"], "phi2": np.mod(-np.degrees(ev.values["s2"]), 360.0),
            "x_B": ev.joints["B"][:, 0]}


@pytest.mark.parametrize("row", TABLE_4_3, ids=lambda r: f"φ1={r[0]}°")
def test_ice_crank_slider_reproduces_chaika_vasylenko_table_4_3(row):
    phi1, v_qb, u21, phi2, x_b = row
    got = {k: v[0] for k, v in ice_kinematics(phi1).items()}
    assert abs(got["V_qB"] - v_qb) <= half_unit(4)
    assert abs(got["u21"] - MISPRINTS_4_3.get(phi1, u21)) <= half_unit(4)
    assert abs(got["x_B"] - x_b) <= half_unit(4)
    # 360.0° and 0.0° are the same rod direction
    assert abs((got["phi2"] - phi2 + 180.0) % 360.0 - 180.0) <= half_unit(1)


def test_table_4_3_prints_0_2187_where_the_rod_ratio_gives_0_2182():
    u21 = ice_kinematics([30, 150])["u21"]
    assert_allclose(u21, [-0.2182, 0.2182], atol=half_unit(4))
    assert np.all(np.abs(np.abs(u21) - 0.2187) > 4e-4)   # the printed digits are off by 5 units


def test_ice_stroke_is_twice_the_crank_090_m():
    x_b = ice_kinematics(np.linspace(0, 360, 3601))["x_B"]
    assert np.ptp(x_b) == pytest.approx(0.090, abs=1e-12)


# --- Drakunov–Tuleshova (3)–(8) evaluated: four-bar oracle, l₀ = 1, l₁ = 0.3, l₂ = 1, l₃ = 0.8, φ₁ = 0.7 rad -----------------

ORACLE_003 = {  # assembly: φ₂ (deg), φ₃ (deg), u₂₁, u₃₁ (true, corrected sign), u′₃₁
    1: (37.32641, 88.23453, -0.287823, 0.0234393, 0.615568),
    -1: (-65.48684, -116.39496, -0.154116, -0.465378, 0.267585),
}
OAK = {"l0": 1.0, "l1": 0.3, "l2": 1.0, "l3": 0.8}


@pytest.mark.parametrize("assembly", ORACLE_003)
def test_four_bar_reproduces_the_drakunov_tuleshova_oracle(assembly):
    phi2, phi3, u21, u31, du31 = ORACLE_003[assembly]
    v = values_at(FOUR_BAR, OAK | {"assembly": assembly}, 0.7)
    wrap = lambda deg: (deg + 180.0) % 360.0 - 180.0
    assert abs(wrap(np.degrees(v["s2"][0]) - phi2)) <= half_unit(5)
    assert abs(wrap(np.degrees(v["s"][0]) - phi3)) <= half_unit(5)
    assert abs(v["u21"][0] - u21) <= half_unit(6)
    assert abs(v["u31"][0] - u31) <= half_unit(7 if assembly == 1 else 6)
    assert abs(v["du31"][0] - du31) <= half_unit(6)


@pytest.mark.parametrize("assembly", [1, -1])
def test_drakunov_tuleshova_cramer_formulas_hold_with_the_corrected_sign_of_8(assembly):
    """(7) u₂₁ = −l₁sin(φ₃−φ₁)/(l₂sin(φ₃−φ₂)); (8*) u₃₁ = +l₁sin(φ₁−φ₂)/(l₃sin(φ₃−φ₂)) — the printed
    (8) has a minus sign and gives −u₃₁; (10) u′₃₁ = u₃₁[cot(φ₁−φ₂)(1−u₂₁) − cot(φ₃−φ₂)(u₃₁−u₂₁)]."""
    p = OAK | {"assembly": assembly}
    phi = np.linspace(0, 2 * np.pi, 181)[:-1] + 0.01
    v = values_at(FOUR_BAR, p, phi)
    f2, f3 = v["s2"], v["s"]
    l1, l2, l3 = OAK["l1"], OAK["l2"], OAK["l3"]
    assert_allclose(v["u21"], -l1 * np.sin(f3 - phi) / (l2 * np.sin(f3 - f2)), atol=1e-12)
    u31 = l1 * np.sin(phi - f2) / (l3 * np.sin(f3 - f2))
    assert_allclose(v["u31"], u31, atol=1e-12)
    # where crank and coupler are in line (u₃₁ = 0) cot(φ₁ − φ₂) is infinite: (10) is 0·∞ there
    regular = np.abs(np.sin(phi - f2)) > 1e-3
    du31 = u31 * (1 / np.tan(phi - f2) * (1 - v["u21"]) - 1 / np.tan(f3 - f2) * (u31 - v["u21"]))
    assert_allclose(v["du31"][regular], du31[regular], atol=1e-10)
