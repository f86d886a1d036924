"""Special positions of a general mechanism against closed forms that do not use the group modules.

- the four-bar preset: the smallest |sin μ| of its RRR group equals sin of the smallest transmission angle of the
  closed-form module (cos μ = (l₂² + l₃² − d²)/(2l₂l₃), extreme at φ = 0 and π, both on the 0.5° grid: 1e-12);
- output reversals (Newton on the closed-form analogs): the crank-slider's dead centres and the four-bar's
  rocker extremes of the closed-form modules, to 1e-9 rad and 1e-12 m or rad;
- the shaping machine with a rod too short to reach the ram's guide everywhere: the limits of assembly reported
  lie within one grid step (0.5°) of the roots of |y_D(φ) − y_guide| = BC, with y_D from the lever's line
  through C and the crank pin A (y_D = y_C + CD·(y_A − y_C)/|A − C|), found by brentq.
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
    assert max(abs(r - p) for r, p in zip(roots, limits)) <= grid[1]


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


def test_a_dead_position_on_the_grid_is_said_in_words():
    """A change-point four-bar (l₀ + l₁ = l₂ + l₃): at φ = π all joints line up (μ = 0)."""
    from server.core.mechanisms.general import compute_general
    linkage = copy.deepcopy(presets()["four_bar"]["linkage"])
    linkage["groups"][0]["lengths"] = [0.3, 0.2]
    result = compute_general(linkage, ["angles_d1"], n=361)
    assert [n.code for n in result.warnings] == ["group_dead_position"]
    assert result.warnings[0].context["phi"] == 180.0 and result.warnings[0].context["mu"] < 1e-5
