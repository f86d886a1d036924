"""Wear from tabulated loads: the example of Chaika–Vasylenko §4.3 (a two-stroke engine) driven by the reaction
columns of its Table 4.3, summed as the book's program ISNKPKPM sums them.

The input is a table of rows at crank angles φ₁ (0…360°, the last row repeating the first): the reaction R₂₃
(N) of the rod on the piston pin with its direction γ₃₂ (deg), the guide's reaction R₃₄ (N, + on the side the
book calls right), u₂₁, the rod's angle φ₂ (deg) and the piston's velocity analog V_qB (m/rad).  Every
integral over the cycle is the book's sum, the trapezoid over the rows, Δφ₁/2·Σ(yᵢ + yᵢ₊₁) (§4.2):

    pin, bush   δ(β) = a ∫ R₂₃ |u₂₁| cos ψ dφ₁ over the rows in contact (|ψ| ≤ 90°)       (4.12), (4.13)
    piston      δ₃ = a₃ ∫ R₃₄ |V_qB| dφ₁ over the rows pressing the right side          (4.17)
    cylinder    δ₄(X) = a₄ ∫ R₃₄ |V_qB| dφ₁ over the rows whose piston covers X           (4.18)
    k = I_s/p_m, p_m = 4 R_m/(π l d) with R_m the mean of the rows                          (4.23), (4.24)

The book measures β clockwise (its ψ₃ = β₃ + γ₃₂ and ψ₂ = β₂ + γ₃₂ − φ₂ in Table 4.4 give its integrands
R₂₃|u₂₁||cos ψ|); the answer's β is counter-clockwise like the rest of the app, so the book's point
β = 190° is β = 170° here.
"""
from __future__ import annotations

import time

import numpy as np

from ..numerics import Numerics
from .report import BOOK_WEAR
from .wear import mean_pressure, piston_wear, revolute_wear

# Chaika–Vasylenko, Table 4.3 (computed by the authors' program DWS): the engine of §4.3 at 2400 rpm,
# l₁ = 0.045 m, l₂ = 0.18 m, axial.  As printed, u₂₁ = ∓0.2187 at 30° and 150° included (the formulas give
# ∓0.2182; the erratum is shown with the scene: the wear changes by 0.1 %).
TABLE_4_3 = {
    "phi": [0, 30, 60, 90, 120, 150, 180, 210, 240, 270, 300, 330, 360],
    "V_qB": [0, -0.0274, -0.0440, -0.0450, -0.0340, -0.0176, 0, 0.0176, 0.0340, 0.0450, 0.0440, 0.0274, 0],
    "u21": [-0.25, -0.2187, -0.128, 0, 0.128, 0.2187, 0.25, 0.2182, 0.128, 0, -0.128, -0.2182, -0.25],
    "phi2": [360, 352.8, 347.5, 345.5, 347.5, 352.8, 0, 7.2, 12.5, 14.5, 12.5, 7.2, 360],
    "R34": [0, 3013, 3720, 3449, 2766, 1467, 0, -841, -1828, -2002, -664, -2456, 0],
    "R23": [1324, 10507, 6540, 5366, 4668, 3471, 2927, 1356, 2299, 2518, 811, 2847, 1324],
    "gamma32": [359.6, 343.4, 325.3, 320.0, 323.7, 334.9, 0, 37.4, 52.6, 52.5, 55.0, 59.8, 359.6],
}
BOOK_LINKS = (0.045, 0.18)              # l₁, l₂ of the table's mechanism, m (§4.3)
BOOK_POINT = 190.0                      # β₂ = β₃ = 190° of Table 4.4, the book's (clockwise) angle, deg
BOOK_CYLINDER_LIMITS = ((0.0, 120.0), (330.0, 360.0))   # the printed limits of D₄'s integral, deg (§4.3 (B))
PRINTED_PISTON_INTEGRAND_150 = 61.0     # Table 4.4 at φ₁ = 150°: R₃₄|V_qB| printed 61 N·m/rad (1467·0.0176 = 25.8)
PRINTED_MEAN_R23 = 3468.0               # §4.3 (A) step 1: the mean of R₂₃ printed 3468 N (the 13 rows: 3535 N)
PRINTED_CYLINDER_K = 1.41e-17           # §4.3 (B) step 3: k₃₄⁽⁴⁾ printed 1.41·10⁻¹⁷ m²/N (I_s = 3·10⁻¹² gives 1.21)
# §4.3, the maxima the text reads from Fig. 4.7, µm: the pin δ₃,max = 36 (β₃ = 180…200°), the bush δ₂,max ≈ 68,
# the cylinder's right side δ₄,max ≈ 59 (region II, X ≈ 0.076…0.090 m)
FIGURE_4_7 = {"pin_23": 36.0, "bush_23": 68.0, "cylinder": 59.0}
# §4.3 steps 3: the wear coefficients as printed, m²/N (pin 0.68·10⁻¹⁷, bush 1.14·10⁻¹⁷, cylinder 1.41·10⁻¹⁷)
PRINTED_K = {"pin": 0.68e-17, "bush": 1.14e-17, "cylinder": 1.41e-17}
BOOK_PARTS = {"pin_diameter": 0.02, "pin_length": 0.025, "piston_diameter": 0.075, "piston_length": 0.076,
              "I_pin": 0.6e-10, "I_bush": 1.0e-10, "I_piston": 2e-12, "I_cylinder": 3e-12}     # §4.3's data
