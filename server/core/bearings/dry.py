"""Sizing and checks of a plain radial bearing by Chaika–Vasylenko §2.2 (dry friction; semi-fluid and the first
stage of fluid bearings are computed the same way with the allowables of Table 2.2, §2.3–2.4).  SI inside:
N, m, Pa, m/s, W, J/(kg·K), W/(m²·K), s; temperatures in °C.
"""
from __future__ import annotations

import math

import numpy as np

# The book's heat units (2.11)–(2.13): k' in kcal/(m²·h·°C), c' in kcal/(kg·°C); 1 kcal = 4186.8 J.
KCAL = 4186.8
KCAL_PER_HOUR = KCAL / 3600.0                  # W
BOOK_FACTOR = 8.43                             # (2.12): 1 kgf·m/s = 9.80665 W = 8.432 kcal/h
STEEL_DENSITY = 7850.0                         # kg/m³, the shaft of (2.13)
STEEL_HEAT = 0.12 * KCAL                       # c' = 0.12 kcal/(kg·°C), (2.13)


def size(load: float, pressure: float, length_ratio: float) -> dict:
    """Chaika–Vasylenko (2.4), (2.5) from (2.3) with l_z = l̄_z·d: l_z = √(F_e·l̄_z/[p_m]), d = √(F_e/([p_m]·l̄_z)).

    (2.4) is printed with l_z itself under the root, l_z = √(F_e·l_z/[p_m]); read so, its only solution is
    l_z = F_e/[p_m], an area (m²), not a length: the relative length l̄_z belongs there."""
    d = math.sqrt(load / (pressure * length_ratio))
    return {"diameter": d, "length": length_ratio * d}


def mean_pressure(load, length: float, diameter: float):
    """Chaika–Vasylenko (2.1)–(2.3): p_m = F_e/(l_z·d), the load over the projected area A = l_z·d (2.2)."""
    return load / (length * diameter)


def sliding_speed(omega, diameter: float):
    """V_s = ω·d/2, the book's π·d·n/60 of (2.6) with n in rev/min (ω = πn/30)."""
    return omega * diameter / 2


def friction_power(friction: float, load, speed):
    """Chaika–Vasylenko (2.7): P_f = ω₁T₁ = l_z·d·f·p_m·V_s = f·F_e·V_s."""
    return friction * load * speed


def bushing_temperature(power: float, ambient: float, transfer: float, area: float) -> float:
    """Chaika–Vasylenko (2.12), heat removed through the bushing (Q₁ = Q₂, (2.8) and (2.10)):
    T_n = T_B + P_f/(k'·A_k) in SI, which is the book's T_B + 8.43·l_z·d·f·p_m·V_s/(k'·A_k) with p_m in kgf/m²,
    V_s in m/s, k' in kcal/(m²·h·°C): 8.43 turns kgf·m/s into kcal/h.  (The print has "Γ" for f.)"""
    return ambient + power / (transfer * area)


def shaft(diameter: float, length_factor: float) -> dict:
    """The shaft of (2.13): a steel journal of diameter d over (3…4)·d on each side of the bearing, its mass G
    and surface A_k."""
    length = 2 * length_factor * diameter
    return {"mass": STEEL_DENSITY * math.pi * diameter**2 / 4 * length, "area": math.pi * diameter * length}


def shaft_temperature(power: float, ambient: float, transfer: float, mass: float, area: float,
                      hours: float, heat: float = STEEL_HEAT) -> float:
    """Chaika–Vasylenko (2.13), heat removed through the shaft over a working time t_z:
    T_n = T_B + P_f·t_z/(G·c' + 0.5·A_k·k'·t_z) in SI (reconstructed: the print's numerator,
    8.43·l_z·d·f·t_z, lacks p_m·V_s and is not a heat at all)."""
    seconds = hours * 3600.0
    return ambient + power * seconds / (mass * heat + 0.5 * area * transfer * seconds)


def shaft_temperature_as_printed(length: float, diameter: float, friction: float, ambient: float,
                                 transfer: float, mass: float, area: float, hours: float) -> float:
    """The printed (2.13) in the book's units, T_B + 8.43·l_z·d·f·t_z/(G·c' + 0.5·A_k·k'·t_z) (k' in
    kcal/(m²·h·°C), c' in kcal/(kg·°C), t_z in h): without p_m·V_s it barely rises above T_B."""
    k_book = transfer / KCAL_PER_HOUR
    return ambient + BOOK_FACTOR * length * diameter * friction * hours / (
        mass * STEEL_HEAT / KCAL + 0.5 * area * k_book * hours)


def check(value: float | None, allowable: float | None) -> str:
    """'pass' if value ≤ allowable, 'fail' if not, 'unknown' where the table gives no allowable."""
    if allowable is None or value is None:
        return "unknown"
    return "pass" if value <= allowable else "fail"


def feasible_diameters(peak_load: float, heat_load: float, peak_omega: float, allowable: dict,
                       length_ratio: float) -> dict:
    """Step 6 of the procedure: the diameters at l_z = l̄_z·d that satisfy (2.3), (2.6) and (2.9) together.

    (2.3) p_m = F/(l̄_z·d²) ≤ [p_m] gives d ≥ √(F_peak/([p_m]·l̄_z)), (2.5);
    (2.9) the mean of p·V = mean(F·ω_rel)/(2·l̄_z·d) ≤ [pV] gives d ≥ mean(F·ω_rel)/(2·l̄_z·[pV]) (heat_load is
    that mean of F·ω_rel, N/s);
    (2.6) V = ω_rel,max·d/2 ≤ [V] gives d ≤ 2·[V]/ω_rel,max.  None where the table gives no allowable."""
    strength = math.sqrt(peak_load / (allowable["pressure"] * length_ratio)) if allowable["pressure"] > 0 else math.inf
    heat = heat_load / (2 * length_ratio * allowable["pv"]) if allowable["pv"] else None
    speed = 2 * allowable["speed"] / peak_omega if peak_omega > 0 else math.inf
    smallest = max(strength, heat or 0.0)
    return {"strength": strength, "heat": heat, "speed": None if math.isinf(speed) else speed,
            "smallest": None if math.isinf(smallest) else smallest, "feasible": bool(smallest <= speed)}


def cycle_pv(load: np.ndarray, omega: np.ndarray, length: float, diameter: float) -> np.ndarray:
    """p(φ)·V(φ) over the cycle, Pa·m/s: (2.3) times (2.6) at each angle."""
    return mean_pressure(load, length, diameter) * sliding_speed(omega, diameter)
