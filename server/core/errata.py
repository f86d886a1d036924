"""The sources' misprints that change a number, each printed beside corrected with the value each gives for
the scene's own data (one row format for every scene, the bearings' (2.4), (2.13), (2.16) among them):

    {"key", "source", "equation", "printed_value", "printed_unit", "corrected_value", "unit"}

``key`` names the formulas and the reason (the interface texts erratum_printed_<key>, erratum_corrected_<key>,
erratum_why_<key>), ``source`` the source (source_<source>),
``unit`` the unit (erratum_unit_<unit>), ``printed_unit`` the printed value's: the same but where the printed
formula gives another quantity than the corrected one (the bearings' (2.4): an area for a length).  The
computations use the corrected forms; these rows only show what the printed ones would give.
"""
from __future__ import annotations

import numpy as np


def row(key: str, source: str, equation: str, printed_value: float, corrected_value: float, unit: str,
        printed_unit: str | None = None) -> dict:
    """One erratum: the value of the printed formula and of the corrected one (the formulas themselves are
    interface texts, erratum_printed_<key> and erratum_corrected_<key>, read in the page's language); the
    printed value's own unit where it differs from the corrected one's."""
    return {"key": key, "source": source, "equation": equation, "printed_value": float(printed_value),
            "printed_unit": printed_unit or unit, "corrected_value": float(corrected_value), "unit": unit}


ROUNDING = 1e-12   # a mean below this fraction of the function's largest value is rounding: shown as 0


def _cycle_mean(values: np.ndarray) -> float:
    """Mean over a uniform open grid of one period (spectrally exact for trigonometric polynomials); a mean
    that is rounding alone (below ROUNDING of the largest |value|) is 0."""
    mean = float(np.mean(values))
    return 0.0 if abs(mean) <= ROUNDING * float(np.max(np.abs(values))) else mean


def variable_inertia(m3: float, l1: float, lam: float, points: int = 720) -> list[dict]:
    """Eremyants (3.38)/(3.39), the crank-slider's variable part J̃ = J_M − J̄ of m₃u₃₁² (λ = l₂/l₁): as
    printed (3.39) −(m₃l₁²/2)[1 − sin²φ(1 − (2/λ)cos φ)] has the mean −m₃l₁²/4, not zero; the corrected
    (3.39*) −(m₃l₁²/2)[1 − 2sin²φ(1 − (2/λ)cos φ)] has mean 0.  (3.38) printed lacks the factor 2 and the
    sin φ of the bracket: −(m₃l₁²/2)[1 + 1/(4λ²) − sin²(1 − (2/λ)cos φ) + cos²φ/λ²] (the OCR's "sin²" read as
    sin²φ); (3.38*) −(m₃l₁²/2)[1 + 1/(4λ²) − 2sin²φ(1 − (2/λ)cos φ + cos²φ/λ²)].  Each row gives the cycle
    mean, kg·m²: a variable part's mean is zero."""
    phi = np.arange(points) * 2 * np.pi / points
    s2, c = np.sin(phi) ** 2, np.cos(phi)
    k = m3 * l1**2 / 2
    printed_39 = -k * (1 - s2 * (1 - 2 / lam * c))
    fixed_39 = -k * (1 - 2 * s2 * (1 - 2 / lam * c))
    printed_38 = -k * (1 + 1 / (4 * lam**2) - s2 * (1 - 2 / lam * c) + c**2 / lam**2)
    fixed_38 = -k * (1 + 1 / (4 * lam**2) - 2 * s2 * (1 - 2 / lam * c + c**2 / lam**2))
    return [row("variable_inertia_38", "eremyants", "(3.38)", _cycle_mean(printed_38), _cycle_mean(fixed_38),
                "mean_kgm2"),
            row("variable_inertia_39", "eremyants", "(3.39)", _cycle_mean(printed_39), _cycle_mean(fixed_39),
                "mean_kgm2")]


