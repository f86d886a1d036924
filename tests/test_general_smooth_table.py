"""J, J′, M_useful and S of a general mechanism between its kinks as piecewise Chebyshev interpolants
(GeneralMachine.smooth_table, server/core/dynamics/kink_table.py) against what they are interpolated from: the
linkage composed at the same angles (GeneralMachine.smooth_columns), on every six-bar preset with random masses,
loads and viscous pairs; and the table builder itself on functions known in closed form.

Tolerances: the table declares, per function, the measured error of the interpolant of half the degree at the
points it leaves out plus the coefficients it chops (below SMOOTH_TOLERANCE = 1e-13 of the function's largest
magnitude); the composed values carry their own round-off, a few ulps of that magnitude (≈ 1e-15), so an
interpolated value may differ from them by the estimate plus 1e-14 of the scale.  Values at the kinks are kept
from the build: bitwise the composed ones.  The answers of /motion and /flywheel with the table equal those with
every node composed to 1e-10 (the standard of the general path against the dedicated modules: the table's error,
≤ 1e-13, is far below it).
"""
from __future__ import annotations

import copy

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from server.api.endpoints import compute, machine
from server.api.schemas_dynamics import MotionRequest
from server.core.dynamics import kink_table
from server.core.dynamics.general_machine import SMOOTH_TOLERANCE, GeneralMachine
from server.core.dynamics.integrator import KINK_SIDE
from server.core.dynamics.machine import Tables
from server.core.mechanisms.general import assembly_notices
from server.core.structure.compose import compose
from server.core.structure.presets import presets

from test_general_dynamics_machine import SIX_BARS, agree, preset_body

ROUNDING = 1e-14       # of a function's scale: the composed values' own round-off, with margin


def composed_tables(self: GeneralMachine, phi: np.ndarray) -> Tables:
    """The reference: J, J′, M_useful, S composed at every angle (no table), as the machine did before it."""
    phi = np.asarray(phi, float)
    comp = compose(self.linkage.linkage, phi)
    J, dJ, useful, sliding = self.smooth_columns(phi, comp)
    drive = np.full(phi.shape, self.motor.M0 * self.inertias.gear_ratio) if self.motor.kind == "constant" \
        else np.zeros(phi.shape)
    dry, locking = self.dry_moment(phi)
    return Tables(phi, J, dJ, drive, useful, dry, sliding, locking + assembly_notices(comp))


def check_table(built: GeneralMachine, phi: np.ndarray) -> None:
    table, _ = built.smooth_table()
    scale = table.scale
    assert (table.error <= SMOOTH_TOLERANCE * scale).all(), (table.error, scale)
    kinks = np.asarray(built.kinematic_kinks())
    sided = np.concatenate([kinks + KINK_SIDE, kinks - KINK_SIDE])       # the integrator's nodes beside a kink
    phi = np.concatenate([phi, sided, kinks])
    values, direct = table.at(phi)
    reference = built.smooth_columns(phi)
    assert not direct.any()                               # every segment interpolated, the sided nodes too
    error = np.abs(values - reference)
    assert (error.max(axis=1) <= table.error + ROUNDING * scale).all(), (error.max(axis=1), table.error, scale)
    assert np.array_equal(values[:, -kinks.size:], reference[:, -kinks.size:])       # kept from the build


@pytest.mark.parametrize("name", SIX_BARS)
def test_every_presets_table_reproduces_the_composed_linkage(name):
    dynamics = presets()[name]["dynamics"]
    built = machine(MotionRequest(**preset_body(name, motor=dynamics["motor"], outputs=["steady"])))
    check_table(built, np.random.default_rng(3).uniform(-1.0, 2 * np.pi + 1.0, 3000))      # any turn


