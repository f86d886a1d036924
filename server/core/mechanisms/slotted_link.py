"""Slotted-link (кулисный) mechanism: crank 1, block 2, slotted lever 3; Eremyants §2.4.

Crank pivot A at the origin, lever pivot C at (0, −l₀) directly below it.  φ = 0 with
crank and lever vertical and B above A (l_BC = l₀ + l₁); φ and the lever angle ψ grow
clockwise from the vertical, B = (l₁sin φ, l₁cos φ).  λ = l₀/l₁ (pivot distance/crank):
λ < 1 rotating lever, λ > 1 oscillating (quick-return) lever, λ = 1 special.

    ψ = arctan(sin φ/(λ + cos φ))                                     (2.33)
    y = l₁(1 + λ − √(1 + λ² + 2λ cos φ))  (block travel along the lever)  (2.34)
    u₃₁ = (1 + λ cos φ)/(1 + λ² + 2λ cos φ)                              (2.27)
    u′₃₁ = λ(1 − λ²) sin φ/(1 + λ² + 2λ cos φ)²                          (2.28)
    u₂₁ = l₁λ sin φ/√(1 + λ² + 2λ cos φ)                                 (2.31)
    u′₂₁ = l₁λ/√D · (cos φ + λ sin²φ/D),  D = 1 + λ² + 2λ cos φ           (2.32)

At λ = 1 and φ = π the block sits on the lever pivot (D = 0): u₂₁, u′₂₁ and ψ are
undefined there (the textbook's jamming position, §3.3); u₂₁ jumps from +l₁ to −l₁, but
u₂₁² = l₁² sin²(φ/2) → l₁² is continuous, so the viscous moment keeps its limit (sliding_squares).
"""
from __future__ import annotations

import numpy as np

from ..dynamics.resisting_forces import slotted_link_moment
from ..errata import slotted_viscous
from .base import Evaluation, Notice, ParamSpec, SpecialPosition, point
from .mechanism import Mechanism