def slotted_viscous(omega: float, l1: float, lam: float, points: int = 720) -> list[dict]:
    """Eremyants (3.50)/(3.53), the slotted link's viscous moment M_T = βωu₂₁² (λ = l₀/l₁), as cycle means of
    M_T/(βω) in m² (any β): (3.50) printed l₁²λ sin²φ/(1 + λ² + 2λcos φ), corrected (3.50*) with λ²; (3.53) at
    λ = 1 printed βω² sin²(φ/2), i.e. M_T/(βω) = ω sin²(φ/2) (mean ω/2, in s⁻¹, not m²), corrected (3.53*)
    βωl₁² sin²(φ/2) (mean l₁²/2)."""
    phi = np.arange(points) * 2 * np.pi / points
    shape = np.sin(phi) ** 2 / (1 + lam**2 + 2 * lam * np.cos(phi))
    half = np.sin(phi / 2) ** 2
    return [row("slotted_viscous_50", "eremyants", "(3.50)", _cycle_mean(l1**2 * lam * shape),
                _cycle_mean(l1**2 * lam**2 * shape), "per_beta_omega"),
            row("slotted_viscous_53", "eremyants", "(3.53), λ = 1", _cycle_mean(omega * half),
                _cycle_mean(l1**2 * half), "per_beta_omega")]


def gutyar_squares(work: np.ndarray, inertia_ii: np.ndarray, omega_mean: float, delta: float,
                   corrected: float) -> dict:
    """Lecture 10 (L27), Gutyar's curve pieces ΔT − I_II ω_max²/2, ΔT − I_II ω_min²/2 printed without the
    squares: I_I from the printed pieces (their extremes over the whole cycle) beside
    the corrected method's I_I (``corrected``), kg·m²."""
    w_max, w_min = (1 + delta / 2) * omega_mean, (1 - delta / 2) * omega_mean
    swing = float(np.max(work - 0.5 * inertia_ii * w_max) - np.min(work - 0.5 * inertia_ii * w_min))
    return row("gutyar_squares", "lecture10", "(L27)", swing / (delta * omega_mean**2), corrected, "kgm2")


def wittenbauer_axes(omega_mean: float, delta: float) -> dict:
    """Lecture 10 (L28)–(L29): the tangent of slope tg ψ_max = ω_max²/2 (energy T on y, inertia I on x, μ_T =
    μ_I = 1); the text places y_I = μ_I·I_I, x_I = μ_T·T_нач, i.e. I on y: the same tangent would then have
    the slope 2/ω_max², J/(kg·m²) against (kg·m²)/J."""
    w_max = (1 + delta / 2) * omega_mean
    return row("wittenbauer_axes", "lecture10", "(L28)–(L29)", 2 / w_max**2, w_max**2 / 2, "slope")


def flywheel_part(required: float, crank: float, rotor_reduced: float) -> dict:
    """Lecture 10 (L7): I_м = I_I − (I_рот + I_ред + I₀₁); the print I_м = I_I − (I_ред + I₀₁ + I_м) has the
    flywheel on both sides and no rotor, which solves to I_м = (I_I − I₀₁)/2 (the reducer taken with the crank
    here, I_ред = 0 as in the app's group I = J₁ + J_rotor·i²), kg·m²."""
    return row("flywheel_part", "lecture10", "(L7)", (required - crank) / 2, required - crank - rotor_reduced, "kgm2")


def wear_example(l1: float, l2: float, steps: int = 13) -> list[dict]:
    """Chaika–Vasylenko, Table 4.3 and the §4.3 example: u₂₁(30°) = λ cos φ/√(1 − λ²sin²φ) (λ = l₁/l₂) is
    printed 0.2187 where the formulas of §2.3.1 give 0.2182 for the book's mechanism; the trapezoid step over
    the 13 table rows Δφ₁ = 2π/(N_p − 1) is printed 0.432, the formula gives π/6 = 0.5236."""
    lam, phi = l1 / l2, np.radians(30.0)
    u21 = lam * np.cos(phi) / np.sqrt(1 - (lam * np.sin(phi)) ** 2)
    return [row("u21_slip", "chaika_vasylenko", "§4.3: φ₁ = 30°", 0.2187, u21, "none"),
            row("trapezoid_step", "chaika_vasylenko", "§4.3: Δφ₁", 0.432, 2 * np.pi / (steps - 1), "rad")]


