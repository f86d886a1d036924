"""API fuzzing of the solvers behind the scenes: no set-up a student can reach makes the server answer 5xx.

Random inputs mostly fail the models' cross-field checks (a motor needs its torque, a machine its inertia), so
the solvers are reached from the scenes' own set-ups instead: each scene variant's request with one to three
inputs moved anywhere their schema (or the mechanism's parameter ranges, or a slider) allows, boundaries
included. Every answer is 200 or 422, never a crash. In-process (no server, no network), with a fixed seed so
CI is reproducible (MDL_FUZZ_SEED=<n> explores other inputs; MDL_FUZZ_EXAMPLES=<n> sets the examples per
endpoint, 12 by default in the suite, the set-ups' budgets below scaled alike; a deeper run:
MDL_FUZZ_EXAMPLES=100). Requests the OpenAPI schema describes, valid and broken, over every operation, with a
student's and an instructor's secrets: tests/test_schemathesis_api.py.

Data the app might store goes to a pytest tmp directory (MDL_DATA_DIR), and Hypothesis keeps no example
database in the repository. Each crash the fuzzing found is pinned by a plain test at the end of this file.
"""
from __future__ import annotations

import copy
import faulthandler
import json
import math
import os
import sys

import numpy as np
import pytest
from fastapi.testclient import TestClient
from hypothesis import HealthCheck, Phase, given, seed, settings
from hypothesis import strategies as st

from server.api.app import create_app
from server.lessons.scenes import scenes
from server.core.mechanisms import MECHANISMS

from openapi_document import openapi_document

SEED = int(os.environ.get("MDL_FUZZ_SEED", "20269"))
SCALE = float(os.environ.get("MDL_FUZZ_EXAMPLES", "12")) / 30       # the budgets below are written for 30
API = "/api/v1"
QUIET = [HealthCheck.too_slow, HealthCheck.filter_too_much, HealthCheck.data_too_large,
         HealthCheck.function_scoped_fixture]


def examples(n: int) -> int:
    return max(1, round(n * SCALE))


OPENAPI = openapi_document()     # the document only; the requests go to fuzz_app, built with its data dir


@pytest.fixture(autouse=True)
def watchdog():
    """A request that never returns (an endless loop in a solver) ends the run with every thread's traceback
    instead of hanging CI."""
    faulthandler.dump_traceback_later(600 * max(1.0, SCALE), exit=True, file=sys.__stderr__)
    yield
    faulthandler.cancel_dump_traceback_later()


@pytest.fixture(scope="module")
def fuzz_app(tmp_path_factory):
    """The app built afresh with its data directory (MDL_DATA_DIR) in a pytest tmp directory."""
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv("MDL_DATA_DIR", str(tmp_path_factory.mktemp("mdl-data")))
        yield create_app()


@pytest.fixture(scope="module")
def client(fuzz_app):
    return TestClient(fuzz_app, raise_server_exceptions=True)


# --- 1. the scenes' set-ups, moved within their bounds -------------------------------------------------------

def set_path(body: dict, path: tuple, value) -> None:
    for key in path[:-1]:
        if not isinstance(body.get(key), dict):
            body[key] = {}
        body = body[key]
    body[path[-1]] = value


def get_path(body: dict, path: tuple):
    for key in path:
        body = body[key]
    return body


def scene_body(scene, variant) -> dict:
    """The body the scene page sends with every slider and toggle at its default (scene_model.js)."""
    if scene.kind == "kinematics":
        params = dict(variant.fixed)
        for toggle in variant.toggles:
            params[toggle.param] = toggle.default
        for slider in variant.sliders:
            params[slider.param] = slider.default * (params[slider.scale] if slider.scale else 1)
        return {"mechanism": variant.mechanism, "params": params, "n": 361}
    body = copy.deepcopy(variant.request) | {"mechanism": variant.mechanism}
    for toggle in variant.toggles:
        set_path(body, tuple(toggle.param.split(".")), toggle.default)
    for slider in variant.sliders:
        scale = get_path(body, tuple(slider.scale.split("."))) if slider.scale else 1
        for path in (slider.param, *slider.also):
            set_path(body, tuple(path.split(".")), slider.default * slider.to_si * scale)
    return body


