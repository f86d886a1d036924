"""Friction's influence on the crank-slider machine (server/core/kinetostatics/friction_influence.py and POST
/api/v1/friction-influence; Chaika–Vasylenko §3.4 steps 18–19, §4), each number against something that is not the
code under test:
- the stacked solve over f against crank_slider.analyse at each f (the plain path), to the last bit;
- at f = 0 the balancing moment against the reduced moment by virtual work (power equality), to 1e-9;
- with friction the energy balance at every angle, M_ур = M_vw + M_тр (3.30), and over the cycle η·A_д = A_пол;
- f → 0: every figure continuous;
- a massless mechanism with guide friction alone against the closed form P|dx_B/dφ|/(1 − f|tan ψ|) and the onset
  of self-locking 1/max|tan ψ| = √(λ² − 1);
- the flywheel needed against the equation of motion integrated by scipy (DOP853), the piston's wear against (4.17),
  (4.19) written out, the error estimate against a 16× finer grid.
The notes of Chaika–Vasylenko have no worked numbers for friction's influence (their Fig. 3.10 is lost in the OCR;
the only δ they allow, ≈ 0.0083 from Table 4.3's ω column, is an engine's, whose gas force the notes do not give).
"""
from __future__ import annotations

import json

import numpy as np
import pytest
from fastapi.testclient import TestClient
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from server.api.app import app
from server.api.endpoints import compute_answer, compute_answers
from server.core.dynamics.reduction import Inertias, reduced_inertia
from server.core.kinetostatics.crank_slider import Loads, Pairs, analyse
from server.core.kinetostatics.friction_influence import (FIGURES, Flywheel, MachineSetup, Study, WearParts,
                                                          figure_scale, friction_moment, load_moment, thinned)
from server.core.kinetostatics.friction_influence_report import explorer_answer
from server.core.kinetostatics.report import efficiency
from server.core.kinetostatics.virtual_work import reduced_moment
from server.core.mechanisms import MECHANISMS
from server.lessons.scenes import interface_texts

client = TestClient(app)
PARAMS = MECHANISMS["slider_crank"].check({"l1": 0.1, "l2": 0.4, "a2": 0.3})
LOADS = Loads(m2=3.0, J_S2=0.05, m3=2.0, J1=1.0, omega=50.0, force=1000.0, return_factor=0.2)
RADII = Pairs(r14=0.02, r12=0.015, r23=0.01)
SCENE = {"params": {"l1": 0.1, "l2": 0.4, "a2": 0.3}, "loads": {"m2": 3.0, "J_S2": 0.05, "m3": 2.0, "J1": 1.0,
         "omega": 50.0, "force": 1000.0, "return_factor": 0.2}, "f": 0.1, "n": 181}


def machine(n: int = 181, params: dict = PARAMS, loads: Loads = LOADS, radii: Pairs = RADII,
            wear: WearParts | None = WearParts()) -> MachineSetup:
    return MachineSetup(params, loads, radii, np.linspace(0.0, 2 * np.pi, n), 1e-10, wear)


def test_the_stacked_solve_is_analyse_at_each_f_to_the_last_bit():
    """Every angle's friction equilibrium is solved by itself, so stacking the f's changes nothing: equal."""
    setup, values = machine(), np.array([0.0, 0.05, 0.2, 0.45])
    study = Study(setup, values)
    for f, analysis in zip(values, study.analyses):
        plain = analyse(PARAMS, LOADS, Pairs(f, f, f, f, 0.02, 0.015, 0.01), setup.phi, 1e-10, table=False)
        assert np.array_equal(analysis.balancing_moment, plain.balancing_moment)
        assert np.array_equal(analysis.final.R23, plain.final.R23) and np.array_equal(analysis.final.N, plain.final.N)


def test_without_friction_the_balancing_moment_is_the_virtual_work_moment():
    """(3.2): f = 0, the crank's equilibrium against power equality, to 1e-9 of its largest value (rounding)."""
    analysis = Study(machine(), np.array([0.0])).analyses[0]
    expected = reduced_moment(PARAMS, analysis.applied, analysis.phi)
    assert np.max(np.abs(analysis.balancing_moment - expected)) <= 1e-9 * np.max(np.abs(expected))
    assert np.all(friction_moment(analysis) == 0) and efficiency(analysis)["efficiency"] == 1.0


