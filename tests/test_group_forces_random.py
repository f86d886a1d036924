"""Kinetostatics by groups on random mechanisms: the generator of tests/test_structure_random.py (a crank and
two groups of every kind and branch, moving guides included), each link given a random mass, centre and
inertia, a useful force on a slider where there is one.  At φ₀ and two angles beside it (±0.01 rad: the
generator keeps every group's |det| ≥ 0.2 at φ₀):
- f = 0: the balancing moment equals the moment the dynamics' reduction implies, J ε₁ + ½J′ω₁² + M_c
  (structure/reduction.py: kinetic-energy and power equality, another code; 1e-9 of the largest |M|), and at φ₀
  the reduced moment by power equality with velocities from differences of the positions (1e-7: the
  differences' own accuracy near dead positions); every link in equilibrium (1e-9);
- f > 0: every approximation of the table in equilibrium (1e-9) and the solved balancing moment against fsolve of
  the full nonlinear equilibrium (1e-8 of its scale, ε_R = 1e-11), where the mechanism does not lock.
"""
import numpy as np
from hypothesis import HealthCheck, Phase, assume, given, settings
from hypothesis import strategies as st

from server.core.kinetostatics.groups.analysis import analyse
from server.core.mechanisms.general import GeneralMechanism
from server.core.structure.compose import compose
from server.core.structure.masses import LinkMass, MassModel, SliderForce
from server.core.structure.spec import KINDS

from group_force_checks import direct, power_fd, reduction_moment, residual
from test_structure_random import checked, linkages


@settings(max_examples=60, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.too_slow],
          phases=[Phase.explicit, Phase.reuse, Phase.generate])      # no shrinking: a failure prints its case
@given(data=st.data())
def test_random_group_forces(data):
    kind = data.draw(st.sampled_from(KINDS))
    raw, phi0 = data.draw(linkages(kind, data.draw(st.sampled_from([1, -1]))))
    linkage = checked(raw)
    assume(linkage is not None)
    phi = phi0 + np.array([-0.01, 0.0, 0.01])
    comp = compose(linkage, phi)
    assume(all(g.closes.all() and np.abs(g.determinant).min() >= 0.2 for g in comp.groups))
    mechanism = GeneralMechanism(linkage)
    mass = st.floats(0.1, 5.0)
    centre = st.tuples(st.floats(-0.2, 0.2), st.floats(-0.2, 0.2))
    links = tuple(LinkMass(k, data.draw(mass), data.draw(centre), data.draw(st.floats(0.0, 0.05)))
                  for k in sorted(comp.links))
    slides = sorted(comp.slides)
    forces = (SliderForce(data.draw(st.sampled_from(slides)), data.draw(st.floats(0, 500)),
                          data.draw(st.floats(0, 1))),) if slides else ()
    omega, epsilon = data.draw(st.floats(1, 30)), data.draw(st.floats(-20, 20))
    model = MassModel(links, forces=forces)

    result = analyse(mechanism, model, phi, omega, epsilon)
    assert not result.influence.singular.any()
    expected = reduction_moment(mechanism, model, result, omega, epsilon)
    scale = np.abs(expected).max() + 1e-12
    assert np.abs(result.solution.balancing - expected).max() <= 1e-9 * scale
    # at φ₀ (|det| ≥ 0.2) also against velocities from differences of the positions, to their accuracy: the
    # five-point difference's truncation h⁴|z⁽⁵⁾|/30 grows as 1/det⁵ near a dead position (1e-7 here)
    assert abs(result.solution.balancing[1] - power_fd(mechanism, result)[1]) <= 1e-7 * scale
    assert residual(result, result.solution) <= 1e-9

    friction = MassModel(links, forces=forces, friction=data.draw(st.floats(0.01, 0.3)),
                         pair_radius=data.draw(st.floats(0.002, 0.03)))
    rough = analyse(mechanism, friction, phi, omega, epsilon, tolerance=1e-11)
    for row in rough.approximations:
        assert residual(rough, row) <= 1e-9
    free = ~rough.locked
    assert rough.converged[free].all()
    for k in np.flatnonzero(free):
        start = np.concatenate([*(x[k] for x in rough.approximations[0].unknowns),
                                [rough.approximations[0].R01[k].real, rough.approximations[0].R01[k].imag,
                                 rough.approximations[0].balancing[k]]])
        (unknowns, R01, balancing), left = direct(rough, k, start)
        size = np.nanmax(np.abs(rough.solution.balancing)) + 1e-12
        assert left <= 1e-9 * max(size, 1.0)
        assert abs(balancing[0] - rough.solution.balancing[k]) <= 1e-8 * size
