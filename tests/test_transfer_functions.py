"""The closed-form transfer functions are the derivatives of the motion the linkage actually makes.

For every mechanism and a sweep of parameters, including near-singular ones, the output
and intermediate positions are measured on the drawn joints (a slider's x, a link's
direction by atan2; see linkage_geometry.py) and differentiated numerically.  The
closed-form u₃₁, u′₃₁, u₂₁, u′₂₁ of the core must agree, the links must keep their lengths,
sliders stay on their guides, and the motion repeats after one kinematic cycle.
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache, partial

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from linkage_geometry import MEASURED, fd_transfer_functions, joints, measured_positions
from server.core.mechanisms import MECHANISMS

assert_allclose = partial(np.testing.assert_allclose, equal_nan=False)   # a NaN on either side fails

# Finite differences against closed forms.  Richardson-extrapolated central differences
# have a truncation error ~ (h/w)⁴ relative to the curve, w being the width of its sharpest
# feature (≈ 1 rad for ordinary linkages, ≈ |1 − λ| for the slotted link near λ = 1, ≈ the
# smallest transmission angle near a change point), plus rounding ≈ ε·|s|/h² ≈ 2e-10 in the
# second derivative at h = 1e-3.  Choosing h ≤ w/20 keeps both below 1e-7 of the curve's
# largest value, so the tolerance 1e-6 of that value has ≥ 10× margin, while any wrong sign,
# factor or term shows up as an O(1) error.
FD_RTOL = 1e-6
# Joint coordinates of a drawing of size L carry rounding ≈ ε·L (ε = 2.2e-16); a link of
# length l then reads l(1 ± ε·L/l).  L/l ≤ 100 here, so 1e-12 leaves a 50× margin.
LENGTH_RTOL = 1e-12

TRANSFER_FUNCTIONS = ("u31", "du31", "u21", "du21")


@dataclass(frozen=True)
class Case:
    """A mechanism set-up, the finite-difference step that resolves it, where to look hardest and what to skip."""

    id: str
    mechanism: str
    params: tuple = ()
    h: float = 1e-3
    hot: tuple = ()           # crank angles of the sharpest features: sampled densely around them
    avoid: tuple = ()         # crank angles of jumps or singular points: not differentiated across

    @property
    def p(self) -> dict[str, float]:
        return MECHANISMS[self.mechanism].check(dict(self.params))

    def angles(self) -> np.ndarray:
        """About 150 crank angles over one cycle, denser near the hot spots, at least 3h from any jump."""
        cycle = MECHANISMS[self.mechanism].cycle(self.p)
        phi = np.linspace(0.0, cycle, 121)[:-1] + 0.0123
        near = np.array([-0.1, -0.03, -0.01, -0.003, 0.003, 0.01, 0.03, 0.1])
        phi = np.concatenate([phi, *[hot + near for hot in self.hot]])
        for bad in self.avoid:
            distance = np.abs(np.angle(np.exp(1j * (phi - bad) * 2 * np.pi / cycle))) * cycle / (2 * np.pi)
            phi = phi[distance > max(3 * self.h, 0.02)]
        return np.sort(phi)


def case(id_, mechanism, h=1e-3, hot=(), avoid=(), **params) -> Case:
    return Case(id_, mechanism, tuple(sorted(params.items())), h, hot, avoid)


PI = np.pi
CASES = [
    case("sine", "sine", l1=0.1),
    # crank-slider, λ = l₂/l₁; the rod is steepest (cos ψ smallest) near φ = 90°, 270°
    case("slider λ=3", "slider_crank", l1=0.1, l2=0.3),
    case("slider λ=1.5", "slider_crank", l1=0.1, l2=0.15),
    case("slider λ=1.05", "slider_crank", l1=0.1, l2=0.105, hot=(PI / 2, 3 * PI / 2)),
    case("slider λ=5 long", "slider_crank", l1=1.0, l2=5.0),
    case("slider offset e=+l1/2", "slider_crank", l1=0.1, l2=0.3, e=0.05),
    case("slider offset e=-l1/2 λ=1.6", "slider_crank", l1=0.1, l2=0.16, e=-0.05),
    # l₂ − l₁ − |e| = 0.002 l₁: the rod nearly reaches the perpendicular to the guide
    case("slider offset near assembly limit", "slider_crank", h=2.5e-4, hot=(PI / 2,), l1=0.1, l2=0.1052, e=0.005),
    # slotted link, λ = l₀/l₁: the block passes closest to the lever pivot at φ = 180°
    case("slotted λ=0.5 rotating", "slotted_link", l0=0.05, l1=0.1),
    case("slotted λ=0.2 rotating", "slotted_link", l0=0.02, l1=0.1),
    case("slotted λ=0.98", "slotted_link", h=2.5e-4, hot=(PI,), l0=0.098, l1=0.1),
    case("slotted λ=1 (jamming at 180°)", "slotted_link", avoid=(PI,), l0=0.1, l1=0.1),
    case("slotted λ=1.02", "slotted_link", h=2.5e-4, hot=(PI,), l0=0.102, l1=0.1),
    case("slotted λ=2 oscillating", "slotted_link", l0=0.2, l1=0.1),
    case("slotted λ=5 oscillating", "slotted_link", l0=0.5, l1=0.1),
    # hinged four-bar
    case("crank-rocker +", "four_bar", l0=0.4, l1=0.1, l2=0.35, l3=0.3, assembly=1),
    case("crank-rocker −", "four_bar", l0=0.4, l1=0.1, l2=0.35, l3=0.3, assembly=-1),
    case("crank-rocker Drakunov–Tuleshova +", "four_bar", l0=1.0, l1=0.3, l2=1.0, l3=0.8, assembly=1),
    case("crank-rocker Drakunov–Tuleshova −", "four_bar", l0=1.0, l1=0.3, l2=1.0, l3=0.8, assembly=-1),
    case("crank-rocker Eremyants check case", "four_bar", l0=4.0, l1=1.0, l2=3.5, l3=3.0, assembly=1),
    case("double-crank +", "four_bar", l0=0.1, l1=0.3, l2=0.35, l3=0.4, assembly=1),
    case("double-crank −", "four_bar", l0=0.1, l1=0.3, l2=0.35, l3=0.4, assembly=-1),
    # within 1° of a change point: smallest transmission angle 0.79° at φ = 180°, 0.54° at φ = 0
    case("crank-rocker μmin=0.79° +", "four_bar", h=2.5e-4, hot=(PI,), l0=0.4, l1=0.1, l2=0.35, l3=0.15001, assembly=1),
    case("crank-rocker μmin=0.79° −", "four_bar", h=2.5e-4, hot=(PI,), l0=0.4, l1=0.1, l2=0.35, l3=0.15001, assembly=-1),
    case("crank-rocker μmin=0.54° −", "four_bar", h=2.5e-4, hot=(0.0, 2 * PI), l0=0.4, l1=0.1, l2=0.45, l3=0.15001,
         assembly=-1),
    # change-point ("special") four-bars of Eremyants §2.5, (λ₂, λ₃, λ₀) = (4, 3, 2), (3, 4, 2), (3, 2, 4).
    # Without limiter the rocker passes the change point (at φ = 2π for schemes 1, 2; 3π for scheme 3)
    # smoothly: it is sampled densely there.  With the limiter u₃₁ jumps there: not differentiated across.
    case("scheme 1 no limiter", "four_bar", hot=(0.0, 2 * PI), l0=2, l1=1, l2=4, l3=3, assembly=1, limiter=0),
    case("scheme 1 limiter", "four_bar", avoid=(0.0,), l0=2, l1=1, l2=4, l3=3, assembly=1, limiter=1),
    case("scheme 1 other branch", "four_bar", hot=(2 * PI,), l0=2, l1=1, l2=4, l3=3, assembly=-1, limiter=0),
    case("scheme 2 no limiter", "four_bar", hot=(0.0, 2 * PI), l0=2, l1=1, l2=3, l3=4, assembly=-1, limiter=0),
    case("scheme 2 limiter", "four_bar", avoid=(0.0,), l0=2, l1=1, l2=3, l3=4, assembly=-1, limiter=1),
    case("scheme 3 no limiter", "four_bar", hot=(PI, 3 * PI), l0=4, l1=1, l2=3, l3=2, assembly=1, limiter=0),
    case("scheme 3 limiter", "four_bar", avoid=(PI,), l0=4, l1=1, l2=3, l3=2, assembly=1, limiter=1),
    case("scheme 3 limiter other branch", "four_bar", avoid=(PI,), l0=4, l1=1, l2=3, l3=2, assembly=-1, limiter=1),
]
CASE_IDS = [c.id for c in CASES]


@lru_cache(maxsize=None)
def comparison(c: Case) -> tuple[np.ndarray, dict, dict]:
    """Crank angles, closed-form values and finite-difference values for one case (computed once)."""
    phi = c.angles()
    closed = MECHANISMS[c.mechanism].evaluate(c.p, phi, set()).values
    return phi, closed, fd_transfer_functions(c.mechanism, c.p, phi, c.h)


def natural_scale(mechanism: str, p: dict[str, float], name: str) -> float:
    """1 for transfer functions of an angle (rad/rad), l₁ for those of a length: the floor of the tolerance
    where a transfer function is identically zero (u′₃₁ of the slotted link at λ = 1)."""
    (_, angle3), (_, angle2) = MEASURED[mechanism]
    return 1.0 if (angle3 if name in ("u31", "du31") else angle2) else p["l1"]


def assert_matches_finite_differences(c: Case, name: str) -> None:
    phi, closed, numeric = comparison(c)
    exact = closed[name]
    assert np.all(np.isfinite(exact)), f"{c.id}: {name} undefined at a regular position"
    scale = max(np.max(np.abs(exact)), natural_scale(c.mechanism, c.p, name))
    worst = int(np.argmax(np.abs(numeric[name] - exact)))
    assert_allclose(
        numeric[name], exact, rtol=FD_RTOL, atol=FD_RTOL * scale,
        err_msg=f"{c.id}: {name} vs finite differences, worst at φ = {np.degrees(phi[worst]):.3f}°")


@pytest.mark.parametrize("c", CASES, ids=CASE_IDS)
def test_output_velocity_analog_u31_matches_finite_differences_of_the_joints(c):
    assert_matches_finite_differences(c, "u31")


@pytest.mark.parametrize("c", CASES, ids=CASE_IDS)
def test_output_acceleration_analog_du31_matches_finite_differences_of_the_joints(c):
    assert_matches_finite_differences(c, "du31")


@pytest.mark.parametrize("c", CASES, ids=CASE_IDS)
def test_intermediate_link_velocity_analog_u21_matches_finite_differences_of_the_joints(c):
    assert_matches_finite_differences(c, "u21")


@pytest.mark.parametrize("c", CASES, ids=CASE_IDS)
def test_intermediate_link_acceleration_analog_du21_matches_finite_differences_of_the_joints(c):
    assert_matches_finite_differences(c, "du21")


def link_lengths(mechanism: str, p: dict[str, float], j: dict[str, np.ndarray]) -> list[tuple[str, np.ndarray, float, float]]:
    """(link, measured length over the cycle, nominal length, length of the whole link) for the drawing.

    The centre of mass S2 sits on the rod/coupler at the fraction a₂ of its length from A (B).
    """
    dist = lambda a, b: np.hypot(*(j[a] - j[b]).T)
    if mechanism == "sine":
        return [("crank OA", dist("A", "O"), p["l1"], p["l1"])]
    if mechanism == "slider_crank":
        return [("crank OA", dist("A", "O"), p["l1"], p["l1"]), ("rod AB", dist("B", "A"), p["l2"], p["l2"]),
                ("rod part AS2", dist("S2", "A"), p["a2"] * p["l2"], p["l2"]),
                ("rod part S2B", dist("B", "S2"), (1 - p["a2"]) * p["l2"], p["l2"])]
    if mechanism == "slotted_link":
        return [("crank AB", dist("B", "A"), p["l1"], p["l1"]), ("frame AC", dist("C", "A"), p["l0"], p["l0"]),
                ("drawn lever C–end", dist("lever_end", "C"), p["l0"] + p["l1"], p["l0"] + p["l1"])]
    return [("frame AD", dist("D", "A"), p["l0"], p["l0"]), ("crank AB", dist("B", "A"), p["l1"], p["l1"]),
            ("coupler BC", dist("C", "B"), p["l2"], p["l2"]), ("rocker DC", dist("C", "D"), p["l3"], p["l3"]),
            ("coupler part BS2", dist("S2", "B"), p["a2"] * p["l2"], p["l2"]),
            ("coupler part S2C", dist("C", "S2"), (1 - p["a2"]) * p["l2"], p["l2"])]


def assert_links_keep_their_lengths(mechanism: str, p: dict[str, float], j: dict[str, np.ndarray], label: str) -> None:
    for link, measured, nominal, whole in link_lengths(mechanism, p, j):
        error = np.max(np.abs(measured - nominal)) / whole
        assert error <= LENGTH_RTOL, f"{label}: {link} is off by {error:.1e} of its length"


def dense_angles(mechanism: str, p: dict[str, float], n: int = 2001) -> np.ndarray:
    return np.linspace(0.0, MECHANISMS[mechanism].cycle(p), n)


@pytest.mark.parametrize("c", CASES, ids=CASE_IDS)
def test_links_keep_their_lengths_in_every_position(c):
    assert_links_keep_their_lengths(c.mechanism, c.p, joints(c.mechanism, c.p, dense_angles(c.mechanism, c.p)), c.id)


@pytest.mark.parametrize("c", [c for c in CASES if c.mechanism == "slider_crank"],
                         ids=[c.id for c in CASES if c.mechanism == "slider_crank"])
def test_slider_stays_on_its_guide_y_equals_e(c):
    j = joints(c.mechanism, c.p, dense_angles(c.mechanism, c.p))
    assert np.all(j["B"][:, 1] == c.p["e"])   # exactly: the slider's y is the guide's


def test_sine_yoke_stays_under_the_crank_pin_and_on_its_guide():
    p = MECHANISMS["sine"].check({"l1": 0.1})
    j = joints("sine", p, dense_angles("sine", p))
    assert np.all(j["yoke"][:, 0] == j["A"][:, 0]) and np.all(j["yoke"][:, 1] == 0.0)


@pytest.mark.parametrize("c", [c for c in CASES if c.mechanism == "slotted_link"],
                         ids=[c.id for c in CASES if c.mechanism == "slotted_link"])
def test_block_stays_on_the_slotted_lever(c):
    """B lies on the drawn lever: on the line C–lever_end (cross product 0) and between its ends."""
    p = c.p
    j = joints(c.mechanism, p, dense_angles(c.mechanism, p))
    cb, ce = j["B"] - j["C"], j["lever_end"] - j["C"]
    lever = p["l0"] + p["l1"]
    cross = (cb[:, 0] * ce[:, 1] - cb[:, 1] * ce[:, 0]) / lever**2
    along = np.einsum("ij,ij->i", cb, ce) / lever**2
    assert np.max(np.abs(cross)) < LENGTH_RTOL      # same rounding argument as the link lengths
    assert np.all(along >= -LENGTH_RTOL) and np.all(along <= 1 + LENGTH_RTOL)


def origin_of_s(mechanism: str, p: dict[str, float]) -> float:
    """s minus the measured output position: the yoke travel starts at x = −l₁, the slider's at the inner dead centre."""
    if mechanism == "sine":
        return p["l1"]
    if mechanism == "slider_crank":
        return -np.sqrt((p["l2"] - p["l1"]) ** 2 - p["e"] ** 2)
    return 0.0


