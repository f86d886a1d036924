"""A general machine solves each angle's friction equilibrium once in its life (GeneralMachine.dry keeps them in
its memo): tables asked for angles partly solved before (nested grids, as the steady cycle's levels; a grid on
the kinks' scan, as the flywheel's nodes) equal the dry moment, the locked angles and the normal forces solved
afresh at exactly those angles by kinetostatics/groups/dry_moment.py, to 1e-12 of the moment's scale (the
friction solve's ε_R; each angle's equilibrium does not depend on the other angles solved with it, so in practice
they are equal to the last bit), the normal forces to 1e-12 of the largest one.  With f large enough to lock the
mechanism, the locked angles are the fresh solve's too, and exactly they have no moment and no normal forces
(NaN, sent null): the numbers are compared only where they exist, with a finite tolerance.
"""
from __future__ import annotations

import numpy as np
import pytest

from server.api.endpoints import machine
from server.api.schemas_dynamics import MotionRequest
from server.core.kinetostatics.groups.dry_moment import dry_moment
from server.core.structure.compose import compose
from server.core.structure.presets import presets

from test_general_dynamics_machine import preset_body


def rough_machine(f: float, r: float):
    dynamics = presets()["shaping_machine"]["dynamics"]
    body = preset_body("shaping_machine", motor=dynamics["motor"], outputs=["steady"])
    body["masses"] = body["masses"] | {"friction": f, "pair_radius": r}
    return machine(MotionRequest(**body))


@pytest.mark.parametrize("f, r, locks", [(0.1, 0.02, False), (2.0, 0.2, True)])
def test_angles_solved_before_equal_a_fresh_solve(f, r, locks):
    built = rough_machine(f, r)
    built.tables(np.linspace(0, 2 * np.pi, 49))
    built.normals(np.linspace(0, 2 * np.pi, 97)[::3])
    phi = np.concatenate([np.linspace(0, 2 * np.pi, 97), [1.2345, 4.0]])     # half of it solved before
    moment, notices, normals = built.dry(compose(built.linkage.linkage, phi))
    fresh = dry_moment(built.linkage, compose(built.linkage.linkage, phi), built.masses)
    solved = ~fresh.locked                  # a locked angle has no moment and no normal forces (NaN, sent null)
    assert np.array_equal(np.isnan(moment), ~solved) and np.array_equal(np.isnan(fresh.moment), ~solved)
    assert solved.any() and np.isfinite(fresh.moment[solved]).all()
    scale = np.max(np.abs(fresh.moment[solved]))
    assert scale > 0 and np.max(np.abs(moment[solved] - fresh.moment[solved])) <= 1e-12 * scale
    expected = np.array(fresh.normals)
    assert np.array_equal(normals.shape, expected.shape)
    assert np.array_equal(np.isnan(normals), np.isnan(expected))
    assert np.isfinite(expected[:, solved]).all() and np.isnan(expected[:, ~solved]).all()
    size = np.max(np.abs(expected[:, solved]))          # the largest normal force: a finite, positive scale
    assert size > 0 and np.max(np.abs(normals[:, solved] - expected[:, solved])) <= 1e-12 * size
    assert bool(fresh.locked.any()) == locks and bool(notices) == locks