@pytest.mark.parametrize("f", [0.05, 0.3])
def test_energy_balance_at_every_angle_and_over_the_cycle(f):
    """The crank's equilibrium with friction against the pairs' power: M_ур(φ) = M_vw(φ) + M_тр(φ) at every angle
    (the inertia, gravity and load by virtual work, the friction by (3.30)), to 1e-9 of M_ур's largest value; then
    over the cycle η·A_д = A_пол, where A_д also holds the inertia's and gravity's works, zero over a cycle but for
    the trapezoid rule's error on smooth periodic functions (spectrally small): 1e-9 relative."""
    study = Study(machine(), np.array([0.0, f]))
    analysis = study.analyses[1]
    balance = reduced_moment(PARAMS, analysis.applied, analysis.phi) + friction_moment(analysis)
    assert np.max(np.abs(analysis.balancing_moment - balance)) <= 1e-9 * np.max(np.abs(balance))
    works = efficiency(analysis)
    assert works["efficiency"] * works["work_driving"] == pytest.approx(works["work_useful"], rel=1e-9)
    assert study.figures(1, Flywheel(0.02), study.grids[0])[0]["balancing_mean"] == pytest.approx(
        works["work_driving"] / (2 * np.pi), rel=1e-12)


def test_every_figure_is_continuous_as_f_goes_to_zero():
    """Each figure is Lipschitz in f (the friction loads are f times the reactions): at f = 10⁻⁸ within 10⁻⁶ of f = 0
    (relative; the slope of each is O(1) relative per unit f)."""
    study = Study(machine(), np.array([0.0, 1e-8]))
    flywheel = Flywheel(0.02)
    frictionless = study.figures(0, flywheel, study.grids[0])[0]
    rough = study.figures(1, flywheel, study.grids[0])[0]
    for key in FIGURES:
        assert rough[key] == pytest.approx(frictionless[key], rel=1e-6), key


def test_guide_friction_alone_against_the_closed_form_and_the_onset_of_self_locking():
    """A massless rod and slider, no gravity, journals of radius 1e-12 m (friction circles of no size): the
    balancing moment is P|dx_B/dφ|/(1 − f|tan ψ|) (Eremyants' crank-slider series summed, or the rod as a two-force
    member), dx_B/dφ and tan ψ of the exact geometry written out here (φ = 0 with the crank along −x, turning
    clockwise: x_B = −l₁cos φ + √(l₂² − l₁²sin²φ)); to 1e-9 relative. Self-locking begins at
    f·max|tan ψ| = 1, f* = √(λ² − 1) for λ = l₂/l₁ = 1.5, to Brent's tolerance; past it the f's have no values."""
    params = MECHANISMS["slider_crank"].check({"l1": 0.1, "l2": 0.15})
    loads = Loads(omega=10.0, force=1000.0, return_factor=1.0, gravity=False, J1=1.0)
    setup = machine(params=params, loads=loads, radii=Pairs(r14=1e-12, r12=1e-12, r23=1e-12), wear=None)
    study = Study(setup, np.array([0.0, 0.3, 1.5]))
    phi = setup.phi
    s = 0.1 * np.sin(phi)
    root = np.sqrt(0.15**2 - s**2)
    dx_b = 0.1 * np.sin(phi) - s * 0.1 * np.cos(phi) / root
    expected = 1000 * np.abs(dx_b) / (1 - 0.3 * np.abs(s) / root)
    assert np.max(np.abs(study.analyses[1].balancing_moment - expected)) <= 1e-9 * expected.max()
    assert study.onset == pytest.approx(np.sqrt(1.5**2 - 1), rel=1e-8)
    answer, notices = explorer_answer(study, 1.5, Flywheel(0.02), np.array([0.0, 0.3, 1.5]), True)
    assert answer["sweep"]["locked"] == [False, False, True]
    assert np.isnan(answer["sweep"]["efficiency"][2]) and answer["comparison"][6]["friction"] is None
    assert [n.code for n in notices] == ["friction_influence_self_locking"]
    assert "f = 1.5" in notices[0].text and "1.118" in notices[0].text


def periodic_delta_by_ode(setup: MachineSetup, resisting: np.ndarray, group_one: float) -> float:
    """δ of the periodic motion with group I = group_one, integrated by scipy: dT/dφ = M_д − M_с(φ) (DOP853, M_с the
    grid's piecewise linear interpolant, which the trapezoid rule integrates exactly), J(φ) evaluated exactly at
    each angle, T₀ by Brent's method so that (ω_max + ω_min)/2 = ω_m, the extremes on 20 001 angles."""
    phi = setup.phi
    driving = np.trapezoid(resisting, phi) / (2 * np.pi)
    grid = np.linspace(0.0, 2 * np.pi, 20001)
    run = solve_ivp(lambda x, T: [driving - np.interp(x, phi, resisting)], (0.0, 2 * np.pi), [0.0], method="DOP853",
                    t_eval=grid, rtol=1e-12, atol=1e-12, max_step=phi[1] - phi[0])
    inertias = Inertias(J1=group_one, m2=LOADS.m2, J_S2=LOADS.J_S2, m3=LOADS.m3)
    total = reduced_inertia("slider_crank", PARAMS, inertias, grid).J

    def speeds(T0):
        return np.sqrt(2 * (T0 + run.y[0]) / total)
    lowest = float(np.max(-run.y[0])) + 1e-9
    T0 = brentq(lambda T0: (speeds(T0).max() + speeds(T0).min()) / 2 - LOADS.omega, lowest, 1e7, xtol=1e-12)
    omega = speeds(T0)
    return (omega.max() - omega.min()) / LOADS.omega