@pytest.mark.parametrize("c", CASES, ids=CASE_IDS)
def test_position_functions_are_the_positions_of_the_drawn_links(c):
    """s and s2 are what the drawing shows, up to the stated origin of s (angles modulo 2π)."""
    phi = c.angles()
    values = MECHANISMS[c.mechanism].evaluate(c.p, phi, set()).values
    measured = measured_positions(c.mechanism, c.p, phi)
    for key, position, (what, is_angle), origin in zip(("s", "s2"), measured, MEASURED[c.mechanism],
                                                        (origin_of_s(c.mechanism, c.p), 0.0)):
        offset = values[key] - position - origin
        if is_angle:
            offset = np.angle(np.exp(1j * offset))
        # rounding of positions of size ≤ 5, as for the link lengths
        assert np.max(np.abs(offset)) < 1e-12 * (1 + np.max(np.abs(position))), f"{c.id}: {key} is not the {what}"


def test_slider_travel_is_zero_at_the_inner_dead_centre_and_the_stroke_at_the_outer():
    mech = MECHANISMS["slider_crank"]
    for params in ({"l1": 0.1, "l2": 0.3}, {"l1": 0.1, "l2": 0.16, "e": -0.05}, {"l1": 0.1, "l2": 0.1052, "e": 0.005}):
        p = mech.check(params)
        inner, outer = (sp for sp in mech.special_positions(p) if sp.kind == "dead_centre")
        s = mech.evaluate(p, np.array([inner.phi, outer.phi]), set()).values["s"]
        travel = mech.evaluate(p, dense_angles("slider_crank", p, 20001), set()).values["s"]
        # 1e-12 m: rounding of positions of size ≤ 0.3 m, as for the link lengths
        assert abs(s[0]) < 1e-12 and abs(s[1] - outer.value) < 1e-12
        assert travel.min() > -1e-12 and travel.max() < outer.value + 1e-12


