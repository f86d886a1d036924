"""The equation of motion against analytic solutions, conservation of energy and an independent ODE solver."""
import numpy as np
import pytest
from scipy.integrate import solve_ivp

from server.core.dynamics import integrator
from server.core.dynamics.integrator import RestTable, leave_rest
from server.core.dynamics.machine import Machine
from server.core.dynamics.motion import startup, steady_cycle
from server.core.dynamics.motors import Motor, driving_moment
from server.core.dynamics.reduction import Inertias, reduced_inertia
from server.core.dynamics.resistance import Load, resisting_moment
from server.core.mechanisms import MECHANISMS


def crank_slider_machine(motor=Motor(kind="linear", M0=60.0, b=0.3), load=Load(2000.0, 0.2, 0.1)):
    p = MECHANISMS["slider_crank"].check({"l1": 0.1, "l2": 0.3})
    return Machine("slider_crank", p, Inertias(J1=0.5, m2=5.0, J_S2=0.05, m3=10.0, J_rotor=0.01, gear_ratio=5.0),
                   load, motor)


def test_constant_inertia_linear_motor_approaches_speed_exponentially():
    """J ω̇ = i(M₀ − b i ω): ω = ω∞(1 − e^{−t/τ}), ω∞ = M₀/(b i), τ = J/(b i²)."""
    p = MECHANISMS["sine"].check({"l1": 0.1})
    machine = Machine("sine", p, Inertias(J1=0.2, J_rotor=0.004, gear_ratio=4.0), Load(), Motor("linear", M0=8.0, b=0.05))
    J, i, b = 0.2 + 0.004 * 16, 4.0, 0.05
    run = startup(machine, 0.0, rtol=1e-9, max_cycles=200).transient
    tau, w_inf = J / (b * i * i), 8.0 / (b * i)
    expected = w_inf * (1 - np.exp(-run.t / tau))
    # RK4 in φ with 256 steps per turn: local error ~h⁵; the start-up from rest is the worst part
    assert run.omega[1:] == pytest.approx(expected[1:], rel=2e-5)
    steady = steady_cycle(machine).steady
    assert steady.omega_mean == pytest.approx(w_inf, rel=1e-10) and steady.delta == pytest.approx(0, abs=1e-10)


def time_domain(machine, omega0, t_end, events=None):
    """Independent check: J(φ)ω̇ + ½J′ω² = M_д − M_c integrated in time by scipy's DOP853."""
    def rhs(t, y):
        phi, omega = np.array([y[0]]), y[1]
        inertia = reduced_inertia(machine.mechanism, machine.params, machine.inertias, phi)
        resisting = resisting_moment(machine.mechanism, machine.params, machine.load, phi, omega).total[0]
        i = machine.inertias.gear_ratio
        drive = i * machine.motor.torque(i * omega)[0]
        return [omega, (drive - resisting - 0.5 * inertia.dJ[0] * omega**2) / inertia.J[0]]
    return solve_ivp(rhs, (0, t_end), [0.0, omega0], method="DOP853", rtol=1e-12, atol=1e-12, events=events,
                     dense_output=True)


def test_steady_cycle_by_shooting_matches_many_cycles_of_a_time_domain_solver():
    machine = crank_slider_machine()
    steady = steady_cycle(machine, rtol=1e-9).steady
    period = steady.t[-1]
    crossing = lambda t, y: np.sin(y[0] / 2)          # φ = 2πk
    crossing.direction = 0
    # from 10 % below, the cycle-start speed settles by a factor ~7 a cycle: 0.1 / 7¹¹ ≈ 5e-11 by cycle 12
    sol = time_domain(machine, steady.omega[0] * 0.9, 12 * period, events=crossing)
    starts = sol.y_events[0][:, 1]
    times = sol.t_events[0]
    assert abs(starts[-1] - starts[-2]) < 1e-9 * starts[-1]          # the time-domain run has settled
    assert starts[-1] == pytest.approx(steady.omega[0], rel=1e-8)   # ω at φ = 0 on the cycle
    assert times[-1] - times[-2] == pytest.approx(period, rel=1e-8)  # cycle time


