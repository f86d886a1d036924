"""The crank-slider's kinetostatics with friction (Chaika–Vasylenko §3.1, (3.3), (3.17)–(3.20))
against references that are not the code under test:

* fsolve of the full friction equilibrium, written here from the free-body diagrams of rod and slider, with
  the friction of (3.3) taken from the unknown reactions themselves (not from a previous approximation),
  the geometry in closed form and the friction directions from the velocities' signs computed here;
* the closed form of the guide-only case (a two-force rod): |N| = kP|tan ψ|/(1 − f|tan ψ|),
  M_bal = |dx_B/dφ| kP/(1 − f|tan ψ|);
* the textbook's own successive approximations run 5000 steps.

Self-locking must be declared exactly where the guide's friction condition f₃₄|tan ψ| ≥ 1 holds (tan ψ computed
here), or where the friction's feedback on the reactions has a ratio ≥ 1 (the test's own Jacobian by
finite differences).  Tolerances: the app is asked for ε_R = 1e-9 (relative change of the reactions) and must
be within 1e-9 of the reference relative to the reaction's magnitude at that angle; fsolve is run with
xtol = 1e-13 and its residual checked, so its own error is far below that.
"""
import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from scipy.optimize import fsolve

from server.core.kinetostatics.crank_slider import Loads, Pairs, analyse, friction_loads, solve_dyad
from server.core.mechanisms import MECHANISMS, GeometryError

EPS_R = 1e-9


def geometry(params: dict, phi: np.ndarray) -> dict:
    """Closed-form positions (the crank turns clockwise: A = l₁(−cos φ, sin φ), φ̇ = ω), tan ψ of the rod, and
    the derivatives by φ of x_B and of the rod's angle θ (sin θ = (e − l₁ sin φ)/l₂), which give the friction's
    directions."""
    l1, l2, e, a2 = params["l1"], params["l2"], params["e"], params["a2"]
    A = np.stack([-l1 * np.cos(phi), l1 * np.sin(phi)], 1)
    root = np.sqrt(l2**2 - (e - A[:, 1]) ** 2)                      # l₂ cos θ
    B = np.stack([A[:, 0] + root, np.full_like(phi, e)], 1)
    return {"A": A, "B": B, "S2": A + a2 * (B - A), "tan_psi": (e - A[:, 1]) / root,
            "dxB": l1 * np.sin(phi) + (e - l1 * np.sin(phi)) * l1 * np.cos(phi) / root,
            "dtheta": -l1 * np.cos(phi) / root}


def cross(a, b):
    return a[0] * b[1] - a[1] * b[0]