@settings(max_examples=12, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow])     # no dependence on the machine's speed
@given(data=st.data())
def test_random_masses_loads_and_viscous_pairs(data):
    """A preset with its masses, centres and inertias scaled at random, its loads' working forces and k drawn,
    gravity on or off, and viscous friction β in the prismatic pairs (S ≠ 0)."""
    name = data.draw(st.sampled_from(SIX_BARS))
    dynamics = presets()[name]["dynamics"]
    body = preset_body(name, motor=dynamics["motor"], outputs=["steady"])
    masses = copy.deepcopy(body["masses"])
    for link in masses["links"]:
        link["mass"] *= data.draw(st.floats(0.2, 5))
        link["inertia"] = link.get("inertia", 0.0) * data.draw(st.floats(0.2, 5))
        link["centre"] = [c + data.draw(st.floats(-0.05, 0.05)) for c in link.get("centre", [0.0, 0.0])]
    for force in masses.get("forces", []):
        force["working"] = data.draw(st.floats(10, 5000))
        force["k"] = data.draw(st.floats(0, 1))
    masses["gravity"] = data.draw(st.sampled_from([0.0, 9.81]))
    body["masses"] = masses
    body["load"] = body.get("load", {}) | {"beta": data.draw(st.floats(0.1, 50))}
    built = machine(MotionRequest(**body))
    check_table(built, np.random.default_rng(data.draw(st.integers(0, 99))).uniform(0, 2 * np.pi, 1000))
    slides = compose(built.linkage.linkage, np.zeros(1)).slides
    assert (built.smooth_table()[0].scale[3] > 0) == bool(slides)       # S(φ) is tabulated too, where it is


def motion_bodies(name: str) -> tuple[dict, dict]:
    dynamics = presets()[name]["dynamics"]
    return (preset_body(name, motor=dynamics["motor"], outputs=["steady", "startup"]),
            preset_body(name, **dynamics["flywheel"]))


@pytest.mark.parametrize("name", ["shaping_machine", "v_engine", "whitworth"])
def test_answers_with_the_table_equal_those_composed_at_every_node(monkeypatch, name):
    motion, flywheel = motion_bodies(name)
    answers = [compute("motion", motion), compute("flywheel", flywheel)]
    with monkeypatch.context() as patch:
        patch.setattr(GeneralMachine, "tables", composed_tables)
        references = [compute("motion", motion), compute("flywheel", flywheel)]
    for answer, reference in zip(answers, references):
        agree(answer, reference)


def test_builder_on_closed_forms():
    """f₁ = sin 3φ + [φ > 2] (a jump at the kink 2), f₂ = exp(cos φ), f₃ = |φ − 4.5| (a corner nobody named),
    f₄ = NaN on (5.5, 5.6) (a value that does not exist): the segments with f₃'s corner and f₄'s gap are left to
    direct evaluation, the others interpolated within their estimates; the kinks' values are kept; within
    KINK_SIDE / 2 of a kink (not on it) is direct, the sided nodes KINK_SIDE inside are not."""
    def functions(phi):
        psi = np.mod(phi, 2 * np.pi)
        gap = np.where((psi > 5.5) & (psi < 5.6), np.nan, 1.0)
        return np.stack([np.sin(3 * psi) + (psi > 2.0), np.exp(np.cos(psi)), np.abs(psi - 4.5), gap])

    kinks = np.array([2.0, 4.0, 5.0])
    table = kink_table.build(functions, kinks, 1e-13, (32, 64, 128))
    interpolated = [c is not None for c in table.coefficients]
    assert interpolated == [True, True, False, False]             # [0, 2], [2, 4]; [4, 5] corner; [5, 2π] gap
    assert (table.error <= 1e-13 * table.scale).all()
    phi = np.random.default_rng(5).uniform(0, 4.0, 2000)
    values, direct = table.at(phi)
    assert not direct.any()
    error = np.abs(values - functions(phi)).max(axis=1)
    assert (error <= table.error + 1e-15 * table.scale).all(), (error, table.error)
    values, direct = table.at(np.array([4.3, 5.2, 2.0, 2.0 + KINK_SIDE, 2.0 - KINK_SIDE, 2.0 + 0.25 * KINK_SIDE]))
    assert direct.tolist() == [True, True, False, False, False, True]
    assert np.array_equal(values[:, 2], functions(np.array([2.0]))[:, 0])
    beside = functions(np.array([2.0 + KINK_SIDE, 2.0 - KINK_SIDE]))[0]       # each side its own value:
    assert values[0, 3:5] == pytest.approx(beside, abs=1e-12) and beside[0] - beside[1] == pytest.approx(1.0)


