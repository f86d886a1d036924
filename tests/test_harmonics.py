"""The harmonic content of the transfer functions equals their Fourier integrals.

The core samples a transfer function on a uniform grid and takes its FFT.  Here each
coefficient is computed independently by adaptive quadrature (scipy.integrate.quad) of

    a₀ = (1/T)∫u dφ,   a_k = (2/T)∫u cos kνφ dφ,   b_k = (2/T)∫u sin kνφ dφ,   ν = 2π/T,

over one kinematic cycle T (2π, or 4π for a change-point four-bar without limiter).
"""
from __future__ import annotations

import warnings
from functools import partial

import numpy as np
import pytest
from fastapi.testclient import TestClient
from scipy.integrate import IntegrationWarning, quad

from server.api.app import app
from server.core.harmonics import HARMONIC_COUNT, HARMONIC_GRID, harmonics
from server.core.mechanisms import MECHANISMS

assert_allclose = partial(np.testing.assert_allclose, equal_nan=False)   # a NaN on either side fails

# (mechanism, params, output).  Smooth periodic transfer functions: the trapezoidal rule behind
# the FFT converges geometrically, and quad is asked for 1e-13; both errors are far below
# 1e-9 of the function's largest value.
SMOOTH = [
    ("sine", {"l1": 0.1}, "u31"),
    ("slider_crank", {"l1": 0.1, "l2": 0.3}, "u31"),
    ("slider_crank", {"l1": 0.1, "l2": 0.3}, "du31"),
    ("slider_crank", {"l1": 0.1, "l2": 0.15}, "u21"),
    ("slider_crank", {"l1": 0.1, "l2": 0.3, "e": 0.05}, "u31"),
    ("slotted_link", {"l0": 0.05, "l1": 0.1}, "u31"),
    ("slotted_link", {"l0": 0.2, "l1": 0.1}, "u31"),
    ("slotted_link", {"l0": 0.2, "l1": 0.1}, "du21"),
    ("four_bar", {}, "u31"),
    ("four_bar", {"assembly": -1}, "du31"),
    ("four_bar", {"l0": 0.1, "l1": 0.3, "l2": 0.35, "l3": 0.4}, "u21"),
    # change-point four-bar without limiter: 4π-periodic and smooth through the change point
    ("four_bar", {"l0": 2, "l1": 1, "l2": 4, "l3": 3, "limiter": 0}, "u31"),
    ("four_bar", {"l0": 4, "l1": 1, "l2": 3, "l3": 2, "limiter": 0}, "du31"),
]
SMOOTH_RTOL = 1e-9

# With a stroke limiter u₃₁ jumps at the change point.  The core samples the jump with the mean of
# both sides, so the trapezoidal rule is O(h²): error ≈ h²/12·k·|jump| ≈ 3e-6·8·3.3 ≈ 8e-5 for
# h = 2π/1024, k ≤ 8 and the largest jump (scheme 1, 3.27).  1e-4 of the largest value covers it.
WITH_JUMP = [
    ("four_bar", {"l0": 2, "l1": 1, "l2": 4, "l3": 3, "limiter": 1}, "u31"),
    ("four_bar", {"l0": 2, "l1": 1, "l2": 3, "l3": 4, "assembly": -1, "limiter": 1}, "u31"),
    ("four_bar", {"l0": 4, "l1": 1, "l2": 3, "l3": 2, "limiter": 1}, "u31"),
]
JUMP_RTOL = 1e-4


def fourier_by_quadrature(mech, p: dict, output: str, count: int = HARMONIC_COUNT) -> tuple[float, np.ndarray, np.ndarray]:
    """Mean, cosine and sine coefficients by adaptive quadrature over one cycle, starting at a jump if any."""
    cycle = mech.cycle(p)
    nu = 2 * np.pi / cycle
    start = mech.jumps(p)[0] if mech.jumps(p) else 0.0   # integrate between jumps: quad needs a smooth integrand
    u = lambda x: float(mech.evaluate(p, np.array([x]), set()).values[output][0])
    integrate = lambda f: quad(f, start, start + cycle, limit=200, epsabs=1e-13, epsrel=1e-13)[0]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", IntegrationWarning)   # "roundoff detected" once 1e-13 is reached
        mean = integrate(u) / cycle
        cos = np.array([integrate(lambda x, k=k: u(x) * np.cos(k * nu * x)) for k in range(1, count + 1)]) * 2 / cycle
        sin = np.array([integrate(lambda x, k=k: u(x) * np.sin(k * nu * x)) for k in range(1, count + 1)]) * 2 / cycle
    return mean, cos, sin


