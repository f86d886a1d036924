"""The compiled loops of the equation of motion against their reference paths, on random machines.

- RK4 in φ (compiled.rk4_steps) against the plain Python loop of integrator.integrate: the same scalar
  operations in the same order in IEEE double arithmetic, so the two agree to rounding. We allow 1e-12
  relative: LLVM may contract a·b + c into one fused multiply-add (one rounding instead of two, ~1e-16 per
  operation), and those differences may accumulate over a cycle of a few thousand steps (≲1e-13).
- DOP853 leaving rest (dop853.leave_rest) against scipy's solve_ivp(method="DOP853") with the same events on
  the same right-hand side (the same Chebyshev table): the same coefficients, step control and event
  location, with sums in another order than numpy's dot products (BLAS). Where both take the same steps the
  event times and speeds agree to ~1e-13 (8 of these 12 machines). But the first steps from rest have error
  estimates at rounding level (~1e-8 of the tolerance), so the summation order can change the next step
  size and the two step sequences part; the results then agree to the method's accuracy at rtol = 1e-11
  (measured ≤ 5e-11). We allow 1e-9.
- The whole start from rest (compiled table over a longer reach against the reference table with direct
  evaluation outside it) agrees within DOP853's tolerance: 1e-9 relative (measured ≤ 1e-10).
"""
import time

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from server.core.dynamics import compiled, dop853, integrator
from server.core.dynamics.machine import Machine
from server.core.dynamics.motion import cycle_tables, node_tables, startup, steady_cycle
from server.core.dynamics.motors import Motor
from server.core.dynamics.reduction import Inertias
from server.core.dynamics.resistance import Load
from server.core.mechanisms import MECHANISMS

RNG_SEEDS = range(12)


def random_machine(seed: int) -> Machine:
    """A crank-slider or sine machine with a random speed-dependent motor, load and friction."""
    rng = np.random.default_rng(seed)
    kind = ("linear", "induction", "kloss", "constant")[seed % 4]
    mechanism = "slider_crank" if seed % 3 else "sine"
    params = {"l1": 0.1, "l2": float(rng.uniform(0.25, 0.5))} if mechanism == "slider_crank" else {"l1": 0.1}
    p = MECHANISMS[mechanism].check(params)
    motor = {"linear": Motor("linear", M0=float(rng.uniform(60, 120)), b=float(rng.uniform(0.1, 0.5))),
             "induction": Motor("induction", M_nominal=float(rng.uniform(20, 40)), omega_nominal=145.0,
                                omega_sync=157.0),
             "kloss": Motor("kloss", M_max=float(rng.uniform(40, 80)), s_critical=float(rng.uniform(0.1, 0.3)),
                            omega_sync=157.0),
             "constant": Motor("constant", M0=float(rng.uniform(20, 40)))}[kind]
    beta = float(rng.uniform(1.0, 20.0)) if kind == "constant" else float(rng.choice([0.0, rng.uniform(0, 10)]))
    load = Load(float(rng.uniform(500, 2000)), float(rng.uniform(0.1, 1.0)), float(rng.uniform(0, 0.2)), beta=beta)
    inertias = Inertias(J1=float(rng.uniform(0.2, 1.0)), m2=float(rng.uniform(1, 8)), J_S2=0.05,
                        m3=float(rng.uniform(2, 15)), J_rotor=0.01, gear_ratio=5.0)
    return Machine(mechanism, p, inertias, load, motor)


@pytest.mark.parametrize("seed", RNG_SEEDS)
def test_compiled_rk4_agrees_with_the_python_loop(seed):
    machine = random_machine(seed)
    tables = node_tables(machine, 256)
    T0 = 0.5 * tables.J[0] * float(np.random.default_rng(seed).uniform(5, 40)) ** 2
    fast = integrator.integrate(machine, tables, T0, 256, compiled=True)
    reference = integrator.integrate(machine, tables, T0, 256, compiled=False)
    assert fast.stall_phi == reference.stall_phi
    assert fast.T.size == reference.T.size
    assert fast.T == pytest.approx(reference.T, rel=1e-12)
    assert fast.t == pytest.approx(reference.t, rel=1e-12)
    assert fast.sensitivity == pytest.approx(reference.sensitivity, rel=1e-12)


