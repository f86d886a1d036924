"""The compiled friction solve (kinetostatics/groups/compiled.py) against the numpy reference
(friction.solve_reference) it replaces: random general mechanisms (the generator of tests/test_structure_random.py,
as tests/test_group_forces_random.py draws them, f up to 1 and r up to 0.1 m so that some angles lock or jam) and
every crank-driven preset over the whole turn, without and with locking.

Both must decide alike at every angle: the same locked, converged and singular angles.  Their friction loads are
both within ε_R of the root (each stops after a correction of the reactions below ε_R of their largest; Newton
converges quadratically there, so the root is far closer than the last correction), and they differ only in the
rounding of their LU and eigenvalue routines: so the balancing moment and the dry-friction moment M_T agree to
10 ε_R of the largest balancing moment of the cycle (1e-10 here with ε_R = 1e-11), and the series' ratio q,
the spectral radius of Jacobians at friction loads ε_R apart, to 1e-8.

The sign proof of the normal forces (compiled.certified_normals, without the solve) against the reference's
solve: where it proves a sign, the reference neither locks nor finds another sign; the kinks the machine brackets
from the proved signs equal, bitwise, those from the solve at every scan angle.
"""
from dataclasses import replace

import numpy as np
import pytest
from hypothesis import HealthCheck, Phase, assume, given, settings
from hypothesis import strategies as st

from server.core.dynamics.general_machine import GeneralMachine
from server.core.kinetostatics.groups import friction as fr
from server.core.kinetostatics.groups.analysis import setup
from server.core.kinetostatics.groups.compiled import certified_normals
from server.core.kinetostatics.groups.dry_moment import dry_moment, normal_signs
from server.core.kinetostatics.groups.loads import power_moment
from server.core.mechanisms.general import GeneralMechanism
from server.core.structure.compose import compose
from server.core.structure.masses import LinkMass, MassModel, SliderForce, with_strokes
from server.core.structure.spec import KINDS

from group_force_checks import crank_driven
from test_general_dry_memo import rough_machine
from test_group_forces import preset_model
from test_structure_random import checked, linkages

TOLERANCE = 1e-11
AGREE = 10 * TOLERANCE      # module docstring


def agree(mechanism, comp, model, omega=0.0, epsilon=0.0):
    """Both solves on one setup; the number of locked angles."""
    s = setup(mechanism, comp, model, omega, epsilon)
    new = fr.solve(s.fmap, TOLERANCE)
    old = fr.solve_reference(s.fmap, TOLERANCE)
    assert np.array_equal(new.locked, old.locked)
    assert np.array_equal(new.converged, old.converged)
    free = ~new.locked & ~s.influence.singular
    moments = [s.influence.at(s.fmap.apply(x.z))[2] for x in (new, old)]
    scale = np.nanmax(np.abs(moments[1][free]), initial=0.0) + 1e-12
    assert np.abs(moments[0] - moments[1])[free].max(initial=0.0) <= AGREE * scale
    assert np.abs(new.ratio - old.ratio)[free].max(initial=0.0) <= 1e-8
    # where the normal forces' signs are proved without solving, the reference neither locks nor changes them
    rows = [row for row, index in enumerate(s.rough) if s.pairs[index].kind == "P"]
    if rows:
        proved = certified_normals(np.ascontiguousarray(s.fmap.base.transpose(1, 0, 2)), s.fmap.lever,
                                   np.ascontiguousarray(s.fmap.coefficient.T), np.array(rows, np.int64))
        solved = s.fmap.reactions(old.z)[rows, :, 0]
        assert not (old.locked & proved).any() and old.converged[proved].all()
        assert np.array_equal(np.sign(solved[:, proved]), np.sign(s.fmap.base[rows][:, proved, 0]))
    return int(new.locked.sum())