def test_the_flywheel_needed_gives_the_delta_asked_by_an_independent_integration():
    """J₁ + J_м needed, put on the machine and integrated by scipy, fluctuates by [δ]: to 10⁻⁴ relative (the
    extremes read on 20 001 angles, h²/8·|ω″|/ω ≈ 10⁻⁸; the ODE at 10⁻¹²); and δ of the machine as it is too."""
    setup = machine(wear=None)
    study = Study(setup, np.array([0.0, 0.2]))
    flywheel = Flywheel(0.02)
    figures, lost, _ = study.figures(1, flywheel, study.grids[0])
    resisting = load_moment(setup, study.analyses[1].applied) + lost
    needed = LOADS.J1 + figures["flywheel"]
    assert periodic_delta_by_ode(setup, resisting, needed) == pytest.approx(0.02, rel=1e-4)
    assert periodic_delta_by_ode(setup, resisting, LOADS.J1) == pytest.approx(figures["delta"], rel=1e-4)


def test_the_piston_wear_is_the_books_formula_with_the_frictionless_wear_coefficient():
    """(4.17), (4.19), b = 4/π: δ₃ = 10⁶ b k n_c/(l_p d_p) ∫|R₃₄ V_qB| dφ over the pressed side, with k = I_s/p_m of
    the frictionless machine (4.23), (4.24), p_m = 4 R̄₃₄/(π l_p d_p), written out here; to 1e-12 (the same
    trapezoid sums, rounding)."""
    parts, f = WearParts(), 0.25
    setup = machine(wear=parts)
    study = Study(setup, np.array([0.0, f]))
    cycles = 3600 * LOADS.omega / (2 * np.pi) * parts.hours

    def pressed(analysis):
        normal = analysis.final.N
        side = 1 if np.sum(np.clip(normal, 0, None)) >= np.sum(np.clip(-normal, 0, None)) else -1
        return np.where(np.sign(normal) == side, np.abs(normal), 0.0)
    area = parts.piston_length * parts.piston_diameter
    k = parts.I_piston / (4 * np.mean(pressed(study.analyses[0])) / (np.pi * area))
    rough = study.analyses[1]
    integral = np.trapezoid(pressed(rough) * np.abs(rough.applied["u31"]), setup.phi)
    expected = 1e6 * (4 / np.pi) * k * cycles / (parts.piston_length * parts.piston_diameter) * integral
    assert study.figures(1, Flywheel(0.02), study.grids[0])[0]["wear_piston"] == pytest.approx(expected, rel=1e-12)


def test_the_wear_figures_are_the_wear_reports_maxima_at_the_frictionless_pressures():
    """wear_of (the pin's and bush's cosine pressure by the angle-addition formula, the trapezoid sums as one
    matrix product) against report.wear_report, the book's formulas over every surface point, made at each f's
    own p_m and scaled by p_m(f)/p_m(0): every f of a sweep into self-locking, both grids, to 1e-12."""
    from server.core.kinetostatics.friction_influence import thinned, wear_of
    from server.core.kinetostatics.report import wear_report
    setup = machine()
    study = Study(setup, np.linspace(0.0, 0.6, 13))
    checked = 0
    for k, analysis in enumerate(study.analyses):
        if study.locked[k].any():
            continue
        for grid in study.grids:
            coarse = thinned(analysis, grid.every)
            report, frictionless = wear_report(coarse, setup.wear.__dict__, study.cycles), grid.reference
            revolute = report["mean_pressure_23"] / frictionless["mean_pressure_23"]
            prismatic = report["mean_pressure_34"] / frictionless["mean_pressure_34"]
            expected = {"wear_bush": np.max(report["bush"]) * revolute, "wear_pin": np.max(report["pin"]) * revolute,
                        "wear_piston": report["piston"] * prismatic,
                        "wear_cylinder": np.max(report["cylinder"]) * prismatic}
            found = wear_of(coarse, grid.reference, setup.wear, study.cycles)
            assert found == pytest.approx(expected, rel=1e-12)
            checked += 1
    assert checked >= 10