def reference(params, loads: Loads, pairs: Pairs, phi, applied):
    """fsolve of the five equations of rod and slider at each angle, unknowns R₁₂ (crank on rod), R₂₃ (rod on
    slider), N (guide on slider), with the friction of (3.3) from these same unknowns; then the crank's moment
    equation about O.  The loads G, F_in, M_in, F_3p are the app's (their frictionless balance is checked
    against virtual work in test_kinetostatics.py).  Returns R₁₂, R₂₃, N, M_bal (along ω₁) and whether fsolve
    solved the equations ("ok"): from the frictionless solution, else following it with the friction switched
    on in 20 steps."""
    g = geometry(params, phi)
    w = loads.omega
    s_v, s_2 = np.sign(g["dxB"] * w), np.sign(g["dtheta"] * w)      # sgn V_B, sgn ω₂
    s_rel = np.sign(g["dtheta"] * w + w)                             # sgn(ω₂ − ω₁), ω₁ = −ω (clockwise)
    rho_a, rho_b, rho_o = pairs.f12 * pairs.r12, pairs.f23 * pairs.r23, pairs.f14 * pairs.r14
    M_in1 = np.broadcast_to(applied["M_in1"], phi.shape)
    out = {k: np.empty((phi.size, 2)) for k in ("R12", "R23")}
    out["N"], out["M"], out["ok"] = np.empty(phi.size), np.empty(phi.size), np.empty(phi.size, bool)
    for i in range(phi.size):
        A, B, S = g["A"][i], g["B"][i], g["S2"][i]
        rod = applied["G2"][i] + applied["F_in2"][i]
        slider = applied["F_3p"][i] + applied["G3"][i] + applied["F_in3"][i]

        def equations(x, s=1.0):
            R12, R23, N = x[:2], x[2:4], x[4]
            M_fr2 = -s_rel[i] * rho_a * np.hypot(*R12) - s_2[i] * rho_b * np.hypot(*R23)
            F_fr = -s_v[i] * pairs.f34 * abs(N)
            return [R12[0] - R23[0] + rod[0], R12[1] - R23[1] + rod[1],
                    cross(B - A, -R23) + cross(S - A, rod) + applied["M_in2"][i] + s * M_fr2,
                    R23[0] + s * F_fr + slider[0], R23[1] + N + slider[1]]

        def solved(x):
            scale = max(np.abs(x).max(), 1e-300)
            return np.abs(equations(x)).max() <= 1e-11 * scale

        def along_the_branch(x):
            for s in np.linspace(0.05, 1, 20):
                x = fsolve(equations, x, args=(s,), xtol=1e-13)
            return x

        # frictionless start: the same equations without friction are linear
        M = np.array([[1, 0, -1, 0, 0], [0, 1, 0, -1, 0], [0, 0, -(B - A)[1], (B - A)[0], 0],
                      [0, 0, 1, 0, 0], [0, 0, 0, 1, 1]], float)
        rhs = -np.array([rod[0], rod[1], cross(S - A, rod) + applied["M_in2"][i], slider[0], slider[1]])
        x = fsolve(equations, np.linalg.solve(M, rhs), xtol=1e-13)
        if not solved(x):                   # continuation: the friction switched on in steps from zero
            x = along_the_branch(np.linalg.solve(M, rhs))
        out["ok"][i] = solved(x)
        out["R12"][i], out["R23"][i], out["N"][i] = x[:2], x[2:4], x[4]
        R12 = x[:2]
        # crank: A×(−R₁₂) + M_ccw + M_in1 + s_rel ρ_A|R₁₂| − sgn(ω₁) ρ_O |R₄₁| = 0, R₄₁ = R₁₂; M_bal = −M_ccw
        out["M"][i] = cross(A, -R12) + M_in1[i] + s_rel[i] * rho_a * np.hypot(*R12) + rho_o * np.hypot(*R12)
    return out, g


def relative_gap(answer, expected, scale):
    return np.abs(answer - expected) / np.maximum(scale, 1e-300)


def check_against_reference(params, loads, pairs, phi, tolerance=EPS_R):
    """The app's answer beside fsolve at every angle that does not lock; returns (analysis, reference, geometry,
    the angles compared)."""
    analysis = analyse(params, loads, pairs, phi, tolerance)
    ref, g = reference(params, loads, pairs, phi, analysis.applied)
    free = np.isfinite(analysis.balancing_moment)                  # where the app does not declare self-locking
    # dead centres (V_B = 0 up to the finite differences' rounding): the friction's direction is undefined there
    moving = np.abs(g["dxB"]) > 1e-7 * params["l1"]
    check = free & moving & ref["ok"]
    sol = analysis.solution
    scale = np.maximum(np.linalg.norm(ref["R12"], axis=1), np.abs(ref["N"]))
    for name, answer, expected in (("R12", sol.R12, ref["R12"]), ("R23", sol.R23, ref["R23"])):
        gap = relative_gap(np.linalg.norm(answer - expected, axis=1), 0, scale)
        assert gap[check].max(initial=0) <= tolerance, name
    assert relative_gap(sol.N, ref["N"], scale)[check].max(initial=0) <= tolerance
    moment_scale = scale * params["l1"] + np.abs(analysis.applied["M_in1"])   # |A × R₁₂| ≤ l₁|R₁₂|, and J₁ε
    assert relative_gap(analysis.balancing_moment, ref["M"], moment_scale)[check].max(initial=0) <= tolerance
    return analysis, ref, g, check


