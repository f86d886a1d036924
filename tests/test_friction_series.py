"""The textbook's friction series of /reduction (Eremyants §3.1, §3.2, (3.24)) against its closed form and
a 5000-step run: the ratio test decides whether the series converges, never the number of rows shown.

Crank-slider at φ: F_T,k = P Σ_{i=1}^{k} (f|tan ψ|)^i → P q/(1 − q), q = f|tan ψ|, sin ψ = l₁ sin φ/l₂ (e = 0);
sine mechanism: R₂₃ → P/(1 − f²).  Tolerances are stated at each assertion.
"""
import numpy as np
import pytest
from fastapi.testclient import TestClient
from hypothesis import given, settings
from hypothesis import strategies as st

from server.api.app import app
from server.core.dynamics.friction_iteration import friction_iteration
from server.core.mechanisms import MECHANISMS

client = TestClient(app)


def tan_psi(lam: float, phi: float) -> float:
    """|tan ψ| of the central crank-slider, computed here: sin ψ = sin φ/λ."""
    s = np.sin(phi) / lam
    return abs(s) / np.sqrt(1 - s * s)


def series_by_hand(force: float, q: float, steps: int) -> float:
    """The textbook's recursion F_T ← f R₀₃, R₀₃ = (P + F_T) tan ψ, written as F_T ← q (P + F_T), run ``steps`` times."""
    f_t = 0.0
    for _ in range(steps):
        f_t = q * (force + f_t)
    return f_t


def test_issue_case_ratio_081_converges_and_is_not_called_diverging():
    """λ = 1.03, f = 0.2 at φ = 90°: q = 0.2/√(1.03² − 1) = 0.810; the old 30-row cap called it diverging."""
    body = {"mechanism": "slider_crank", "params": {"l1": 0.1, "l2": 0.103}, "load": {"force": 1000, "f": 0.2},
            "outputs": ["friction_iteration"]}
    data = client.post("/api/v1/reduction", json=body).json()
    q = 0.2 * tan_psi(1.03, np.pi / 2)
    series = data["friction_iteration"]
    assert series["ratio"] == pytest.approx(0.81, abs=5e-3) and series["ratio"] == pytest.approx(q, rel=1e-12)
    assert series["converged"] and not data["warnings"]
    assert series["limit"]["F_T"] == pytest.approx(1000 * q / (1 - q), rel=1e-12)      # closed form, rounding only
    # the 5000-step run of the same recursion (q⁵⁰⁰⁰ ≈ 1e-458: converged to rounding) agrees with the limit
    assert series_by_hand(1000.0, q, 5000) == pytest.approx(series["limit"]["F_T"], rel=1e-12)
    # the rows shown are partial sums of the series: the last is within q/(1 − q)·(its change) of the limit
    last = series["steps"][-1]
    assert abs(last["F_T"] - series["limit"]["F_T"]) <= last["change"] * last["F_T"] * q / (1 - q) * (1 + 1e-9)


@settings(max_examples=60, deadline=None, derandomize=True)
@given(lam=st.floats(1.01, 5.0), phi=st.floats(0.05, np.pi - 0.05), q=st.floats(0.0, 1.5))
def test_the_ratio_test_decides_convergence_and_the_limit_is_the_closed_form(lam, phi, q):
    """f chosen so that f|tan ψ| = q: converged exactly when q < 1 (q within 1e-12 of 1 left out: rounding of
    tan ψ decides there); the limit P q/(1 − q) to 1e-12 relative (rounding amplified by 1/(1 − q) ≤ 1e3 when
    q ≤ 0.999; the test keeps q ≤ 1 − 1e-3 for that comparison)."""
    t = tan_psi(lam, phi)
    f = q / t
    params = MECHANISMS["slider_crank"].check({"l1": 1.0, "l2": lam})
    log = friction_iteration("slider_crank", params, phi, force=1.0, f=f)
    assert log.ratio == pytest.approx(q, rel=1e-9, abs=1e-15)
    if abs(q - 1) > 1e-12:
        assert log.converged == (q < 1)
    if q < 1 - 1e-3:
        assert log.limit["F_T"] == pytest.approx(q / (1 - q), rel=1e-12, abs=1e-15)
        assert log.needed == (1 if q == 0 else max(1, int(np.ceil(np.log(1e-6) / np.log(q)))))
    elif q >= 1:
        assert not log.limit and log.needed is None


def test_ratio_just_below_one_converges_and_just_above_diverges():
    """q = 1 ∓ 1e-3 at φ = 90°: the series converges (its table is truncated: ~1.4·10⁴ terms for 1e-6) or diverges."""
    lam = 1.03
    t = tan_psi(lam, np.pi / 2)
    params = MECHANISMS["slider_crank"].check({"l1": 1.0, "l2": lam})
    below = friction_iteration("slider_crank", params, np.pi / 2, force=1.0, f=(1 - 1e-3) / t)
    assert below.converged and below.truncated and below.needed > len(below.steps)
    assert below.limit["F_T"] == pytest.approx((1 - 1e-3) / 1e-3, rel=1e-9)   # 1/(1 − q) = 1e3 amplifies rounding
    above = friction_iteration("slider_crank", params, np.pi / 2, force=1.0, f=(1 + 1e-3) / t)
    assert not above.converged and not above.limit


def test_sine_mechanism_series_ratio_is_f_squared():
    """R₂₃ → P/(1 − f²) (Eremyants §3.1): f = 0.99 (ratio 0.98) converges, the table is not what decides."""
    log = friction_iteration("sine", {"l1": 1.0}, 0.3, force=2.0, f=0.99)
    assert log.converged and log.ratio == pytest.approx(0.9801)
    assert log.limit["R23"] == pytest.approx(2.0 / (1 - 0.9801), rel=1e-12)