@pytest.mark.parametrize("c", CASES, ids=CASE_IDS)
def test_motion_repeats_after_one_kinematic_cycle(c):
    mech = MECHANISMS[c.mechanism]
    phi = c.angles()
    later = phi + mech.cycle(c.p)
    now, then = measured_positions(c.mechanism, c.p, phi), measured_positions(c.mechanism, c.p, later)
    for a, b, (what, is_angle) in zip(now, then, MEASURED[c.mechanism]):
        change = np.angle(np.exp(1j * (b - a))) if is_angle else b - a   # a full turn of the output counts as 0
        # φ + cycle is rounded by ≈ 1e-15 rad; times |u| ≤ 50 that is far below 1e-9
        assert np.max(np.abs(change)) < 1e-9, f"{c.id}: {what}"
    u_now, u_then = (mech.evaluate(c.p, x, set()).values["u31"] for x in (phi, later))
    assert_allclose(u_then, u_now, rtol=1e-9, atol=1e-9 * np.max(np.abs(u_now)))


# --- change points: passing through without limiter, rebounding with it --------------------------

SCHEMES = {1: dict(l0=2, l1=1, l2=4, l3=3, assembly=1), 2: dict(l0=2, l1=1, l2=3, l3=4, assembly=-1),
           3: dict(l0=4, l1=1, l2=3, l3=2, assembly=1)}


