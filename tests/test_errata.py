"""The sources' misprints shown beside the corrected formulas: each row's printed and corrected numbers against
the notes' values or a computation by another route (tolerances stated per test)."""
import numpy as np
import pytest

from server.api.endpoints import compute
from server.core import errata
from server.core.dynamics import flywheel as fw
from server.core.mechanisms import MECHANISMS
from server.lessons.requests import scene_request
from server.lessons.scenes import scenes

ROW_KEYS = {"key", "source", "equation", "printed_value", "printed_unit", "corrected_value", "unit"}


@pytest.mark.parametrize("lam", [2.0, 3.0, 6.0])
def test_variable_inertia_printed_means_and_corrected_zero(lam):
    """Eremyants (3.38)/(3.39): a variable part has zero mean.  By hand (means of sin²φ = 1/2, sin²φ cos φ = 0,
    cos²φ = 1/2, sin²φcos²φ = 1/8): printed (3.39) −m₃l₁²/4, printed (3.38) −(m₃l₁²/2)(1/2 + 3/(4λ²)), both
    corrected 0 (the 720-point mean is exact for these trigonometric polynomials; rounding is shown as 0)."""
    m3, l1 = 10.0, 0.1
    rows = {r["key"]: r for r in errata.variable_inertia(m3, l1, lam)}
    k = m3 * l1**2 / 2
    assert rows["variable_inertia_39"]["printed_value"] == pytest.approx(-m3 * l1**2 / 4, rel=1e-12)
    assert rows["variable_inertia_38"]["printed_value"] == pytest.approx(-k * (0.5 + 0.75 / lam**2), rel=1e-12)
    assert rows["variable_inertia_39"]["corrected_value"] == 0.0      # rounding below 1e-12 of J̃'s size is 0
    assert rows["variable_inertia_38"]["corrected_value"] == 0.0


@pytest.mark.parametrize("lam", [0.5, 2.0])
def test_slotted_viscous_corrected_is_the_mechanisms_own_sliding_square(lam):
    """Eremyants (3.50*): M_T/(βω) = u₂₁²; its cycle mean against the slotted link's sliding_squares (its own
    closed form through sin(φ/2)) averaged on another grid (rel 1e-9: both spectrally exact, smooth for λ ≠ 1).
    The printed (3.50) differs by the factor λ exactly."""
    l1 = 0.1
    row50, row53 = errata.slotted_viscous(7.0, l1, lam)
    mech, p = MECHANISMS["slotted_link"], {"l0": lam * l1, "l1": l1}
    phi = np.arange(2000) * 2 * np.pi / 2000
    mean = float(np.mean(mech.sliding_squares(mech.check(p), mech.evaluate(mech.check(p), phi, set()))))
    assert row50["corrected_value"] == pytest.approx(mean, rel=1e-9)
    assert row50["printed_value"] == pytest.approx(row50["corrected_value"] / lam, rel=1e-12)
    # (3.53) at λ = 1: printed ω/2 (s⁻¹), corrected l₁²/2 (m²), by hand
    assert row53["printed_value"] == pytest.approx(7.0 / 2, rel=1e-12)
    assert row53["corrected_value"] == pytest.approx(l1**2 / 2, rel=1e-12)


def test_chaika_vasylenko_table_slip_and_step():
    """Chaika–Vasylenko Table 4.3 (l₁ = 0.045 m, l₂ = 0.18 m): u₂₁(30°) printed 0.2187, exact 0.2182 (the notes,
    4 decimals: 5e-5); the step printed 0.432, correct 0.5236 (π/6, 1e-4)."""
    slip, step = errata.wear_example(0.045, 0.18)
    assert (slip["printed_value"], step["printed_value"]) == (0.2187, 0.432)
    assert slip["corrected_value"] == pytest.approx(0.2182, abs=5e-5)
    assert step["corrected_value"] == pytest.approx(0.5236, abs=1e-4)


def test_piston_pressure_by_hand():
    """Chaika–Vasylenko (4.16): F = 1000 N, l_p = 0.05 m, d_p = 0.075 m: printed 2F/(π l d) = 169765.3 Pa,
    corrected 4F/(π l d) = 339530.5 Pa (7 digits by hand)."""
    row = errata.piston_pressure(1000.0, 0.05, 0.075)
    assert row["printed_value"] == pytest.approx(169765.3, rel=1e-6)
    assert row["corrected_value"] == pytest.approx(339530.5, rel=1e-6)