def closed_form(params, force, f, phi, return_factor=1.0):
    """Guide friction only, massless links, no gravity: the rod is a two-force member along AB."""
    g = geometry(params, phi)
    t = np.abs(g["tan_psi"])
    k = np.where(g["dxB"] >= 0, 1.0, return_factor)
    return {"N": k * force * t / (1 - f * t), "M": np.abs(g["dxB"]) * k * force / (1 - f * t), "ratio": f * t}, g


# --- the issue's request -----------------------------------------------------------------------------------

ISSUE = {"params": {"l1": 0.1, "l2": 0.13}, "loads": {"force": 1000, "gravity": False, "omega": 10},
         "pairs": {"f34": 0.8}, "n": 73}


def issue_analysis(tolerance=EPS_R):
    params = MECHANISMS["slider_crank"].check(ISSUE["params"])
    phi = np.linspace(0, 2 * np.pi, 73)
    return params, phi, analyse(params, Loads(force=1000.0, gravity=False, omega=10.0), Pairs(f34=0.8), phi, tolerance)


def test_issue_body_is_not_self_locking_and_matches_the_closed_form_to_eps_r():
    params, phi, analysis = issue_analysis()
    expected, g = closed_form(params, 1000.0, 0.8, phi)
    assert expected["ratio"].max() == pytest.approx(0.963, abs=1e-3) and expected["ratio"].max() < 1
    assert not analysis.notices and analysis.converged.all()
    # ε_R = 1e-9 relative; the closed form is exact up to rounding amplified by 1/(1 − 0.963) ≈ 27
    assert analysis.balancing_moment == pytest.approx(expected["M"], rel=EPS_R, abs=EPS_R * expected["M"].max())
    assert np.abs(analysis.solution.N) == pytest.approx(expected["N"], rel=EPS_R, abs=EPS_R * expected["N"].max())
    true_error = np.max(np.abs(analysis.balancing_moment - expected["M"]) / expected["M"].max())
    assert true_error <= max(3 * analysis.numerics["error_estimate"], 1e-13)   # the estimate holds (rounding floor)
    from server.core.kinetostatics.report import efficiency
    eta = efficiency(analysis)["efficiency"]
    assert eta is not None and 0 < eta < 1


def test_issue_body_agrees_with_the_textbook_iteration_run_5000_steps():
    """0.963⁵⁰⁰⁰ ≈ 1e-82: the 5000th approximation is converged to rounding; the 60-step table is not (0.963⁶⁰ ≈ 0.1)."""
    params, phi, analysis = issue_analysis()
    points, applied = analysis.points, analysis.applied
    pairs, friction = Pairs(f34=0.8), {"F34": np.zeros(phi.size), "M2": np.zeros(phi.size)}
    for _ in range(5000):
        R12, R23, N = solve_dyad(points, applied, friction)
        friction = friction_loads(pairs, applied, R12, R23, N, R12, -10.0)
    R12, R23, N = solve_dyad(points, applied, friction)
    scale = np.linalg.norm(R12, axis=1)
    assert np.all(np.linalg.norm(analysis.solution.R12 - R12, axis=1) <= EPS_R * scale)
    assert np.all(np.abs(analysis.solution.N - N) <= EPS_R * scale)
    assert len(analysis.approximations) == 60 and analysis.approximations[-1].change > EPS_R   # the table, truncated
    assert analysis.numerics["message_code"] == "approximations_truncated"


