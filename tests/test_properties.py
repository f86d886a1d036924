"""Property-based layer over random valid machines: the reduction and the equation of motion keep their invariants."""
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from server.core.dynamics.machine import Machine
from server.core.dynamics.motion import steady_cycle
from server.core.dynamics.motors import Motor
from server.core.dynamics.reduction import Inertias, reduced_inertia
from server.core.dynamics.resistance import Load
from server.core.mechanisms import MECHANISMS

from test_reduced_moments import kinetic_energy_by_finite_differences

masses = st.floats(0.01, 50.0)
lam = st.floats(1.3, 8.0)
offset = st.floats(-0.2, 0.2)


@settings(max_examples=25, deadline=None, derandomize=True)
@given(lam=lam, offset=offset, m2=masses, m3=masses, j=st.floats(0.001, 1.0))
def test_reduced_inertia_is_the_kinetic_energy_of_the_links(lam, offset, m2, m3, j):
    p = MECHANISMS["slider_crank"].check({"l1": 0.1, "l2": 0.1 * lam, "e": offset * 0.1 * (lam - 1)})
    inertias = Inertias(J1=j, m2=m2, J_S2=j / 10, m3=m3)
    phi = np.linspace(0.05, 6.2, 23)
    J = reduced_inertia("slider_crank", p, inertias, phi).J
    assert J == pytest.approx(kinetic_energy_by_finite_differences("slider_crank", p, inertias, phi), rel=1e-6)


@settings(max_examples=12, deadline=None, derandomize=True)
@given(lam=lam, m3=masses, force=st.floats(100.0, 3000.0), f=st.floats(0.0, 0.3), b=st.floats(0.05, 2.0))
def test_steady_cycle_balances_the_work_of_all_moments(lam, m3, force, f, b):
    p = MECHANISMS["slider_crank"].check({"l1": 0.1, "l2": 0.1 * lam})
    machine = Machine("slider_crank", p, Inertias(J1=0.5, m2=2.0, J_S2=0.02, m3=m3, gear_ratio=5.0),
                      Load(force, 0.3, f), Motor("linear", M0=200.0, b=b))
    result = steady_cycle(machine, rtol=1e-8)
    if result.steady is None:                      # a stall or self-locking is said in words, never a number
        assert result.notices
        return
    works = result.steady.works
    # the works are Simpson sums on the step nodes of the level that met rtol (as few as 64 a turn):
    # their own quadrature error, ~h⁴M⁗/180 ≲ 1e-6 of the driving work, bounds the balance here
    assert abs(works["net"]) <= 1e-6 * works["driving"]
    assert result.numerics.error_estimate <= 1e-8
