"""The compiled elastic path (server/core/elastic/compiled.py, dop853.py, radau.py) against the Python models and
scipy's solve_ivp, the reference path it was ported from."""
import math

import numpy as np
import pytest

from server.lessons.scenes import scenes
from server.api.endpoints import elastic_machine
from server.lessons.requests import scene_request, slider_values
from server.api.schemas_elastic import ElasticRequest
from server.core.elastic import report
from server.core.elastic.compiled import jac_of, rhs_of
from server.core.elastic.warm import ready
from server.core.elastic.periodic_table import PeriodicTable
from server.core.elastic.report import absolute_tolerances, build, simulate
from server.core.elastic.simulate import integrate
from test_elastic import STIFF_CASES

MOTORS = [{"kind": "constant", "M0": 40.0}, {"kind": "linear", "M0": 60.0, "b": 0.3},
          {"kind": "induction", "M_nominal": 10.0, "omega_nominal": 140.0, "omega_sync": 157.0},
          {"kind": "kloss", "M_max": 30.0, "omega_sync": 157.0, "s_critical": 0.2}]


def elastic_variants():
    return [(scene, variant) for scene in scenes().values() if scene.endpoint == "elastic" for variant in scene.variants
            if variant.id != "bearings"]


def random_machine(rng, scene, variant, motor=None, viscous=False):
    """The variant's request with every slider at a random position of its range (log sliders in log)."""
    values = {slider.id: float(rng.choice(slider_values(slider))) for slider in variant.sliders}
    body = scene_request(scene, variant, values, outputs=["histories"])
    if motor is not None and body["model"] != "kinematic_drive":
        body["motor"] = motor
    if viscous:
        body["load"] = body["load"] | {"beta": 50.0}
    return elastic_machine(ElasticRequest.model_validate(body))


def random_state(rng, model, y0):
    y = y0 + rng.normal(size=y0.size) * np.array([3.0, 20.0, 1e-3, 0.5] + [1e-3, 0.5, 1.0, 1.0, 1.0][:y0.size - 4])
    y[0] = rng.uniform(-20, 20)
    return y


@pytest.mark.parametrize("motor", MOTORS, ids=[m["kind"] for m in MOTORS])
def test_compiled_right_hand_side_and_jacobian_equal_the_python_models(motor):
    """Same formulas, same operation order for the tables: equal to 1e-12 of each row's scale (only the motor's
    and the tables' arithmetic may round differently)."""
    rng = np.random.default_rng(13)
    for scene, variant in elastic_variants():
        machine = random_machine(rng, scene, variant, motor, viscous=bool(rng.integers(2)))
        model, y0 = build(machine)
        f, J = rhs_of(model.compiled), jac_of(model.compiled)
        for _ in range(20):
            t, y = rng.uniform(0, 1), random_state(rng, model, y0)
            python, compiled = np.array(model.rhs(t, y)), f(t, y)
            assert compiled == pytest.approx(python, rel=1e-12, abs=1e-12 * np.abs(python).max())
            python_jac, compiled_jac = model.jac(t, y), J(t, y)
            for row_p, row_c in zip(python_jac, compiled_jac):
                assert row_c == pytest.approx(row_p, rel=1e-12, abs=1e-12 * np.abs(row_p).max() + 1e-300)


def test_compiled_jacobian_against_central_differences():
    """Central differences of the compiled f with step δ = 1e-6·max(1, |y_j|), the mechanism's angle in the middle
    of a table cell (the cubic pieces join with continuous slopes only, so a step across a node would differ by
    the jump of f″): truncation δ²f‴/6 and rounding ε|f|/δ stay below 1e-8 of the row's scale; 1e-6 of it
    leaves room, while a wrong entry is off by O(1)."""
    rng = np.random.default_rng(7)
    for scene, variant in elastic_variants():
        for motor in MOTORS:
            machine = random_machine(rng, scene, variant, motor, viscous=True)
            model, y0 = build(machine)
            f, J = rhs_of(model.compiled), jac_of(model.compiled)
            t, y = rng.uniform(0, 1), random_state(rng, model, y0)
            h = model.side.inertia.h                 # the mechanism's angle at a table cell's middle: no node
            middle = (rng.integers(model.side.inertia.n) + 0.5) * h      # within the steps (tables are C¹ only)
            if machine.model == "kinematic_drive":
                t = (middle + y[2]) / machine.speed
            else:
                y[0] = middle
            analytic = J(t, y)
            numeric = np.empty_like(analytic)
            for j in range(y.size):
                step = 1e-6 * max(1.0, abs(y[j]))
                up, down = y.copy(), y.copy()
                up[j] += step
                down[j] -= step
                numeric[:, j] = (f(t, up) - f(t, down)) / (2 * step)
            for row_a, row_n in zip(analytic, numeric):
                assert row_a == pytest.approx(row_n, abs=1e-6 * max(np.abs(row_n).max(), np.abs(row_a).max(), 1e-9))