def test_issue_body_agrees_with_fsolve_of_the_full_equilibrium():
    params, phi, _ = issue_analysis()
    analysis, ref, _, check = check_against_reference(params, Loads(force=1000.0, gravity=False, omega=10.0),
                                                      Pairs(f34=0.8), phi)
    assert check.sum() >= 60                       # all but the dead centres (and nothing locks)


# --- the boundary f·tan ψ → 1 ------------------------------------------------------------------------------

@settings(max_examples=30, deadline=None, derandomize=True)
@given(lam=st.floats(1.05, 4.0), margin=st.floats(1e-6, 0.2), above=st.booleans(), force=st.floats(1.0, 1e5),
       return_factor=st.floats(0.0, 1.0))
def test_self_locking_is_declared_exactly_where_f_tan_psi_reaches_one(lam, margin, above, force, return_factor):
    """f = (1 ∓ margin)/max|tan ψ| with max|tan ψ| = 1/√(λ² − 1) at φ = 90°, 270° (on the grid): locked exactly
    where f|tan ψ| ≥ 1, with tan ψ computed here; elsewhere the closed form to ε_R, however close the ratio is
    to 1 (ratio 1 − 1e-6: the textbook would need ~2·10⁷ approximations).  Angles with |f|tan ψ| − 1| < 1e-12
    are left out: there rounding of tan ψ decides, not the mechanism."""
    params = MECHANISMS["slider_crank"].check({"l1": 0.1, "l2": 0.1 * lam})
    phi = np.linspace(0, 2 * np.pi, 145)
    f = (1 + margin if above else 1 - margin) * np.sqrt(lam**2 - 1)
    analysis = analyse(params, Loads(force=force, gravity=False, omega=3.0, return_factor=return_factor),
                       Pairs(f34=f), phi, EPS_R)
    expected, g = closed_form(params, force, f, phi, return_factor)
    ratio = f * np.abs(g["tan_psi"])
    decided = np.abs(ratio - 1) > 1e-12
    locked = ~np.isfinite(analysis.balancing_moment)
    assert np.array_equal(locked[decided], (ratio >= 1)[decided])
    assert bool(analysis.notices) == bool(locked.any())
    free = ~locked & decided & (ratio < 1)
    assert np.all(np.abs(analysis.balancing_moment - expected["M"])[free] <= EPS_R * expected["M"][free] + 1e-12 * force * 0.1)
    assert analysis.converged[free].all()


def test_just_below_and_just_above_one_at_the_issue_geometry():
    params = MECHANISMS["slider_crank"].check({"l1": 0.1, "l2": 0.13})
    phi = np.linspace(0, 2 * np.pi, 73)
    t_max = 0.1 / np.sqrt(0.13**2 - 0.1**2)
    below = analyse(params, Loads(force=1000.0, gravity=False), Pairs(f34=(1 - 1e-3) / t_max), phi)
    assert not below.notices and np.isfinite(below.balancing_moment).all()
    assert below.ratio == pytest.approx(1 - 1e-3, rel=1e-12)
    above = analyse(params, Loads(force=1000.0, gravity=False), Pairs(f34=(1 + 1e-3) / t_max), phi)
    locked = np.degrees(phi[~np.isfinite(above.balancing_moment)])
    assert locked == pytest.approx([90.0, 270.0])
    assert above.notices[0].code == "kinetostatics_self_locking"


# --- random machines against fsolve ------------------------------------------------------------------------

def amount(high, low=1e-3):
    """Zero or a physical size: loads of 1e-300 would leave reactions in the subnormal range, where no relative
    tolerance can hold (that is floating point, not friction)."""
    return st.one_of(st.just(0.0), st.floats(low, high))


