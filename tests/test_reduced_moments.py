"""Reduced moments of resistance and inertia against Eremyants' numbers ((3.12), (3.32) and its formulas evaluated) and geometry."""
import numpy as np
import pytest

from server.core.dynamics.friction_iteration import friction_iteration
from server.core.dynamics.reduction import Inertias, reduced_inertia, textbook_inertia_approximation
from server.core.dynamics.resistance import Load, mean_over_cycle, resisting_moment
from server.core.mechanisms import MECHANISMS

# 72001 closed-grid points: the trapezoid mean of a function with kinks errs by O(h²) ≈ 1e-9
PHI = np.linspace(0.0, 2 * np.pi, 72001)


def at(values, degrees):
    return [float(values[int(round(d / 360 * (PHI.size - 1)))]) for d in degrees]


def params(mechanism, **given):
    return MECHANISMS[mechanism].check(given)


def test_sine_mean_resisting_moment_is_the_printed_0_748():
    m = resisting_moment("sine", params("sine", l1=1.0), Load(force=1.0, f=0.15, convention="textbook"), PHI)
    # the printed 0.748 is 0.748585 truncated (Eremyants (3.12))
    assert mean_over_cycle(m.total) == pytest.approx(2 * (1 + 0.15**2) * (1 + 0.15) / np.pi, rel=1e-8)   # (3.12)
    assert int(mean_over_cycle(m.total) * 1000) == 748


def test_sine_exact_friction_limit_is_1_over_1_minus_f_squared():
    m = resisting_moment("sine", params("sine", l1=1.0), Load(force=1.0, f=0.15), PHI)
    # ∮(|sin| + f|cos|)dφ/(2π(1 − f²)) = 2(1 + f)/(π(1 − f²)) = 2/(π(1 − f))
    assert mean_over_cycle(m.total) == pytest.approx(2 / (np.pi * 0.85), rel=1e-8)