@pytest.mark.parametrize("seed", RNG_SEEDS)
def test_compiled_rk4_agrees_with_the_python_loop_with_the_kinks_on_nodes(seed):
    """The same on motion.cycle_tables: segments between the kinks, each kink a node on either side."""
    machine = random_machine(seed)
    tables = cycle_tables(machine, machine.kinks(), 256)
    steps = tables.starts.size
    T0 = 0.5 * tables.J[0] * float(np.random.default_rng(seed).uniform(5, 40)) ** 2
    fast = integrator.integrate(machine, tables, T0, steps, compiled=True)
    reference = integrator.integrate(machine, tables, T0, steps, compiled=False)
    assert fast.stall_phi == reference.stall_phi and fast.T.size == reference.T.size
    assert fast.T == pytest.approx(reference.T, rel=1e-12)
    assert fast.t == pytest.approx(reference.t, rel=1e-12)
    assert fast.sensitivity == pytest.approx(reference.sensitivity, rel=1e-12)


def test_compiled_rk4_finds_the_same_stall():
    """A weak motor: both loops stop at the same node."""
    p = MECHANISMS["slider_crank"].check({"l1": 0.1, "l2": 0.3})
    machine = Machine("slider_crank", p, Inertias(J1=0.5, m2=5.0, J_S2=0.05, m3=10.0, J_rotor=0.01, gear_ratio=5.0),
                      Load(2000.0, 0.2, 0.1), Motor("linear", M0=10.0, b=0.3))
    tables = node_tables(machine, 256)
    fast = integrator.integrate(machine, tables, 5.0, 256, compiled=True)
    reference = integrator.integrate(machine, tables, 5.0, 256, compiled=False)
    assert fast.stall_phi is not None and fast.stall_phi == reference.stall_phi
    assert fast.T == pytest.approx(reference.T, rel=1e-12)


def scipy_leave_rest(machine, table, phi, t_end):
    """scipy's DOP853 with the reference's events on the right-hand side of the same table."""
    def rhs(_, y):
        J, dJ, moment, sliding = table.at(y[0])
        if machine.speed_dependent:
            moment += machine.speed_moment(y[1], sliding)[0]
        return [y[1], (moment - 0.5 * dJ * y[1] ** 2) / J]

    def passing(node):
        def event(_, y):
            return y[0] - node
        event.terminal = node == phi[-1]
        return event

    def stalls(_, y):
        return y[1]
    stalls.terminal, stalls.direction = True, -1
    solution = solve_ivp(rhs, (0.0, t_end), [phi[0], 0.0], method="DOP853", rtol=1e-11, atol=1e-14,
                         events=[passing(node) for node in phi[1:]] + [stalls])
    times = np.array([e[0] if e.size else np.nan for e in solution.t_events[:-1]])
    speeds = np.array([y[0][1] if y.size else np.nan for y in solution.y_events[:-1]])
    return times, speeds


@pytest.mark.parametrize("seed", RNG_SEEDS)
def test_compiled_dop853_takes_scipys_steps(seed):
    machine = random_machine(seed)
    phi = node_tables(machine, 256).phi[0:33:2]
    span = phi[-1] - phi[0]
    table = integrator.RestTable(machine, float(phi[0]), float(phi[-1] + integrator.REST_REACH * span))
    assert table.tabulated
    t_end = integrator._time_bound(machine, table, phi)
    speed, kind, params = compiled.speed_parameters(machine)
    times, speeds = np.empty(phi.size - 1), np.empty(phi.size - 1)
    compiled.warm_up()
    outcome = dop853.leave_rest(table.nodes, table.weights, np.ascontiguousarray(table.values), table.a, table.b,
                                speed, kind, params, np.ascontiguousarray(phi[1:]), t_end, 1e-11, 1e-14,
                                time.perf_counter() + 60.0, times, speeds)
    assert outcome == dop853.DONE
    ref_times, ref_speeds = scipy_leave_rest(machine, table, phi, t_end)
    assert np.array_equal(np.isnan(times), np.isnan(ref_times))
    assert times == pytest.approx(ref_times, rel=1e-9, nan_ok=True)
    assert speeds == pytest.approx(ref_speeds, rel=1e-9, nan_ok=True)


@pytest.mark.parametrize("seed", RNG_SEEDS)
def test_the_compiled_start_from_rest_agrees_with_the_reference_path(seed):
    machine = random_machine(seed)
    phi = node_tables(machine, 256).phi[0:33:2]
    fast = np.array(integrator.leave_rest(machine, phi, 0.0, compiled=True))
    reference = np.array(integrator.leave_rest(machine, phi, 0.0, compiled=False))
    assert fast.shape == reference.shape
    assert fast == pytest.approx(reference, rel=1e-9)