def number(spec: dict) -> st.SearchStrategy:
    """Any value the bounds allow, its edges and a log-uniform spread over decades."""
    low, high = spec.get("minimum", spec.get("exclusiveMinimum")), spec.get("maximum", spec.get("exclusiveMaximum"))
    low_open, high_open = "exclusiveMinimum" in spec, "exclusiveMaximum" in spec
    if spec.get("type") == "integer":
        return st.integers(math.floor(low) + 1 if low_open else math.ceil(low), math.ceil(high) - 1 if high_open
                           else math.floor(high))
    edge_low = math.nextafter(low, math.inf) if low_open else low
    edge_high = math.nextafter(high, -math.inf) if high_open else high
    choices = [st.sampled_from([edge_low, edge_high]),
               st.floats(low, high, exclude_min=low_open, exclude_max=high_open)]
    if high > 0:
        floor = max(edge_low, 1e-12)
        choices.append(st.floats(math.log10(floor), math.log10(edge_high)).map(
            lambda x: min(max(10.0 ** x, edge_low), edge_high)))
    return st.one_of(choices)


def resolve(node: dict) -> dict:
    while "$ref" in node:
        node = OPENAPI["components"]["schemas"][node["$ref"].rsplit("/", 1)[1]]
    if "anyOf" in node:
        node = next(resolve(n) for n in node["anyOf"] if n.get("type") != "null")
    return node


def leaves(node: dict, path: tuple = ()) -> list[tuple[tuple, st.SearchStrategy]]:
    """Every bounded number, choice and switch of a request model, by its path in the body."""
    node = resolve(node)
    if node.get("type") == "object" and "properties" in node:
        return [leaf for name, sub in node["properties"].items() for leaf in leaves(sub, path + (name,))]
    if "enum" in node and len(node["enum"]) > 1:
        return [(path, st.sampled_from(node["enum"]))]
    if node.get("type") == "boolean":
        return [(path, st.booleans())]
    if node.get("type") in ("number", "integer") and {"minimum", "exclusiveMinimum"} & set(node) \
            and {"maximum", "exclusiveMaximum"} & set(node):
        return [(path, number(node))]
    return []


OUTPUTS = {"reduction": ["inertia", "resisting", "friction_iteration", "cycle_moments"], "motion": ["steady", "startup"],
           "flywheel": ["flywheel"], "elastic": ["histories", "modal", "rigid", "bearings"],
           "forces": ["forces", "wear"], "wear": ["forces"], "angular-acceleration": ["angular"]}


def setups(endpoint: str) -> list[tuple[dict, list]]:
    """(body, leaves) of every scene variant that posts to `endpoint`: the model's own bounds, the mechanism's
    parameter ranges and the variant's sliders (what a student can reach)."""
    found = []
    for scene in scenes().values():
        if scene.endpoint != endpoint.removeprefix("work-precision/"):
            continue
        request = OPENAPI["paths"][f"{API}/{endpoint}"]["post"]["requestBody"]["content"]["application/json"]
        for variant in scene.variants:
            body, own = scene_body(scene, variant), leaves(request["schema"])
            mechanism = MECHANISMS.get(variant.mechanism)
            params = [(("params", p.name), st.integers(int(p.minimum), int(p.maximum)) if p.integer
                       else st.floats(p.minimum, p.maximum)) for p in (mechanism.params if mechanism else [])]
            sliders = [((s.param,) if scene.kind == "kinematics" else tuple(s.param.split(".")),
                        st.floats(s.min, s.max).map(lambda v, s=s: v * s.to_si)) for s in variant.sliders
                       if not s.scale]
            if scene.kind == "kinematics":
                sliders = [(("params",) + path, strategy) for path, strategy in sliders]
                names = [o.name for o in mechanism.outputs] + ["special", "harmonics", "info"]
            else:
                names = OUTPUTS[scene.endpoint]
            found.append((body, own + params + sliders, names))
    return found


