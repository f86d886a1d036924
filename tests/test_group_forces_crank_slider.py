"""The crank-slider through the general path (the preset content/mechanisms/slider_crank.json, groups I(0,1) →
II₂(2,3)) against today's dedicated kinetostatics (server/core/kinetostatics/crank_slider.py, itself checked
against fsolve and the closed form in tests/test_friction_equilibrium.py): reactions R₁₂, R₂₃, N, R₄₁, the
balancing moment, the friction loads and the table of approximations, to 1e-10 relative, with and without
friction, up to where the slider locks (the same angles must lock).  Both solve the same equations to
ε_R = 1e-12, so they agree to round-off (~1e-15).  The grid avoids the exact dead centres and φ = 90°, where a
slide or a relative rotation vanishes to round-off and each code takes the friction's (and the piston load's)
sense from the sign of a round-off number.
"""
import numpy as np
import pytest

from server.core.kinetostatics import crank_slider as cs
from server.core.kinetostatics.groups.analysis import analyse
from server.core.kinetostatics.groups.friction import PairFriction
from server.core.mechanisms import MECHANISMS
from server.core.mechanisms.general import GeneralMechanism
from server.core.structure.masses import LinkMass, MassModel, SliderForce
from server.core.structure.presets import presets

PHI = np.linspace(0, 2 * np.pi, 361) + 0.0123


def general(loads: cs.Loads, pairs: cs.Pairs, l2: float = 0.3):
    raw = presets()["slider_crank"]["linkage"]
    raw = {**raw, "groups": [{**raw["groups"][0], "length": l2, "points": {"S2": {"link": 2, "along": 0.32 * l2}}}]}
    model = MassModel((LinkMass(1, 0.0, (0.0, 0.0), loads.J1), LinkMass(2, loads.m2, (0.32 * l2, 0.0), loads.J_S2),
                       LinkMass(3, loads.m3)), forces=(SliderForce("B", loads.force, loads.return_factor),))
    friction = {"O": PairFriction(pairs.f14, pairs.r14), "A": PairFriction(pairs.f12, pairs.r12),
                "B": PairFriction(pairs.f23, pairs.r23), "x": PairFriction(pairs.f34)}
    return analyse(GeneralMechanism(raw), model, PHI, loads.omega, loads.epsilon, 1e-12, friction)


@pytest.mark.parametrize("l2, pairs, locks", [
    (0.3, cs.Pairs(), False),
    (0.3, cs.Pairs(f14=0.1, f12=0.12, f23=0.15, f34=0.2), False),
    (0.3, cs.Pairs(f14=0.05, f12=0.3, f23=0.3, f34=2.0, r12=0.03, r23=0.02), False),
    (0.13, cs.Pairs(f14=0.1, f12=0.12, f23=0.15, f34=0.9), True),
])
def test_crank_slider_agrees_with_dedicated(l2, pairs, locks):
    loads = cs.Loads(m2=2.0, J_S2=0.03, m3=1.5, J1=0.2, omega=30.0, epsilon=5.0, force=800.0, return_factor=0.3)
    params = MECHANISMS["slider_crank"].check({"l1": 0.1, "l2": l2, "e": 0.0, "a2": 0.32})
    dedicated = cs.analyse(params, loads, pairs, PHI, 1e-12)
    result = general(loads, pairs, l2)
    assert np.array_equal(result.locked, np.isnan(dedicated.balancing_moment))
    assert result.locked.any() == locks
    free = ~result.locked
    x = result.solution.unknowns[0]
    d = dedicated.solution
    scale = np.abs(d.R12[free]).max()
    close = lambda a, b: np.abs(a - b)[free].max() <= 1e-10 * scale
    assert close(x[:, 0:2], d.R12) and close(x[:, 2:4], d.R23) and close(x[:, 4], d.N)
    R01 = np.stack([result.solution.R01.real, result.solution.R01.imag], 1)
    assert close(R01, dedicated.R41)
    moment = np.abs(dedicated.balancing_moment[free]).max()
    assert np.abs(result.solution.balancing - dedicated.balancing_moment)[free].max() <= 1e-10 * moment
    # the friction loads: A on the rod (−), B on the slider, the guide on the slider, O on the crank
    z = result.solution.friction
    assert np.abs(np.abs(z[0]) - d.friction["M_A"])[free].max() <= 1e-10 * moment
    assert np.abs(np.abs(z[1]) - d.friction["M_B"])[free].max() <= 1e-10 * moment
    assert np.abs(z[2] - d.friction["F34"])[free].max() <= 1e-10 * scale
    assert np.abs(np.abs(z[3]) - d.friction["M_O"])[free].max() <= 1e-10 * moment
    # the table of approximations row by row where neither locks (its length may differ by a row or two: the
    # dedicated table stops on the change of R₁₂ alone, this one on the change of every reaction)
    rows = list(zip(result.approximations, dedicated.approximations))
    assert len(rows) >= min(8, len(dedicated.approximations))
    for ours, theirs in rows:
        if np.isfinite(theirs.R12[free]).all() and np.abs(theirs.R12[free]).max() < 1e6 * scale:
            assert np.abs(ours.unknowns[0][:, 0:2] - theirs.R12)[free].max() <= 1e-10 * scale
