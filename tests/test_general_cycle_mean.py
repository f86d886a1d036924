"""The cycle mean M_c0 of a general mechanism (general_machine.cycle_mean: Gauss–Legendre between the kinks, the
difference of two orders as its error estimate) against scipy.integrate.quad (QUADPACK's adaptive Gauss–Kronrod,
run between each two kinks, at relative 1e-13), an independent integrator of the same M_c(φ).

The estimate must hold: |M_c0 − quad| ≤ estimate × (cycle mean of |M_c|) + quad's own error bound, on every
six-bar preset without and with dry friction, on the crank-slider as a general linkage against the quadrature of
the dedicated crank-slider's closed form (Eremyants (3.24)–(3.28), other code), and with the kinks withheld (the rule then halves its segments onto the corners it was not told: slower, still honest).  The
estimates are also small (≤ 1e-9: the rule is not honest by being vague).  Where friction locks the mechanism
there is no mean, said in words.
"""
from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import quad

from server.api.endpoints import compute, machine
from server.api.schemas_dynamics import MotionRequest
from server.core.dynamics.general_machine import GeneralMachine, TURN, cycle_mean, resisting_total
from server.core.dynamics.resistance import Load, resisting_moment

from test_general_dynamics_machine import SIX_BARS, pair, preset_body

QUAD_RTOL = 1e-13


def quadrature(f, kinks: np.ndarray) -> tuple[float, float]:
    """(1/2π)∫₀²π f dφ and quad's error bound of it, quad run on each stretch between two kinks."""
    edges = np.unique(np.concatenate([[0.0], kinks[(kinks > 0) & (kinks < TURN)], [TURN]]))
    parts = [quad(f, a, b, epsabs=0.0, epsrel=QUAD_RTOL, limit=500) for a, b in zip(edges[:-1], edges[1:])]
    return sum(p[0] for p in parts) / TURN, sum(p[1] for p in parts) / TURN


def scalar(built: GeneralMachine, omega: float):
    return lambda phi: float(resisting_total(built, np.array([phi]), omega)[0])


def holds(built: GeneralMachine, omega: float, reference=None) -> float:
    """The mean and its estimate against quad; the estimate returned."""
    found = cycle_mean(built, omega)
    kinks = np.asarray(built.kinks())
    value, bound = quadrature(reference or scalar(built, omega), kinks)
    grid = resisting_total(built, np.linspace(0, TURN, 4097), omega)
    scale = float(np.mean(np.abs(grid[:-1])))           # the cycle mean of |M_c| (the estimate's unit; to ~1e-7)
    assert found.mean is not None and found.angles > 0
    assert abs(found.mean - value) <= found.error * scale * (1 + 1e-6) + bound, (found, value, bound, scale)
    return found.error


def preset_machine(name: str, friction: float) -> GeneralMachine:
    body = preset_body(name, motor={"kind": "constant", "M0": 10.0}, outputs=["steady"], load={"beta": 0.4})
    if friction:
        body["masses"] = body["masses"] | {"friction": friction, "pair_radius": 0.02}
    return machine(MotionRequest(**body))


@pytest.mark.parametrize("friction", [0.0, 0.1])
@pytest.mark.parametrize("name", SIX_BARS)
def test_presets_against_quad(name, friction):
    assert holds(preset_machine(name, friction), 3.0) <= 1e-9


def test_kinks_withheld(monkeypatch):
    """Told no kinks, the rule halves its segments where the two orders differ, onto the corners."""
    built = preset_machine("shaping_machine", 0.1)
    kinks = np.asarray(built.kinks())
    assert kinks.size > 2
    monkeypatch.setattr(GeneralMachine, "kinks", lambda self: np.zeros(0))
    found = cycle_mean(built, 3.0)
    value, bound = quadrature(scalar(built, 3.0), kinks)
    scale = float(np.mean(np.abs(resisting_total(built, np.linspace(0, TURN, 4097), 3.0)[:-1])))
    assert abs(found.mean - value) <= found.error * scale * (1 + 1e-6) + bound
    assert found.error <= 1e-8


def test_crank_slider_against_the_dedicated_closed_form():
    """The crank-slider as a general linkage with friction in its guide: M_c0 against quad of the dedicated
    machine's closed form M_c = k P|u₃₁|/(1 − f|tan ψ|) + β ω s′² (resistance.py, other code)."""
    dedicated, general = pair("slider_crank", beta=0.5, outputs=["steady"], motor={"kind": "constant", "M0": 10.0})
    general["pair_friction"] = {"x": {"f": 0.25}}
    built = machine(MotionRequest(**general))
    load = Load(**dedicated["load"] | {"f": 0.25})
    params = machine(MotionRequest(**dedicated)).params
    closed = lambda phi: float(resisting_moment("slider_crank", params, load, np.array([phi]), 3.0).total[0])
    assert holds(built, 3.0, closed) <= 1e-9


def test_self_locking_has_no_mean():
    body = preset_body("shaping_machine", outputs=["inertia", "resisting"], n=91)
    body["masses"] = body["masses"] | {"friction": 2.0, "pair_radius": 0.2}
    answer = compute("reduction", body)
    assert answer["resisting"]["mean"] is None
    assert answer["numerics"]["message_code"] == "no_mean_moment" and answer["numerics"]["error_estimate"] == 0.0