BUDGETS = {"kinematics": 60, "reduction": 60, "forces": 40, "wear": 30, "angular-acceleration": 40, "motion": 40,
           "flywheel": 30, "elastic": 25, "work-precision/motion": 2, "work-precision/elastic": 2}   # ~6 s per study


@pytest.mark.parametrize("endpoint", list(BUDGETS))
def test_the_scenes_set_ups_moved_within_their_bounds_never_crash(endpoint, client):
    variants = setups(endpoint)
    assert variants, f"no scene posts to /{endpoint}"

    @seed(SEED)
    @settings(max_examples=examples(BUDGETS[endpoint]), deadline=None, database=None, suppress_health_check=QUIET,
              phases=[Phase.explicit, Phase.generate])       # no shrinking: the failing body is in the message
    @given(st.data())
    def run(data):
        body, moves, names = data.draw(st.sampled_from(variants), label="set-up")
        body = copy.deepcopy(body)
        body["outputs"] = data.draw(st.lists(st.sampled_from(names), min_size=1, max_size=3, unique=True),
                                    label="outputs")
        for path, strategy in data.draw(st.lists(st.sampled_from(moves), min_size=1, max_size=3,
                                                 unique_by=lambda m: m[0]), label="moves"):
            set_path(body, path, data.draw(strategy, label=".".join(path)))
        try:
            response = client.post(f"{API}/{endpoint}?lang=en", json=body)
        except Exception as error:                        # the server's traceback, and the body to reproduce it
            raise AssertionError(f"{error!r} for {json.dumps(body)}") from error
        assert response.status_code in (200, 422), f"{response.status_code} for {json.dumps(body)}"
    run()


# --- 2. what the fuzzing found, pinned -----------------------------------------------------------------------

def test_wear_of_an_unloaded_crank_slider_is_refused_in_words_not_a_division_by_zero(client):
    """Found: POST /wear with no piston force, gas or masses divided by a zero mean pressure (k = I_s/p_m)."""
    response = client.post(f"{API}/wear", json={})
    assert response.status_code == 422
    detail = response.json()["detail"][0]
    assert detail["loc"] == ["body", "loads"] and "wear needs a load" in detail["msg"]


def test_wear_dimensions_below_a_millimetre_are_refused():
    """Found: pin_length = 5e-324 (a subnormal, > 0) made π·l·d underflow to zero."""
    response = TestClient(create_app()).post(f"{API}/wear", json={"pin_length": 5e-324, "loads": {"m2": 1}})
    assert response.status_code == 422 and response.json()["detail"][0]["loc"] == ["body", "pin_length"]


def test_efficiency_chain_works_are_bounded_so_their_sum_stays_finite(client):
    """Found: works of 1e308 summed to infinity and the parallel efficiency became NaN (not JSON)."""
    response = client.post(f"{API}/efficiency-chain", json={"efficiencies": [1, 1], "works": [1e308, 1e308]})
    assert response.status_code == 422 and response.json()["detail"][0]["loc"] == ["body", "works", 0]
    fine = client.post(f"{API}/efficiency-chain", json={"efficiencies": [1, 0.5], "works": [1e12, 1e12]})
    answer = fine.json()
    assert (answer["series"], answer["parallel"]) == (0.5, 0.75)
    # Chaika–Vasylenko (3.40) as printed sums the η_k (1.5); the answer is the corrected, work-weighted one
    assert [(e["equation"], e["printed_value"], e["corrected_value"]) for e in answer["errata"]] == [("(3.40)", 1.5, 0.75)]


