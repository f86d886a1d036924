"""The presets of content/mechanisms/ through the general path, and the four existing mechanisms reproduced.

Every preset: W = 1 and its structural formula; assembled over the whole turn (721 angles; a slider-driven
preset over its travel); lengths and guide
constraints to 1e-12 m there; analogs against Richardson-extrapolated central differences of the exact
positions at 24 angles (rel 1e-6, floor 1e-7; the presets stay at |det| ≥ 0.5, far from dead positions);
positions against fsolve of each group's closure to 1e-10; the plans' equations to 1e-12.
The four existing closed-form modules (server/core/mechanisms/) are the independent check of the general
solver: their outputs mapped to the general ones agree to 1e-12 (both are closed forms: only round-off).
"""
import numpy as np
import pytest

from server.core.mechanisms import MECHANISMS
from server.core.mechanisms.general import GeneralMechanism
from server.core.structure.compose import compose
from server.core.structure.plans import plans
from server.core.structure.presets import presets

from structure_checks import analog_errors, constraint_residuals, fsolve_errors

FORMULAS = {
    "slider_crank": "I(0,1) → II₂(2,3)", "sine": "I(0,1) → II₅(2,3)", "slotted_link": "I(0,1) → II₃(2,3)",
    "four_bar": "I(0,1) → II₁(2,3)", "shaping_machine": "I(0,1) → II₃(2,3) → II₂(4,5)",
    "whitworth": "I(0,1) → II₃(2,3) → II₂(4,5)", "jaw_crusher": "I(0,1) → II₁(2,3) → II₁(4,5)",
    "knuckle_press": "I(0,1) → II₁(2,3) → II₂(4,5)", "v_engine": "I(0,1) → II₂(2,3) → II₂(4,5)",
    "lever_ram": "I(0,1) → II₃(2,3) → II₄(4,5)", "slider_driven_crank": "I(0,1) → II₁(2,3)",
}


def test_every_preset_is_listed_with_three_languages_and_a_source():
    assert set(presets()) == set(FORMULAS)
    for preset in presets().values():
        assert set(preset["title"]) == set(preset["source"]) == {"ru", "uk", "en"}
        assert all(text.strip() for text in preset["title"].values())


@pytest.mark.parametrize("name", sorted(FORMULAS))
def test_preset(name):
    mech = GeneralMechanism(presets()[name]["linkage"])
    assert mech.structure["W"] == 1 and mech.structure["formula"] == FORMULAS[name]
    assert mech.structure["n"] == 1 + 2 * len(mech.linkage.groups)
    mech.check_geometry({})
    turn = mech.turn(721)                       # the crank's turn, or the input slider's travel
    comp = compose(mech.linkage, turn)
    assert all(g.closes.all() and np.min(np.abs(g.determinant)) >= 0.5 for g in comp.groups)
    assert max(constraint_residuals(mech.linkage, comp)) <= 1e-12
    for k in range(0, 721, 30):
        assert max(fsolve_errors(mech.linkage, comp, k)) <= 1e-10
    for phi0 in turn[::30] + 0.013 * (turn[-1] - turn[0]) / (2 * np.pi):
        for label, error, size in analog_errors(mech.linkage, phi0):
            assert error <= 1e-6 * size + 1e-7, (label, phi0)
        plan = plans(compose(mech.linkage, np.array([phi0])), 12.0, 4.0)
        for equation in plan["velocity"] + plan["acceleration"]:
            assert equation["residual"] <= 1e-12 * (max(v["value"] for v in equation["vectors"]) + 144 * 0.1)


def general(name, phi):
    return compose(GeneralMechanism(presets()[name]["linkage"]).linkage, phi)


def reference(name, phi):
    mech = MECHANISMS[name]
    return mech.evaluate(mech.check({}), phi, {"joints"})


def close(a, b):
    """Agreement to 1e-12 (absolute: the values are of order 0.1…10 m or rad)."""
    return np.max(np.abs(np.asarray(a) - np.asarray(b))) <= 1e-12


PHI = np.linspace(0, 2 * np.pi, 181)


def test_slider_crank_reproduced():
    """A = (−l₁cos φ, l₁sin φ): θ₁ = π − φ; the rod angle ψ is clockwise: ψ = −θ₂; S2 at a₂l₂ from A."""
    comp, ref = general("slider_crank", PHI), reference("slider_crank", PHI)
    b, rod, s2 = comp.joints["B"], comp.links[2][1], comp.joints["S2"]
    x_min = ref.joints["B"][0, 0] - ref.values["s"][0]
    assert close(b.z.real - x_min, ref.values["s"]) and close(b.d1.real, ref.values["u31"])
    assert close(b.d2.real, ref.values["du31"])
    assert close(-rod.th, ref.values["s2"]) and close(-rod.d1, ref.values["u21"]) and close(-rod.d2, ref.values["du21"])
    assert close(np.c_[s2.d1.real, s2.d1.imag], ref.values["v_s2"])
    assert close(np.c_[s2.d2.real, s2.d2.imag], ref.values["a_s2"])
    assert close(np.c_[s2.z.real, s2.z.imag], ref.joints["S2"])


def test_sine_reproduced():
    """The yoke's point Y on the guide: x = s − l₁; the block's travel in the slot: s2 = y."""
    comp, ref = general("sine", PHI), reference("sine", PHI)
    yoke, slot = comp.slides["Y/x"], comp.slides["A/slot"]
    assert close(yoke.s + 0.1, ref.values["s"]) and close(yoke.d1, ref.values["u31"])
    assert close(yoke.d2, ref.values["du31"])
    assert close(slot.s, ref.values["s2"]) and close(slot.d1, ref.values["u21"]) and close(slot.d2, ref.values["du21"])


def test_slotted_link_reproduced():
    """ψ from the vertical, clockwise: ψ = π/2 − θ₃; the block's travel y = l₁(1 + λ) − |BC|, u₂₁ = −s′."""
    comp, ref = general("slotted_link", PHI), reference("slotted_link", PHI)
    lever, slide = comp.links[3][1], comp.slides["s23"]
    psi = np.angle(np.exp(1j * (np.pi / 2 - lever.th)))
    assert close(np.angle(np.exp(1j * (psi - ref.values["s"]))), 0 * PHI)
    assert close(-lever.d1, ref.values["u31"]) and close(-lever.d2, ref.values["du31"])
    assert close(0.1 * 1.5 - slide.s, ref.values["s2"])
    assert close(-slide.d1, ref.values["u21"]) and close(-slide.d2, ref.values["du21"])


def test_four_bar_reproduced():
    comp, ref = general("four_bar", PHI), reference("four_bar", PHI)
    coupler, rocker, s2 = comp.links[2][1], comp.links[3][1], comp.joints["S2"]
    assert close(np.angle(np.exp(1j * (rocker.th - ref.values["s"]))), 0 * PHI)
    assert close(np.angle(np.exp(1j * (coupler.th - ref.values["s2"]))), 0 * PHI)
    assert close(rocker.d1, ref.values["u31"]) and close(rocker.d2, ref.values["du31"])
    assert close(coupler.d1, ref.values["u21"]) and close(coupler.d2, ref.values["du21"])
    assert close(np.c_[s2.d1.real, s2.d1.imag], ref.values["v_s2"])
    assert close(np.c_[s2.d2.real, s2.d2.imag], ref.values["a_s2"])
    assert close(np.c_[comp.joints["C"].z.real, comp.joints["C"].z.imag], ref.joints["C"])
