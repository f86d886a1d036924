"""Flywheel for a given δ (Lecture 10 §10.3–§10.8): four methods against the analytic case, each other and a time simulation."""
import numpy as np
import pytest
from scipy.integrate import solve_ivp

from server.core.dynamics import flywheel as fw
from server.core.dynamics.machine import Machine
from server.core.dynamics.motors import Motor
from server.core.dynamics.reduction import Inertias, reduced_inertia
from server.core.dynamics.report import flywheel
from server.core.dynamics.resistance import Load
from server.core.mechanisms import MECHANISMS

OMEGA, DELTA = 47.124, 1 / 80
PARAMS = MECHANISMS["slider_crank"].check({"l1": 0.12, "l2": 0.528, "a2": 0.169 / 0.528})
ENGINE = Motor("indicator", p_max=4.4e6, piston_diameter=0.1)
RIG = Machine("slider_crank", PARAMS, Inertias(J1=2.72, m2=24.2, J_S2=1.21, m3=36.2), Load(), ENGINE)


def test_analytic_case_all_four_methods_give_7_2050():
    """I_II = 0, M_Σ = M_a sin φ: A = M_a(1 − cos φ), ΔT_max = 2M_a, I_I = 2M_a/(δω²) (an analytic case, not in Lecture 10)."""
    phi = np.linspace(0, 2 * np.pi, 4097)
    cycle = fw.Cycle(phi, 100.0 * (1 - np.cos(phi)), np.zeros_like(phi))
    expected = 2 * 100.0 / (DELTA * OMEGA**2)
    assert expected == pytest.approx(7.2050, abs=5e-5)
    methods = [fw.merzalov(cycle, OMEGA, DELTA), fw.gutyar(cycle, OMEGA, DELTA),
               fw.wittenbauer(cycle, OMEGA, DELTA)[0], fw.exact(cycle, OMEGA, DELTA, 7.0)]
    # the parabola through the sampled extremes of 1 − cos φ errs by ~h⁴ ≈ 1e-12
    assert [m.inertia for m in methods] == pytest.approx([expected] * 4, rel=1e-9)


def test_wittenbauers_touching_angles_are_the_curves_own_and_move_smoothly():
    """The angles where the tangents touch, against scipy's bounded search on the analytic curve A − I_II ω²/2
    (A = M₁ sin φ + M₂ sin 2φ, I_II = I₀ + I₁ cos 2φ): within 2e-6 rad, where the best node alone errs up to
    half a node (h/2 = 7.7e-4 rad on 4097 nodes); the vertex of the parabola through three nodes is off by
    O(h²·|y‴/y″|), 1–3e-7 rad measured here. As δ moves the slopes by 1e-5 of themselves the angles move by that much and
    smoothly (a node's angle would stay put or jump a node)."""
    from scipy.optimize import minimize_scalar
    phi = np.linspace(0, 2 * np.pi, 4097)
    work = lambda x: 60.0 * np.sin(x) + 25.0 * np.sin(2 * x)
    inertia = lambda x: 0.02 + 0.006 * np.cos(2 * x)
    cycle = fw.Cycle(phi, work(phi), inertia(phi))
    angles = []
    for delta in (0.05, 0.05 * (1 + 1e-5)):
        diagram = fw.wittenbauer(cycle, OMEGA, delta)[1]
        w_max, w_min = (1 + delta / 2) * OMEGA, (1 - delta / 2) * OMEGA
        for key, sign, speed in (("phi_up", -1, w_max), ("phi_low", +1, w_min)):
            curve = lambda x: sign * (work(x) - 0.5 * inertia(x) * speed**2)
            node = phi[int(np.argmin(curve(phi)))]
            best = minimize_scalar(curve, bounds=(node - 0.01, node + 0.01), method="bounded",
                                   options={"xatol": 1e-12}).x
            assert abs(diagram[key] - best) <= 2e-6, (key, diagram[key], best, node)
        angles.append((diagram["phi_up"], diagram["phi_low"]))
    moved = np.subtract(angles[1], angles[0])
    assert np.all(np.abs(moved) > 0) and np.all(np.abs(moved) < 1e-4)


def test_sizing_table_of_the_lecture():
    assert fw.disk_as_printed(1.0).diameter == pytest.approx(0.3660, abs=5e-5)
    assert fw.disk_as_printed(1.0).mass == pytest.approx(60.30, abs=5e-3)
    assert fw.disk_as_printed(10.0).diameter == pytest.approx(0.5801, abs=5e-5)
    assert fw.disk_as_printed(10.0).mass == pytest.approx(240.08, abs=5e-3)
    exact = fw.disk(1.0)          # the printed constants round (32/(ρπψ_b))^{1/5} = 0.36557 and ρπψ_b/4 = 1225.2
    assert exact.diameter == pytest.approx(0.36557, abs=5e-6)
    assert exact.mass * exact.diameter**2 / 8 == pytest.approx(1.0, rel=1e-12)     # I = mD²/8