machines = st.fixed_dictionaries({
    "l1": st.floats(0.03, 0.3), "lam": st.floats(1.1, 5.0), "offset": st.floats(-0.3, 0.3), "a2": st.floats(0.1, 0.9),
    "m2": amount(10), "J_S2": amount(0.1, 1e-5), "m3": amount(10), "J1": amount(0.5, 1e-4),
    "omega": st.floats(1, 100), "epsilon": st.one_of(st.just(0.0), st.floats(-200, -0.1), st.floats(0.1, 200)),
    "force": amount(5000, 1.0), "return_factor": amount(1, 0.01), "gravity": st.booleans(),
    "f14": amount(0.3), "f12": amount(0.3), "f23": amount(0.3), "f34": amount(1.5)})


def build(m):
    try:
        params = MECHANISMS["slider_crank"].check({"l1": m["l1"], "l2": m["l1"] * m["lam"], "e": m["offset"] * m["l1"],
                                                   "a2": m["a2"]})
    except GeometryError:
        assume(False)
    loads = Loads(m2=m["m2"], J_S2=m["J_S2"], m3=m["m3"], J1=m["J1"], omega=m["omega"], epsilon=m["epsilon"],
                  force=m["force"], return_factor=m["return_factor"], gravity=m["gravity"])
    return params, loads, Pairs(f14=m["f14"], f12=m["f12"], f23=m["f23"], f34=m["f34"])


def wedged(params, loads, pairs, g, i, points=4001) -> bool:
    """Whether the slider can be wedged at angle i: the free-body equations with the loads left out (reactions
    growing without bound) have a nonzero solution with the guide's friction coefficient μf₃₄ for some
    μ ∈ (0, 1] (the friction circles at their full size).  Slider: R_x = μ sgn(V_B) f₃₄ |R_y|, so
    R ∥ (μ sgn(V_B) f₃₄, ±1); rod (a two-force member, R₁₂ = R₂₃ = R):
    (B − A)×(−R) − (sgn(ω₂ − ω₁) ρ_A + sgn ω₂ ρ_B)|R| = 0, scanned over μ (μ = 1 on the grid) for a sign
    change.  Where it has a root the rod's line of force lies within the guide's friction angle: self-locking."""
    w = loads.omega
    s_v, s_2, s_rel = np.sign(g["dxB"][i] * w), np.sign(g["dtheta"][i] * w), np.sign(g["dtheta"][i] * w + w)
    AB = g["B"][i] - g["A"][i]
    rho = s_rel * pairs.f12 * pairs.r12 + s_2 * pairs.f23 * pairs.r23
    mu = np.linspace(1 / points, 1, points)
    for up in (1.0, -1.0):
        R = np.stack([mu * s_v * pairs.f34, np.full_like(mu, up)])
        rod = -(AB[0] * R[1] - AB[1] * R[0]) - rho * np.hypot(*R)
        if np.any(np.sign(rod[1:]) != np.sign(rod[:-1])) or np.any(rod == 0):
            return True
    return False


@settings(max_examples=40, deadline=None, derandomize=True)
@given(machines)
def test_random_machines_agree_with_fsolve_and_lock_only_for_physical_reasons(m):
    check_random_machine(m)


def check_random_machine(m):
    """Where the app finds an equilibrium, fsolve finds the same (to ε_R) and the app says it converged; it
    declares self-locking exactly where the slider can be wedged (the test's own limit analysis of the
    free-body equations), which without friction circles is f₃₄|tan ψ| ≥ 1 (tan ψ from the test's geometry).
    Angles within 1e-6 of the boundary (the app's f₃₄|tan ψ'|) are left out: the grid in α decides there."""
    params, loads, pairs = build(m)
    phi = np.linspace(0, 2 * np.pi, 37)
    analysis, ref, g, check = check_against_reference(params, loads, pairs, phi)
    locked = ~np.isfinite(analysis.balancing_moment)
    moving = np.abs(g["dxB"]) > 1e-7 * params["l1"]
    assert ref["ok"][~locked & moving].all()                        # the app's equilibrium exists: fsolve finds it
    assert analysis.converged[~locked].all() and not analysis.notices[1:]
    guide = pairs.f34 * np.abs(g["tan_psi"])
    if not (pairs.f12 or pairs.f23):
        decided = np.abs(guide - 1) > 1e-12
        assert np.array_equal(locked[decided & moving], (guide >= 1)[decided & moving])
    if pairs.f34 > 0:      # κ = ∞: the joints' friction turns the rod's line past the normal (checked apart)
        for i in np.flatnonzero(moving & (np.abs(analysis.guide_ratio - 1) > 1e-6) & np.isfinite(analysis.guide_ratio)):
            assert locked[i] == wedged(params, loads, pairs, g, i), np.degrees(phi[i])