BOOK_CYCLES = 1.44e8                    # §4.3 step 0: N_c = 60·n₁·t = 60·2400·1000
# §4.3 Table 4.4 as printed, β₂ = β₃ = 190°: per row of Table 4.3 ψ₂ (deg), R₂₃|u₂₁|cos ψ₂, ψ₃ (deg),
# R₂₃|u₂₁|cos ψ₃ and R₃₄|V_qB| (N·m/rad; the left side's values printed in parentheses are None here: 0 for the
# right side)
TABLE_4_4 = {
    "psi2": [200.0, 190.6, 177.8, 174.5, 176.2, 182.1, 200.0, 230.2, 240.1, 238.0, 242.5, 252.6, 199.4],
    "bush": [311, 2252, 836, 0, 596, 756, 688, 194, 147, 0, 48, 185, 311],
    "psi3": [189.6, 173.4, -10.0, 196.9, 117.7, 129.9, -165.4, -186.5, -180.5, -178.0, -179.8, -175.2, 167.0],
    "pin": [326, 2277, 760, 0, 536, 716, 721, 204, 132, 0, 60, 314, 326],
    "piston": [0, 83, 164, 155, 94, 61, 0, 0, 0, 0, 0, 0, 0],
}
# §4.3 steps 5 and 0 as printed: a₂ (bush), a₃ (pin), a₃п (piston), a₄ (cylinder), N_c
PRINTED_COEFFICIENTS = {"N_c": 1.44e8, "a_2": 0.042, "a_3": 0.025, "a_{3p}": 0.261, "a_4": 0.454}


def book_sum(phi: np.ndarray, values: np.ndarray) -> np.ndarray:
    """The book's integral over the cycle (ISNKPKPM, §4.2): Δφ/2·Σ(yᵢ + yᵢ₊₁) over the rows, along the last axis."""
    return np.trapezoid(values, phi, axis=-1)


def table_columns(table: dict) -> dict:
    """The table in SI: angles in rad, the reaction of the rod on the pin as vectors (n, 2)."""
    phi = np.radians(np.asarray(table["phi"], float))
    r23, gamma = np.asarray(table["R23"], float), np.radians(np.asarray(table["gamma32"], float))
    return {"phi": phi, "R23": np.stack([r23 * np.cos(gamma), r23 * np.sin(gamma)], 1),
            "R23_magnitude": r23, "gamma": gamma, "u21": np.asarray(table["u21"], float),
            "phi2": np.radians(np.asarray(table["phi2"], float)), "R34": np.asarray(table["R34"], float),
            "V_qB": np.asarray(table["V_qB"], float)}


def piston_travel(phi: np.ndarray, l1: float, l2: float) -> np.ndarray:
    """The piston's travel from top dead centre of the axial crank-slider, l₁ + l₂ − x_B,
    x_B = l₁cos φ₁ + √(l₂² − l₁²sin²φ₁) (Chaika–Vasylenko §2.3.1)."""
    return l1 + l2 - (l1 * np.cos(phi) + np.sqrt(l2 ** 2 - (l1 * np.sin(phi)) ** 2))


