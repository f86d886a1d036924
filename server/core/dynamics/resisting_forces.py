"""Reduced moment of the resisting forces M_c(φ, ω): useful load, dry and viscous friction.

Eremyants, chapter 3.  M_c is positive when it resists the crank.  k(φ) = 1 on the
working stroke (u₃₁ > 0: slider or lever moving forward) and k_p (k_M) on the return.

Sine mechanism (§3.1): the successive approximations converge to R₂₃ = P_c/(1 − f²), so
    M_c = k P_c (|u₃₁| + f|u₂₁|)/(1 − f²)                  exact limit (self-locking for f ≥ 1)
    M_c = k P_c l₁ (1 + f²)(|sin φ| + f|cos φ|)             textbook (3.6)–(3.9), series cut at f²
Crank-slider (§3.2): (F_T)_k = P_c Σ (f tan ψ)^i → P_c f tan ψ/(1 − f tan ψ), so
    M_c = k P_c |u₃₁|/(1 − f|tan ψ|)                       exact limit (self-locking for f|tan ψ| ≥ 1)
    M_c = P_c l₁[sin φ + f/(2λ) − f cos 2φ/(2λ) − sin 2φ/(2λ)],  0 < φ < π          (3.29)
    M_c = −k_p P_c l₁[same bracket],  π < φ < 2π   (3.30) as printed: friction helps on the return;
    consistent physics: −k_p P_c l₁[sin φ − f/(2λ) + f cos 2φ/(2λ) − sin 2φ/(2λ)]
Slotted link (§3.3): R₁₂ᵗ = M₃/l_BC, F_T = f R₁₂ᵗ, so
    M_c = k M₃ (|u₃₁| + f|u₂₁|/l_BC)                       (3.42)–(3.43), friction always resisting
    textbook (3.44)–(3.49): k M₃ [1 + λ(cos φ ± f sin φ)]/(1 + λ² + 2λ cos φ), negative on the idle stroke
Four-bar: the rocker load M₃ reduced by u₃₁ (Drakunov–Tuleshova (1)), no friction model in the sources.
Viscous friction (3.15)–(3.17), (3.33), (3.50*): M_T = β ω Σ u², u the sliding-velocity analogs.

M_c is smooth in φ except where the argument of a |·| or of a stroke condition changes sign: the output's
reversal u₃₁ = 0 (k switches, |u₃₁| has a corner) and the friction terms' own arguments. Each builder names
those arguments (``ResistingMoment.switches``); the integrator puts their zeros on its nodes (machine.py).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..mechanisms.base import Notice
from ..mechanisms.base import angle_ranges, ranges_text

CONVENTIONS = ("consistent", "textbook")


@dataclass(frozen=True)
class Load:
    """Useful load and friction.

    force: P_c in N on the slider/yoke (sine, crank-slider) or M₃ in N·m on the lever/rocker;
    return_factor: k_p (k_M), load on the return stroke relative to the working one;
    f: dry sliding-friction coefficient in the prismatic pairs; beta: viscous coefficient β
    in N·s/m; convention: 'consistent' physics or the formulas 'textbook' prints;
    crank_moment: a constant resisting moment on the crank shaft, N·m (the driven machine
    of a piston engine, Lecture 10 §10.5: M_c = A_д/Φ).
    """

    force: float = 0.0
    return_factor: float = 1.0
    f: float = 0.0
    beta: float = 0.0
    convention: str = "consistent"
    crank_moment: float = 0.0


@dataclass
class ResistingMoment:
    """M_c split into useful load, dry friction and viscous friction (N·m), plus notices."""

    useful: np.ndarray
    dry: np.ndarray
    viscous: np.ndarray
    notices: list[Notice] = field(default_factory=list)
    self_locking: np.ndarray | None = None
    switches: list[np.ndarray] = field(default_factory=list)   # M_c has a corner or a jump where one changes sign

    @property
    def total(self) -> np.ndarray:
        """M_c = useful + dry + viscous: M_p (3.5), the dry friction (3.1)–(3.4), (3.24)–(3.30), (3.42)–(3.49)
        and the viscous (3.15)–(3.17), (3.33), (3.50*) of Eremyants, chapter 3."""
        return self.useful + self.dry + self.viscous


def stroke_factor(u31: np.ndarray, k: float) -> np.ndarray:
    """1 on the working stroke (u₃₁ ≥ 0), k on the return stroke (k_p of Eremyants (3.30), k_M of §3.3)."""
    return np.where(u31 >= 0, 1.0, k)


def sine_moment(p, load, phi, values, k):
    f, P = load.f, load.force
    if load.convention == "textbook":
        useful = k * P * np.abs(values["u31"])
        total = k * P * p["l1"] * (1 + f**2) * (np.abs(np.sin(phi)) + f * np.abs(np.cos(phi)))
        return ResistingMoment(useful, total - useful, 0 * phi, switches=[np.sin(phi), np.cos(phi)])
    if f >= 1:
        return _locked(phi, np.ones_like(phi, bool), Notice(
            "sine_self_locking", f"Self-locking: f = {f:g} ≥ 1, the successive approximations "
            "R₂₃ = P_c(1 + f² + f⁴ + …) diverge at every angle.", {"f": f}))
    useful = k * P * np.abs(values["u31"])
    total = k * P * (np.abs(values["u31"]) + f * np.abs(values["u21"])) / (1 - f**2)
    return ResistingMoment(useful, total - useful, 0 * phi, switches=[values["u21"]])


def slider_crank_moment(p, load, phi, values, k):
    f, P, l1 = load.f, load.force, p["l1"]
    lam = p["l2"] / l1
    u31 = values["u31"]
    useful = k * P * np.abs(u31)
    if load.convention == "textbook":
        s, c2, s2 = np.sin(phi), np.cos(2 * phi), np.sin(2 * phi)
        bracket = s + f / (2 * lam) - f * c2 / (2 * lam) - s2 / (2 * lam)
        total = np.where(np.mod(phi, 2 * np.pi) <= np.pi, P * l1 * bracket, -load.return_factor * P * l1 * bracket)
        notices = [Notice("textbook_series", "Textbook formulas (3.29), (3.30): series for λ² ≫ 1; on the return "
                          "stroke (3.30) as printed lets friction help the crank (the consistent sign is shown in the "
                          "other mode).")]
        if p["e"] != 0:
            notices.append(Notice("approx_offset", "The approximations are derived for the central crank-slider "
                                  "(e = 0); with an offset they ignore e."))
        return ResistingMoment(useful, total - useful, 0 * phi, notices, switches=[np.sin(phi)])
    tan_psi = np.abs(np.tan(values["s2"]))
    locked = f * tan_psi >= 1
    if locked.any():
        ranges = angle_ranges(phi, locked)
        total = np.where(locked, np.nan, useful / np.where(locked, 1.0, 1 - f * tan_psi))
        return ResistingMoment(np.where(locked, np.nan, useful), total - useful, 0 * phi, [Notice(
            "slider_crank_self_locking",
            f"Self-locking: f·tan ψ ≥ 1 for φ in {ranges_text(ranges)}: the rod presses the slider into its guide "
            f"harder than the rod can push it along (f = {f:g}, largest tan ψ = {tan_psi.max():.3g}).",
            {"f": f, "ranges": ranges})],
            locked)
    total = useful / (1 - f * tan_psi)
    return ResistingMoment(useful, total - useful, 0 * phi, switches=[np.tan(values["s2"])])


def slotted_link_moment(p, load, phi, values, k):
    f, M3 = load.f, load.force
    lam = p["l0"] / p["l1"]
    d2 = (1 - lam) ** 2 + 4 * lam * np.cos(phi / 2) ** 2
    u31 = values["u31"]
    useful = k * M3 * np.abs(u31)
    if load.convention == "textbook":
        sign = np.where(np.mod(phi, 2 * np.pi) <= np.pi, 1.0, -1.0)
        total = k * M3 * (1 + lam * (np.cos(phi) + sign * f * np.sin(phi))) / d2
        return ResistingMoment(useful, total - useful, 0 * phi, [Notice(
            "textbook_idle_stroke", "Textbook formulas (3.44)–(3.49): on the idle stroke of the oscillating lever "
            "the printed moment is negative, i.e. the idle load would drive the crank.")], switches=[np.sin(phi)])
    on_pivot = d2 < 1e-24                      # λ = 1, φ = π: the block on the lever pivot
    with np.errstate(divide="ignore", invalid="ignore"):
        dry = np.where(on_pivot, np.nan, k * M3 * f * lam * np.abs(np.sin(phi)) / d2)
    result = ResistingMoment(useful, dry, 0 * phi, switches=[np.sin(phi)])
    if f > 0 and on_pivot.any():
        result.notices.append(Notice("slotted_jamming_friction", "λ = 1: at φ = 180° the dry-friction moment "
                                     "M_T = ±0.5 M₃ f tan(φ/2) is unbounded, the mechanism jams for any load "
                                     "(Eremyants (3.52)); in a real machine clearances prevent it."))
    return result


def four_bar_moment(p, load, phi, values, k):
    useful = k * load.force * np.abs(values["u31"])
    return ResistingMoment(useful, 0 * phi, 0 * phi)


def _locked(phi, mask, notice):
    """A self-locked mechanism: the crank cannot drive it where ``mask`` holds; no finite moment there."""
    undefined = np.where(mask, np.nan, 0.0)
    return ResistingMoment(undefined, undefined, 0 * phi, [notice], mask)


def mean_over_cycle(values: np.ndarray) -> float:
    """Mean of a periodic function sampled on a closed uniform grid (trapezoid rule): M_c0, Eremyants (3.11), (3.31)."""
    return float(np.mean(values[:-1]))


def kink_bound(values: np.ndarray) -> float:
    """A bound on the error of ``mean_over_cycle`` from the corners and jumps of a periodic function sampled
    on a closed uniform grid of N intervals, wherever they fall among the nodes.

    By the Euler–Maclaurin formula with periodic Bernoulli functions, a corner with slope jump Δ at the fraction
    θ of a step h adds h²Δ(θ² − θ + 1/6)/2 to the trapezoid rule's integral, at most h²|Δ|/12, and a jump J adds
    hJ(θ − 1/2), at most h|J|/2; halving the grid moves θ, so the difference of two grids can be far smaller than
    either error. The samples show each: their second differences d₂ carry hΔ (or ±J) in the one or two steps
    across it, beside the smooth h²f″; the excess |d₂ᵢ − (d₂ᵢ₋₂ + d₂ᵢ₊₂)/2| sums to twice the carried amounts
    (each is also seen, halved, by the cells two steps away) and to O(h³) elsewhere. (h/8)·Σ excess then bounds
    both kinds of error (h²|Δ|/4 ≥ h²|Δ|/12, h|J|/2 for a jump), and divided by the cycle h·N the mean's."""
    samples = values[:-1]
    wrapped = np.concatenate([samples[-3:], samples, samples[:3]])         # periodic: three samples each side
    second = wrapped[2:] - 2 * wrapped[1:-1] + wrapped[:-2]                # d₂ at the samples and two beyond
    excess = np.abs(second[2:-2] - 0.5 * (second[:-4] + second[4:]))
    return float(excess.sum()) / (8 * samples.size)