def test_vectorised_table_reads_equal_the_scalar_ones():
    rng = np.random.default_rng(3)
    nodes = np.linspace(0, 2 * np.pi, 65)
    table = PeriodicTable(2 * np.pi, np.sin(3 * nodes) + 2, 3 * np.cos(3 * nodes))
    phi = np.concatenate([rng.uniform(-30, 30, 200), [0.0, 2 * np.pi, -2 * np.pi, np.nan, np.inf]])
    value, slope, curvature = table.evaluate(phi)
    scalar = np.array([table(p) for p in phi])
    vector = np.column_stack([value, slope, curvature])
    assert np.isfinite(vector[:-2]).all() and np.isfinite(scalar[:-2]).all()       # every finite angle: numbers
    assert np.allclose(vector[:-2], scalar[:-2], rtol=1e-14, atol=1e-13)
    assert np.isnan(vector[-2:]).all() and np.isnan(scalar[-2:]).all()             # NaN and ∞ in: NaN out


def drakunov_tuleshova_four_bar():
    scene = scenes()["elastic-four-bar"]
    return elastic_machine(ElasticRequest.model_validate(scene_request(scene, scene.variants[0])))


def test_compiled_dop853_takes_scipys_steps_on_the_drakunov_tuleshova_four_bar():
    """A line-for-line port: the same accepted and rejected steps (this case does not sit on a rounding-level
    step-size decision) and the twist to rounding amplified by the motion (1e-9 of its largest value)."""
    ready()
    machine = drakunov_tuleshova_four_bar()
    model, y0 = build(machine)
    samples = np.linspace(0.0, 0.5, 601)
    runs = [integrate(model, y0, 0.5, 1e-6, "DOP853", samples, math.inf, absolute_tolerances(machine, model, 1e-6),
                      engine=engine) for engine in ("scipy", "compiled")]
    (steps, rejected), (steps_c, rejected_c) = [(r.numerics["steps"], r.numerics["rejected"]) for r in runs]
    assert (steps_c, rejected_c) == (steps, rejected) and steps > 500
    twist = runs[0].y[2]
    assert np.max(np.abs(runs[1].y[2] - twist)) <= 1e-9 * np.max(np.abs(twist))


def test_compiled_radau_takes_scipys_steps_on_the_stiffest_belt():
    """Radau IIA ported: same steps, right-hand-side calls, Jacobians and LU decompositions as scipy's on the
    stiffness-ratio-1e6 belt; the twist to 1e-9 of its largest value (the LU differs from LAPACK's in rounding)."""
    ready()
    machine = STIFF_CASES["stiffness ratio 1e6"]
    model, y0 = build(machine)
    samples = np.linspace(0.0, 0.2, 201)
    runs = [integrate(model, y0, 0.2, 1e-6, "Radau", samples, math.inf, absolute_tolerances(machine, model, 1e-6),
                      engine=engine) for engine in ("scipy", "compiled")]
    counts = [tuple(r.numerics[k] for k in ("steps", "nfev", "njev", "nlu")) for r in runs]
    assert counts[0] == counts[1]
    twist = runs[0].y[2]
    assert np.max(np.abs(runs[1].y[2] - twist)) <= 1e-9 * np.max(np.abs(twist))


def test_compiled_and_scipy_paths_agree_on_random_machines_to_their_error_estimates():
    """Random slider positions of every elastic scene (and its motors). Where both take the same steps they agree
    to rounding; where a rounding-level difference flips one step-size decision (the belt's many rejections do)
    they are two runs at the same tolerance, so they differ by at most the sum of their true errors — which the
    app's error estimate bounds within a factor 10 (test_elastic's stiff cases check that against a reference)."""
    rng = np.random.default_rng(2026)
    for scene, variant in elastic_variants():
        machine = random_machine(rng, scene, variant)
        scipy_run, compiled_run = [simulate(machine, 0.2, 101, 1e-6, with_rigid=False, engine=engine)[0]
                                   for engine in ("scipy", "compiled")]
        scale = np.max(np.abs(scipy_run["twist"]))
        bound = 10 * (scipy_run["numerics"]["error_estimate"] + compiled_run["numerics"]["error_estimate"]) + 1e-9
        assert np.max(np.abs(compiled_run["twist"] - scipy_run["twist"])) <= bound * scale, (scene.id, variant.id)
        assert compiled_run["numerics"]["method"] == scipy_run["numerics"]["method"]
        steps = scipy_run["numerics"]["steps"]
        assert abs(compiled_run["numerics"]["steps"] - steps) <= 0.05 * steps