@pytest.mark.parametrize("scheme", SCHEMES)
def test_without_limiter_the_rocker_passes_the_change_point_with_continuous_u31(scheme):
    mech = MECHANISMS["four_bar"]
    p = mech.check(SCHEMES[scheme] | {"limiter": 0})
    passage = mech.change_point(p) + 2 * np.pi
    delta = 1e-7
    u31 = mech.evaluate(p, passage + np.array([-delta, 0.0, delta]), set()).values["u31"]
    slope = np.max(np.abs(mech.evaluate(p, passage + np.linspace(-delta, delta, 21), set()).values["du31"]))
    # mean-value theorem: a continuous u₃₁ moves by at most δ·max|u′₃₁| (+ rounding); a jump would be O(1)
    assert np.max(np.abs(u31 - u31[1])) <= delta * slope * 1.01 + 1e-12


@pytest.mark.parametrize("scheme", SCHEMES)
def test_without_limiter_the_rocker_leaves_the_change_point_as_it_arrived_mirrored_in_time(scheme):
    """u₃₁(passage + x) = u₃₁(passage − x): the passage is symmetric (mirror image of the arrival reversed)."""
    mech = MECHANISMS["four_bar"]
    p = mech.check(SCHEMES[scheme] | {"limiter": 0})
    passage = mech.change_point(p) + 2 * np.pi
    x = np.array([1e-4, 0.01, 0.3, 1.0, 2.5])
    after, before = (mech.evaluate(p, passage + sign * x, set()).values["u31"] for sign in (1, -1))
    assert_allclose(after, before, rtol=0, atol=1e-12)   # rounding of O(1) values