def test_chop_drops_a_tail_no_larger_than_allowed():
    c = 2.0 ** -np.arange(40)
    kept, dropped = kink_table.chop(c, 1e-6)
    assert dropped == pytest.approx(np.abs(c[kept.size:]).sum()) and dropped <= 1e-6
    assert np.abs(c[kept.size - 1:]).sum() > 1e-6                        # the longest such tail
    assert kink_table.chop(np.zeros(9), 0.0)[0].size == 1                 # c₀ stays


def plain_at(table: kink_table.KinkTable, phi: np.ndarray) -> np.ndarray:
    """KinkTable.at in plain numpy (the reference of the compiled ``evaluate``): numpy's chebval on each angle's
    segment, NaN within KINK_SIDE / 2 of an inner kink around the turn (off the kink) or on a segment without
    interpolants, the kept values on a given kink."""
    turn = 2 * np.pi
    out = np.full((table.kink_values.shape[0], phi.size), np.nan)
    inner = table.edges[table.sided]
    for i, angle in enumerate(phi):
        psi = angle % turn
        k = min(max(int(np.searchsorted(table.edges, psi, side="right")) - 1, 0), len(table.coefficients) - 1)
        gaps = np.abs(psi - inner)
        near = bool((np.minimum(gaps, turn - gaps) < 0.5 * KINK_SIDE).any())
        if not near and table.coefficients[k] is not None:
            t = (2 * psi - table.low[k] - table.high[k]) / (table.high[k] - table.low[k])
            out[:, i] = [np.polynomial.chebyshev.chebval(t, c) for c in table.coefficients[k]]
        if angle in table.kinks:
            out[:, i] = table.kink_values[:, list(table.kinks).index(angle)]
    return out


def test_compiled_evaluation_equals_the_plain_reference():
    """Random angles over three turns (negative ones too), the kinks ± KINK_SIDE·{0.25, 0.5, 1} and a kink near
    0 (its neighbourhood across the turn's end): the compiled evaluation equals numpy's chebval to 1e-14 of each
    function's scale (Clenshaw's and chebval's roundings differ), NaN exactly where the reference has NaN."""
    def functions(phi):
        psi = np.mod(phi, 2 * np.pi)
        return np.stack([np.sin(3 * psi) + (psi > 2.0), np.exp(np.cos(psi)), np.abs(psi - 4.5)])

    kinks = np.array([1e-4, 2.0, 4.0, 5.0])
    table = kink_table.build(functions, kinks, 1e-13, (32, 64, 128))
    offsets = KINK_SIDE * np.array([-1, -0.5, -0.25, 0, 0.25, 0.5, 1])
    phi = np.concatenate([np.random.default_rng(7).uniform(-2 * np.pi, 4 * np.pi, 3000),
                          (kinks[:, None] + offsets).ravel(), kinks, [0.0, 2 * np.pi - 1e-9]])
    values, direct = table.at(phi)
    reference = plain_at(table, phi)
    assert np.array_equal(np.isnan(values), np.isnan(reference)) and np.array_equal(direct, np.isnan(reference).any(0))
    finite = ~np.isnan(reference)
    assert (np.abs(values - reference)[finite] <= 1e-14 * np.repeat(table.scale[:, None], phi.size, 1)[finite]).all()