def test_an_elastic_run_stops_at_its_work_bound_even_inside_its_first_chunk():
    """Found: a very stiff belt (c = 1e12 N·m/rad, DOP853) ran one chunk for minutes and gigabytes, and a run
    stopped before its first chunk ended had no samples, which crashed the error estimate."""
    from server.core.elastic.simulate import integrate

    class Oscillator:                                      # ω = 10⁶ rad/s, undamped: tiny explicit steps
        def rhs(self, t, y):
            return np.array([y[1], -1e12 * y[0]])
    run = integrate(Oscillator(), np.array([1.0, 0.0]), 1.0, 1e-10, "DOP853", np.linspace(0, 1, 11),
                    deadline=math.inf, max_evaluations=5000)
    assert not run.complete and run.t.size == 0 and "work bound" in run.numerics["message"]


def test_a_stiff_belt_stops_at_its_work_bound_with_a_partial_result_and_says_so(client):
    """Found: a very stiff belt (c = 1e12 N·m/rad) ran for minutes. The run may call the right-hand side
    MAX_EVALUATIONS times and finish the step it is in (DOP853: 12 stages, and 3 more for the dense output at a
    sample): a bound on work, whatever the machine's speed (a slow machine may stop it sooner, at its time budget)."""
    from server.core.elastic.simulate import MAX_EVALUATIONS
    body = scene_body(scenes()["elastic-transmission"], scenes()["elastic-transmission"].variants[0])
    response = client.post(f"{API}/elastic", json=body | {"c": 1e12, "t_end": 20, "rtol": 1e-10, "n": 4001,
                                                          "outputs": ["histories"]})
    assert response.status_code == 200
    data = response.json()
    assert "work bound" in data["numerics"]["message"] and data["numerics"]["nfev"] <= MAX_EVALUATIONS["compiled"] + 16
    assert any("work bound" in w for w in data["warnings"])


def test_a_flywheel_study_of_a_machine_that_stalls_without_its_flywheel_draws_no_speed_before_and_says_why(client):
    """Found: J1 = 0 (group I empty) in the flywheel scene: no periodic speed exists without the flywheel at that
    mean speed, and the root finding for 'ω before' raised."""
    scene = scenes()["flywheel"]
    body = scene_body(scene, scene.variants[0]) | {"outputs": ["flywheel"]}
    body["inertias"] = body["inertias"] | {"J1": 0.0}
    response = client.post(f"{API}/flywheel?lang=en", json=body)
    assert response.status_code == 200
    data = response.json()
    assert set(data["curves"]["omega_before"]) == {None} and None not in data["curves"]["omega_after"]
    assert data["flywheel_inertia"] > 0 and any("Without the flywheel" in w for w in data["warnings"])


def test_an_elastic_work_precision_study_without_a_finished_reference_skips_every_run(client, monkeypatch):
    """Found: a stiff belt (J_motor = 1e-5) whose reference run stopped at the work bound had fewer samples than
    the runs compared with it (shapes could not broadcast); with none at all its scale had no maximum."""
    from server.runtime import heavy
    from server.core import work_precision
    monkeypatch.setattr(heavy, "HEAVY_PROCESSES", 0)           # in this process, where the budget is patched
    monkeypatch.setattr(work_precision, "BUDGET_S", 1e-4)
    scene = scenes()["elastic-transmission"]
    response = client.post(f"{API}/work-precision/elastic", json=scene_body(scene, scene.variants[0])
                           | {"outputs": ["histories"]})
    assert response.status_code == 200
    study = response.json()["study"]
    assert study["rows"] == [] and len(study["skipped"]) == 12


def test_a_diverged_elastic_state_is_reported_by_the_solver_not_raised_by_the_table():
    """Found: an explicit run with very strong damping (b = 1e9) diverged, and the table of J(φ) was read at
    φ = ∞: int(NaN) raised inside the right-hand side instead of the run stopping with a message."""
    from server.core.elastic.periodic_table import PeriodicTable
    from server.core.elastic.simulate import integrate
    table = PeriodicTable(2 * np.pi, np.ones(9), np.zeros(9))
    assert all(math.isnan(v) for v in (*table.value_slope(math.inf), *table(math.nan)))

    class Breaks:                                        # the derivative becomes infinite half-way
        def rhs(self, t, y):
            return np.array([table.value_slope(y[0])[0] * (np.inf if t > 0.5 else 1.0), 0.0])
    run = integrate(Breaks(), np.array([0.0, 0.0]), 1.0, 1e-6, "DOP853", np.linspace(0, 1, 5), math.inf)
    assert not run.complete and "stopped at t = 0.5 s" in run.numerics["message"]