@pytest.mark.parametrize("f, r", [(0.1, 0.02), (0.4, 0.05), (2.0, 0.2)])
def test_dry_moment_agrees(monkeypatch, f, r):
    """M_T of the shaping machine (the equation of motion's), locking and not: the same blanks, M_T to AGREE of
    the largest balancing moment (M_T is the balancing moment with friction minus the one without)."""
    built = rough_machine(f, r)
    comp = compose(built.linkage.linkage, np.linspace(0, 2 * np.pi, 721))
    new = dry_moment(built.linkage, comp, built.masses, tolerance=TOLERANCE)
    with monkeypatch.context() as patch:
        patch.setattr(fr, "solve", fr.solve_reference)
        old = dry_moment(built.linkage, comp, built.masses, tolerance=TOLERANCE)
    for field in ("locked", "singular", "unsettled"):
        assert np.array_equal(getattr(new, field), getattr(old, field))
    assert np.array_equal(np.isnan(new.moment), np.isnan(old.moment))
    loads = power_moment(setup(built.linkage, comp, built.masses, 0.0, 0.0).loads)
    scale = np.nanmax(np.abs(old.moment + loads))
    assert np.nanmax(np.abs(new.moment - old.moment)) <= AGREE * scale
    assert new.locked.any() == (f > 1)


@pytest.mark.parametrize("f, r", [(0.1, 0.02), (0.4, 0.05), (2.0, 0.2)])
def test_kinks_from_proved_signs_equal_the_solved_scan(monkeypatch, f, r):
    """The normal forces' kinks bracketed from the signs proved without solving (GeneralMachine.scan_normals)
    equal those from the friction solve at every scan angle, bitwise (the brackets' ends are solved either way)."""
    built = rough_machine(f, r)
    kinks = built.find_kinks()
    with monkeypatch.context() as patch:
        patch.setattr(GeneralMachine, "scan_normals", GeneralMachine.normals)
        solved = rough_machine(f, r).find_kinks()
    assert np.array_equal(kinks, solved)
    phi = np.linspace(0, 2 * np.pi, 1025)
    _, proved = normal_signs(built.linkage, compose(built.linkage.linkage, phi), built.masses, dict(built.pairs))
    assert proved.all() == (f == 0.1)        # f = 0.1, r = 20 mm: every angle proved; the others solved


@pytest.mark.parametrize("name", crank_driven())
@pytest.mark.parametrize("f, r", [(0.15, 0.01), (0.5, 0.05), (1.0, 0.1)])    # none, some, most angles locked
def test_presets_agree(name, f, r):
    mechanism, model = preset_model(name, friction=f)
    model = replace(model, pair_radius=r)
    comp = compose(mechanism.linkage, np.linspace(0, 2 * np.pi, 181) + 0.0123)
    assert all(g.closes.all() for g in comp.groups)
    agree(mechanism, comp, with_strokes(mechanism, model), omega=12.0, epsilon=-4.0)


@settings(max_examples=60, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.too_slow],
          phases=[Phase.explicit, Phase.reuse, Phase.generate])      # no shrinking: a failure prints its case
@given(data=st.data())
def test_random_mechanisms_agree(data):
    kind = data.draw(st.sampled_from(KINDS))
    raw, phi0 = data.draw(linkages(kind, data.draw(st.sampled_from([1, -1]))))
    linkage = checked(raw)
    assume(linkage is not None)
    comp = compose(linkage, phi0 + np.linspace(-0.05, 0.05, 11))
    assume(all(g.closes.all() for g in comp.groups))
    mechanism = GeneralMechanism(linkage)
    links = tuple(LinkMass(k, data.draw(st.floats(0.1, 5.0)),
                           data.draw(st.tuples(st.floats(-0.2, 0.2), st.floats(-0.2, 0.2))),
                           data.draw(st.floats(0.0, 0.05))) for k in sorted(comp.links))
    slides = sorted(comp.slides)
    forces = (SliderForce(data.draw(st.sampled_from(slides)), data.draw(st.floats(0, 500)),
                          data.draw(st.floats(0, 1))),) if slides else ()
    model = MassModel(links, forces=forces, friction=data.draw(st.floats(0.01, 1.0)),
                      pair_radius=data.draw(st.floats(0.002, 0.1)))
    agree(mechanism, comp, model, data.draw(st.floats(1, 30)), data.draw(st.floats(-20, 20)))