def test_the_flywheel_needed_by_the_secant_method_is_flywheel_exacts():
    """needed_inertia (the secant method on log δ from Merzalov's guess) against flywheel.exact (Brent's method
    on a bracket) on the sweep's cycles, for a tight, a usual and a loose [δ]: to 1e-12 (both stop at 1e-14 in
    log I)."""
    from server.core.dynamics import flywheel as fw
    from server.core.kinetostatics.friction_influence import needed_inertia
    setup = machine()
    study = Study(setup, np.linspace(0.0, 0.3, 7))
    grid = study.grids[0]
    for k in range(7):
        resisting = grid.loaded + study.forces_figures(k, grid)[1]
        driving = np.trapezoid(resisting, grid.phi) / (2 * np.pi)
        work = np.concatenate([[0.0], np.cumsum(np.diff(grid.phi) * (2 * driving - resisting[1:] - resisting[:-1])
                                                / 2)])
        cycle = fw.Cycle(grid.phi, work, grid.inertia - LOADS.J1)
        for delta in (0.002, 0.02, 0.5):
            guess = fw.merzalov(cycle, LOADS.omega, delta).inertia
            expected = fw.exact(cycle, LOADS.omega, delta, guess).inertia
            assert expected > 0
            assert needed_inertia(cycle, LOADS.omega, delta, guess) == pytest.approx(expected, rel=1e-12, abs=0)

@pytest.mark.parametrize("params, force", [({"l1": 0.1, "l2": 0.4, "a2": 0.3}, 1000.0),
                                           ({"l1": 0.1, "l2": 0.25, "a2": 0.1, "e": 0.03}, 2500.0)])
def test_the_error_estimate_holds_against_a_finer_grid(params, force):
    """Every figure at 181 angles, at every f of a sweep, within the answer's error estimate of the same at 2881
    angles (16× finer: its own error is ~1/16 of the coarse one at first order); M_ур's mean relative to M_ур's peak
    (figure_scale), the others to themselves."""
    setup = machine(params=MECHANISMS["slider_crank"].check(params), loads=Loads(**{**LOADS.__dict__, "force": force}))
    sweep = np.linspace(0.0, 0.3, 7)
    answer, _ = explorer_answer(Study(setup, np.unique([*sweep, 0.1])), 0.1, Flywheel(0.02), sweep, True)
    fine = Study(machine(2881, setup.params, setup.loads), sweep)
    estimate = answer["numerics"]["error_estimate"]
    for k in range(sweep.size):
        reference = fine.figures(k, Flywheel(0.02), fine.grids[0])[0]
        for key, value in reference.items():
            column = answer["sweep"]["wear"][key[5:]] if key.startswith("wear_") else (
                answer["sweep"]["peak"][key] if key.startswith("R") else answer["sweep"][key])
            assert abs(column[k] - value) <= estimate * figure_scale(reference, key), (key, sweep[k], value, estimate)


def test_thinning_an_analysis_is_analysing_on_the_coarser_grid():
    """The kinetostatics is exact at each angle: the analysis on every other angle is the coarser grid's own."""
    study = Study(machine(181), np.array([0.0, 0.2]))
    coarse = Study(machine(91), np.array([0.0, 0.2]))
    assert np.array_equal(thinned(study.analyses[1], 2).balancing_moment, coarse.analyses[1].balancing_moment)


def strict(response) -> dict:
    assert response.status_code == 200, response.text
    return json.loads(response.text, parse_constant=lambda name: pytest.fail(f"{name} in the response"))


def test_the_scene_request_answers_finite_numbers_in_russian_with_a_decimal_comma():
    data = strict(client.post("/api/v1/friction-influence?lang=ru", json=SCENE))
    assert set(data) == {"f", "locking_onset", "sweep", "cycle", "comparison", "numerics", "warnings"}
    assert data["warnings"] == [] and data["locking_onset"] is None          # f* = √15 ≈ 3.9 > 2
    assert len(data["sweep"]["f"]) == 13 and not any(data["sweep"]["locked"])
    assert all(None not in values for values in (data["sweep"]["efficiency"], data["cycle"]["omega"]["friction"]))
    rows = {row["quantity"]: row for row in data["comparison"]}
    assert rows["efficiency"]["frictionless"] == 1 and 0.8 < rows["efficiency"]["friction"] < 0.95
    assert rows["flywheel"]["change"] > 0 and rows["wear_piston"]["change"] > 0
    assert "сетке" in data["numerics"]["message"] and "," in data["numerics"]["message"]