def test_work_of_all_moments_over_the_steady_cycle_is_zero():
    steady = steady_cycle(crank_slider_machine(load=Load(2000.0, 0.2, 0.1, beta=20.0)), rtol=1e-9).steady
    w = steady.works
    assert abs(w["net"]) <= 1e-8 * w["driving"]
    # η = A_useful/(A_useful + A_losses) (the driving work by the energy balance of the cycle); the driving
    # work integrated directly agrees to the energy residual, ≤ 1e-8 here
    assert steady.efficiency == pytest.approx(w["useful"] / (w["useful"] + w["dry_friction"] + w["viscous_friction"]),
                                              rel=1e-15)
    assert steady.efficiency == pytest.approx(w["useful"] / w["driving"], rel=1e-8)
    assert 0 < steady.efficiency < 1


def test_energy_path_agrees_with_time_domain_solution_for_moments_of_phi_alone():
    machine = crank_slider_machine(motor=Motor("constant", M0=30.0))
    run = startup(machine, omega0=20.0, rtol=0.0, max_cycles=2).transient
    sol = time_domain(machine, 20.0, run.t[-1])
    phi_at = sol.sol(run.t)[0]
    omega_at = sol.sol(run.t)[1]
    assert phi_at == pytest.approx(run.phi, abs=1e-7)              # Simpson's t(φ) against the ODE's φ(t)
    assert omega_at == pytest.approx(run.omega, rel=1e-7)


def test_weak_motor_stalls_with_words_and_no_numbers():
    machine = crank_slider_machine(motor=Motor(kind="linear", M0=10.0, b=0.3))
    result = steady_cycle(machine)
    assert result.steady is None and "Stall" in result.numerics.message
    start = startup(machine, 0.0)
    assert "cannot start" in start.numerics.message or "Stall" in start.numerics.message


def test_self_locking_machine_does_not_move():
    p = MECHANISMS["slider_crank"].check({"l1": 0.1, "l2": 0.101})
    machine = Machine("slider_crank", p, Inertias(J1=1.0), Load(100.0, f=0.3), Motor("linear", M0=100.0, b=1.0))
    result = steady_cycle(machine)
    assert result.steady is None and result.notices[0].code == "slider_crank_self_locking"


def test_unbalanced_moments_of_phi_alone_have_no_steady_cycle():
    result = steady_cycle(crank_slider_machine(motor=Motor("constant", M0=30.0)), omega_mean=20.0)
    assert result.steady is None and result.notices[0].code == "no_steady_cycle_speeds"


def test_piston_engine_with_balanced_load_runs_at_the_given_mean_speed():
    p = MECHANISMS["slider_crank"].check({"l1": 0.12, "l2": 0.528, "a2": 0.169 / 0.528})
    engine = Motor("indicator", p_max=4.4e6, piston_diameter=0.1)
    inertias = Inertias(J1=2.72, m2=24.2, J_S2=1.21, m3=36.2)
    probe = steady_cycle(Machine("slider_crank", p, inertias, Load(), engine), omega_mean=47.124)
    assert probe.notices[0].code.startswith("no_steady_cycle")
    result = steady_cycle(Machine("slider_crank", p, inertias, Load(), engine), omega_mean=47.124, balance=True)
    steady = result.steady
    assert steady.omega_mean == pytest.approx(47.124, rel=1e-9)
    assert 0 < steady.delta < 0.2
    # the balancing moment is the mean driving moment A_д/2π (Lecture 10 (L8))
    phi = np.linspace(0, 2 * np.pi, 400001)
    mean_drive = np.mean(driving_moment(engine, "slider_crank", p, phi, 0.0)[:-1])
    assert steady.works["balancing_moment"] == pytest.approx(mean_drive, rel=1e-6)


def test_the_start_from_rest_table_matches_direct_evaluation_between_its_nodes():
    """The Chebyshev table of J, J′, M(φ), S(φ) over the first steps reproduces the machine's own functions
    at random angles to 1e-12 of their size (the polynomial of 33 points converges geometrically for these
    smooth functions; measured ~1e-15)."""
    machine = crank_slider_machine(load=Load(2000.0, 0.2, 0.1, beta=3.0))
    table = RestTable(machine, 0.0, 0.5)
    assert table.tabulated
    for phi in np.random.default_rng(3).uniform(0.0, 0.5, 50):
        direct = table.direct(np.array([phi]))[0]
        assert np.all(np.abs(table.at(phi) - direct) <= 1e-12 * np.max(np.abs(table.values), axis=0))
    assert np.array_equal(table.at(float(table.nodes[5])), table.values[5])       # on a node: its value