def test_sine_resisting_moment_table_of_the_notes():
    m = resisting_moment("sine", params("sine", l1=1.0), Load(force=1.0, f=0.15, convention="textbook"), PHI)
    expected = [0.15337, 0.64408, 0.83147, 0.96220, 1.02250, 0.96220, 0.15337]
    assert at(m.total, [0, 30, 45, 60, 90, 120, 180]) == pytest.approx(expected, abs=6e-6)  # table rounding
    peak = PHI[np.argmax(m.total[: PHI.size // 2])]
    assert np.degrees(peak) == pytest.approx(90 - np.degrees(np.arctan(0.15)), abs=0.01)   # φ = 90° − θ


def test_crank_slider_mean_moment_as_printed_and_consistent():
    p = params("slider_crank", l1=1.0, l2=3.0)
    printed = resisting_moment("slider_crank", p, Load(1.0, 0.2, 0.2, convention="textbook"), PHI)
    exact = resisting_moment("slider_crank", p, Load(1.0, 0.2, 0.2), PHI)
    assert mean_over_cycle(printed.total) == pytest.approx(1.2 / np.pi + 0.8 * 0.2 / 12, rel=1e-9)   # (3.32): 0.395
    assert mean_over_cycle(exact.total) == pytest.approx(0.40419, abs=5e-6)                          # Eremyants §3.2
    assert at(printed.total, [30, 90, 120, 240, 270]) == pytest.approx(
        [0.37233, 1.06667, 1.06036, 0.19207, 0.18667], abs=6e-6)
    assert at(exact.total, [30, 90, 120, 240, 270]) == pytest.approx(
        [0.36599, 1.07609, 1.08203, 0.21641, 0.21522], abs=6e-6)


def test_slotted_link_resisting_moment_tables():
    rotating = resisting_moment("slotted_link", params("slotted_link", l0=0.5, l1=1.0), Load(1.0, f=0.2), PHI)
    assert at(rotating.total, [0, 45, 90, 135, 180]) == pytest.approx([0.66667, 0.72774, 0.88, 1.32099, 2.0], abs=6e-6)
    assert mean_over_cycle(rotating.total) == pytest.approx(1.06994, abs=6e-6)
    p = params("slotted_link", l0=2.0, l1=1.0)
    printed = resisting_moment("slotted_link", p, Load(1.0, 0.5, 0.2, convention="textbook"), PHI)
    consistent = resisting_moment("slotted_link", p, Load(1.0, 0.5, 0.2), PHI)
    assert at(printed.total, [0, 90, 150, 180]) == pytest.approx([0.33333, 0.28, -0.17321, -0.5], abs=6e-6)
    assert at(consistent.total, [150, 180]) == pytest.approx([0.30342, 0.5], abs=6e-6)
    assert mean_over_cycle(printed.total) == pytest.approx(0.1358, abs=1e-4)
    assert mean_over_cycle(consistent.total) == pytest.approx(0.3025, abs=1e-4)


def test_viscous_friction_of_the_sine_mechanism_is_beta_omega_l1_squared():
    m = resisting_moment("sine", params("sine", l1=0.2), Load(beta=3.0), PHI, omega=5.0)
    assert m.viscous == pytest.approx(np.full_like(PHI, 3.0 * 5.0 * 0.04), rel=1e-12)     # (3.17)


def test_crank_slider_self_locks_where_f_tan_psi_reaches_one():
    p = params("slider_crank", l1=1.0, l2=1.01)
    m = resisting_moment("slider_crank", p, Load(1.0, f=0.2), PHI)
    assert m.self_locking.any() and not m.self_locking.all()
    assert m.notices[0].code == "slider_crank_self_locking"
    assert np.isnan(m.total[m.self_locking]).all() and np.isfinite(m.total[~m.self_locking]).all()
    free = resisting_moment("slider_crank", params("slider_crank", l1=1.0, l2=1.03), Load(1.0, f=0.2), PHI)
    assert free.self_locking is None        # λ > √(1 + f²) = 1.0198: no self-locking (Eremyants §3.2)


def test_friction_iteration_converges_to_the_closed_form_and_diverges_when_locked():
    sine = friction_iteration("sine", {"l1": 1.0}, 0.3, force=1.0, f=0.15)
    assert sine.converged and sine.steps[1]["R23"] == pytest.approx(1 + 0.15**2)            # first approximation
    assert sine.steps[-1]["R23"] == pytest.approx(1 / (1 - 0.15**2), rel=1e-6)
    p = params("slider_crank", l1=1.0, l2=1.01)
    locked = friction_iteration("slider_crank", p, np.pi / 2, force=1.0, f=0.2)
    assert locked.ratio > 1 and not locked.converged
    assert locked.steps[-1]["F_T"] > locked.steps[1]["F_T"] * 100


def kinetic_energy_by_finite_differences(mechanism, p, inertias, phi, h=1e-6):
    """2T/ω² from joint positions: Σ m |dr/dφ|² + J (dθ/dφ)², derivatives by central differences."""
    mech = MECHANISMS[mechanism]
    plus, minus = (mech.evaluate(p, phi + s, {"joints"}) for s in (h, -h))
    def rate(name):
        return (plus.joints[name] - minus.joints[name]) / (2 * h)
    def angle(ev, a, b):
        d = ev.joints[b] - ev.joints[a]
        return np.arctan2(d[:, 1], d[:, 0])
    def angular_rate(a, b):
        return np.angle(np.exp(1j * (angle(plus, a, b) - angle(minus, a, b)))) / (2 * h)
    total = inertias.J1 + inertias.J_rotor * inertias.gear_ratio**2
    if mechanism == "sine":
        return total + inertias.m2 * np.sum(rate("A") ** 2, 1) + inertias.m3 * rate("yoke")[:, 0] ** 2
    if mechanism == "slider_crank":
        return (total + inertias.m2 * np.sum(rate("S2") ** 2, 1) + inertias.J_S2 * angular_rate("A", "B") ** 2
                + inertias.m3 * rate("B")[:, 0] ** 2)
    if mechanism == "slotted_link":
        lever = angular_rate("C", "B")
        return total + inertias.m2 * np.sum(rate("B") ** 2, 1) + (inertias.J_S2 + inertias.J3) * lever**2
    return (total + inertias.m2 * np.sum(rate("S2") ** 2, 1) + inertias.J_S2 * angular_rate("B", "C") ** 2
            + inertias.J3 * angular_rate("D", "C") ** 2)


@pytest.mark.parametrize("mechanism, given", [
    ("sine", {"l1": 0.15}),
    ("slider_crank", {"l1": 0.12, "l2": 0.528, "a2": 0.32}),
    ("slider_crank", {"l1": 0.1, "l2": 0.2, "e": 0.05}),
    ("slotted_link", {"l0": 0.05, "l1": 0.1}),
    ("slotted_link", {"l0": 0.2, "l1": 0.1}),
    ("four_bar", {}),
    ("four_bar", {"assembly": -1}),
])
def test_reduced_inertia_equals_kinetic_energy_of_every_link(mechanism, given):
    rng = np.random.default_rng(7)
    phi = rng.uniform(0, 2 * np.pi, 40)
    p = params(mechanism, **given)
    inertias = Inertias(J1=0.3, m2=4.0, J_S2=0.07, m3=6.0, J3=0.4, J_rotor=0.01, gear_ratio=3.0)
    J = reduced_inertia(mechanism, p, inertias, phi).J
    # central differences of exact positions: truncation ~h² ≈ 1e-12, round-off ~eps/h ≈ 1e-10 relative
    assert J == pytest.approx(kinetic_energy_by_finite_differences(mechanism, p, inertias, phi), rel=1e-7)


@pytest.mark.parametrize("mechanism", ["sine", "slider_crank", "slotted_link", "four_bar"])
def test_derivative_of_reduced_inertia_matches_finite_differences(mechanism):
    p = MECHANISMS[mechanism].check({})
    inertias = Inertias(J1=0.3, m2=4.0, J_S2=0.07, m3=6.0, J3=0.4)
    phi, h = np.linspace(0.1, 6.1, 50), 1e-5
    dJ = reduced_inertia(mechanism, p, inertias, phi).dJ
    fd = (reduced_inertia(mechanism, p, inertias, phi + h).J - reduced_inertia(mechanism, p, inertias, phi - h).J) / (2 * h)
    assert dJ == pytest.approx(fd, abs=1e-7 * np.abs(dJ).max())   # O(h²) truncation ≈ 1e-10 of the scale


def test_crank_slider_inertia_approximation_of_the_textbook():
    p = params("slider_crank", l1=1.0, l2=3.0)
    inertias = Inertias(m3=1.0)
    approx = textbook_inertia_approximation("slider_crank", p, inertias, PHI)
    assert at(approx, [30, 90, 120]) == pytest.approx([0.12650, 1.0, 1.02083], abs=6e-6)     # (3.36)
    assert mean_over_cycle(approx) == pytest.approx(0.5 * (1 + 1 / 36), rel=1e-8)            # (3.37)
    exact = reduced_inertia("slider_crank", p, inertias, PHI)
    assert exact.mean == pytest.approx(0.514719, abs=1e-6)                                    # exact u₃₁²


def test_lecture_10_group_two_inertia():
    p = params("slider_crank", l1=0.12, l2=0.528, a2=0.169 / 0.528)
    J = reduced_inertia("slider_crank", p, Inertias(m2=24.2, J_S2=1.21, m3=36.2), PHI)
    assert J.J.max() == pytest.approx(0.90191, abs=1e-5) and J.J.min() == pytest.approx(0.22360, abs=1e-5)
    assert J.mean == pytest.approx(0.55079, abs=1e-5)                                         # Lecture 10 §10.5


def test_partial_self_locking_keeps_the_moment_where_the_slider_moves():
    p = params("slider_crank", l1=1.0, l2=1.05)
    m = resisting_moment("slider_crank", p, Load(1.0, f=0.5), PHI)
    free = ~m.self_locking
    tan_psi = np.abs(np.tan(MECHANISMS["slider_crank"].evaluate(p, PHI, set()).values["s2"]))
    u31 = np.abs(MECHANISMS["slider_crank"].evaluate(p, PHI, set()).values["u31"])
    assert m.total[free] == pytest.approx(u31[free] / (1 - 0.5 * tan_psi[free]), rel=1e-12)
    assert np.isnan(m.total[m.self_locking]).all()
