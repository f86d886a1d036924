"""Crank-slider mechanism, central and with offset e: Eremyants §2.3, Chaika–Vasylenko §3.1.

Crank 1 (l₁) turns about O, connecting rod 2 (l₂) joins the crank pin A to the slider
B, which runs along the line y = e.  Textbook convention (Eremyants Fig. 2.2):
φ = 0 with the crank along −x (slider near its left, inner dead centre), φ grows
clockwise, A = (−l₁cos φ, l₁sin φ); the rod angle ψ is counted the same way,
sin ψ = (l₁sin φ − e)/l₂.  λ = l₂/l₁ (rod/crank); the English r/l = 1/λ.

    x_B = −l₁cos φ + l₂cos ψ,  s = x_B − x_B,min                         (2.7)–(2.11)
    u₂₁ = dψ/dφ = l₁cos φ /(l₂cos ψ)                                      (2.14), (3.7)
    u′₂₁ = (−l₁sin φ + l₂u₂₁² sin ψ)/(l₂cos ψ)                            (2.15), derived for e ≠ 0
    u₃₁ = l₁sin φ − l₂u₂₁ sin ψ                                          (2.12), V_qB of Chaika–Vasylenko
    u′₃₁ = l₁cos φ − l₂(u′₂₁ sin ψ + u₂₁² cos ψ)                          (2.13)

With e = 0 these reduce to (2.11)–(2.15).  Textbook approximations for λ > 3:
    u₃₁ ≈ l₁(sin φ − sin 2φ/(2λ)),  u₂₁ ≈ cos φ/λ                         (2.16)
    u′₃₁ ≈ l₁(cos φ − cos 2φ/λ − 1/(8λ³) + cos 4φ/(8λ³)),  u′₂₁ ≈ (1−λ²)sin φ/λ³   (2.17*)
The textbook prints −cos 4φ/(8λ³) and (λ²−1)/λ³ in (2.17); both signs are wrong
(checked against finite differences), the corrected (2.17*) is computed here.
"""
from __future__ import annotations

from functools import lru_cache

import numpy as np

from ..dynamics.resisting_forces import slider_crank_moment
from ..errata import variable_inertia
from .base import DIVERGED, Evaluation, GeometryError, Notice, OutputSpec, ParamSpec, SpecialPosition, point, wrap_angle
from .mechanism import Mechanism

APPROXIMATIONS = ("u31_approx", "du31_approx", "u21_approx", "du21_approx")


