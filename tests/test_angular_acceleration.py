"""The two components of the coupler's angular acceleration (Kuleshova–Tokhtar (2)–(4)) against the paper, its table and ψ(t)."""
import json

import numpy as np
import pytest
from fastapi.testclient import TestClient

from server.api.app import app
from server.core.angular_acceleration import CrankLaw, crank_slider, trammel

TABLE = [(0, 0.26180, 0.00000), (30, 0.23416, -0.05663), (60, 0.14522, -0.12157), (90, 0.0, -0.15828),
         (120, -0.14522, -0.12157), (150, -0.23416, -0.05663), (180, -0.26180, 0.0), (210, -0.23416, 0.05663),
         (240, -0.14522, 0.12157), (270, 0.0, 0.15828), (300, 0.14522, 0.12157), (330, 0.23416, 0.05663)]


def test_paper_example_gives_minus_0_0566():
    result = crank_slider(0.5, 1.0, CrankLaw(), np.array([1.0]))
    assert result["epsilon"][0] == pytest.approx(-0.0566294, abs=1e-7)   # the paper prints −0.0565
    assert result["epsilon_star"][0] == 0.0 and 1 / result["inv_AP"][0] == pytest.approx(np.sqrt(5))


@pytest.mark.parametrize("degrees, omega_ab, epsilon", TABLE)
def test_table_of_the_notes(degrees, omega_ab, epsilon):
    t = np.array([np.radians(degrees) / (np.pi / 6)])
    result = crank_slider(0.5, 1.0, CrankLaw(), t)
    assert result["omega_coupler"][0] == pytest.approx(omega_ab, abs=1e-4)    # table printed to 5 decimals
    assert result["epsilon"][0] == pytest.approx(epsilon, abs=1e-4)


@pytest.mark.parametrize("seed", range(6))
def test_components_add_up_to_the_second_derivative_of_psi(seed):
    """ε* + ε** against central differences of ψ(t) = arcsin(λ sin φ(t)), independent of the formulas."""
    rng = np.random.default_rng(seed)
    lam = rng.uniform(0.1, 0.9)
    law = [CrankLaw("constant", rng.uniform(0.5, 3)), CrankLaw("accelerating", rng.uniform(0.5, 3), rng.uniform(0, 2)),
           CrankLaw("harmonic", rng.uniform(0.5, 3), amplitude=rng.uniform(0, 0.8), frequency=rng.uniform(0.5, 4))][seed % 3]
    t = rng.uniform(0, 5, 50)
    psi = lambda tt: np.arcsin(lam * np.sin(law.at(tt)[0]))
    central = lambda h: (psi(t + h) - 2 * psi(t) + psi(t - h)) / h**2
    second = (4 * central(5e-4) - central(1e-3)) / 3            # Richardson: error O(h⁴ψ⁽⁶⁾)
    result = crank_slider(lam, 1.0, law, t)
    # truncation h⁴ψ⁽⁶⁾/360 ≲ 1e-9 for ω ≲ 13 rad/s, round-off ε/h² ~ 1e-9 relative
    assert result["epsilon"] == pytest.approx(second, abs=1e-7 * max(1, np.abs(second).max()))
    assert result["epsilon"] == pytest.approx(result["psi_dd"], abs=1e-12 * max(1, np.abs(second).max()))


def test_instantaneous_translation_is_finite():
    t = np.array([np.pi / 2, 3 * np.pi / 2]) / (np.pi / 6)
    result = crank_slider(0.5, 1.0, CrankLaw(), t)
    assert result["inv_AP"] == pytest.approx([0, 0], abs=1e-15)
    assert np.isfinite(result["epsilon"]).all() and np.isnan(result["points"]["P"]).all()
    body = json.loads(TestClient(app).post("/api/v1/angular-acceleration", json={"t": list(t)}).text,
                      parse_constant=lambda c: pytest.fail(c))
    assert body["points"]["P"] == [[None, None], [None, None]] and body["epsilon"][0] == pytest.approx(-0.15828, abs=1e-5)


def test_trammel_keeps_ap_equal_to_oa_and_reverses_the_acceleration():
    law = CrankLaw("harmonic", 1.0, amplitude=0.5, frequency=2.0)
    t = np.linspace(0, 3, 31)
    result = trammel(0.2, law, t)
    P, A = result["points"]["P"], result["points"]["A"]
    assert np.linalg.norm(P - A, axis=1) == pytest.approx(np.full(31, 0.2), rel=1e-12)
    B, D = result["points"]["B"], result["points"]["D"]
    assert np.linalg.norm(B - A, axis=1) == pytest.approx(np.full(31, 0.2)) and np.linalg.norm(D - A, axis=1) == \
        pytest.approx(np.full(31, 0.2))
    # counted in the crank's sense, which is clockwise in the drawing (one convention: angular_acceleration.py)
    bd_angle = -np.unwrap(np.arctan2(D[:, 1] - B[:, 1], D[:, 0] - B[:, 0]))
    h = t[1] - t[0]
    second = (bd_angle[2:] - 2 * bd_angle[1:-1] + bd_angle[:-2]) / h**2
    assert second == pytest.approx(result["epsilon"][1:-1], abs=0.05)       # O(h²) with h = 0.1 s
    assert result["epsilon_star2"] == pytest.approx(np.zeros(31)) and result["epsilon"] == pytest.approx(-law.at(t)[2])