@pytest.mark.parametrize("scheme", SCHEMES)
def test_with_limiter_u31_jumps_at_the_change_point_while_the_rocker_position_is_continuous(scheme):
    mech = MECHANISMS["four_bar"]
    p = mech.check(SCHEMES[scheme] | {"limiter": 1})
    cp = mech.change_point(p)
    before_after = cp + 2 * np.pi + np.array([-1e-9, 0.0])
    u31 = mech.evaluate(p, before_after, set()).values["u31"]
    free = mech.check(SCHEMES[scheme] | {"limiter": 0})
    arriving, leaving = mech.evaluate(free, np.array([cp + 2 * np.pi, cp]), set()).values["u31"]
    # the rocker arrives with the no-limiter speed and leaves as at the start of the cycle: a jump of O(1)
    assert u31[0] == pytest.approx(arriving, abs=1e-6) and u31[1] == pytest.approx(leaving, abs=1e-12)
    assert abs(leaving - arriving) > 0.5
    rocker, _ = measured_positions("four_bar", p, before_after)
    assert abs(np.angle(np.exp(1j * (rocker[1] - rocker[0])))) < 1e-6   # |u₃₁|·1e-9 rad


def test_crank_pins_follow_the_stated_sign_conventions():
    """Crank-slider and sine: A = (−l₁cos φ, l₁sin φ) (φ clockwise from −x); four-bar: B = l₁(cos φ, sin φ)."""
    phi = np.linspace(0, 2 * np.pi, 13)
    for mechanism in ("sine", "slider_crank"):
        j = joints(mechanism, MECHANISMS[mechanism].check({"l1": 0.1}), phi)
        assert_allclose(j["A"], 0.1 * np.c_[-np.cos(phi), np.sin(phi)], atol=1e-15)
    j = joints("four_bar", MECHANISMS["four_bar"].check({"l1": 0.1}), phi)
    assert_allclose(j["B"], 0.1 * np.c_[np.cos(phi), np.sin(phi)], atol=1e-15)
    j = joints("slotted_link", MECHANISMS["slotted_link"].check({"l1": 0.1}), phi)
    assert_allclose(j["B"], 0.1 * np.c_[np.sin(phi), np.cos(phi)], atol=1e-15)


