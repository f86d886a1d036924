"""Special positions of a general mechanism against closed forms that do not use the group modules.

- the four-bar preset: the smallest |sin μ| of its RRR group equals sin of the smallest transmission angle of the
  closed-form module (cos μ = (l₂² + l₃² − d²)/(2l₂l₃), extreme at φ = 0 and π, both on the 0.5° grid: 1e-12);
- output reversals (Newton on the closed-form analogs): the crank-slider's dead centres and the four-bar's
  rocker extremes of the closed-form modules, to 1e-9 rad and 1e-12 m or rad;
- limits of assembly, exact (bisection of the grid's step): a four-bar whose crank cannot turn against the
  closed form of its RRR group's flattened triangle, |O₁A| = l_AB + l_BO₁ with |O₁A|² = r² + d² − 2rd cos φ
  (and the limits in the sentence of the table's warning); a crank-slider with its guide offset against
  r sin φ − e = ±l; the shaping machine with a rod too short to reach the ram's guide everywhere against the
  roots of |y_D(φ) − y_guide| = BC, with y_D from the lever's line through C and the crank pin A
  (y_D = y_C + CD·(y_A − y_C)/|A − C|), found by brentq.  All to 1e-12 rad: the closed forms' own round-off
  (arccos near ±1 loses digits as √ε·… only at a tangent, where no limit is crossed).
"""
import copy

import numpy as np
from scipy.optimize import brentq

from server.core.mechanisms import MECHANISMS
from server.core.mechanisms.general import GeneralMechanism
from server.core.structure.presets import presets


def test_four_bar_smallest_transmission_angle():
    special = GeneralMechanism(presets()["four_bar"]["linkage"]).special_positions({})
    smallest = [sp for sp in special if sp.kind == "smallest_determinant"]
    mu = MECHANISMS["four_bar"].describe(MECHANISMS["four_bar"].check({}))["min_transmission_angle"]
    assert len(smallest) == 1 and abs(smallest[0].value - np.sin(mu)) <= 1e-12
    assert not [sp for sp in special if sp.kind in ("dead_position", "limit_of_assembly")]


def test_shaping_machine_limits_of_assembly():
    linkage = copy.deepcopy(presets()["shaping_machine"]["linkage"])
    rod = 0.01
    linkage["groups"][1]["length"] = rod
    special = GeneralMechanism(linkage).special_positions({})
    limits = sorted(sp.phi for sp in special if sp.kind == "limit_of_assembly")

    def gap(phi):
        a = 0.1 * np.exp(1j * phi)
        c = -0.3j
        y_d = c.imag + 0.55 * (a - c).imag / abs(a - c)
        return abs(y_d - 0.25) - rod
    grid = np.linspace(0, 2 * np.pi, 721)
    values = np.array([gap(p) for p in grid])
    roots = [brentq(gap, grid[k], grid[k + 1], xtol=1e-14)
             for k in np.flatnonzero(np.sign(values[:-1]) != np.sign(values[1:]))]
    assert len(roots) == len(limits) == 4
    assert max(abs(r - p) for r, p in zip(roots, limits)) <= 1e-12


def four_bar(crank: float) -> dict:
    """The four-bar preset (O at the origin, O₁ at d = 0.4 m, coupler 0.35 m, rocker 0.3 m) with its crank."""
    linkage = copy.deepcopy(presets()["four_bar"]["linkage"])
    linkage["input"]["length"] = crank
    return linkage


def test_four_bar_limits_of_assembly_against_the_flattened_triangle():
    r, d, coupler, rocker = 0.3, 0.4, 0.35, 0.3
    special = GeneralMechanism(four_bar(r)).special_positions({})
    limits = [(sp.phi, sp.assembles_after, sp.name) for sp in special if sp.kind == "limit_of_assembly"]
    # |O₁A| = coupler + rocker: cos φ = (r² + d² − (l_AB + l_BO₁)²)/(2rd), the crank past it on both sides
    stretched = np.arccos((r**2 + d**2 - (coupler + rocker) ** 2) / (2 * r * d))
    assert len(limits) == 2
    (first, after_first, name), (second, after_second, _) = limits
    assert abs(first - stretched) <= 1e-12 and abs(second - (2 * np.pi - stretched)) <= 1e-12
    assert (after_first, after_second, name) == (False, True, "II₁(2,3)")     # apart between them
    from server.core.mechanisms.general import compute_general
    warning = next(n for n in compute_general(four_bar(r), ["joints"], n=361).warnings
                   if n.code == "group_cannot_assemble")
    assert warning.context["group"] == "II₁(2,3)"
    assert np.allclose(warning.context["ranges"], [[np.degrees(stretched), 360 - np.degrees(stretched)]], atol=1e-10)


def test_crank_slider_limits_of_assembly_against_the_offset():
    linkage = copy.deepcopy(presets()["slider_crank"]["linkage"])
    r, rod, e = linkage["input"]["length"], 0.15, 0.2            # the guide 0.2 m above O: the rod reaches it only
    linkage["groups"][0]["length"] = rod                        # while the pin is higher than e − l = 0.05 m
    linkage["frame"]["guides"][linkage["groups"][0]["guide"]]["through"] = [0, e]
    special = GeneralMechanism(linkage).special_positions({})
    limits = sorted(sp.phi for sp in special if sp.kind == "limit_of_assembly")
    low = np.arcsin((e - rod) / r)                              # r sin φ = e − l: the rod ⊥ the guide
    assert len(limits) == 2
    assert abs(limits[0] - low) <= 1e-12 and abs(limits[1] - (np.pi - low)) <= 1e-12


def reversals(name, what):
    special = GeneralMechanism(presets()[name]["linkage"]).special_positions({})
    return sorted((sp.phi, sp.value) for sp in special if sp.kind == "output_reversal" and what in sp.description)


def test_slider_dead_centres():
    module = MECHANISMS["slider_crank"]
    dead = sorted((sp.phi, sp.value) for sp in module.special_positions(module.check({})))
    found = reversals("slider_crank", "slide B/x")
    x_min = 0.2                                   # l₂ − l₁: the slider's travel s is counted from there
    assert len(found) == len(dead) == 2
    for (phi, x), (phi_ref, s_ref) in zip(found, dead):
        assert abs(phi - phi_ref) <= 1e-9 and abs(x - x_min - s_ref) <= 1e-12


def test_rocker_extremes():
    module = MECHANISMS["four_bar"]
    extremes = module.rocker_extremes(module.check({}))
    found = reversals("four_bar", "link 3")
    assert len(found) == len(extremes) == 2
    for (phi, theta), (phi_ref, theta_ref) in zip(found, extremes):
        assert abs(phi - phi_ref) <= 1e-9 and abs(theta - theta_ref) <= 1e-12


def test_a_change_point_on_the_grid_is_said_in_words():
    """A change-point four-bar (l₀ + l₁ = l₂ + l₃): at φ = π all joints line up (μ = 0) while the crank passes,
    a change point, not a dead position (the continuing motion's analogs stay bounded; test_change_points.py);
    it is passed once a turn, which is said too."""
    from server.core.mechanisms.general import compute_general
    linkage = copy.deepcopy(presets()["four_bar"]["linkage"])
    linkage["groups"][0]["lengths"] = [0.3, 0.2]
    result = compute_general(linkage, ["angles_d1"], n=361)
    assert [n.code for n in result.warnings] == ["group_change_point", "group_change_point_odd"]
    assert result.warnings[0].context["phi"] == 180.0
