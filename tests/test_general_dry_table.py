"""The dry-friction moment between the kinks as piecewise Chebyshev interpolants (server/core/dynamics/kink_table.py)
against the friction solve itself at every angle (GeneralMachine.solved), and the equation of motion's error
estimates with the interpolated moment against runs that solve the moment at every node.

Tolerances: the table declares, per segment, the measured error of the interpolant of half its degree at the
points it leaves out, below TOLERANCE (the friction solve's ε_R = 1e-12) of the largest |M_T|; the solved moment
the test compares with carries the solve's own error of that order, so an interpolated value may differ from it
by the table's estimate plus one ε_R of the scale.  Where a segment locks (or its interpolant does not settle),
the table leaves it to the solve: there the values, the NaN where it locks and the sentences must be those of
the solve exactly.
"""
from __future__ import annotations

import numpy as np
import pytest

from server.api.endpoints import compute, machine
from server.api.schemas_dynamics import MotionRequest
from server.core.dynamics import general_machine
from server.core.dynamics.general_machine import GeneralMachine, dry_notices
from server.core.dynamics.integrator import KINK_SIDE
from server.core.dynamics.motion import steady_cycle
from server.core.kinetostatics.groups.dry_moment import TOLERANCE as DRY_TOLERANCE
TOLERANCE = DRY_TOLERANCE     # the table's: the solve's own ε_R
from server.core.structure.presets import presets

from test_error_estimates import ROUNDING, true_error
from test_general_dry_memo import rough_machine
from test_general_dynamics_machine import SIX_BARS, preset_body


@pytest.fixture(autouse=True)
def no_work_bound(monkeypatch):
    """The friction solve's work bound is wall clock (DRY_BUDGET_S): on a loaded machine the references' solves of
    thousands of angles could reach it and leave angles unsolved; the comparisons here must not depend on that."""
    monkeypatch.setattr(general_machine, "DRY_BUDGET_S", None)


def dry_solved(machine: GeneralMachine, phi: np.ndarray) -> tuple[np.ndarray, list]:
    """M_T and its notices solved at every angle (no table)."""
    moment, locked, unsettled, _ = machine.solved(phi)
    return moment, dry_notices(phi, locked, unsettled)


def solved_everywhere(monkeypatch) -> None:
    """The reference: the machine's M_T solved at every node (no table)."""
    monkeypatch.setattr(GeneralMachine, "dry_moment", lambda self, phi: dry_solved(self, phi))


@pytest.mark.parametrize("f, r, everywhere", [(0.1, 0.02, True), (0.3, 0.05, True), (0.6, 0.1, False)])
def test_table_reproduces_the_solved_moment(f, r, everywhere):
    """f = 0.1 and 0.3: every segment interpolated; f = 0.6: some segments near self-locking left to the solve."""
    built = rough_machine(f, r)
    table = built.dry_table()
    assert table.error <= TOLERANCE * table.scale and table.scale > 0
    assert all(c is not None for c in table.coefficients) == everywhere
    assert table.evaluated < 600                                   # the point of it: a few hundred solves a turn
    kinks = np.asarray(built.kinks())
    phi = np.concatenate([np.random.default_rng(7).uniform(-1.0, 2 * np.pi + 1.0, 3000),    # any turn
                          kinks + KINK_SIDE, kinks - KINK_SIDE, kinks])
    (values,), direct = table.at(phi)
    reference = built.solved(phi)[0]
    at_kinks = np.isin(phi, kinks)
    interpolated = ~direct & ~at_kinks
    assert interpolated.sum() > 2000 and np.isnan(values[direct]).all()
    kept = ~direct & at_kinks                          # the kinks' values solved as the table was built, kept
    assert np.array_equal(direct[-kinks.size:], np.isnan(reference[-kinks.size:]))   # solved there where none is
    assert kept.sum() >= kinks.size - 2 and np.array_equal(values[kept], reference[kept])
    assert np.isfinite(reference[interpolated]).all()
    error = np.abs(values[interpolated] - reference[interpolated])
    assert error.max() <= table.error + DRY_TOLERANCE * table.scale, (error.max(), table.error, table.scale)


@pytest.mark.parametrize("name", SIX_BARS)
def test_every_presets_table_reproduces_the_solved_moment(name):
    """Every six-bar preset with f = 0.1 in every pair: each segment interpolated, to its estimate."""
    dynamics = presets()[name]["dynamics"]
    body = preset_body(name, motor=dynamics["motor"], outputs=["steady"])
    body["masses"] = body["masses"] | {"friction": 0.1, "pair_radius": 0.02}
    built = machine(MotionRequest(**body))
    table = built.dry_table()
    assert all(c is not None for c in table.coefficients) and table.error <= TOLERANCE * table.scale
    phi = np.random.default_rng(11).uniform(0, 2 * np.pi, 2000)
    (values,), direct = table.at(phi)
    assert not direct.any()
    assert np.abs(values - built.solved(phi)[0]).max() <= table.error + DRY_TOLERANCE * table.scale


