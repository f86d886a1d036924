"""Kinetostatics by structural groups (Chaika–Vasylenko §3.1) on every preset of content/mechanisms/.

Without friction the balancing moment must equal the reduced moment of all the loads by power equality
(3.24), here with velocities from five-point differences of the exact positions (h = 2.5e-4: truncation
~h⁴·|z⁽⁵⁾| ≲ 1e-12 of the moment's scale, round-off ~1e-16/h ≈ 1e-12; bound 1e-9 of the largest |M|) and the
moment the dynamics' reduction implies (J ε₁ + ½J′ω₁² + M_c, structure/reduction.py; 1e-9), and
every link must be in equilibrium: ΣF and ΣM_O summed here load by load and pair by pair (1e-9 of the largest
force on the link, and of it times the mechanism's size; the solve itself leaves ~1e-15).  With friction the
same sums hold at every approximation of the textbook's table (each approximation is an equilibrium with the
friction of the previous one as a known load), and the converged balancing moment agrees with fsolve of the
full nonlinear equilibrium (the friction of each pair from its own reaction) to 1e-8 of its scale, the
requested ε_R being 1e-11 (fsolve's own xtol 1e-14 on reactions of ~10³ N).
"""
import numpy as np
import pytest

from server.core.kinetostatics.groups.analysis import analyse
from server.core.mechanisms.general import GeneralMechanism
from server.core.structure.compose import compose
from server.core.structure.masses import LinkMass, LinkMoment, MassModel, SliderForce
from server.core.structure.presets import presets

from group_force_checks import crank_driven, direct, power_fd, reduction_moment, residual

PHI = np.linspace(0, 2 * np.pi, 73) + 0.0123      # off the exact special angles (a friction sense undefined)


def preset_model(name, friction=0.0):
    """Masses on every link (centres off the links' lines), a useful force on the first slider, or a load
    moment on the last link where there is no slider."""
    mechanism = GeneralMechanism(presets()[name]["linkage"])
    comp = compose(mechanism.linkage, np.zeros(1))
    links = sorted(comp.links)
    slides = list(comp.slides)
    model = MassModel(tuple(LinkMass(k, 0.5 + k, (0.02 * k, 0.01), 0.002 * k) for k in links),
                      forces=(SliderForce(slides[0], 300.0, 0.4),) if slides else (),
                      moments=() if slides else (LinkMoment(links[-1], 20.0, 0.5),),
                      friction=friction, pair_radius=0.01)
    return mechanism, model


@pytest.mark.parametrize("name", crank_driven())
def test_frictionless_balancing_moment_is_virtual_work(name):
    mechanism, model = preset_model(name)
    result = analyse(mechanism, model, PHI, omega=12.0, epsilon=-4.0)
    ok = ~result.influence.singular
    assert ok.sum() > 0.9 * PHI.size
    moment = result.solution.balancing
    expected = power_fd(mechanism, result)
    scale = np.abs(expected[ok]).max()
    assert np.abs(moment - expected)[ok].max() <= 1e-9 * scale
    dynamics = reduction_moment(mechanism, model, result, 12.0, -4.0)
    assert np.abs(moment - dynamics)[ok].max() <= 1e-9 * scale
    assert residual(result, result.solution) <= 1e-9
    assert len(result.approximations) == 1 and result.numerics["error_estimate"] == 0.0


@pytest.mark.parametrize("name", crank_driven())
def test_friction_every_approximation_in_equilibrium_and_fsolve(name):
    mechanism, model = preset_model(name, friction=0.15)
    result = analyse(mechanism, model, PHI, omega=12.0, epsilon=-4.0, tolerance=1e-11)
    free = ~result.locked & ~result.influence.singular
    assert free.sum() > 0.9 * PHI.size
    assert len(result.approximations) >= 2
    for row in result.approximations:
        assert residual(result, row) <= 1e-9
    assert residual(result, result.solution) <= 1e-9
    assert result.converged[free].all()
    # the textbook's series, where it converges, ends where Newton's solve does
    last = result.approximations[-1]
    if last.change is not None and last.change < 1e-11:
        scale = np.abs(result.solution.balancing[free]).max()
        assert np.abs(last.balancing - result.solution.balancing)[free].max() <= 1e-8 * scale
    scale = np.nanmax(np.abs(result.solution.balancing))
    for k in np.flatnonzero(free)[::9]:
        frictionless = result.approximations[0]
        start = np.concatenate([*(x[k] for x in frictionless.unknowns),
                                [frictionless.R01[k].real, frictionless.R01[k].imag,
                                 frictionless.balancing[k]]])
        (unknowns, R01, balancing), left = direct(result, k, start)
        assert left <= 1e-9 * scale                  # fsolve reached the equilibrium (N and N·m)
        assert abs(balancing[0] - result.solution.balancing[k]) <= 1e-8 * scale


@pytest.mark.parametrize("name", crank_driven())
def test_power_balance_with_friction_and_the_efficiency(name):
    """The pairs' reactions do no work (a revolute pair's force at the common joint, a prismatic pair's normal
    force across the sliding and its couple on two links turning alike), so at every angle the balancing moment
    pays the loads' reduced moment and what friction dissipates: M_b = −Σ(F·z′ + Mθ′) + Σ_p |z_p||relative_p|
    (1e-9 of the largest |M_b|).  Over the cycle that is A_driving = A_useful + A_friction where inertia and
    gravity do no net work (ε₁ = 0: the cycle closes), so η = A_useful/(A_useful + A_friction) is the useful
    share of the driving work (1e-6: trapezoid sums of the same grid); η = 1 without friction."""
    from server.core.kinetostatics.groups.report import efficiency
    mechanism, model = preset_model(name, friction=0.15)
    phi = np.linspace(0, 2 * np.pi, 721)
    result = analyse(mechanism, model, phi, omega=12.0, epsilon=0.0, tolerance=1e-11)
    free = ~result.locked & ~result.influence.singular
    lost = sum(np.abs(result.solution.friction[k] * p.relative) for k, p in enumerate(result.pairs))
    moment = result.solution.balancing
    assert np.abs(moment - (result.reduced_moment + lost))[free].max() <= 1e-9 * np.abs(moment[free]).max()
    if free.all():
        works = efficiency(result)
        assert abs(works["work_driving"] - works["work_useful"] - works["work_friction"]) <= 1e-6 * works["work_driving"]
        assert 0 < works["efficiency"] < 1
    smooth = analyse(mechanism, MassModel(model.links, forces=model.forces, moments=model.moments), phi, omega=12.0)
    assert efficiency(smooth)["efficiency"] == 1.0
