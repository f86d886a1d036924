"""Flywheel for a given coefficient of speed fluctuation δ: Lecture 10 §10.3–§10.8.

The moments depend on φ alone and balance over the cycle (A_Σ(Φ) = 0).  Links split into
group I (constant reduced inertia I_I: crank, rotor, flywheel) and group II (I_II(φ)).
With the total work A(φ) = ∫(M_д − M_c)dφ and δ = (ω_max − ω_min)/ω_m, ω_m = (ω_max + ω_min)/2:

  Merzalov (L9)–(L10), (L6):  ΔT_I = A − I_II ω_m²/2 (+const),  I_I = [max ΔT_I − min ΔT_I]/(δ ω_m²)
  Gutyar (L27):               the same with I_II ω_max²/2 near the top and I_II ω_min²/2 near the bottom,
                              ω_max,min = (1 ± δ/2) ω_m  (the lecture prints the squares without ², an OCR slip)
  Wittenbauer (L28)–(L29):    tangents of slopes ω_max²/2, ω_min²/2 to the curve (I_II, A):
                              I_I = (b_up − b_low)/(δ ω_m²), b_up = max(A − I_II ω_max²/2), b_low = min(A − I_II ω_min²/2)
  exact:                      ω(φ)² = 2(T₀ + A)/(I_I + I_II) with T₀ chosen so that (ω_max + ω_min)/2 = ω_m,
                              and I_I found by root finding so that this periodic solution has the target δ.
Sizing (step 6): solid disk I = mD²/8, m = ρπψ_b D³/4 ⇒ D = (32I/(ρπψ_b))^{1/5}
(0.366·I^{1/5}, m = 1230·D³ for ψ_b = 0.2, ρ = 7800 kg/m³); thin rim of mean diameter D: m = 4I/D².
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from ..numerics import parabola_extremum, parabola_vertex
from .compiled import mean_of_extremes, periodic_level, speed_extremes

GUTYAR_WINDOW = np.pi / 4      # half-width of the curve pieces Gutyar draws around the extremes, rad
BRENT_ITERATIONS = 100         # scipy's brentq default, and its refusals by compiled.periodic_level's status
BRENT_FAILURES = {1: "Failed to converge after 100 iterations, value is {}",
                  2: "The function value at x={} is NaN; solver cannot continue.",
                  3: "f(a) and f(b) must have different signs"}


@dataclass(frozen=True)
class Cycle:
    """Tabulated cycle: φ on a closed uniform grid, A(φ) = ∫(M_д − M_c)dφ (J), I_II(φ) (kg·m²)."""

    phi: np.ndarray
    work: np.ndarray
    inertia_ii: np.ndarray


@dataclass
class Method:
    name: str
    inertia: float              # I_I, kg·m²
    energy_swing: float         # ΔT used, J


def merzalov(cycle: Cycle, omega_mean: float, delta: float) -> Method:
    """Merzalov, Lecture 10 §10.4, (L9)–(L10), (L6): ΔT_I = A − I_II ω_m²/2 (group II at the mean speed),
    I_I = (max ΔT_I − min ΔT_I)/(δ ω_m²)."""
    group_one = cycle.work - 0.5 * cycle.inertia_ii * omega_mean**2
    swing = parabola_extremum(group_one, +1) - parabola_extremum(group_one, -1)
    return Method("merzalov", swing / (delta * omega_mean**2), swing)


def tangent_intercepts(cycle: Cycle, omega_mean: float, delta: float, window: float | None = None):
    """b_up = max(A − I_II ω_max²/2), b_low = min(A − I_II ω_min²/2), optionally within ±window of the
    extremes of Merzalov's ΔT_I; returns the intercepts and the angles where the tangents touch, each at the
    vertex of the parabola that refines its intercept (numerics.parabola_vertex: it moves smoothly with the
    machine's parameters, where the best node alone would move in steps of the grid)."""
    w_max, w_min = (1 + delta / 2) * omega_mean, (1 - delta / 2) * omega_mean
    upper = cycle.work - 0.5 * cycle.inertia_ii * w_max**2
    lower = cycle.work - 0.5 * cycle.inertia_ii * w_min**2
    near_top = near_bottom = np.ones_like(cycle.phi, bool)
    if window is not None:
        group_one = cycle.work - 0.5 * cycle.inertia_ii * omega_mean**2
        def near(k):
            return np.abs(np.angle(np.exp(1j * (cycle.phi - cycle.phi[k])))) <= window
        near_top, near_bottom = near(int(np.argmax(group_one))), near(int(np.argmin(group_one)))
    b_up, at_up = parabola_vertex(upper, +1, allowed=near_top)
    b_low, at_low = parabola_vertex(lower, -1, allowed=near_bottom)
    step, start = cycle.phi[1] - cycle.phi[0], cycle.phi[0]
    angle = lambda at: float(start + (at * step) % (cycle.phi[-1] - start))     # the closed grid's period
    return b_up, b_low, angle(at_up), angle(at_low)


def gutyar(cycle: Cycle, omega_mean: float, delta: float) -> Method:
    """Gutyar, Lecture 10 §10.7 (L27): I_I = (b_up − b_low)/(δ ω_m²), the intercepts of A − I_II ω_max²/2 near
    the top and A − I_II ω_min²/2 near the bottom (within GUTYAR_WINDOW), ω_max,min = (1 ± δ/2) ω_m."""
    b_up, b_low, _, _ = tangent_intercepts(cycle, omega_mean, delta, GUTYAR_WINDOW)
    return Method("gutyar", (b_up - b_low) / (delta * omega_mean**2), b_up - b_low)


def wittenbauer(cycle: Cycle, omega_mean: float, delta: float) -> tuple[Method, dict]:
    """Wittenbauer, Lecture 10 §10.8 (L28)–(L29): I_I = (b_up − b_low)/(δ ω_m²) from the tangents of slopes
    ω_max²/2, ω_min²/2 to the curve (I_II, A); the diagram: intercepts, touching angles, the tangents' intersection."""
    b_up, b_low, phi_up, phi_low = tangent_intercepts(cycle, omega_mean, delta)
    inertia = (b_up - b_low) / (delta * omega_mean**2)
    w_max = (1 + delta / 2) * omega_mean
    diagram = {"b_up": b_up, "b_low": b_low, "phi_up": phi_up, "phi_low": phi_low,
               "slope_up": 0.5 * w_max**2, "slope_low": 0.5 * ((1 - delta / 2) * omega_mean) ** 2,
               "origin_inertia": -inertia, "origin_energy": b_up - inertia * 0.5 * w_max**2}
    return Method("wittenbauer", inertia, b_up - b_low), diagram


def periodic_speed(cycle: Cycle, inertia_i: float, omega_mean: float) -> np.ndarray:
    """ω(φ) of the exact periodic solution with group-I inertia I_I and mean (ω_max + ω_min)/2 = ω_m;
    NaN everywhere when there is none (too little inertia for that mean speed: the speed would reach zero).
    T₀ by Brent's method compiled (compiled.periodic_level: scipy's brentq line for line, the same root)."""
    total = np.ascontiguousarray(inertia_i + cycle.inertia_ii, dtype=np.float64)
    work = np.ascontiguousarray(cycle.work, dtype=np.float64)
    lowest = float(np.max(-cycle.work))
    high = lowest + 0.5 * float(total.max()) * (2 * omega_mean) ** 2 + 1.0
    if mean_of_extremes(work, total, lowest + 1e-12 * high) - omega_mean > 0:   # even as ω_min → 0 the mean
        return np.full_like(cycle.work, np.nan)     # exceeds ω_m: the machine would stall within the cycle
    T0, status = periodic_level(work, total, float(omega_mean), lowest + 1e-12 * high, high, 1e-15 * high, 1e-15,
                                BRENT_ITERATIONS)
    if status:
        raise (RuntimeError if status == 1 else ValueError)(BRENT_FAILURES[status].format(T0))
    return np.sqrt(2 * (T0 + cycle.work) / total)


def achieved_delta(cycle: Cycle, inertia_i: float, omega_mean: float) -> float:
    """δ = (ω_max − ω_min)/ω_m, ω_m = (ω_max + ω_min)/2 (Lecture 10 (L3)), of the exact periodic solution
    ω(φ)² = 2(T₀ + A)/(I_I + I_II) with group-I inertia I_I."""
    w_max, w_min = speed_extremes(periodic_speed(cycle, inertia_i, omega_mean))   # parabola_extremum, compiled
    return (w_max - w_min) / (0.5 * (w_max + w_min))


def exact(cycle: Cycle, omega_mean: float, delta: float, guess: float) -> Method:
    """I_I of the periodic solution with exactly the target δ (δ falls monotonically as I_I grows)."""
    def error(log_inertia):
        return np.log(achieved_delta(cycle, float(np.exp(log_inertia)), omega_mean) / delta)
    # Group II alone may keep δ: then no group-I inertia is needed (and the bracket below would widen for
    # ever). Where J_II is zero somewhere, group II alone cannot carry the machine through the cycle.
    if cycle.inertia_ii.min() > 0 and achieved_delta(cycle, 0.0, omega_mean) <= delta:
        return Method("exact", 0.0, 0.0)
    low, high = np.log(guess) - 1.0, np.log(guess) + 1.0
    for _ in range(200):                                   # a bracket in e^±400, never an endless loop
        if not error(low) < 0:
            break
        low -= 2.0
    for _ in range(200):
        if not error(high) > 0:
            break
        high += 2.0
    inertia = float(np.exp(brentq(error, low, high, xtol=1e-14, rtol=1e-14)))
    return Method("exact", inertia, delta * inertia * omega_mean**2)


@dataclass(frozen=True)
class Disk:
    """Solid steel disk for inertia I: diameter D, width b = ψ_b D, mass m."""

    diameter: float
    width: float
    mass: float


def disk(inertia: float, width_ratio: float = 0.2, density: float = 7800.0) -> Disk:
    """Solid disk of inertia I, Lecture 10 §10.6 (L25) with its constants kept: I = mD²/8, m = ρπψ_b D³/4,
    so D = (32I/(ρπψ_b))^{1/5}, b = ψ_b D."""
    diameter = (32 * inertia / (density * np.pi * width_ratio)) ** 0.2
    return Disk(diameter, width_ratio * diameter, density * np.pi * width_ratio * diameter**3 / 4)


def disk_as_printed(inertia: float) -> Disk:
    """Lecture 10 (L25), its rounded constants for ψ_b = 0.2, ρ = 7800 kg/m³: D = 0.366·I^{1/5}, m = 1230·D³."""
    diameter = 0.366 * inertia**0.2
    return Disk(diameter, 0.2 * diameter, 1230 * diameter**3)


def rim(inertia: float, diameter: float, density: float = 7800.0) -> dict:
    """Thin rim of mean diameter D: m = 4I/D², square cross-section of area m/(ρπD)."""
    mass = 4 * inertia / diameter**2
    area = mass / (density * np.pi * diameter)
    return {"diameter": diameter, "mass": mass, "section_side": float(np.sqrt(area))}