class SliderCrank(Mechanism):
    name = "slider_crank"
    title = "Crank-slider mechanism"
    conventions = ("Crank pivot O at the origin, slider guide along y = e. φ = 0: crank along −x; φ grows "
                   "clockwise (Eremyants Fig. 2.2). s = slider travel from the inner dead centre (m); "
                   "s2 = rod angle ψ, clockwise, sin ψ = (l₁ sin φ − e)/l₂ (rad). λ = l₂/l₁ (textbook), "
                   "r/l = l₁/l₂ = 1/λ (English texts).")
    sliding_pairs = ("u31",)
    link3_translates = True
    piston = True

    def textbook_inertia(self, p, constant, inertias, phi):
        """Eremyants (3.36), λ² ≫ 1, the rod's mass neglected: J ≈ J₁ + m₃l₁² sin²φ (1 − cos φ/λ)²."""
        l1 = p["l1"]
        lam = p["l2"] / l1
        return constant + inertias.m3 * l1**2 * np.sin(phi) ** 2 * (1 - np.cos(phi) / lam) ** 2

    def friction_steps(self, p, phi, force, f, tolerance, max_steps):
        """Group 2–3 (Eremyants Fig. 3.3): (R₀₃)₀ = P_c tan ψ; F_T = f R₀₃, R₀₃ = (P_c + F_T) tan ψ (3.24);
        the ratio f|tan ψ|, the limit P_c f tan ψ/(1 − f tan ψ)."""
        values = self.evaluate(p, np.array([phi]), set()).values
        tan_psi = abs(float(np.tan(values["s2"][0])))
        ratio = f * tan_psi
        f_t, r03 = 0.0, force * tan_psi
        steps = [{"n": 0, "F_T": 0.0, "R03": r03, "R12": force * np.sqrt(1 + tan_psi**2), "change": None}]
        for n in range(1, max_steps + 1):
            new = f * r03
            change = abs(new - f_t) / abs(new) if new else 0.0
            f_t = new
            r03 = (force + f_t) * tan_psi
            steps.append({"n": n, "F_T": f_t, "R03": r03, "R12": (force + f_t) * np.sqrt(1 + tan_psi**2),
                          "change": change})
            if change < tolerance or f_t > DIVERGED * force:
                break
        return ratio, steps, ({"F_T": force * ratio / (1 - ratio)} if ratio < 1 else {})

    def elastic_angles(self, values):
        """The crank along (−cos φ, sin φ): angle π − φ; the rod's angle −ψ (ψ clockwise)."""
        phi = values["phi"]
        theta12 = np.pi - phi + values["s2"]
        return theta12, values["u21"] - 1.0, np.zeros_like(phi), np.zeros_like(phi)

    def reduction_errata(self, p, m3, omega):
        """Eremyants (3.38)/(3.39), λ = l₂/l₁."""
        return variable_inertia(m3, p["l1"], p["l2"] / p["l1"])

    def proximity_warnings(self, p):
        margin = p["l2"] - p["l1"] - abs(p["e"])
        if margin >= 0.1 * p["l1"]:
            return []
        angle = np.degrees(np.arcsin((p["l1"] + abs(p["e"])) / p["l2"]))
        return [Notice("slider_crank_near_limit",
                       f"Near the assembly limit: l₂ − l₁ − |e| = {margin:.3g} m. The rod swings up to "
                       f"{angle:.1f}°, u₂₁ and u′₃₁ grow large where the rod is nearly perpendicular to "
                       "the guide.", {"margin": margin, "angle": angle})]

    def piston_travel(self, p, phi, ev=None):
        """x/H: the piston's travel from top dead centre over its stroke H (the indicator diagram's abscissa)."""
        values = (ev or self.evaluate(p, phi, set())).values
        stroke = piston_stroke(p["l1"], p["l2"], p["e"])
        return np.clip((stroke - values["s"]) / stroke, 0.0, 1.0)

    def harmonic_claim(self, p, spectrum):
        """The book's claim is for the central crank-slider."""
        if p["e"] != 0:
            return None
        from ..harmonics import fourth_harmonic_claim
        return fourth_harmonic_claim(spectrum, p["l2"] / p["l1"])
    params = (
        ParamSpec("l1", "m", "crank length OA", 0.1, 0.01, 1.0),
        ParamSpec("l2", "m", "connecting-rod length AB", 0.3, 0.01, 10.0),
        ParamSpec("e", "m", "offset of the slider guide from the crank pivot (y = e)", 0.0, -1.0, 1.0),
        ParamSpec("a2", "1", "position of the rod's centre of mass S2 as a fraction of AB from A", 0.32, 0.0, 1.0),
    )
    extra_outputs = (
        OutputSpec("u31_approx", "m", "textbook approximation (2.16) of u₃₁ (central, λ > 3)"),
        OutputSpec("du31_approx", "m", "textbook approximation (2.17*) of u′₃₁, corrected"),
        OutputSpec("u21_approx", "1", "textbook approximation (2.16) of u₂₁"),
        OutputSpec("du21_approx", "1", "textbook approximation (2.17*) of u′₂₁, corrected"),
        OutputSpec("approx_error", "m or 1", "maximum absolute error of (2.16)/(2.17*) on the requested grid"),
    )

    def check_geometry(self, p):
        """A full turn needs l₂ > l₁ + |e| (λ > 1 + |e|/l₁)."""
        if p["l2"] <= p["l1"] + abs(p["e"]):
            raise GeometryError(
                "l2", f"the crank cannot turn fully: l₂ = {p['l2']:.4g} m must exceed l₁ + |e| = "
                      f"{p['l1'] + abs(p['e']):.4g} m (λ = l₂/l₁ > 1 + |e|/l₁)",
                "slider_crank_no_full_turn", l2=p["l2"], limit=p["l1"] + abs(p["e"]))

    def evaluate(self, p, phi, wanted):
        """x_B, ψ, u₂₁, u′₂₁, u₃₁, u′₃₁ at φ, offset e included: Eremyants (2.7)–(2.15) (module docstring)."""
        l1, l2, e, a2 = p["l1"], p["l2"], p["e"], p["a2"]
        c, s = np.cos(phi), np.sin(phi)
        sin_psi = (l1 * s - e) / l2
        cos_psi = np.sqrt((1 - sin_psi) * (1 + sin_psi))
        u21 = l1 * c / (l2 * cos_psi)
        du21 = (-l1 * s + l2 * u21**2 * sin_psi) / (l2 * cos_psi)
        x_b = -l1 * c + l2 * cos_psi
        ev = Evaluation(phi)
        ev.values = {
            "s": x_b - np.sqrt((l2 - l1) ** 2 - e**2),
            "u31": l1 * s - l2 * u21 * sin_psi,
            "du31": l1 * c - l2 * (du21 * sin_psi + u21**2 * cos_psi),
            "s2": np.arcsin(sin_psi), "u21": u21, "du21": du21,
        }
        # S2 = A + a₂(B − A); B − A = l₂(cos ψ, −sin ψ)
        vx = l1 * s - a2 * l2 * u21 * sin_psi
        vy = l1 * c - a2 * l2 * u21 * cos_psi
        ev.values["v_s2"] = point(vx, vy)
        ev.values["chi21"] = np.hypot(vx, vy)
        ev.values["a_s2"] = point(l1 * c - a2 * l2 * (du21 * sin_psi + u21**2 * cos_psi),
                                  -l1 * s - a2 * l2 * (du21 * cos_psi - u21**2 * sin_psi))
        if "joints" in wanted:
            ax, ay = -l1 * c, l1 * s
            ev.joints = {"O": point(0 * phi, 0 * phi), "A": point(ax, ay), "B": point(x_b, e + 0 * phi),
                         "S2": point(ax + a2 * (x_b - ax), ay + a2 * (e - ay))}
        if np.ndim(l1) == 0:
            self.per_linkage(p, ev, wanted)
        return ev

    def per_linkage(self, p, ev, wanted):
        """The textbook series when asked for (their largest errors are reductions over φ, and they warn)."""
        if wanted & set(APPROXIMATIONS + ("approx_error",)):
            self._approximations(p, ev.phi, ev)

    def _approximations(self, p, phi, ev):
        """Textbook series (2.16), (2.17*); defined for the central mechanism (e = 0)."""
        l1, lam = p["l1"], p["l2"] / p["l1"]
        approx = {
            "u31_approx": l1 * (np.sin(phi) - np.sin(2 * phi) / (2 * lam)),
            "u21_approx": np.cos(phi) / lam,
            "du31_approx": l1 * (np.cos(phi) - np.cos(2 * phi) / lam - 1 / (8 * lam**3)
                                 + np.cos(4 * phi) / (8 * lam**3)),
            "du21_approx": (1 - lam**2) * np.sin(phi) / lam**3,
        }
        ev.values |= approx
        ev.values["approx_error"] = {
            key.removesuffix("_approx"): float(np.max(np.abs(val - ev.values[key.removesuffix("_approx")])))
            if len(phi) else 0.0
            for key, val in approx.items()}
        if p["e"] != 0.0:
            ev.warnings.append(Notice("approx_offset", "The approximations (2.16), (2.17*) are derived for the "
                                      "central crank-slider (e = 0); with an offset they ignore e."))
        if lam <= 3:
            ev.warnings.append(Notice("approx_small_lambda", f"The approximations (2.16), (2.17*) assume λ > 3 "
                                      f"(λ² ≫ 1); here λ = {lam:.3g}.", {"lam": lam}))

    def resisting(self, p, load, phi, values, k):
        return slider_crank_moment(p, load, phi, values, k)

    def special_positions(self, p):
        """Dead centres, crank and rod in line (u₃₁ = 0): x_out = √((l₁ + l₂)² − e²), x_in = √((l₂ − l₁)² − e²),
        stroke x_out − x_in (2l₁ for e = 0, Eremyants §2.3); an offset makes the strokes' crank angles unequal."""
        l1, l2, e = p["l1"], p["l2"], p["e"]
        # Crank and rod in line: outer (A on OB) and inner (A opposite OB) dead centres.
        x_out, x_in = np.sqrt((l1 + l2) ** 2 - e**2), np.sqrt((l2 - l1) ** 2 - e**2)
        phi_out = np.arctan2(e / (l1 + l2), -x_out / (l1 + l2))
        phi_in = np.arctan2(-e / (l2 - l1), x_in / (l2 - l1))
        stroke = x_out - x_in
        positions = [
            SpecialPosition("dead_centre", wrap_angle(phi_in), "inner dead centre: crank and rod folded, u₃₁ = 0", 0.0),
            SpecialPosition("dead_centre", wrap_angle(phi_out), "outer dead centre: crank and rod in line, u₃₁ = 0", stroke),
        ]
        if e != 0.0:
            working = wrap_angle(phi_out - phi_in)
            positions.append(SpecialPosition(
                "stroke_ratio", wrap_angle(phi_in),
                f"offset crank-slider: the working stroke takes {np.degrees(working):.2f}° of crank rotation, "
                f"the return stroke {360 - np.degrees(working):.2f}°", working / (2 * np.pi - working)))
        return positions

    def describe(self, p):
        lam = p["l2"] / p["l1"]
        return {"lambda": lam, "r_over_l": 1 / lam,
                "max_rod_angle": float(np.arcsin((p["l1"] + abs(p["e"])) / p["l2"]))}


@lru_cache(maxsize=256)
def piston_stroke(l1: float, l2: float, e: float) -> float:
    """H: the piston's travel between the dead centres of the crank-slider (once per geometry)."""
    positions = SliderCrank().special_positions({"l1": l1, "l2": l2, "e": e})
    return next(sp.value for sp in positions if sp.kind == "dead_centre" and sp.value)