@pytest.mark.parametrize("seed", RNG_SEEDS[:6])
def test_steady_cycle_and_start_up_agree_between_the_paths(monkeypatch, seed):
    """The whole answer: Newton shooting and the start-up with the compiled loops and with the references."""
    machine = random_machine(seed)
    fast_steady, fast_start = steady_cycle(machine, rtol=1e-8), startup(machine, 0.0, 1e-8, 80)
    monkeypatch.setattr(integrator, "COMPILED", False)
    slow_steady, slow_start = steady_cycle(machine, rtol=1e-8), startup(machine, 0.0, 1e-8, 80)
    assert (fast_steady.steady is None) == (slow_steady.steady is None)
    if fast_steady.steady is not None:
        assert fast_steady.numerics.steps == slow_steady.numerics.steps
        assert fast_steady.steady.omega == pytest.approx(slow_steady.steady.omega, rel=1e-12)
        assert fast_steady.steady.delta == pytest.approx(slow_steady.steady.delta, rel=1e-9, abs=1e-14)
    assert fast_start.numerics.cycles == slow_start.numerics.cycles
    if fast_start.transient is not None:
        # the start from rest differs within DOP853's tolerance (1e-9 above); it carries into the cycles
        assert fast_start.transient.omega == pytest.approx(slow_start.transient.omega, rel=1e-8)
        assert fast_start.transient.t == pytest.approx(slow_start.transient.t, rel=1e-8)


@pytest.mark.parametrize("seed", RNG_SEEDS[:6])
def test_cycles_run_at_once_are_the_cycles_run_one_by_one_bit_for_bit(seed):
    """integrator.cycles (compiled.rk4_cycles: whole cycles in one compiled call, the start-up's motion._cycles)
    against integrate called cycle after cycle from each cycle's end, as the start-up did before: the same
    floating-point operations in the same order, so every node's T, ω, t, the sensitivity, the stall and where
    the cycle-start energy settles are equal exactly."""
    machine = random_machine(seed)
    tables = cycle_tables(machine, machine.kinks(), 256)
    steps, T0 = tables.starts.size, 0.5 * float(tables.J[0]) * 40.0 ** 2
    runs = integrator.cycles(machine, tables, T0, 0.0, steps, 12, 1e-6)
    T, t = T0, 0.0
    for run in runs:
        one = integrator.integrate(machine, tables, T, steps, t)
        for a, b in ((run.phi, one.phi), (run.T, one.T), (run.omega, one.omega), (run.t, one.t)):
            assert np.array_equal(a, b)
        assert (run.sensitivity, run.stall_phi) == (one.sensitivity, one.stall_phi)
        T, t = one.T[-1], one.t[-1]
    last = runs[-1]
    assert len(runs) == 12 or last.stall_phi is not None or abs(last.T[-1] - last.T[0]) <= 1e-6 * last.T[-1]


def test_the_compiled_mean_of_the_extremes_is_the_numpy_one_exactly():
    """flywheel.periodic_speed's equation (ω_max + ω_min)/2 = ω_m, compiled without arrays, against
    numerics.parabola_extremum on the numpy array: the same divisions, square roots and parabola in the same order, and the
    first of tied samples taken as numpy's argmax does (the kernel compares ω² and resolves ties of ω after),
    so equal to the last bit, also where a zero inertia gives inf or a negative energy NaN (numpy's argmax
    takes the first NaN)."""
    from server.core.dynamics.compiled import mean_of_extremes
    from server.core.numerics import parabola_extremum as _extreme
    rng = np.random.default_rng(7)
    phi = np.linspace(0, 2 * np.pi, 2049)
    for trial in range(400):
        work = (rng.normal() * np.sin(phi + rng.uniform()) + 0.3 * rng.normal() * np.sin(3 * phi) if trial % 3
                else np.cumsum(rng.normal(size=phi.size)) * 0.01)
        total = rng.uniform(0.5, 2) + rng.uniform(0, 1) * np.cos(phi) ** 2
        if trial % 7 == 0:                 # equal samples: the first of a tie must be the one taken
            work, total = np.round(work, 2), np.round(total, 1)
        if trial % 10 == 0:
            total[int(rng.integers(0, phi.size))] = 0.0
        T0 = float(rng.uniform(-0.5, 3))
        with np.errstate(all="ignore"):
            omega = np.sqrt(2 * (T0 + work) / total)
            expected = 0.5 * (_extreme(omega, +1) + _extreme(omega, -1))
        assert mean_of_extremes(work, total, T0) == pytest.approx(expected, rel=0, abs=0, nan_ok=True)
