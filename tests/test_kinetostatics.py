"""Kinetostatics of the crank-slider with friction (Chaika–Vasylenko §3.1) against virtual work, equilibrium and the iteration."""
import numpy as np
import pytest

from server.core.kinetostatics.crank_slider import Loads, Pairs, analyse
from server.core.kinetostatics.report import efficiency, equilibrium_residuals
from server.core.kinetostatics.virtual_work import reduced_moment
from server.core.mechanisms import MECHANISMS

PARAMS = MECHANISMS["slider_crank"].check({"l1": 0.1, "l2": 0.4, "a2": 0.3})
PHI = np.linspace(0, 2 * np.pi, 721)
LOADS = Loads(m2=3.0, J_S2=0.05, m3=2.0, J1=0.1, omega=50.0, epsilon=20.0, force=1000.0, return_factor=0.2)
FRICTION = Pairs(f14=0.05, f12=0.08, f23=0.08, f34=0.12)


def virtual_work_moment(params, analysis):
    """M_bal = −Σ(F·V_q + M·u) over gravity, inertia and the piston force: independent of the dyad solution."""
    return reduced_moment(params, analysis.applied, analysis.phi)


@pytest.mark.parametrize("offset", [0.0, 0.03])
def test_frictionless_balancing_moment_equals_the_reduced_moment_of_all_forces(offset):
    params = MECHANISMS["slider_crank"].check({"l1": 0.1, "l2": 0.4, "a2": 0.3, "e": offset})
    analysis = analyse(params, LOADS, Pairs(), PHI)
    expected = virtual_work_moment(params, analysis)
    assert analysis.balancing_moment == pytest.approx(expected, abs=1e-9 * np.abs(expected).max())


@pytest.mark.parametrize("k", [0, 1, 2, -1])
def test_every_link_is_in_equilibrium_at_every_approximation(k):
    analysis = analyse(PARAMS, LOADS, FRICTION, PHI)
    residual = equilibrium_residuals(analysis, k)
    scale = np.abs(analysis.approximations[k].R12).max()
    for name in ("rod_force", "rod_moment", "slider_force"):
        assert residual[name].max() <= 1e-9 * scale, name


def test_iteration_converges_geometrically_with_a_rate_growing_with_f():
    rates = []
    for f in (0.05, 0.1, 0.2):
        analysis = analyse(PARAMS, LOADS, Pairs(f, f, f, f), PHI, tolerance=1e-12)
        changes = [a.change for a in analysis.approximations[1:]]
        assert all(b < a for a, b in zip(changes, changes[1:]))          # monotone, geometric decrease
        rates.append(analysis.ratio)
    assert rates[0] < rates[1] < rates[2] < 1
    assert rates[1] == pytest.approx(2 * rates[0], rel=0.35)             # first order in f


def test_friction_costs_work_and_efficiency_lies_between_zero_and_one():
    frictionless = efficiency(analyse(PARAMS, Loads(**{**LOADS.__dict__, "epsilon": 0.0}), Pairs(), PHI))
    with_friction = efficiency(analyse(PARAMS, Loads(**{**LOADS.__dict__, "epsilon": 0.0}), FRICTION, PHI))
    assert frictionless["efficiency"] == pytest.approx(1.0, rel=1e-5)      # trapezoid on 721 points
    assert 0.5 < with_friction["efficiency"] < 1.0
    assert with_friction["work_driving"] > frictionless["work_driving"]


def test_slider_self_locking_is_reported_not_a_number():
    near_limit = MECHANISMS["slider_crank"].check({"l1": 0.1, "l2": 0.102, "a2": 0.3})
    analysis = analyse(near_limit, Loads(force=1000.0, omega=1.0, gravity=False), Pairs(f34=0.5), PHI)
    assert analysis.notices and analysis.notices[0].code == "kinetostatics_self_locking"
    assert not analysis.converged.all() and analysis.converged.any()
    finite = np.isfinite(analysis.balancing_moment)
    assert np.array_equal(finite, analysis.converged)


def test_piston_wear_of_the_book_reproduces_76_micrometres_from_its_own_integrands():
    """Chaika–Vasylenko §4.3 (B): δ₃p = a₃p ∫|R₃₄V_qB|dφ with the printed integrands of Table 4.4 (right side)."""
    from server.core.kinetostatics.wear import mean_pressure, piston_wear
    phi = np.radians(np.arange(0, 361, 30))
    integrand = np.array([0, 83, 164, 155, 94, 61, 0, 0, 0, 0, 0, 0, 0], float)     # printed, N·m/rad
    r34 = np.array([0, 3013, 3720, 3449, 2766, 1467, 0, -841, -1828, -2002, -664, -2456, 0], float)
    p_mean = mean_pressure(np.where(r34 > 0, r34, 0.0), 0.076, 0.075)
    assert p_mean == pytest.approx(0.248e6, rel=5e-3)                   # printed ≈ 0.248·10⁶ N/m²
    k = 2e-12 / 0.248e6                                                 # printed k = 0.81·10⁻¹⁷
    velocity = np.divide(integrand, np.abs(r34), out=np.zeros_like(integrand), where=r34 > 0)
    wear = piston_wear(phi, r34, velocity, k, 60 * 2400 * 1000, 0.076, 0.075)
    assert wear == pytest.approx(76, abs=0.5)


def test_journal_wear_follows_the_cosine_law_under_a_constant_load():
    """(4.1)–(4.5): a fixed bush under a constant downward load with the journal turning wears as cos ψ."""
    from server.core.kinetostatics.wear import revolute_wear
    phi = np.linspace(0, 2 * np.pi, 721)
    load = np.tile([0.0, -1000.0], (phi.size, 1))           # the journal presses the bush downwards
    beta = np.radians(np.arange(0, 360, 10))
    bush = revolute_wear(phi, load, np.ones_like(phi), np.zeros_like(phi), beta, 1e-17, 1e8, 0.02, journal=False)
    expected = 2e6 * 1e-17 * 1e8 / (np.pi * 0.02) * 1000 * 2 * np.pi * np.clip(np.cos(beta + np.pi / 2), 0, None)
    assert bush == pytest.approx(expected, abs=1e-9 * expected.max())
