"""Sine (Scotch-yoke) mechanism, Eremyants §2.2, Fig. 2.1.

Crank 1 (length l₁) turns about O; block 2 on the crank pin A slides in the slot of
yoke 3, which translates along x.  φ = 0 with the crank pointing to −x (yoke at its
left extreme), φ grows clockwise in the drawing (A = (−l₁cos φ, l₁sin φ)).

    x = l₁(1 − cos φ)       (2.1)     y = l₁ sin φ      (2.2)
    u₃₁ = l₁ sin φ          (2.3)     u′₃₁ = l₁ cos φ   (2.4)
    u₂₁ = l₁ cos φ          (2.5)     u′₂₁ = −l₁ sin φ  (2.6)

x is the yoke travel from φ = 0; y is the block's travel in the slot, so u₂₁ is the
sliding-velocity analog V₂₃/ω₁ that reduces slot friction to the crank.
"""
from __future__ import annotations

import numpy as np

from ..dynamics.resisting_forces import sine_moment
from .base import DIVERGED, Evaluation, ParamSpec, SpecialPosition, point
from .mechanism import Mechanism


class Sine(Mechanism):
    name = "sine"
    title = "Sine (Scotch-yoke) mechanism"
    conventions = ("Crank pivot O at the origin, x to the right, y up. φ = 0: crank along −x, yoke at its "
                   "left extreme; φ grows clockwise. s = x = l₁(1 − cos φ) is the yoke travel (m); "
                   "s2 = y = l₁ sin φ is the block's travel along the slot (m).")
    sliding_pairs = ("u21", "u31")
    link2_rotation = None                   # the block translates with the crank pin
    link3_translates = True

    def textbook_inertia(self, p, constant, inertias, phi):
        """Eremyants (3.18), exact: J = J₁ + m₂l₁² + m₃l₁² sin²φ."""
        l1 = p["l1"]
        return constant + inertias.m2 * l1**2 + inertias.m3 * l1**2 * np.sin(phi) ** 2

    def friction_steps(self, p, phi, force, f, tolerance, max_steps):
        """Yoke 3 (Eremyants Fig. 3.1): (R₂₃)₀ = P_c; F_T2 = f R₂₃, R₀₃ = F_T2, F_T3 = f R₀₃, R₂₃ = P_c + F_T3;
        the ratio f², the limit P_c/(1 − f²)."""
        ratio = f**2
        r23 = force
        steps = [{"n": 0, "R23": r23, "F_T2": 0.0, "F_T3": 0.0, "R03": 0.0, "change": None}]
        for n in range(1, max_steps + 1):
            f_t2 = f * r23
            r03 = f_t2
            f_t3 = f * r03
            new = force + f_t3
            change = abs(new - r23) / abs(new) if new else 0.0
            r23 = new
            steps.append({"n": n, "R23": r23, "F_T2": f_t2, "F_T3": f_t3, "R03": r03, "change": change})
            if change < tolerance or r23 > DIVERGED * force:
                break
        return ratio, steps, ({"R23": force / (1 - ratio)} if ratio < 1 else {})
    params = (ParamSpec("l1", "m", "crank length OA", 0.1, 0.01, 1.0),)

    def check_geometry(self, p):
        """Any crank length in the offered range works: the yoke follows the pin everywhere."""

    def evaluate(self, p, phi, wanted):
        """x, y, u₃₁, u′₃₁, u₂₁, u′₂₁ at φ: Eremyants (2.1)–(2.6) (module docstring)."""
        l1 = p["l1"]
        c, s = np.cos(phi), np.sin(phi)
        ev = Evaluation(phi)
        ev.values = {
            "s": l1 * (1 - c), "u31": l1 * s, "du31": l1 * c,
            "s2": l1 * s, "u21": l1 * c, "du21": -l1 * s,
            # S2 (block) sits on the crank pin A = (−l₁cos φ, l₁sin φ)
            "chi21": l1 + 0 * phi,
            "v_s2": point(l1 * s, l1 * c), "a_s2": point(l1 * c, -l1 * s),
        }
        if "joints" in wanted:
            ev.joints = {"O": point(0 * phi, 0 * phi), "A": point(-l1 * c, l1 * s),
                         "yoke": point(-l1 * c, 0 * phi)}
        return ev

    def resisting(self, p, load, phi, values, k):
        return sine_moment(p, load, phi, values, k)

    def special_positions(self, p):
        """Dead centres at φ = 0 and π, where u₃₁ = l₁ sin φ = 0 (Eremyants (2.3)); the stroke is 2l₁."""
        l1 = p["l1"]
        return [SpecialPosition("dead_centre", 0.0, "yoke at its left extreme, u₃₁ = 0", 0.0),
                SpecialPosition("dead_centre", np.pi, "yoke at its right extreme, u₃₁ = 0", 2 * l1)]