def piston_pressure(force: float, length: float, diameter: float) -> dict:
    """Chaika–Vasylenko (4.16): p_max = 2F_e/(π l_p d_p) printed; with d_p a diameter (as (4.4), (4.20) and the
    example's 4R/(π L_p D_p)) it is 4F_e/(π l_p d_p), Pa, for the largest piston side force."""
    return row("piston_pressure", "chaika_vasylenko", "(4.16)", 2 * force / (np.pi * length * diameter),
               4 * force / (np.pi * length * diameter), "Pa")


def reduction(mechanism, params: dict, m3: float, omega: float) -> list[dict]:
    """The misprints of the reduction formulas of the mechanism (Mechanism.reduction_errata): Eremyants
    (3.38)/(3.39) for the crank-slider (λ = l₂/l₁), (3.50)/(3.53) for the slotted link (λ = l₀/l₁)."""
    return mechanism.reduction_errata(params, m3, omega)


def _central_crank_slider(l1: float, l2: float, points: int) -> dict:
    """Chaika–Vasylenko §3.1's central crank-slider in its own frame (φ₁ counter-clockwise from the crank
    pointing at the slider, φ₂ the rod's angle, λ₂ = l₂/l₁): sin φ₂ = −sin φ₁/λ₂, u₂₁ = −cos φ₁/(λ₂cos φ₂)
    (3.7) and du₂₁/dφ₁ = (sin φ₁ + λ₂u₂₁² sin φ₂)/(λ₂cos φ₂), on a closed grid of the cycle."""
    lam = l2 / l1
    phi = np.linspace(0.0, 2 * np.pi, points)
    s2 = -np.sin(phi) / lam
    c2 = np.sqrt(1 - s2**2)
    u21 = -np.cos(phi) / (lam * c2)
    du21 = (np.sin(phi) + lam * u21**2 * s2) / (lam * c2)
    return {"lam": lam, "phi": phi, "s2": s2, "c2": c2, "u21": u21, "du21": du21}


def crank_slider_kinetostatics(l1: float, l2: float, l_as2: float, omega: float, m2: float,
                               points: int = 1441) -> list[dict]:
    """Chaika–Vasylenko §3.1, the central crank-slider at constant ω₁ (ε₁ = 0), each misprint by the largest value
    over the cycle it gives, printed beside corrected:

    (3.6) a_B's bracket with 2cos²φ₁ where d(V_qB)/dφ₁ gives cos 2φ₁: max |a_B|, m/s²;
    (3.6) a_S2x with u₂₁²cos²φ₂ where it is u₂₁²cos φ₂: a_S2x at φ₁ = 45°, m/s² (about where the two differ
          most; at the dead centres φ₂ = 0 and they agree);
    (3.7) φ₂ = arcsin(λ_e sin φ₁/λ₂) where (3.5) gives arcsin((λ_e − sin φ₁)/λ₂): max |φ₂|, deg (λ_e = 0);
    (3.19) the arm of F₂ᵢₙ about A, (F_y cos φ₂ + F_x sin φ₂)·l_AS2 where the vector product gives
           (F_y cos φ₂ − F_x sin φ₂)·l_AS2: max |M_A(F₂ᵢₙ)|, N·m (F₂ᵢₙ = −m₂a_S2);
    (3.27) the crank pin's relative angular velocity analog |u₁₁ + u₂₁| where it is |u₁₁ − u₂₁|: its value at
           φ₁ = 0, where it is largest (1 + 1/λ₂)."""
    k = _central_crank_slider(l1, l2, points)
    lam, phi, s2, c2, u21, du21 = (k[key] for key in ("lam", "phi", "s2", "c2", "u21", "du21"))
    w2 = l1 * omega**2
    root = np.sqrt(lam**2 - np.sin(phi) ** 2)
    tail = np.sin(phi) ** 2 * np.cos(phi) ** 2 / root**2
    a_b = lambda first: -w2 * (np.cos(phi) + (first + tail) / root)
    ratio = l_as2 / l2
    a_s2x = lambda c: -(np.cos(phi) + lam * ratio * (du21 * s2 + u21**2 * c)) * w2
    a_s2y = (ratio - 1) * np.sin(phi) * w2
    fx, fy = -m2 * a_s2x(c2), -m2 * a_s2y
    largest = lambda v: float(np.max(np.abs(v)))
    return [row("slider_acceleration_36", "chaika_vasylenko", "(3.6), a_B", largest(a_b(2 * np.cos(phi) ** 2)),
                largest(a_b(np.cos(2 * phi))), "m_s2"),
            row("rod_centre_acceleration_36", "chaika_vasylenko", "(3.6), a_S2x, φ₁ = 45°",
                float(np.interp(np.pi / 4, phi, a_s2x(c2**2))), float(np.interp(np.pi / 4, phi, a_s2x(c2))), "m_s2"),
            row("rod_angle_37", "chaika_vasylenko", "(3.7)", 0.0, np.degrees(np.arcsin(1 / lam)), "deg"),
            row("inertia_arm_319", "chaika_vasylenko", "(3.19)", largest((fy * c2 + fx * s2) * l_as2),
                largest((fy * c2 - fx * s2) * l_as2), "Nm"),
            row("relative_rate_327", "chaika_vasylenko", "(3.27), φ₁ = 0", abs(1 + u21[0]), abs(1 - u21[0]), "none")]