# --- property-based layer: random valid linkages --------------------------------------------------

PROPERTY_SETTINGS = settings(max_examples=30, deadline=None, derandomize=True)
PROPERTY_ANGLES = np.linspace(0.0, 2 * np.pi, 37)[:-1] + 0.0071


def assert_random_linkage_is_consistent(mechanism: str, params: dict[str, float], h: float) -> None:
    mech = MECHANISMS[mechanism]
    p = mech.check(params)
    phi = PROPERTY_ANGLES * mech.cycle(p) / (2 * np.pi)
    closed = mech.evaluate(p, phi, set()).values
    numeric = fd_transfer_functions(mechanism, p, phi, h)
    for name in TRANSFER_FUNCTIONS:
        scale = max(np.max(np.abs(closed[name])), natural_scale(mechanism, p, name))
        assert_allclose(numeric[name], closed[name], rtol=FD_RTOL, atol=FD_RTOL * scale,
                                   err_msg=f"{mechanism} {params}: {name}")
    assert_links_keep_their_lengths(mechanism, p, joints(mechanism, p, phi), f"{mechanism} {params}")


lengths = st.floats(0.02, 1.0)


@PROPERTY_SETTINGS
@given(l1=lengths, lam=st.floats(1.1, 8.0), offset=st.floats(-0.9, 0.9), a2=st.floats(0.0, 1.0))
def test_random_crank_sliders_have_consistent_transfer_functions(l1, lam, offset, a2):
    # offset as a fraction of the largest admissible |e| < l₂ − l₁, so every draw can be assembled
    e = offset * min((lam - 1) * l1, 1.0)   # the scene offers |e| ≤ 1 m
    assert_random_linkage_is_consistent("slider_crank", {"l1": l1, "l2": lam * l1, "e": e, "a2": a2}, h=1e-3)


@PROPERTY_SETTINGS
@given(l1=lengths, lam=st.floats(0.05, 10.0).filter(lambda x: abs(x - 1) > 0.05))
def test_random_slotted_links_have_consistent_transfer_functions(l1, lam):
    # the sharpest feature has width ≈ |1 − λ| ≥ 0.05 rad: h = 2.5e-4 resolves it (see FD_RTOL)
    assert_random_linkage_is_consistent("slotted_link", {"l0": lam * l1, "l1": l1}, h=2.5e-4)


@PROPERTY_SETTINGS
@given(l0=lengths, l1=lengths, reach=st.floats(0.05, 1.5), spread=st.floats(-0.9, 0.9),
       assembly=st.sampled_from([1, -1]), a2=st.floats(0.0, 1.0))
def test_random_fully_rotating_four_bars_have_consistent_transfer_functions(l0, l1, reach, spread, assembly, a2):
    # l₂ + l₃ = (1 + reach)(l₀ + l₁) and l₂ − l₃ = spread·|l₀ − l₁| make P₀ > 0 and Q₀ > 0: the crank turns fully
    if abs(l0 - l1) < 0.05 * max(l0, l1):
        l0 = l1 * 1.5   # keep the crank pin away from the rocker pivot (l₀ = l₁ is rejected)
    total, difference = (1 + reach) * (l0 + l1), spread * abs(l0 - l1)
    params = {"l0": l0, "l1": l1, "l2": (total + difference) / 2, "l3": (total - difference) / 2,
              "assembly": assembly, "a2": a2}
    mu = MECHANISMS["four_bar"].describe(MECHANISMS["four_bar"].check(params))["min_transmission_angle"]
    # resolve the sharpest feature, whose width is about the smallest transmission angle (see FD_RTOL)
    assert_random_linkage_is_consistent("four_bar", params, h=float(np.clip(mu / 20, 1e-4, 1e-3)))