def test_the_compiled_run_stops_at_its_work_bound_and_says_so():
    """A very stiff undamped belt under DOP853: tiny explicit steps; the bound on right-hand-side calls holds inside
    the compiled loop, and the partial result says so in words."""
    machine = report.ElasticMachine(**{**STIFF_CASES["no damping"].__dict__, "c": 1e12})
    model, y0 = build(machine)
    run = integrate(model, y0, 1.0, 1e-10, "DOP853", np.linspace(0, 1, 11), math.inf,
                    absolute_tolerances(machine, model, 1e-10), max_evaluations=5000)
    assert not run.complete and run.t.size == 0 and "work bound" in run.numerics["message"]
    assert run.numerics["nfev"] <= 5000 + 16


def test_simulate_computes_the_rigid_start_up_only_when_asked():
    machine = STIFF_CASES["no damping"]
    without, _ = simulate(machine, 0.1, 51, 1e-6, with_rigid=False)
    with_rigid, _ = simulate(machine, 0.1, 51, 1e-6, with_rigid=True)
    assert "rigid" not in without and np.isfinite(with_rigid["rigid"]["omega"]).all()


@pytest.mark.parametrize("case", ["belt", "four-bar"])
def test_the_compiled_rigid_start_up_equals_the_equation_of_motions_start_up(case):
    """report.rigid (J(φ)ω̇ + ½J′ω² = M − M_c in time, compiled DOP853 at rtol 1e-10) against /motion's start-up
    (RK4 in φ on dT/dφ, another method in another variable), read at the start-up's own nodes (no interpolation).
    Tolerance 5e-6 of the top speed: the RK4 steps across the load's jumps at the dead centres (first order there)
    and differs from a DOP853 run at rtol 1e-12 by 1e-6; the compiled run differs from that one by 4e-9."""
    from server.core.dynamics.machine import Machine
    from server.core.dynamics.motion import startup
    from server.core.dynamics.reduction import Inertias
    machine = STIFF_CASES["no damping"] if case == "belt" else drakunov_tuleshova_four_bar()
    inertias = Inertias(**{**machine.inertias.__dict__, "J1": machine.inertias.J1 + machine.J_motor, "J_rotor": 0.0})
    run = startup(Machine(machine.mechanism, machine.params, inertias, machine.load, machine.motor), 0.0, rtol=0.0,
                  max_cycles=40).transient
    nodes = run.t <= 1.0
    rigid = report.rigid(machine, run.t[nodes])
    scale = np.max(run.omega[nodes])
    assert np.max(np.abs(rigid["omega"] - run.omega[nodes])) <= 5e-6 * scale
    assert np.max(np.abs(rigid["phi"] - run.phi[nodes])) <= 5e-6 * np.max(run.phi[nodes])


def test_the_rigid_machine_that_stalls_stands_where_the_motion_start_up_stalls():
    """A motor torque that moves the crank off the dead centre (M_c = 0 there) but not past the working stroke:
    ω rises, falls back to zero, and from there φ, ω are undefined; /motion's start-up stalls at the same angle
    (to its RK4 step, 2π/256)."""
    from server.core.dynamics.machine import Machine
    from server.core.dynamics.motion import startup
    from server.core.dynamics.motors import Motor
    from server.core.dynamics.reduction import Inertias
    machine = report.ElasticMachine(**{**STIFF_CASES["no damping"].__dict__, "motor": Motor("constant", M0=1e-3)})
    t = np.linspace(0.0, 0.5, 501)
    rigid = report.rigid(machine, t)
    moving = np.isfinite(rigid["omega"])
    assert moving[:2].all() and not moving[-1] and (rigid["omega"][1:][moving[1:]] > 0).all()
    assert np.isnan(rigid["omega"][np.argmin(moving):]).all()              # it stays stopped
    inertias = Inertias(**{**machine.inertias.__dict__, "J1": machine.inertias.J1 + machine.J_motor, "J_rotor": 0.0})
    motion = startup(Machine(machine.mechanism, machine.params, inertias, machine.load, machine.motor), 0.0,
                     rtol=0.0, max_cycles=4)
    assert motion.transient.stall_phi == pytest.approx(np.nanmax(rigid["phi"]), abs=2 * np.pi / 256)


def test_after_warm_up_no_request_compiles_anything():
    """warm_up compiles every signature a request uses: no student's request (nor a run's time budget) ever waits
    for the compiler. Counted as the dispatchers' compiled signatures before and after requests of every kind."""
    from server.core.elastic import compiled, dop853, radau
    ready()
    dispatchers = [getattr(module, name) for module in (compiled, dop853, radau) for name in dir(module)
                   if hasattr(getattr(module, name), "signatures")]
    before = [len(d.signatures) for d in dispatchers]
    rng = np.random.default_rng(5)
    for scene, variant in elastic_variants():
        simulate(random_machine(rng, scene, variant), 0.05, 21, 1e-6, with_rigid=False)
    simulate(STIFF_CASES["stiffness ratio 1e6"], 0.05, 21, 1e-6, with_rigid=False)
    assert [len(d.signatures) for d in dispatchers] == before