def parallel_efficiency(efficiencies, works) -> dict:
    """Chaika–Vasylenko (3.40): η of mechanisms in parallel, printed Σ A_P η_k / A_P (= Σ η_k, which can exceed
    1), corrected Σ A_P,k η_k / A_P with A_P = Σ A_P,k."""
    total = float(np.sum(works))
    corrected = float(np.dot(works, efficiencies)) / total if total > 0 else float("nan")
    return row("parallel_efficiency_340", "chaika_vasylenko", "(3.40)", float(np.sum(efficiencies)), corrected, "none")


DIAGRAM_BASE_MM = 240.0     # b: the length of the abscissa that draws one cycle on the sheet (Lecture 10 §10.6)


def lecture10_rig(group_i: float, inertia_ii: np.ndarray, driving_work: float, omega_mean: float) -> list[dict]:
    """Lecture 10's slips in the drilling-rig example that the flywheel study computes right, each with the value
    it gives for the scene's machine:

    §10.4.1.3  (step 1.3 of §10.4, written as a section number so that no page reads it as a decimal) the
               variable part I_v^пр is assigned to the links of constant transfer functions (and the constant
               part to the variable ones): I_v as printed is group I's inertia, corrected the cycle mean of I_II;
    (L17)      y_Fд called the ordinate of the resisting force: read so, the driving moment changes sign, and its
               work over the cycle with it, J;
    §10.6      the abscissa scale μ_φ = b/(2π) printed μ_p = b/2π, the symbol of the pressure scale (L15): the
               same number (b = DIAGRAM_BASE_MM), mm/rad;
    given data ω₁ср = 47.124 printed in рад/с² (an angular acceleration's unit): the same number, rad/s.

    ``inertia_ii`` on the flywheel cycle's closed uniform grid (its last point is the first again)."""
    mean_ii = float(np.mean(np.asarray(inertia_ii)[:-1]))
    return [row("groups_reversed", "lecture10", "§10.4.1.3", group_i, mean_ii, "kgm2"),
            row("driving_ordinate", "lecture10", "(L17)", -driving_work, driving_work, "J"),
            row("phi_scale", "lecture10", "§10.6", DIAGRAM_BASE_MM / (2 * np.pi), DIAGRAM_BASE_MM / (2 * np.pi),
                "mm_rad", printed_unit="mm_rad_as_pressure"),
            row("omega_unit", "lecture10", "§10.5", omega_mean, omega_mean, "rad_s", printed_unit="rad_s2")]