@pytest.mark.parametrize("f, r", [(0.6, 0.1), (2.0, 0.2)])
def test_locking_is_the_solves(monkeypatch, f, r):
    """Near and at self-locking the tables with the table equal those solved at every node: the same NaN, the
    same sentences, the values to the table's estimate."""
    built = rough_machine(f, r)
    kinks = np.asarray(built.kinks())
    phi = np.sort(np.concatenate([np.linspace(0, 2 * np.pi, 2049), kinks + KINK_SIDE, kinks - KINK_SIDE]))
    tables = built.tables(phi)
    table = built.dry_table()
    with monkeypatch.context() as patch:
        solved_everywhere(patch)
        reference = rough_machine(f, r).tables(phi)
    assert np.array_equal(np.isnan(tables.dry), np.isnan(reference.dry))
    assert [(n.code, n.context) for n in tables.notices] == [(n.code, n.context) for n in reference.notices]
    assert any(n.code == "group_self_locking" for n in tables.notices)
    finite = np.isfinite(reference.dry)
    assert np.abs(tables.dry[finite] - reference.dry[finite]).max() <= table.error + DRY_TOLERANCE * table.scale


@pytest.mark.parametrize("rtol", [1e-7, 1e-9])
def test_the_steady_cycles_estimate_holds_against_the_solved_moment(monkeypatch, rtol):
    """The steady cycle with the table against the run that solves M_T at every node at 1/1000 of the tolerance
    and of the estimate (nested nodes: the kinks are nodes of both): as tests/test_general_dry_friction.py,
    the true error of ω and t is at most 3× the estimate and 2× rtol."""
    built = rough_machine(0.1, 0.02)
    result = steady_cycle(built, rtol)
    estimate = result.numerics.error_estimate
    with monkeypatch.context() as patch:
        solved_everywhere(patch)
        reference = steady_cycle(rough_machine(0.1, 0.02), max(min(rtol, estimate) / 1000, 3e-13))
    assert reference.numerics.steps >= 4 * result.numerics.steps
    error = true_error(result.steady, reference.steady)
    assert error <= 3 * estimate + ROUNDING and error <= 2 * rtol, (error, estimate)


def test_startup_and_flywheel_with_the_table_against_the_solved_moment(monkeypatch):
    """The start-up and the flywheel's inertias with the table equal those with M_T solved at every node, to
    a small share of their own error estimates (the table's error, ≤ 1e-12 of |M_T|, is far below the
    integrators')."""
    dynamics = presets()["shaping_machine"]["dynamics"]
    masses = {"masses": dynamics["masses"] | {"friction": 0.1, "pair_radius": 0.02}}
    motion = preset_body("shaping_machine", motor=dynamics["motor"], outputs=["steady", "startup"]) | masses
    flywheel = preset_body("shaping_machine", **dynamics["flywheel"]) | masses
    answers = [compute("motion", motion), compute("flywheel", flywheel)]
    with monkeypatch.context() as patch:
        solved_everywhere(patch)
        references = [compute("motion", motion), compute("flywheel", flywheel)]
    start, start_ref = answers[0]["startup"], references[0]["startup"]
    assert len(start["omega"]) == len(start_ref["omega"])
    change = np.max(np.abs(np.subtract(start["omega"], start_ref["omega"]))) / np.max(start_ref["omega"])
    assert change <= 0.01 * start["numerics"]["error_estimate"], (change, start["numerics"]["error_estimate"])
    for row, reference in zip(answers[1]["methods"], references[1]["methods"]):
        change = abs(row["inertia"] / reference["inertia"] - 1)
        assert change <= 0.01 * answers[1]["numerics"]["error_estimate"], (row["method"], change)


def test_a_kept_setup_with_new_friction_is_a_fresh_one():
    """The normal forces' scan keeps its setup across f (analysis.with_friction): with the new f and r it is the
    fresh setup's, bitwise, and so are the signs it proves; a change of which pairs are rough is refused."""
    from dataclasses import replace
    from server.core.kinetostatics.groups.analysis import setup, with_friction
    from server.core.kinetostatics.groups.dry_moment import proved_signs
    from server.core.kinetostatics.groups.friction import PairFriction
    from server.core.structure.compose import compose
    built = rough_machine(0.1, 0.02)
    comp = compose(built.linkage.linkage, np.linspace(0, 2 * np.pi, 513))
    kept = setup(built.linkage, comp, built.masses, 0.0, 0.0)
    for f, r, pairs in [(0.4, 0.05, {}), (0.05, 0.01, {"A": PairFriction(0.3, 0.04)})]:
        masses = replace(built.masses, friction=f, pair_radius=r)
        fresh = setup(built.linkage, comp, masses, 0.0, 0.0, pairs)
        moved = with_friction(kept, masses, pairs)
        for name in ("base", "lever", "coefficient"):
            assert np.array_equal(getattr(moved.fmap, name), getattr(fresh.fmap, name)), name
        assert all(np.array_equal(a, b) for a, b in zip(proved_signs(moved), proved_signs(fresh)))
    with pytest.raises(ValueError):
        with_friction(kept, built.masses, {"A": PairFriction(0.0, 0.0)})