def test_wittenbauer_is_exact_and_merzalov_is_conservative():
    result, _ = flywheel(RIG, OMEGA, DELTA, balance=True, width_ratio=0.2, density=7800.0)
    rows = {row["method"]: row for row in result["methods"]}
    assert rows["wittenbauer"]["inertia"] == pytest.approx(rows["exact"]["inertia"], rel=1e-6)
    assert rows["merzalov"]["inertia"] >= rows["exact"]["inertia"]
    assert rows["merzalov"]["delta_achieved"] < DELTA                        # a bigger flywheel, a smaller δ
    assert rows["exact"]["delta_achieved"] == pytest.approx(DELTA, rel=1e-9)


@pytest.mark.parametrize("delta", [0.001, 0.01, 0.05, 0.2])
def test_merzalov_never_asks_for_less_than_the_exact_inertia(delta):
    result, _ = flywheel(RIG, OMEGA, delta, balance=True, width_ratio=0.2, density=7800.0)
    rows = {row["method"]: row for row in result["methods"]}
    assert rows["merzalov"]["inertia"] >= rows["exact"]["inertia"] * (1 - 1e-9)


def test_exact_inertia_gives_the_target_delta_in_a_time_simulation():
    result, _ = flywheel(RIG, OMEGA, DELTA, balance=True, width_ratio=0.2, density=7800.0)
    exact = next(row for row in result["methods"] if row["method"] == "exact")
    machine = Machine("slider_crank", PARAMS, Inertias(J1=exact["inertia"], m2=24.2, J_S2=1.21, m3=36.2),
                      Load(crank_moment=result["balancing_moment"]), ENGINE)

    def rhs(_, y):
        tables = machine.tables(np.array([y[0]]))
        return [y[1], (tables.net_phi[0] - 0.5 * tables.dJ[0] * y[1] ** 2) / tables.J[0]]
    start = result["curves"]["omega_after"][0]
    turn = lambda _, y: y[0] - 2 * np.pi
    turn.terminal = True
    solution = solve_ivp(rhs, (0, 1.0), [0.0, start], method="DOP853", rtol=1e-12, atol=1e-12, events=turn,
                         dense_output=True)
    assert solution.y_events[0][0][1] == pytest.approx(start, rel=1e-8)          # started on the periodic state
    times = np.linspace(0, solution.t_events[0][0], 20001)
    omega = solution.sol(times)[1]
    delta = (omega.max() - omega.min()) / (0.5 * (omega.max() + omega.min()))
    # sampled extremes on 20001 points: error ~ (Δt)²ω''/8 ≈ 1e-9 of ω
    assert delta == pytest.approx(DELTA, rel=1e-6)


def test_machine_with_a_heavy_crank_needs_no_flywheel():
    heavy = Machine("slider_crank", PARAMS, Inertias(J1=200.0, m2=24.2, J_S2=1.21, m3=36.2), Load(), ENGINE)
    result, notices = flywheel(heavy, OMEGA, DELTA, balance=True, width_ratio=0.2, density=7800.0)
    assert result["flywheel_inertia"] == 0.0 and notices[0].code == "no_flywheel_needed"
    assert notices[0].context["achieved"] < DELTA


def test_unbalanced_cycle_is_not_periodic_and_says_why():
    result, notices = flywheel(RIG, OMEGA, DELTA, balance=False, width_ratio=0.2, density=7800.0)
    assert result == {} and notices[0].code.startswith("no_steady_cycle")


@pytest.mark.parametrize("delta", [0.001, 0.2])
def test_extreme_deltas_give_finite_answers(delta):
    result, _ = flywheel(RIG, OMEGA, delta, balance=True, width_ratio=0.2, density=7800.0)
    for row in result["methods"]:
        assert np.isfinite(row["inertia"]) and row["inertia"] > 0
    assert all(np.isfinite(v).all() for v in result["curves"].values())


def test_group_two_inertia_of_the_rig_matches_the_reduction():
    result, _ = flywheel(RIG, OMEGA, DELTA, balance=True, width_ratio=0.2, density=7800.0)
    direct = reduced_inertia("slider_crank", PARAMS, Inertias(m2=24.2, J_S2=1.21, m3=36.2), result["phi"]).J
    assert result["curves"]["inertia_ii"] == pytest.approx(direct, rel=1e-12)