# --- efficiency (3.38) ----------------------------------------------------------------------------------------

def test_efficiency_is_useful_over_useful_plus_friction_work_and_balances_the_driving_work():
    """η = A_u/(A_u + A_fr) (3.38): against the closed form of the issue's case (same trapezoid rule on the same
    grid, so 1e-12 is rounding); exactly 1 without friction; and with masses at constant speed the balancing
    moment's work equals A_u + A_fr: the power balance holds at every angle, and the inertia loads' power, odd
    about φ = π in the central mechanism, sums to zero on the symmetric grid (1e-9: rounding of the sums)."""
    from server.core.kinetostatics.report import efficiency
    params = MECHANISMS["slider_crank"].check({"l1": 0.1, "l2": 0.13})
    phi = np.linspace(0, 2 * np.pi, 721)
    result = efficiency(analyse(params, Loads(force=1000.0, gravity=False, omega=10.0), Pairs(f34=0.8), phi))
    expected, g = closed_form(params, 1000.0, 0.8, phi)
    useful = np.trapezoid(1000.0 * np.abs(g["dxB"]), phi)
    lost = np.trapezoid(0.8 * expected["N"] * np.abs(g["dxB"]), phi)
    assert result["efficiency"] == pytest.approx(useful / (useful + lost), rel=1e-12)
    machine = Loads(m2=3.0, J_S2=0.05, m3=2.0, omega=30.0, force=1000.0, return_factor=0.3)
    assert efficiency(analyse(params, machine, Pairs(), phi))["efficiency"] == 1.0
    rough = efficiency(analyse(params, machine, Pairs(f14=0.05, f12=0.08, f23=0.08, f34=0.3), phi))
    assert 0 < rough["efficiency"] < 1
    assert rough["work_driving"] == pytest.approx(rough["work_useful"] + rough["work_friction"], rel=1e-9)


def test_a_series_ratio_above_one_where_nothing_locks_is_said_as_such_and_solved():
    """Journals of 1 m with f = 2 on a 0.1 m crank (extreme, allowed by the API): at some angles the textbook's
    series has q ≥ 1 (it cannot converge) while the slider cannot be wedged; there the equilibrium still exists,
    fsolve finds the same to ε_R, and the numerics say the series diverges, not that the mechanism locks."""
    params = MECHANISMS["slider_crank"].check({"l1": 0.1, "l2": 0.1001})
    loads = Loads(m2=1e5, m3=1e5, J_S2=1e4, omega=1e4, epsilon=1e6, force=1e7)
    pairs = Pairs(f14=2, f12=2, f23=2, f34=2, r14=1, r12=1, r23=1)
    phi = np.linspace(0, 2 * np.pi, 73)
    analysis, ref, g, check = check_against_reference(params, loads, pairs, phi)
    free = np.isfinite(analysis.balancing_moment)
    assert (analysis.ratios[free] >= 1).any() and check[free & (analysis.ratios >= 1)].any()
    assert analysis.numerics["message_code"] == "approximations_diverge"
    moving = np.abs(g["dxB"]) > 1e-7 * params["l1"]
    for i in np.flatnonzero(moving & (np.abs(analysis.guide_ratio - 1) > 1e-6) & np.isfinite(analysis.guide_ratio)):
        assert free[i] != wedged(params, loads, pairs, g, i)