def test_a_flywheel_that_group_two_makes_unneeded_is_found_at_once_not_searched_for_ever(client):
    """Found: heavy links (group II alone keeps δ ≤ [δ]) with J1 = 0: the exact method widened its bracket
    towards zero inertia for ever, one worker stuck at full CPU; then the relative errors divided by zero."""
    scene = scenes()["flywheel"]
    body = scene_body(scene, scene.variants[0]) | {"outputs": ["flywheel"], "delta": 0.5,
                                                   "inertias": {"J1": 0, "m2": 1e5, "J_S2": 1e4, "m3": 1e5}}
    response = client.post(f"{API}/flywheel?lang=en", json=body)
    assert response.status_code == 200
    data = response.json()
    exact = next(m for m in data["methods"] if m["method"] == "exact")
    assert exact["inertia"] == 0 and exact["delta_achieved"] <= 0.5 and data["flywheel_inertia"] == 0
    assert data["merzalov_excess"] is None and any("No flywheel needed" in w for w in data["warnings"])


@pytest.mark.parametrize("path, body, field", [
    ("angular-acceleration", {"mechanism": "trammel", "omega0": 5e-324}, "omega0"),
    ("flywheel", {"mechanism": "slider_crank", "motor": {"kind": "constant", "M0": 1}, "omega_mean": 5e-324,
                  "delta": 0.05}, "omega_mean"),
])
def test_a_crank_speed_of_a_subnormal_radian_per_second_is_refused(client, path, body, field):
    """Found: ω₀ = 5e-324 rad/s made the trammel's turn time infinite (the root finder raised), and ω_m = 5e-324
    divided the flywheel's energy by ω_m² = 0. Crank speeds start at 1e-3 rad/s."""
    response = client.post(f"{API}/{path}", json=body)
    assert response.status_code == 422 and response.json()["detail"][0]["loc"] == ["body", field]


def test_a_start_up_whose_kinetic_energy_touches_zero_inside_a_step_is_a_stall_not_a_division_by_zero(client):
    """Found: strong viscous friction (β = 8.3e5 N·s/m) on the equation-of-motion scene's machine: T(φ) stayed
    positive at the step's ends but its interpolant reached zero mid-step, and 1/ω there divided by zero."""
    body = {"mechanism": "slider_crank", "params": {"l1": 0.1, "l2": 0.30000000000000004},
            "inertias": {"J1": 0.5, "m2": 5.0, "J_S2": 10000.0, "m3": 10.0, "J_rotor": 0.01, "gear_ratio": 5.0},
            "load": {"force": 2000.0, "return_factor": 0.2, "f": 0.0, "beta": 832779.0634087684}, "rtol": 1e-08,
            "max_cycles": 80, "motor": {"kind": "constant", "M0": 25.0}, "omega0": 0.0, "outputs": ["startup", "steady"]}
    response = client.post(f"{API}/motion?lang=en", json=body)
    assert response.status_code == 200
    assert any(w.startswith(("Stall", "The motor")) for w in response.json()["warnings"])


def test_an_elastic_machine_whose_mechanism_has_no_inertia_is_refused_like_the_rigid_one(client):
    """Found: a massless sine mechanism on a belt (all inertias zero): the Jacobian was infinite and the
    eigenvalues of the stiffness probe raised."""
    response = client.post(f"{API}/elastic", json={"mechanism": "sine", "model": "two_mass", "outputs": ["rigid"],
                                                   "J_motor": 1.0, "c": 1.0})
    assert response.status_code == 422
    assert response.json()["detail"][0]["loc"] == ["body", "inertias"]