def test_gutyar_without_squares_on_a_cycle_solved_by_hand():
    """A(φ) = sin φ J, I_II = c constant: the pieces' extremes are 1 − c·w_max^n/2 and −1 − c·w_min^n/2, so
    printed (n = 1) I_I = (2 − cδω/2)/(δω²), corrected (n = 2) (2 − cδω²)/(δω²) (rel 1e-6: the grid's maxima
    of sin φ on 4097 points, 1 − cos(h/2) ≈ 3e-7)."""
    phi = np.linspace(0, 2 * np.pi, 4097)
    c, omega, delta = 0.3, 10.0, 0.05
    cycle = fw.Cycle(phi, np.sin(phi), np.full_like(phi, c))
    corrected = fw.gutyar(cycle, omega, delta).inertia
    assert corrected == pytest.approx((2 - c * delta * omega**2) / (delta * omega**2), rel=1e-6)
    row = errata.gutyar_squares(cycle.work, cycle.inertia_ii, omega, delta, corrected)
    assert row["printed_value"] == pytest.approx((2 - c * delta * omega / 2) / (delta * omega**2), rel=1e-6)
    assert row["corrected_value"] == corrected


@pytest.fixture(scope="module")
def flywheel_answer():
    scene = scenes()["flywheel"]
    return compute("flywheel", scene_request(scene, scene.variants[0]))


def test_flywheel_errata_against_the_answers_own_numbers(flywheel_answer):
    """Each corrected value is the number the flywheel study itself uses (Gutyar's I_I, Wittenbauer's slope,
    the flywheel I_м = I_I − group I): the same floats (rel 1e-12); the printed ones by their formulas."""
    rows = {r["key"]: r for r in flywheel_answer["errata"]}
    assert all(set(r) == ROW_KEYS for r in rows.values())
    methods = {m["method"]: m for m in flywheel_answer["methods"]}
    assert rows["gutyar_squares"]["corrected_value"] == pytest.approx(methods["gutyar"]["inertia"], rel=1e-12)
    slope = flywheel_answer["wittenbauer"]["slope_up"]
    assert rows["wittenbauer_axes"]["corrected_value"] == pytest.approx(slope, rel=1e-12)
    assert rows["wittenbauer_axes"]["printed_value"] == pytest.approx(1 / slope, rel=1e-12)
    part = rows["flywheel_part"]
    assert part["corrected_value"] == pytest.approx(flywheel_answer["flywheel_inertia"], rel=1e-12)
    required = methods["exact"]["inertia"]
    existing = flywheel_answer["group_i_existing"]
    assert part["corrected_value"] == pytest.approx(required - existing, rel=1e-12)


def test_the_scenes_request_their_errata_and_the_answers_carry_them():
    """Reduced inertia (crank-slider), resisting moment (slotted link) and wear show the rows of their formulas."""
    expected = {("reduced-inertia", "slider_crank"): ("reduction", {"variable_inertia_38", "variable_inertia_39"}),
                ("resisting-moment", "slotted_link"): ("reduction", {"slotted_viscous_50", "slotted_viscous_53"}),
                ("wear", "engine"): ("wear", {"u21_slip", "trapezoid_step", "piston_pressure"})}
    every = scenes()
    for (scene_id, variant_id), (endpoint, keys) in expected.items():
        scene = every[scene_id]
        variant = next(v for v in scene.variants if v.id == variant_id)
        rows = compute(endpoint, scene_request(scene, variant))["errata"]
        assert {r["key"] for r in rows} == keys
        assert all(np.isfinite([r["printed_value"], r["corrected_value"]]).all() for r in rows)


def test_every_rows_words_are_in_three_languages(flywheel_answer):
    import json
    from pathlib import Path
    texts = {lang: json.loads((Path(__file__).parents[1] / "content" / "i18n" / f"{lang}.json").read_text("utf-8"))
             for lang in ("ru", "uk", "en")}
    rows = [*flywheel_answer["errata"], *errata.variable_inertia(1, 1, 3), *errata.slotted_viscous(1, 1, 2),
            *errata.wear_example(1, 4), errata.piston_pressure(1, 1, 1)]
    for lang, t in texts.items():
        for r in rows:
            assert {f"erratum_why_{r['key']}", f"erratum_printed_{r['key']}", f"erratum_corrected_{r['key']}",
                    f"erratum_unit_{r['unit']}", f"source_{r['source']}"} <= set(t), lang