def point_wear(c: dict, k_pin: float, k_bush: float, cycles: float, pin_length: float,
               beta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """δ(β) of the pin (turning with the piston: none) and the bush (turning with the rod, φ₂), µm (4.12), (4.13)."""
    relative = np.abs(c["u21"])                             # |u₂₁ − u₃₁|, the piston does not turn (4.9)
    pin = revolute_wear(c["phi"], c["R23"], relative, np.zeros_like(c["phi"]), beta, k_pin, cycles,
                        pin_length, journal=True)
    bush = revolute_wear(c["phi"], -c["R23"], relative, c["phi2"], beta, k_bush, cycles, pin_length,
                         journal=False)
    return pin, bush


def limited_cylinder_wear(c: dict, k: float, cycles: float, length: float, diameter: float,
                          limits=BOOK_CYLINDER_LIMITS, both_sides: bool = False) -> float:
    """δ₄ (µm) at the book's point D₄ by its printed limits of integration (§4.3 (B) step 7),
    a₄ = 10⁶(4/π)k n_c/(l_p d_p) (4.19); the right side's rows only, or (both_sides) |R₃₄V_qB| of every row as
    the printed sum takes it."""
    phi = c["phi"]
    load = np.abs(c["R34"] * c["V_qB"]) if both_sides else np.where(c["R34"] > 0, np.abs(c["R34"] * c["V_qB"]), 0.0)
    total = 0.0
    for low, high in limits:
        inside = (phi >= np.radians(low) - 1e-9) & (phi <= np.radians(high) + 1e-9)
        total += float(book_sum(phi[inside], load[inside]))
    return 1e6 * (4 / np.pi) * k * cycles / (length * diameter) * total


def footprint_wear(c: dict, travel: np.ndarray, points: np.ndarray, k: float, cycles: float,
                   length: float, diameter: float) -> np.ndarray:
    """δ₄(X) (µm) along the cylinder's right side: the rows whose piston, over [s, s + l_p] from top dead centre,
    covers X (4.18), d = 4/π."""
    load = np.where(c["R34"] > 0, np.abs(c["R34"] * c["V_qB"]), 0.0)
    covered = (points[:, None] >= travel[None, :] - 1e-12) & (points[:, None] <= travel[None, :] + length + 1e-12)
    return 1e6 * (4 / np.pi) * k * cycles / (length * diameter) * book_sum(c["phi"], np.where(covered, load, 0.0))


def _coefficients(c: dict, parts: dict) -> tuple[float, float, dict]:
    """p₂₃, p₃₄ (the right side's rows) by (4.23) and the wear coefficients k = I_s/p_m (4.24)."""
    p23 = mean_pressure(c["R23_magnitude"], parts["pin_length"], parts["pin_diameter"])
    p34 = mean_pressure(np.where(c["R34"] > 0, c["R34"], 0.0), parts["piston_length"], parts["piston_diameter"])
    return p23, p34, {"pin": parts["I_pin"] / p23, "bush": parts["I_bush"] / p23,
                      "piston": parts["I_piston"] / p34, "cylinder": parts["I_cylinder"] / p34}


def _coarse_change(c: dict, cycles: float, parts: dict, beta: np.ndarray, fine: dict) -> float:
    """How much the book's sums change when every other row is dropped (Δφ₁ doubled), relative to the largest
    wear: how much the answer leans on the table's spacing. Not an error bound: the loads between the rows are
    not given, and the contact's edges and the reactions' sign changes are kinks the trapezoid does not
    resolve steadily."""
    half = {key: value[::2] if isinstance(value, np.ndarray) and value.shape[:1] == c["phi"].shape else value
            for key, value in c.items()}
    k = _coefficients(half, parts)[2]
    pin, bush = point_wear(half, k["pin"], k["bush"], cycles, parts["pin_length"], beta)
    piston = piston_wear(half["phi"], half["R34"], half["V_qB"], k["piston"], cycles, parts["piston_length"],
                         parts["piston_diameter"])
    changes = [np.max(np.abs(pin - fine["pin"])), np.max(np.abs(bush - fine["bush"])), abs(piston - fine["piston"])]
    scale = max(float(np.max(fine["pin"])), float(np.max(fine["bush"])), fine["piston"], 1e-300)
    return float(max(changes)) / scale


def tabulated_wear(table: dict, parts: dict, cycles: float, links: tuple[float, float] = BOOK_LINKS) -> dict:
    """The wear of pin, bush, piston and cylinder from a table of reactions (the columns of TABLE_4_3), by the
    book's sums; ``parts``: pin_diameter, pin_length, piston_diameter, piston_length (m) and the wear
    intensities I_pin, I_bush, I_piston, I_cylinder; the coefficients k = I_s/p_m (4.23), (4.24).

    Besides the distributions: the book's points (β = 190° of the pin and the bush, D₄ of the cylinder by the
    printed limits) and the numerics: the sums are exact for the rows given (no error estimate: the loads
    between the rows are unknown); the message says how much they change over every other row."""
    start = time.perf_counter()
    c = table_columns(table)
    rows = c["phi"].size
    if rows < 5 or (rows - 1) % 2:
        raise ValueError("the book's sum and its error estimate need an even number of intervals, at least 4")
    p23, p34, k = _coefficients(c, parts)
    beta = np.radians(np.arange(0, 361, 5))
    pin, bush = point_wear(c, k["pin"], k["bush"], cycles, parts["pin_length"], beta)
    at = np.radians([360.0 - BOOK_POINT])
    pin_point, bush_point = (float(v[0]) for v in point_wear(c, k["pin"], k["bush"], cycles, parts["pin_length"], at))
    piston = piston_wear(c["phi"], c["R34"], c["V_qB"], k["piston"], cycles, parts["piston_length"],
                         parts["piston_diameter"])
    travel = piston_travel(c["phi"], *links)
    along = np.linspace(0.0, float(travel.max()) + parts["piston_length"], 121)
    cylinder = footprint_wear(c, travel, along, k["cylinder"], cycles, parts["piston_length"], parts["piston_diameter"])
    cylinder_point = limited_cylinder_wear(c, k["cylinder"], cycles, parts["piston_length"], parts["piston_diameter"])
    fine = {"pin": pin, "bush": bush, "piston": piston}
    change = _coarse_change(c, cycles, parts, beta, fine)
    return {
        "beta": beta, "pin": pin, "bush": bush, "piston": piston, "cylinder_x": along, "cylinder": cylinder,
        "points": {"pin_23": pin_point, "bush_23": bush_point, "piston": piston, "cylinder": cylinder_point},
        "mean_pressure_23": p23, "mean_pressure_34": p34, "coefficients": k, "pressed_side": 1,
        "numerics": Numerics(
            method="the book's sum (ISNKPKPM, §4.2): the trapezoid over the table's rows",
            code="wear_book_sum", steps=rows - 1, runtime_ms=1e3 * (time.perf_counter() - start),
            error_estimate=None, message_code="wear_book_sum",
            message_context={"intervals": rows - 1, "change": round(100 * change, 1)},
            message=f"the sums over the {rows - 1} intervals are exact for the rows given (the loads between them "
                    f"are not); over every other row they change by {100 * change:.1f} %").as_dict(),
    }


def table_report(table: dict, parts: dict, cycles: float, links: tuple[float, float]) -> dict:
    """The wear from a table of reactions (tabulated_wear) with the constant-load models at its mean loads and
    the allowed wear of an engine cylinder (150…180 µm, Chaika–Vasylenko §4.3 after Kragelsky)."""
    result = tabulated_wear(table, parts, cycles, links)
    mean_r23 = float(np.mean(np.abs(np.asarray(table["R23"], float))))
    stroke = float(piston_travel(np.pi, *links))                   # axial: H_B = 2l₁ (4.22)
    result["constant_load"] = constant_load_rows(mean_r23, parts, result["coefficients"], cycles, stroke)
    result["allowed"] = [150.0, 180.0]
    return result


def book_table_report(parts: dict, cycles: float) -> dict:
    """The §4.3 example from the reaction columns of Table 4.3: the distributions, the book's points beside its
    printed results, the constant-load estimates, and the misprints met on the way (printed beside corrected,
    each with the value it gives for these parts and cycles)."""
    from .. import errata
    result = table_report(TABLE_4_3, parts, cycles, BOOK_LINKS)
    c, k, points = table_columns(TABLE_4_3), result["coefficients"], result["points"]
    a_piston = 1e6 * (4 / np.pi) * k["piston"] * cycles / (parts["piston_length"] * parts["piston_diameter"])
    printed_integrand = np.where(c["R34"] > 0, np.abs(c["R34"] * c["V_qB"]), 0.0)
    printed_integrand[np.isclose(np.degrees(c["phi"]), 150.0)] = PRINTED_PISTON_INTEGRAND_150
    bush_printed_psi = float(point_wear(c, k["pin"], k["bush"], cycles, parts["pin_length"],
                                        np.radians([360.0 - BOOK_POINT - 10.0]))[1][0])
    geometry = (parts["piston_length"], parts["piston_diameter"])
    result["comparison"] = [{"element": key, "printed": BOOK_WEAR[key], "table": points[key]}
                            for key in ("bush_23", "pin_23", "piston", "cylinder")]
    result["book"] = BOOK_WEAR
    result["figure_4_7"] = figure_maxima(result)
    result["table_4_4"] = table_4_4_rows(c, k, cycles, parts)
    result["book_coefficients"] = book_coefficients(k, cycles, parts)
    result["errata"] = [
        *errata.wear_example(*BOOK_LINKS),
        errata.row("wear_mean_reaction", "chaika_vasylenko", "(4.23), §4.3", PRINTED_MEAN_R23,
                   np.mean(c["R23_magnitude"]), "N"),
        errata.row("wear_bush_point", "chaika_vasylenko", "§4.3: ψ₂", bush_printed_psi, points["bush_23"], "um"),
        errata.row("wear_piston_integrand", "chaika_vasylenko", "§4.3: R₃₄|V_qB|, φ₁ = 150°",
                   a_piston * float(book_sum(c["phi"], printed_integrand)), points["piston"], "um"),
        errata.row("wear_cylinder_coefficient", "chaika_vasylenko", "§4.3, k₃₄⁽⁴⁾", PRINTED_CYLINDER_K,
                   3e-12 / result["mean_pressure_34"], "m2_N"),
        errata.row("wear_cylinder_limits", "chaika_vasylenko", "§4.3, δ₄(D₄)",
                   limited_cylinder_wear(c, k["cylinder"], cycles, *geometry, both_sides=True),
                   points["cylinder"], "um"),
    ]
    return result


def table_4_4_rows(c: dict, k: dict, cycles: float, parts: dict) -> list[dict]:
    """Table 4.4 row by row beside ours: at each row of Table 4.3 the printed ψ₂, ψ₃ and integrands, and the
    integrands the app sums for the same points (β = 190° of the book, 170° counter-clockwise here):
    R₂₃|u₂₁|·max(cos ψ, 0) of the bush (the rod's reaction on it, turning with the rod, φ₂) and of the pin (the
    pressed side against the force), and R₃₄|V_qB| of the piston's right side (R₃₄ > 0)."""
    beta = np.radians(360.0 - BOOK_POINT)
    force, rate = c["R23_magnitude"], np.abs(c["u21"])

    def integrand(reaction, link_angle, journal):
        gamma = np.arctan2(reaction[:, 1], reaction[:, 0]) + (np.pi if journal else 0.0)
        return force * rate * np.maximum(np.cos(link_angle + beta - gamma), 0.0)

    bush = integrand(-c["R23"], c["phi2"], False)
    pin = integrand(c["R23"], np.zeros_like(c["phi"]), True)
    piston = np.where(c["R34"] > 0, np.abs(c["R34"] * c["V_qB"]), 0.0)
    return [{"phi": float(np.degrees(c["phi"][i])), "psi2_printed": TABLE_4_4["psi2"][i],
             "bush_printed": float(TABLE_4_4["bush"][i]), "bush": float(bush[i]),
             "psi3_printed": TABLE_4_4["psi3"][i], "pin_printed": float(TABLE_4_4["pin"][i]), "pin": float(pin[i]),
             "piston_printed": float(TABLE_4_4["piston"][i]), "piston": float(piston[i])}
            for i in range(c["phi"].size)]


def book_coefficients(k: dict, cycles: float, parts: dict) -> list[dict]:
    """N_c and the coefficients in front of the integrals, printed (§4.3) beside the answer's: a = 2·10⁶ k N_c/(π l_z)
    of the bush and pin (4.13), a = 10⁶ (4/π) k N_c/(l_p d_p) of the piston and cylinder (4.17), (4.18)."""
    revolute = 2e6 * cycles / (np.pi * parts["pin_length"])
    slider = 1e6 * (4 / np.pi) * cycles / (parts["piston_length"] * parts["piston_diameter"])
    ours = {"N_c": cycles, "a_2": revolute * k["bush"], "a_3": revolute * k["pin"],
            "a_{3p}": slider * k["piston"], "a_4": slider * k["cylinder"]}
    elements = {"N_c": None, "a_2": "bush_23", "a_3": "pin_23", "a_{3p}": "piston", "a_4": "cylinder"}
    equations = {"N_c": "60·n·t", "a_2": "(4.13)", "a_3": "(4.13)", "a_{3p}": "(4.17)", "a_4": "(4.18)"}
    return [{"quantity": key, **({"element": elements[key]} if elements[key] else {}), "equation": equations[key],
             "printed": PRINTED_COEFFICIENTS[key], "value": float(ours[key])} for key in PRINTED_COEFFICIENTS]


def figure_maxima(result: dict) -> list[dict]:
    """Fig. 4.7's maxima (the text's 36, 68, 59 µm) beside the largest wear of the answer's own distributions
    (its parts and hours) and beside the book's data summed the same way with its printed coefficients k
    (PRINTED_K) over half its cycles, N_c/2 = 0.72·10⁸: 38.9, 69.0 and 58.8 µm, within 8 % of the figure.  The
    figure's curves are half of what the book's text and formulas give for N_c = 1.44·10⁸ (500 h at 2400 rpm,
    or one cycle per two revolutions as in a four-stroke engine); the book says neither.  Wear in µm."""
    c = table_columns(TABLE_4_3)
    p23, p34, _ = _coefficients(c, BOOK_PARTS)
    printed = {**BOOK_PARTS, "I_pin": PRINTED_K["pin"] * p23, "I_bush": PRINTED_K["bush"] * p23,
               "I_cylinder": PRINTED_K["cylinder"] * p34}
    half = tabulated_wear(TABLE_4_3, printed, BOOK_CYCLES / 2)
    ours = {"pin_23": result["pin"], "bush_23": result["bush"], "cylinder": result["cylinder"]}
    theirs = {"pin_23": half["pin"], "bush_23": half["bush"], "cylinder": half["cylinder"]}
    return [{"element": "cylinder_max" if key == "cylinder" else key, "figure": figure, "table": float(np.max(ours[key])),
             "book_half": float(np.max(theirs[key]))} for key, figure in FIGURE_4_7.items()]


def constant_load_rows(mean_r23: float, parts: dict, k: dict, cycles: float, stroke: float) -> list[dict]:
    """The constant-load models of Chaika–Vasylenko §4.1 at the cycle's mean loads, beside the cycle's sums:
    the pin's cosine pressure (4.4) and the load it carries back (4.3); the piston under its mean pressure over
    n_c strokes there and back (4.14); the cylinder's middle stretch, S = 2l_p per cycle (4.15).  Wear in µm."""
    from .wear import guide_path, guide_wear, peak_pressure, pressure_resultant, slider_wear
    radius = parts["pin_diameter"] / 2
    peak = float(peak_pressure(mean_r23, parts["pin_length"], radius))
    # the mean pressure of (4.23) back from k = I_s/p_m; a k that underflows to 0 (I_s near the smallest float)
    # leaves p_m unknown, and the wear k·p_m·S·n = I_s·S·n is 0 to the float's precision whatever p_m is
    p34 = parts["I_piston"] / k["piston"] if k["piston"] > 0 else 0.0
    plateau = float(guide_path(stroke / 2 + parts["piston_length"] / 2, parts["piston_length"], stroke))
    return [
        {"quantity": "peak_pressure", "equation": "(4.4)", "value": peak, "unit": "Pa"},
        {"quantity": "carried_load", "equation": "(4.3)",
         "value": float(pressure_resultant(peak, parts["pin_length"], radius)), "unit": "N"},
        {"quantity": "piston_constant", "equation": "(4.14)",
         "value": 1e6 * float(slider_wear(k["piston"], p34, stroke, cycles)), "unit": "um"},
        {"quantity": "cylinder_constant", "equation": "(4.15)",
         "value": 1e6 * float(guide_wear(k["cylinder"], p34, plateau, cycles)), "unit": "um"},
    ]