def test_only_the_outputs_asked_for_are_computed():
    cycle = strict(client.post("/api/v1/friction-influence", json=SCENE | {"outputs": ["cycle"]}))
    assert "sweep" not in cycle and cycle["comparison"]
    sweep = strict(client.post("/api/v1/friction-influence", json=SCENE | {"outputs": ["sweep"], "wear": None}))
    assert "cycle" not in sweep and "wear" not in sweep["sweep"]


def test_self_locking_in_the_sweep_is_said_in_words_with_nulls():
    """λ = 1.2: the guide alone locks at f* = √(1.2² − 1) = 0.663; the friction circles lower it a little."""
    body = SCENE | {"params": {"l1": 0.1, "l2": 0.12, "a2": 0.05}, "f_max": 0.9, "count": 10}
    data = strict(client.post("/api/v1/friction-influence?lang=uk", json=body))
    locked = data["sweep"]["locked"]
    assert locked[0] is False and locked[-1] is True
    first = locked.index(True)
    assert data["sweep"]["efficiency"][first] is None and data["sweep"]["efficiency"][first - 1] is not None
    assert 0.5 < data["locking_onset"] < 0.663
    assert any(text.startswith("Самогальмування з f = ") for text in data["warnings"])


def test_family_members_computed_together_equal_each_alone():
    """The batch shares one Study among members that differ in f or [δ]: each answer as compute_answer's."""
    bodies = [SCENE | {"f": f} for f in (0.0, 0.1, 0.17)] + [SCENE | {"delta": 0.05}]
    together = compute_answers("friction-influence", bodies)
    for body, answer in zip(bodies, together):
        alone = compute_answer("friction-influence", body).payload
        assert answer.payload["comparison"] == alone["comparison"]
        assert np.array_equal(answer.payload["sweep"]["flywheel"], alone["sweep"]["flywheel"])


@pytest.mark.parametrize("change, loc, words", [
    ({"n": 180}, ["body", "n"], ["odd"]),
    ({"loads": {"epsilon": 5.0, "J1": 1.0}}, ["body", "loads"], ["epsilon"]),
    ({"loads": {"gas": {"kind": "indicator", "p_max": 3e6, "piston_diameter": 0.075}, "J1": 1.0}}, ["body", "loads"],
     ["working machine"]),
    ({"loads": {"J1": 0.0}}, ["body"], ["inertia"]),
    ({"f": 2.5}, ["body", "f"], ["less than or equal to 2"]),
    ({"count": 100}, ["body", "count"], ["less than or equal to 41"]),
])
def test_bad_input_is_refused_naming_the_field(change, loc, words):
    response = client.post("/api/v1/friction-influence", json=SCENE | change)
    assert response.status_code == 422, response.text
    error = response.json()["detail"][0]
    assert error["loc"] == loc and all(word in error["msg"] for word in words), error


def test_a_machine_without_loads_needs_no_flywheel_and_says_why_it_has_no_wear():
    """Nothing resists and nothing varies: ω₁ is constant, δ = 0 and no flywheel is needed (not a root search from
    a zero inertia); no wear, said in words."""
    data = strict(client.post("/api/v1/friction-influence?lang=ru", json={"params": {"l1": 0.1, "l2": 0.4},
                                                                          "loads": {"J1": 1.0, "gravity": False}}))
    assert set(data["sweep"]["delta"]) == {0.0} and set(data["sweep"]["flywheel"]) == {0.0}
    assert data["warnings"] == [interface_texts("ru")["warn_friction_influence_no_wear"]]


def test_a_machine_that_stalls_says_so_and_still_gives_the_flywheel_it_needs():
    """The fuzzing found it (a 500): J₁ = 0.5 kg·m² against the rod's J_S2 = 47 kg·m², δ above 1 already without
    friction; at f = 0.3 the kinetic energy runs out within the cycle, no periodic motion keeps ω_m: δ is null
    there, said in words, and the flywheel for [δ] is given."""
    data = strict(client.post("/api/v1/friction-influence", json={"loads": {"J1": 0.5, "J_S2": 47.0}}))
    assert data["sweep"]["delta"][-2] > 1 and data["sweep"]["delta"][-1] is None
    assert data["sweep"]["flywheel"][-1] > data["sweep"]["flywheel"][-2] > 0
    assert "From f = 0.3 on the machine" in data["warnings"][-1]


def test_a_mechanism_that_cannot_turn_is_refused_naming_the_field():
    response = client.post("/api/v1/friction-influence", json=SCENE | {"params": {"l1": 0.1, "l2": 0.05}})
    assert response.status_code == 422 and "l2" in response.text
