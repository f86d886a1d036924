"""The flywheel's compiled pieces against their reference paths, exactly: the periodic energy level T₀ by the
compiled Brent's method (compiled.periodic_level) is the very double scipy's brentq finds on the same function,
and the compiled speed extremes are numerics.parabola_extremum's (both the same operations in the same order, so
no tolerance: any difference would be a porting slip), on random cycles with flat stretches, NaNs and none."""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from server.core.dynamics.compiled import mean_of_extremes, periodic_level, speed_extremes
from server.core.numerics import parabola_extremum


def random_cycle(rng: np.random.Generator):
    """A(φ) (zero at φ = 0) and I(φ) > 0 on a closed grid, and a mean speed ω_m."""
    n = int(rng.integers(40, 3000))
    phi = np.linspace(0.0, 2 * np.pi, n + 1)
    work = rng.uniform(0.1, 50) * np.sin(phi * rng.integers(1, 4) + rng.uniform(0, 6)) \
        + rng.uniform(0, 5) * np.sin(3 * phi)
    work -= work[0]
    total = rng.uniform(0.01, 2) + rng.uniform(0, 0.5) * (1 + np.cos(2 * phi))
    return work, total, float(rng.uniform(1, 200))


@pytest.mark.parametrize("seed", range(4))
def test_the_compiled_brent_root_is_scipys(seed):
    rng = np.random.default_rng(seed)
    solved = 0
    for _ in range(60):
        work, total, omega_mean = random_cycle(rng)
        lowest = float(np.max(-work))
        high = lowest + 0.5 * float(total.max()) * (2 * omega_mean) ** 2 + 1.0
        low = lowest + 1e-12 * high
        if mean_of_extremes(work, total, low) - omega_mean > 0:
            continue                                   # no periodic solution: periodic_speed never solves
        reference = brentq(lambda T0: mean_of_extremes(work, total, T0) - omega_mean, low, high,
                           xtol=1e-15 * high, rtol=1e-15)
        root, status = periodic_level(work, total, omega_mean, low, high, 1e-15 * high, 1e-15, 100)
        assert status == 0 and root == reference
        solved += 1
    assert solved >= 30


def test_the_compiled_brent_refuses_as_scipy_does():
    """No sign change on the bracket, and a cap of iterations too small: scipy's ValueError, RuntimeError."""
    work, total = np.zeros(9), np.ones(9)
    _, status = periodic_level(work, total, 1.0, 10.0, 20.0, 1e-12, 1e-12, 100)     # ω ≥ √20 > 1 throughout
    assert status == 3
    with pytest.raises(ValueError):
        brentq(lambda T0: mean_of_extremes(work, total, T0) - 1.0, 10.0, 20.0)
    _, status = periodic_level(work, total, 1.0, 0.0, 20.0, 1e-15, 1e-15, 2)
    assert status == 1
    with pytest.raises(RuntimeError):
        brentq(lambda T0: mean_of_extremes(work, total, T0) - 1.0, 0.0, 20.0, xtol=1e-15, rtol=1e-15, maxiter=2)


@pytest.mark.parametrize("seed", range(3))
def test_the_compiled_speed_extremes_are_parabola_extremum(seed):
    rng = np.random.default_rng(100 + seed)
    for case in range(1000):
        n = int(rng.integers(3, 500))
        phi = np.linspace(0, 2 * np.pi, n + 1)
        omega = rng.uniform(1, 100) + rng.uniform(0, 5) * np.sin(phi * rng.integers(1, 5) + rng.uniform(0, 6))
        if case % 7 == 0:
            omega = np.round(omega, 1)                 # plateaus: ties for the extreme
        if case % 11 == 0:
            omega[rng.integers(0, n)] = np.nan         # numpy's argmax stops at the first NaN
        if case % 13 == 0:
            omega[:] = np.nan                          # no periodic solution
        omega[-1] = omega[0]
        expected = (parabola_extremum(omega, +1), parabola_extremum(omega, -1))
        for got, want in zip(speed_extremes(omega), expected):
            assert got == want or (math.isnan(got) and math.isnan(want))