def test_a_piston_engine_too_strong_for_its_mean_speed_stalls_in_words_not_in_the_root_finder(client):
    """Found: the flywheel scene's engine at p_max = 1e9 Pa (or at ω_m = 0.01 rad/s) on /motion: no energy level
    has that mean speed without the speed reaching zero, and brentq was given no bracket."""
    scene = scenes()["flywheel"]
    body = scene_body(scene, scene.variants[0]) | {"outputs": ["steady"], "omega_mean": 47.124}
    body["motor"] = body["motor"] | {"p_max": 1e9}
    for key in ("delta", "width_ratio", "density"):
        body.pop(key, None)
    response = client.post(f"{API}/motion?lang=en", json=body)
    assert response.status_code == 200
    data = response.json()
    assert "omega" not in data and any(w.startswith("Stall at φ") for w in data["warnings"])


def test_an_elastic_time_span_below_a_millisecond_is_refused(client):
    """Found: t_end = 5e-324 s divided by zero in the bearing iteration's time grid."""
    scene = scenes()["elastic-linkage"]
    body = scene_body(scene, scene.variants[0]) | {"outputs": ["bearings"], "t_end": 5e-324}
    response = client.post(f"{API}/elastic", json=body)
    assert response.status_code == 422 and response.json()["detail"][0]["loc"] == ["body", "t_end"]


class WorkClock:
    """A clock for the solvers' deadlines that advances by `tick` seconds each time it is read: a budget of B
    seconds becomes B/tick looks at the clock, so a run stopped by its deadline has done a bounded amount of work
    (steps between looks) whatever the machine's speed."""

    def __init__(self, tick: float):
        self.tick, self.reads = tick, 0

    def perf_counter(self) -> float:
        self.reads += 1
        return self.reads * self.tick


def test_a_start_from_rest_with_a_very_steep_motor_ends_within_its_work_bound(client, monkeypatch):
    """Found: the elastic-linkage scene's machine with a linear motor of slope b = 1e6 N·m·s/rad (or 1e4 on
    /motion): leaving rest in time with DOP853 crawled in tiny steps for minutes (the rigid comparison and the
    start-up had no time bound there), a heavy worker process kept busy for ever. On a clock read once per
    CLOCK_EVERY steps and advancing 1 ms a read, the start from rest stops at its first look past REST_BUDGET_S:
    at most REST_BUDGET_S/1 ms + 1 looks (and a warm-up's few), so about CLOCK_EVERY times that many steps
    (16 000), and says so."""
    from server.core.dynamics import dop853, integrator
    clock = WorkClock(1e-3)
    monkeypatch.setattr(dop853, "time", clock)           # the compiled loop looks at it every CLOCK_EVERY steps
    monkeypatch.setattr(integrator, "time", clock)       # the deadline, and scipy's path on each evaluation
    body = {"mechanism": "slider_crank", "params": {"l1": 0.1, "l2": 0.3},
            "inertias": {"J1": 0.5, "m2": 5.0, "J_S2": 0.05, "m3": 10.0, "gear_ratio": 5.0},
            "load": {"force": 2000.0, "return_factor": 0.2, "f": 0.1}, "motor": {"kind": "linear", "M0": 60.0, "b": 1e4},
            "outputs": ["startup"]}
    response = client.post(f"{API}/motion?lang=en", json=body)
    assert response.status_code == 200
    assert any("work bound" in w or w.startswith("Stall") for w in response.json()["warnings"])
    # its deadline and the look past it, and the compiled kernels' warm-up runs' looks in a fresh process
    assert clock.reads <= integrator.REST_BUDGET_S / clock.tick + 4, clock.reads
    clock.reads = 0
    gentle = client.post(f"{API}/motion?lang=en", json=body | {"motor": {"kind": "linear", "M0": 60.0, "b": 1.0}})
    assert gentle.json()["warnings"] == [] and 0 < clock.reads < 100      # a gentle motor leaves rest in a few looks