class SlottedLink(Mechanism):
    name = "slotted_link"
    title = "Slotted-link (кулисный) mechanism"
    conventions = ("Crank pivot A at the origin, lever pivot C at (0, −l₀). φ = 0: crank and lever vertical, "
                   "block B above A; φ and ψ grow clockwise. s = lever angle ψ (rad); s2 = block travel y along "
                   "the lever from φ = 0 (m). λ = l₀/l₁: λ < 1 rotating lever, λ > 1 oscillating "
                   "(quick-return) lever.")
    sliding_pairs = ("u21",)
    link2_rotation = "u31"                  # the block turns with the lever (ω₂ = ω₃)

    def reduction_errata(self, p, m3, omega):
        """Eremyants (3.50)/(3.53), λ = l₀/l₁."""
        return slotted_viscous(omega, p["l1"], p["l0"] / p["l1"])

    def proximity_warnings(self, p):
        lam = p["l0"] / p["l1"]
        if lam == 1 or abs(lam - 1) >= 0.1:
            return []
        return [Notice("slotted_near_one", f"λ = {lam:.3g} is close to 1: near φ = 180° the block passes close to the "
                       f"lever pivot, u₃₁ reaches {1 / abs(1 - lam):.3g} and u′₃₁ is very large.",
                       {"lam": lam, "peak": 1 / abs(1 - lam)})]
    params = (
        ParamSpec("l0", "m", "distance AC between the crank and lever pivots", 0.05, 0.001, 10.0),
        ParamSpec("l1", "m", "crank length AB", 0.1, 0.01, 1.0),
    )

    def check_geometry(self, p):
        """Every λ = l₀/l₁ > 0 assembles; λ = 1 has one undefined position, reported when evaluated."""

    def branch(self, p):
        """Oscillating lever (λ > 1) or rotating (λ ≤ 1): the formula of ψ."""
        lam = p["l0"] / p["l1"]
        return (bool(np.all(lam > 1)) if np.all(lam > 1) == np.any(lam > 1) else None,)

    def evaluate(self, p, phi, wanted):
        """ψ, y, u₃₁, u′₃₁, u₂₁, u′₂₁ at φ: Eremyants (2.27)–(2.34) (module docstring)."""
        l0, l1 = p["l0"], p["l1"]
        lam = l0 / l1
        oscillating, = self.branch(p)
        if oscillating is None:
            raise ValueError("linkages evaluated at once must share their branch (SlottedLink.branch)")
        c, s = np.cos(phi), np.sin(phi)
        # D = l_BC²/l₁², written as (1 − λ)² + 4λcos²(φ/2) so that it is exact near λ = 1, φ = π
        d2 = (1 - lam) ** 2 + 4 * lam * np.cos(phi / 2) ** 2
        with np.errstate(divide="ignore", invalid="ignore"):
            root = np.sqrt(d2)
            if oscillating:
                psi = np.arctan2(s, lam + c)
            else:  # rotating lever: ψ = φ − arg(1 + λe^{−iφ}) stays continuous
                psi = phi - np.arctan2(lam * s, 1 + lam * c)
            values = {
                "s": psi,
                "u31": (1 + lam * c) / d2,
                "du31": lam * (1 - lam**2) * s / d2**2,
                "s2": l1 * (1 + lam - root),
                "u21": l1 * lam * s / root,
                "du21": l1 * lam / root * (c + lam * s**2 / d2),
            }
        values["chi21"] = l1 + 0 * phi               # S2 = block on the crank pin B
        values["v_s2"] = point(l1 * c, -l1 * s)
        values["a_s2"] = point(-l1 * s, -l1 * c)
        ev = Evaluation(phi, values)
        singular = d2 < 1e-24
        if singular.any():
            for key in ("s", "u31", "du31", "u21", "du21"):
                values[key] = np.where(singular, np.nan, values[key])
            ev.warnings.append(Notice("slotted_jamming", "λ = 1 and φ = 180°: the block is on the lever pivot C, the "
                                      "lever's position and the block's sliding speed are undefined there "
                                      "(theoretical jamming, Eremyants §3.3)."))
        if "joints" in wanted:
            lever = l0 + l1  # drawn lever length: reaches B in every position
            ev.joints = {"A": point(0 * phi, 0 * phi), "B": point(l1 * s, l1 * c), "C": point(0 * phi, -l0 + 0 * phi),
                         "lever_end": point(lever * np.sin(psi), -l0 + lever * np.cos(psi))}
        return ev

    def sliding_squares(self, p, ev):
        """S(φ) = u₂₁² = l₁²λ² sin²φ/D (Eremyants (3.50*)), written with sin φ = 2 sin(φ/2) cos(φ/2) and
        D = (1 − λ)² + 4λ cos²(φ/2) so that the removable singularity at λ = 1, φ = π cancels: there u₂₁
        jumps from +l₁ to −l₁ (undefined) but u₂₁² = l₁² sin²(φ/2) → l₁², (3.53*), and the viscous moment
        β ω l₁² is finite."""
        lam, half = p["l0"] / p["l1"], ev.phi / 2
        d2 = (1 - lam) ** 2 + 4 * lam * np.cos(half) ** 2
        with np.errstate(divide="ignore", invalid="ignore"):
            ratio = np.where(d2 > 0, 4 * lam**2 * np.cos(half) ** 2 / d2, lam)   # d2 = 0 only at λ = 1
        return p["l1"] ** 2 * np.sin(half) ** 2 * ratio

    def resisting(self, p, load, phi, values, k):
        return slotted_link_moment(p, load, phi, values, k)

    def special_positions(self, p):
        """λ > 1: the lever's extremes ±ψ_max, ψ_max = arcsin(1/λ); λ < 1: u₃₁ from 1/(1 + λ) at φ = 0 to
        1/(1 − λ) at φ = π; λ = 1: jamming at φ = π (Eremyants §2.4, §3.3)."""
        lam = p["l0"] / p["l1"]
        if lam > 1:
            psi_max = np.arcsin(1 / lam)
            return [
                SpecialPosition("rocker_extreme", np.pi / 2 + psi_max,
                                "lever at its extreme +ψ_max: u₃₁ = 0, end of the working stroke", psi_max),
                SpecialPosition("rocker_extreme", 1.5 * np.pi - psi_max,
                                "lever at its extreme −ψ_max: u₃₁ = 0, end of the return stroke", -psi_max),
            ]
        if lam == 1:
            return [SpecialPosition("jamming", np.pi, "block on the lever pivot: u₂₁ undefined, jamming with dry friction")]
        return [SpecialPosition("fastest_lever", np.pi, "lever fastest: u₃₁ = 1/(1 − λ)", 1 / (1 - lam)),
                SpecialPosition("slowest_lever", 0.0, "lever slowest: u₃₁ = 1/(1 + λ)", 1 / (1 + lam))]

    def describe(self, p):
        lam = p["l0"] / p["l1"]
        info = {"lambda": lam}
        if lam > 1:
            psi_max = np.arcsin(1 / lam)
            info |= {"motion": "oscillating lever (quick return)", "swing": 2 * psi_max,
                     "time_ratio": (np.pi + 2 * psi_max) / (np.pi - 2 * psi_max)}
        else:
            info |= {"motion": "rotating lever" if lam < 1 else "lever turns at half the crank speed"}
        return info