def assert_harmonics_match_quadrature(mechanism: str, params: dict, output: str, rtol: float) -> None:
    mech = MECHANISMS[mechanism]
    p = mech.check(params)
    h = harmonics(mech, p, output)
    mean, cos, sin = fourier_by_quadrature(mech, p, output)
    grid = np.linspace(0, mech.cycle(p), 4001)
    scale = np.max(np.abs(mech.evaluate(p, grid, set()).values[output]))
    assert h["base_period"] == pytest.approx(mech.cycle(p))
    assert h["k"] == list(range(1, HARMONIC_COUNT + 1))
    assert abs(h["mean"] - mean) <= rtol * scale
    assert_allclose(h["cos"], cos, rtol=0, atol=rtol * scale)
    assert_allclose(h["sin"], sin, rtol=0, atol=rtol * scale)
    assert_allclose(h["amplitude"], np.hypot(cos, sin), rtol=0, atol=rtol * scale)


@pytest.mark.parametrize("mechanism, params, output", SMOOTH, ids=[f"{m}-{o}-{p}" for m, p, o in SMOOTH])
def test_harmonics_of_smooth_transfer_functions_equal_their_fourier_integrals(mechanism, params, output):
    assert_harmonics_match_quadrature(mechanism, params, output, SMOOTH_RTOL)


@pytest.mark.parametrize("mechanism, params, output", WITH_JUMP, ids=[f"{m}-{o}-{p}" for m, p, o in WITH_JUMP])
def test_harmonics_with_a_stroke_limiter_jump_equal_their_fourier_integrals(mechanism, params, output):
    assert_harmonics_match_quadrature(mechanism, params, output, JUMP_RTOL)


def test_lever_speed_at_lambda_one_is_a_constant_half_despite_the_undefined_sample():
    """λ = 1: u₃₁ = 0.5 except at φ = 180°, where it is undefined (NaN) and skipped."""
    mech = MECHANISMS["slotted_link"]
    p = mech.check({"l0": 0.1, "l1": 0.1})
    h = harmonics(mech, p, "u31")
    # the FFT sums 1024 samples: rounding up to ≈ 1024·ε·0.5 ≈ 1e-13
    assert h["mean"] == pytest.approx(0.5, abs=1e-13)
    assert max(h["amplitude"]) < 1e-13


def test_harmonic_series_rebuilds_the_transfer_function():
    """Eight harmonics of the crank-slider's u₃₁ (λ = 3) reproduce it to the size of the ninth and beyond."""
    mech = MECHANISMS["slider_crank"]
    p = mech.check({"l1": 0.1, "l2": 0.3})
    h = harmonics(mech, p, "u31")
    phi = np.linspace(0, 2 * np.pi, 997)
    series = h["mean"] + sum(a * np.cos(k * phi) + b * np.sin(k * phi) for k, a, b in zip(h["k"], h["cos"], h["sin"]))
    exact = mech.evaluate(p, phi, set()).values["u31"]
    # the omitted harmonics k ≥ 9 fall off like λ⁻ᵏ: below 1e-5 of l₁ at λ = 3
    assert np.max(np.abs(series - exact)) < 1e-6


def test_api_returns_the_harmonics_of_u31():
    client = TestClient(app)
    body = {"mechanism": "slider_crank", "params": {"l1": 0.1, "l2": 0.3}, "n": 5, "outputs": ["harmonics"]}
    got = client.post("/api/v1/kinematics?precision=full", json=body).json()["outputs"]["harmonics"]
    mech = MECHANISMS["slider_crank"]
    expected = harmonics(mech, mech.check(body["params"]), "u31")
    assert got["output"] == "u31" and got["k"] == expected["k"]
    assert_allclose(got["amplitude"], expected["amplitude"], rtol=1e-15)
    assert HARMONIC_GRID >= 16 * HARMONIC_COUNT   # enough samples per harmonic for the FFT to resolve them
