"""The constant-load wear models of Chaika–Vasylenko §4.1, (4.1)–(4.5), (4.14), (4.15), against hand computation
from the §4.3 example, closed forms, quadrature and the exact crank-slider kinematics."""
import numpy as np
import pytest
from scipy.integrate import quad

from server.core.kinetostatics.wear import (
    cosine_law, cosine_pressure, guide_path, guide_wear, peak_pressure, pressure_resultant, slider_wear)


def test_peak_pressure_of_the_pin_is_the_books_mean_pressure_of_the_example():
    """(4.4) with r = d/2 is the book's 4R/(π l d) of (4.23): R = 3468 N, l_z = 0.025 m, d = 0.02 m gives the
    printed 8.8·10⁶ Pa (two printed digits: 0.5 %)."""
    assert peak_pressure(3468.0, 0.025, 0.01) == pytest.approx(8.8e6, rel=5e-3)
    assert peak_pressure(3468.0, 0.025, 0.01) == pytest.approx(4 * 3468.0 / (np.pi * 0.025 * 0.02), rel=1e-15)


def test_cosine_pressure_carries_the_load_by_quadrature():
    """(4.3): the load is 2∫₀^{π/2} p l_z r cos ψ dψ of the pressure (4.5), by adaptive quadrature (its own
    error, 1e-10, is the tolerance); pressure_resultant is the same integral in closed form."""
    force, length, radius = 2500.0, 0.03, 0.012
    carried, _ = quad(lambda psi: float(cosine_pressure(force, length, radius, psi)) * length * radius * np.cos(psi),
                      -np.pi, np.pi, points=[-np.pi / 2, np.pi / 2], epsabs=0, epsrel=1e-12)
    assert carried == pytest.approx(force, rel=1e-10)
    assert pressure_resultant(peak_pressure(force, length, radius), length, radius) == pytest.approx(force, rel=1e-15)


def test_cosine_law_is_half_at_sixty_degrees_and_nothing_out_of_contact():
    """(4.1), (4.2): δ = δ_max cos ψ on |ψ| ≤ 90°, zero beyond (cos 60° = ½ by hand)."""
    values = cosine_law(80.0, np.radians([0.0, 60.0, -60.0, 90.0, 100.0, 180.0]))
    assert values == pytest.approx([80.0, 40.0, 40.0, 0.0, 0.0, 0.0], abs=1e-12)


def _travel(points: int = 200001, l1: float = 0.045, l2: float = 0.18):
    phi = np.linspace(0.0, 2 * np.pi, points)
    return l1 + l2 - (l1 * np.cos(phi) + np.sqrt(l2 ** 2 - (l1 * np.sin(phi)) ** 2))


def test_slider_wear_per_cycle_uses_the_path_there_and_back():
    """(4.14): the path of a slider over one turn of the exact crank-slider is 2H_B (H_B = 2l₁ for the axial
    mechanism, (4.22)); the total variation of the sampled travel is exact on a grid through both dead centres
    (rounding only: 1e-12)."""
    travel = _travel()
    path = float(np.abs(np.diff(travel)).sum())
    assert path == pytest.approx(2 * 0.09, rel=1e-12)
    assert slider_wear(1.2e-17, 2.5e5, 0.09, 1.44e8) == pytest.approx(1.2e-17 * 2.5e5 * path * 1.44e8, rel=1e-12)


@pytest.mark.parametrize("length", [0.076, 0.12])          # l_p < H_B (the example) and l_p > H_B
def test_guide_path_is_the_footprint_of_the_moving_slider(length):
    """(4.15): S(X) is the path slid under X while the slider [s, s + l_p] covers it, summed over one turn of the
    exact crank-slider (H_B = 0.09 m); the sum is exact but for the grid cell where X enters or leaves the
    footprint, so the tolerance is twice the largest step of the travel."""
    travel = _travel()
    steps = np.abs(np.diff(travel))
    middle = (travel[1:] + travel[:-1]) / 2
    for x in np.linspace(0.0, 0.09 + length, 23):
        covered = (middle <= x) & (x <= middle + length)
        assert guide_path(x, length, 0.09) == pytest.approx(steps[covered].sum(), abs=2 * steps.max())
    assert float(guide_path(length / 2, length, 0.09)) == pytest.approx(length)   # D₄: l_p, as printed
    assert float(guide_path(0.0, length, 0.09)) == 0.0
    assert float(guide_path(0.09 + length, length, 0.09)) == pytest.approx(0.0, abs=1e-15)   # X − l_p rounded
    assert guide_wear(1e-17, 2e5, 0.152, 1e8) == pytest.approx(1e-17 * 2e5 * 0.152 * 1e8, rel=1e-15)