def test_a_kink_inside_the_interval_falls_back_to_direct_evaluation():
    """An indicator diagram is piecewise linear: over half a turn its corners defeat any polynomial."""
    p = MECHANISMS["slider_crank"].check({"l1": 0.12, "l2": 0.528})
    engine = Machine("slider_crank", p, Inertias(J1=2.72, m2=24.2, J_S2=1.21, m3=36.2), Load(),
                     Motor("indicator", p_max=4.4e6, piston_diameter=0.1, strokes=2))
    table = RestTable(engine, 0.1, np.pi - 0.1)
    assert not table.tabulated
    assert np.array_equal(table.at(1.0), table.direct(np.array([1.0]))[0])


def test_leaving_rest_with_the_table_agrees_with_direct_evaluation(monkeypatch):
    machine = crank_slider_machine()
    nodes = np.linspace(0.0, 16 * 2 * np.pi / 256, 17)
    tabulated = leave_rest(machine, nodes, 0.0)
    monkeypatch.setattr(integrator, "REST_TABLE_RTOL", -1.0)          # no table passes: direct evaluation
    direct = leave_rest(machine, nodes, 0.0)
    assert len(tabulated[0]) == len(direct[0]) == 16
    assert np.asarray(tabulated) == pytest.approx(np.asarray(direct), rel=1e-10)   # DOP853 runs at rtol 1e-11


def test_a_piston_engine_at_a_given_mean_speed_stalls_exactly_where_the_energy_runs_out():
    """The two-stroke engine of Lecture 10's flywheel example (balanced, φ-only moments, the mean speed given):
    a periodic motion exists iff some T₀ keeps T₀ + A(φ) > 0 with (ω_max + ω_min)/2 = ω_m, i.e. iff ω_m is above
    the mean of the extremes at T₀ = max(−A). That critical speed from A(φ) on 2,000,001 angles (trapezoid,
    the balancing moment as the cycle's mean moment) is 13.720 rad/s. 0.1 % below it: a stall in words. 0.2 %
    above it and beyond: a steady cycle within rtol (ω_min is small there and the levels go up to 24,576 steps).
    Between (0.1 % above, 13.7354): no crash, and either a steady cycle within rtol or, with no result, the
    words that rtol was not reached within STEPS_MAX steps. (A coarse level's RK4 stage that overshot the dip
    at 14.5 rad/s used to be taken for a stall, and a level stalling where the one before had not crashed the
    Richardson differences at 13.7354 rad/s.)"""
    from scipy.integrate import cumulative_trapezoid
    params = MECHANISMS["slider_crank"].check({"l1": 0.12, "l2": 0.528, "a2": 0.169 / 0.528})
    engine = Machine("slider_crank", params, Inertias(J1=2.72, m2=24.2, J_S2=1.21, m3=36.2), Load(),
                     Motor("indicator", p_max=4.4e6, piston_diameter=0.1))
    phi = np.linspace(0, 2 * np.pi, 2_000_001)
    tables = engine.tables(phi)
    work = cumulative_trapezoid(tables.net_phi, phi, initial=0.0)
    work -= work[-1] * phi / phi[-1]
    lowest = np.max(-work)
    speed = np.sqrt(np.maximum(2 * (lowest + work) / tables.J, 0.0))
    critical = 0.5 * (speed.max() + speed.min())
    assert critical == pytest.approx(13.720, abs=1e-3)
    below = steady_cycle(engine, 1e-8, critical * 0.999, balance=True)
    assert below.steady is None and "Stall" in below.numerics.message
    edge = steady_cycle(engine, 1e-8, 13.7353515625, balance=True)
    assert (edge.steady is not None and edge.numerics.error_estimate <= 1e-8) or \
        (edge.steady is None and "was not reached within" in edge.numerics.message)
    for omega_mean in (critical * 1.002, 14.5):
        result = steady_cycle(engine, 1e-8, omega_mean, balance=True)
        assert result.steady is not None, (omega_mean, result.numerics.message)
        assert result.steady.omega_mean == pytest.approx(omega_mean, rel=1e-8)
        assert result.numerics.error_estimate <= 1e-8