def test_a_bearing_iteration_whose_run_stops_before_any_sample_ends_without_rounds(client):
    """Found: a constant motor of 1e7 N·m on the elastic crank-slider: the run stopped at its work bound inside its
    first chunk, had no samples, and the largest rod force of nothing raised."""
    scene = scenes()["elastic-linkage"]
    body = scene_body(scene, scene.variants[1]) | {"outputs": ["bearings"], "motor": {"kind": "constant", "M0": 1e7}}
    response = client.post(f"{API}/elastic", json=body)
    assert response.status_code == 200
    bearings = response.json()["bearings"]
    assert bearings["rounds"] == [] and bearings["converged"] is False and bearings["message"]


def test_special_positions_of_a_four_bar_with_crank_as_long_as_coupler(client):
    """Found: l₁ = l₂ (8.37 m) on the four-bar: the folded line-up AC = l₂ − l₁ = 0 was divided by before the
    guard that skips it."""
    response = client.post(f"{API}/kinematics", json={
        "mechanism": "four_bar", "params": {"l0": 0.2, "l1": 8.370442563932752, "l2": 8.370442563932752, "l3": 0.4},
        "n": 361, "outputs": ["special", "mu", "u21"]})
    assert response.status_code == 200 and isinstance(response.json()["outputs"]["special"], list)


def test_a_work_precision_run_that_never_reaches_the_next_cycle_stops_at_its_deadline_inside_the_cycle(monkeypatch):
    """Found: the equation-of-motion scene's Kloss motor against a load of 4985 N on /work-precision/motion: the
    time integration from 0.9 ω of the steady cycle stalled, solve_ivp ran its 100 s span without the next
    cycle's event (IndexError on the empty event list), and the budget was checked only between cycles.
    On a clock advancing 1 ms a read (the evaluations look at it every 256 calls), a deadline of 8 ms stops the
    stalled DOP853 run inside its cycle after at most 8 × 256 evaluations and one step more (12), and the run is
    skipped (None); without the look inside the cycle it runs past 20 000 evaluations (here: an error)."""
    from server.api.endpoints import machine as _machine
    from server.api.schemas_dynamics import MotionRequest
    from server.core import work_precision
    from server.core.dynamics.motion import steady_cycle
    from server.core.elastic import simulate
    body = {"mechanism": "slider_crank", "params": {"l1": 0.1, "l2": 0.3},
            "inertias": {"J1": 0.5, "m2": 5.0, "J_S2": 0.05, "m3": 10.0, "J_rotor": 0.01, "gear_ratio": 5.0},
            "load": {"force": 4984.893392663449, "return_factor": 0.2, "f": 0.1},
            "motor": {"kind": "kloss", "M_max": 70.0, "s_critical": 0.2, "omega_sync": 157.0}, "outputs": ["steady"]}
    machine = _machine(MotionRequest(**body))
    omega_steady = steady_cycle(machine, 1e-11).steady.omega[0]
    evaluations, solve_ivp = 0, work_precision.solve_ivp

    def counted_solve_ivp(fun, *args, **kwargs):
        def counted(t, y):
            nonlocal evaluations
            evaluations += 1
            assert evaluations <= 20_000, "the stalled run went on past its deadline"
            return fun(t, y)
        return solve_ivp(counted, *args, **kwargs)
    clock = WorkClock(1e-3)
    monkeypatch.setattr(work_precision, "solve_ivp", counted_solve_ivp)
    monkeypatch.setattr(work_precision, "time", clock)      # the look between cycles
    monkeypatch.setattr(simulate, "time", clock)            # bounded(): the look every 256 evaluations
    deadline = 8e-3
    assert work_precision.cycles_until_periodic(machine, "DOP853", 1e-3, 0.9 * omega_steady, deadline, 200) is None
    assert 0 < evaluations <= deadline / clock.tick * 256 + 12, evaluations
