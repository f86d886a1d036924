"""Kuleshova–Tokhtar's method (a), the vector polygon a_B = a_A + aⁿ_BA + a^τ_BA, against the decomposition
(1)–(4) the app computes: two independent routes, both exact, so they agree to rounding (1e-12 s⁻² on
accelerations of order 0.1–1 s⁻²)."""
import numpy as np
import pytest

from server.core.angular_acceleration import CrankLaw, crank_slider, trammel

LAWS = [CrankLaw(), CrankLaw("accelerating", 0.5, 0.3), CrankLaw("harmonic", np.pi / 6, 0.0, 0.6, 1.7)]


@pytest.mark.parametrize("law", LAWS)
@pytest.mark.parametrize("lam", [0.2, 0.5, 0.9])
def test_method_a_agrees_with_the_decomposition_on_the_crank_slider(law, lam):
    t = np.linspace(0.0, 12.0, 721)
    result = crank_slider(lam, 0.1, law, t)
    assert np.max(np.abs(result["polygon"]["epsilon"] - result["epsilon"])) < 1e-12
    assert np.max(np.abs(result["polygon"]["omega"] - result["omega_coupler"])) < 1e-12
    assert result["polygon"]["difference"] < 1e-12


@pytest.mark.parametrize("law", LAWS)
def test_method_a_agrees_on_the_trammel_through_both_guides(law):
    t = np.linspace(0.0, 12.0, 721)     # passes φ = 90°, where B's guide is useless and D's takes over
    result = trammel(0.1, law, t)
    assert np.max(np.abs(result["polygon"]["epsilon"] - result["epsilon"])) < 1e-12


def test_the_papers_example_by_method_a():
    """Kuleshova–Tokhtar, example 2: AB = 2·OA, φ = πt/6, t = 1 s: ε_AB = −0.0566 s⁻² (printed −0.0565)."""
    polygon = crank_slider(0.5, 1.0, CrankLaw(), np.array([1.0]))["polygon"]
    assert polygon["epsilon"][0] == pytest.approx(-0.0566, abs=5e-5)
    # the tangential acceleration's length is |ε_AB|·AB, AB = 2
    assert polygon["a_tau_BA"][0] == pytest.approx(2 * abs(polygon["epsilon"][0]), rel=1e-12)
