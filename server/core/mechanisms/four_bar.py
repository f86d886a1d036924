"""Hinged four-bar: crank 1, coupler 2, rocker 3, frame 0; Eremyants §2.5, Drakunov–Tuleshova (3)–(10).

A at the origin, D at (l₀, 0); φ from AD, counter-clockwise, B = l₁(cos φ, sin φ).
The diagonal (Zinoviev) method of Eremyants gives the rocker angle ψ = φ₃ from +x at D:

    d² = l₀² + l₁² − 2l₀l₁cos φ,   γ = atan2(−l₁sin φ, l₀ − l₁cos φ)         (2.38), (2.39)
    φ₃ = π + γ − σψ₁,  cos ψ₁ = (l₃² + d² − l₂²)/(2l₃d)                     (2.40), (2.41)

σ = +1 is the textbook's assembly (Drakunov–Tuleshova's "+" sign in (4)); σ = −1 the other one.
The radicand of sin ψ₁ factorises exactly as 4l₃²d² − (l₃² + d² − l₂²)² = P·Q with

    P = (l₂ + l₃)² − (l₀ + l₁)² + 4l₀l₁cos²(φ/2),   Q = (l₀ − l₁)² − (l₂ − l₃)² + 4l₀l₁sin²(φ/2),

so the crank turns fully iff P₀ = P(π) ≥ 0 and Q₀ = Q(0) ≥ 0.  P₀ = 0 or Q₀ = 0 is a
change-point ("special") four-bar, (2.45)–(2.47): sin φ/√(PQ) is then 0/0 at the
change point and is evaluated in the half-angle form of (2.52), (2.53), e.g.
sin φ/√Q = cos(φ/2)/√(l₀l₁) for Q₀ = 0.  Without a stroke limiter the rocker keeps its
direction through the change point and the cycle is 4π; with the limiter it rebounds,
the cycle is 2π and u₃₁ jumps there.

    u₃₁ = γ′ + σ·K·sin φ/√(PQ),  γ′ = l₁(l₁ − l₀cos φ)/d²,  K = l₀l₁(d² + l₂² − l₃²)/d²
                                                  (2.42*, the corrected form; (2.42) is misprinted)
    u₂₁ = Re[(l₃u₃₁e^{iφ₃} − l₁e^{iφ}) e^{−iφ₂}]/l₂          (loop closure (3) differentiated, = (7))
    u′₃₁ = γ″ + σ·d/dφ[K sin φ/√(PQ)]                        (analytic; the textbook gives none)
    u′₂₁ = Im[(l₁e^{iφ} + l₃(iu′₃₁ − u₃₁²)e^{iφ₃}) e^{−iφ₂}]/l₂

These agree with Drakunov–Tuleshova (7), (8) with the corrected sign u₃₁ = +l₁sin(φ₁−φ₂)/(l₃sin(φ₃−φ₂))
and stay finite at the change points, where (7), (8) are 0/0.
"""
from __future__ import annotations

import numpy as np

from ..dynamics.resisting_forces import four_bar_moment
from .base import Evaluation, GeometryError, Notice, OutputSpec, ParamSpec, SpecialPosition, point, wrap_angle
from .mechanism import Mechanism

CHANGE_POINT_TOL = 1e-9


def grashof_class(l0: float, l1: float, l2: float, l3: float) -> str:
    """Grashof class of the linkage with frame l₀ and input crank l₁."""
    lengths = sorted([l0, l1, l2, l3])
    s_plus_l, p_plus_q = lengths[0] + lengths[3], lengths[1] + lengths[2]
    if abs(s_plus_l - p_plus_q) <= CHANGE_POINT_TOL * p_plus_q:
        return "change_point"
    if s_plus_l > p_plus_q:
        return "non_grashof"
    shortest = min(l0, l1, l2, l3)
    if shortest == l1:
        return "crank_rocker"
    if shortest == l0:
        return "double_crank"
    return "double_rocker"


def grashof_row(l0: float, l1: float, l2: float, l3: float) -> dict:
    """The Grashof inequality of the linkage with its numbers (Drakunov–Tuleshova's four-bar: the crank turns
    fully when s + l ≤ p + q and the crank l₁ is the shortest): s + l, p + q, the relation between them, the
    shortest link's name and the class (grashof_class; a change point as "change_point_linkage")."""
    lengths = {"l0": l0, "l1": l1, "l2": l2, "l3": l3}
    ordered = sorted(lengths.values())
    s_plus_l, p_plus_q = ordered[0] + ordered[3], ordered[1] + ordered[2]
    cls = grashof_class(l0, l1, l2, l3)
    relation = "=" if cls == "change_point" else ("<" if s_plus_l < p_plus_q else ">")
    shortest = min(lengths, key=lengths.get)
    return {"class": "change_point_linkage" if cls == "change_point" else cls, "s_plus_l": s_plus_l,
            "relation": relation, "p_plus_q": p_plus_q, "shortest": f"{shortest[0]}_{shortest[1]}"}


class FourBar(Mechanism):
    def elastic_angles(self, values):
        """θ₁₂ = φ − θ₂, θ₂₃ = θ₂ − θ₃."""
        return (values["phi"] - values["s2"], 1.0 - values["u21"], values["s2"] - values["s"],
                values["u21"] - values["u31"])

    def proximity_warnings(self, p):
        mu = self.describe(p)["min_transmission_angle"]
        if self.change_point(p) is not None or mu >= np.radians(10):
            return []
        return [Notice("four_bar_small_mu", f"The smallest transmission angle is {np.degrees(mu):.2f}°: the linkage "
                       "is close to a change point, and the transfer functions are large there.",
                       {"mu": float(np.degrees(mu))})]

    name = "four_bar"
    title = "Hinged four-bar"
    conventions = ("Crank pivot A at the origin, rocker pivot D at (l₀, 0). φ from AD, counter-clockwise. "
                   "s = rocker angle φ₃ from +x at D (rad); s2 = coupler angle φ₂ from +x (rad). "
                   "λ₀ = l₀/l₁, λ₂ = l₂/l₁, λ₃ = l₃/l₁. assembly = +1 is the textbook's branch (2.41), −1 the "
                   "other. For change-point linkages limiter = 1 puts a stroke limiter at the change point "
                   "(cycle 2π), limiter = 0 lets the rocker pass through (cycle 4π).")
    params = (
        ParamSpec("l0", "m", "frame AD", 0.4, 0.001, 10.0),
        ParamSpec("l1", "m", "crank AB", 0.1, 0.001, 10.0),
        ParamSpec("l2", "m", "coupler BC", 0.35, 0.001, 10.0),
        ParamSpec("l3", "m", "rocker DC", 0.3, 0.001, 10.0),
        ParamSpec("assembly", "1", "assembly mode: +1 textbook branch (2.41), −1 the mirror branch", 1, -1, 1, True),
        ParamSpec("limiter", "1", "1: stroke limiter at the change point (special four-bars only)", 0, 0, 1, True),
        ParamSpec("a2", "1", "centre of mass S2 as a fraction of BC from B", 0.5, 0.0, 1.0),
    )
    extra_outputs = (OutputSpec("mu", "rad", "transmission angle μ between coupler and rocker, 0…π"),)

    # --- validity -----------------------------------------------------------------
    @staticmethod
    def _p0_q0(p):
        """P₀ = P(π), Q₀ = Q(0), each set to exactly 0 within CHANGE_POINT_TOL of the scale (a change point);
        elementwise for lengths given as arrays (several linkages at once, ``evaluate``)."""
        l0, l1, l2, l3 = p["l0"], p["l1"], p["l2"], p["l3"]
        scale = (l0 + l1 + l2 + l3) ** 2
        p0 = (l2 + l3) ** 2 - (l0 + l1) ** 2
        q0 = (l0 - l1) ** 2 - (l2 - l3) ** 2
        if np.ndim(scale):
            return (np.where(np.abs(p0) <= CHANGE_POINT_TOL * scale, 0.0, p0),
                    np.where(np.abs(q0) <= CHANGE_POINT_TOL * scale, 0.0, q0))
        p0 = 0.0 if abs(p0) <= CHANGE_POINT_TOL * scale else p0
        q0 = 0.0 if abs(q0) <= CHANGE_POINT_TOL * scale else q0
        return p0, q0

    def branch(self, p) -> tuple:
        """What selects the formulas of ``evaluate``: (Q₀ = 0, P₀ = 0, stroke limiter). Linkages evaluated at
        once (parameters as arrays of shape (M, 1)) must share it."""
        p0, q0 = self._p0_q0(p)
        return tuple(bool(np.all(flag)) if np.all(flag) == np.any(flag) else None
                     for flag in (q0 == 0.0, p0 == 0.0, np.asarray(p["limiter"]) != 0))

    def check_geometry(self, p):
        """Refuse a crank that cannot turn fully: P₀ = (l₂ + l₃)² − (l₀ + l₁)² < 0 (no φ = 180°),
        Q₀ = (l₀ − l₁)² − (l₂ − l₃)² < 0 (no φ = 0), or l₀ = l₁ (the pin through the pivot D); Eremyants §2.5."""
        if p["assembly"] == 0:
            raise GeometryError("assembly", "must be +1 or −1", "assembly_sign")
        p0, q0 = self._p0_q0(p)
        if p0 < 0:
            raise GeometryError("l2", "the crank cannot turn fully: l₀ + l₁ > l₂ + l₃, the linkage cannot "
                                      "reach φ = 180° (crank pointing away from D)",
                                "four_bar_no_full_turn_pi")
        if q0 < 0:
            raise GeometryError("l2", "the crank cannot turn fully: |l₀ − l₁| < |l₂ − l₃|, the linkage cannot "
                                      "reach φ = 0° (crank pointing towards D)",
                                "four_bar_no_full_turn_0")
        if abs(p["l0"] - p["l1"]) <= CHANGE_POINT_TOL * p["l0"]:
            raise GeometryError("l0", "l₀ = l₁: the crank pin would pass through the rocker pivot D",
                                "four_bar_through_pivot")

    def change_point(self, p) -> float | None:
        """Crank angle of the change point: 0 when Q₀ = 0 (schemes 1, 2), π when P₀ = 0 (scheme 3)."""
        p0, q0 = self._p0_q0(p)
        if q0 == 0.0:
            return 0.0
        if p0 == 0.0:
            return np.pi
        return None

    def change_points(self, p) -> list[float]:
        """Every change point of the turn: both 0 and π when P₀ = Q₀ = 0 (a parallelogram, l₀ = l₂ and l₁ = l₃, or
        a kite, l₀ = l₃ and l₁ = l₂: all four joints line up at both), else the one of ``change_point``."""
        p0, q0 = self._p0_q0(p)
        if p0 == 0.0 and q0 == 0.0:
            return [0.0, np.pi]
        cp = self.change_point(p)
        return [] if cp is None else [cp]

    def cycle(self, p):
        """4π when the rocker passes one change point a turn (it comes back after two); 2π with the limiter, and
        when it passes two (a parallelogram or kite: its half-angle branch is periodic over one turn)."""
        return 4 * np.pi if len(self.change_points(p)) == 1 and not p["limiter"] else 2 * np.pi

    def jumps(self, p):
        """With a stroke limiter the rocker rebounds at the change point: u₃₁ jumps there (Eremyants Fig. 2.9b)."""
        cp = self.change_point(p)
        return [cp] if cp is not None and p["limiter"] else []

    # --- kinematics ---------------------------------------------------------------
    def evaluate(self, p, phi_in, wanted):
        """At crank angles phi_in (N,); the parameters may be arrays of shape (M, 1), M linkages of one
        ``branch`` at once, each output then of shape (M, N) (points (M, N, 2))."""
        l0, l1, l2, l3, sigma, a2 = (p[k] for k in ("l0", "l1", "l2", "l3", "assembly", "a2"))
        p0, q0 = self._p0_q0(p)
        q_zero, p_zero, limiter = self.branch(p)
        if None in (q_zero, p_zero, limiter):
            raise ValueError("linkages evaluated at once must share their branch (FourBar.branch)")
        cp = 0.0 if q_zero else np.pi if p_zero else None
        phi = phi_in
        if cp is not None and limiter:
            phi = cp + np.mod(phi_in - cp, 2 * np.pi)   # restart the branch after each impact
        half_s, half_c = np.sin(phi / 2), np.cos(phi / 2)
        sin, cos = np.sin(phi), np.cos(phi)
        k = 2 * np.sqrt(l0 * l1)
        d2 = l0**2 + l1**2 - 2 * l0 * l1 * cos
        big_p = p0 + 4 * l0 * l1 * half_c**2
        big_q = q0 + 4 * l0 * l1 * half_s**2
        with np.errstate(divide="ignore", invalid="ignore"):
            # signed square roots: in half-angle form at a change point (branch continues through it)
            root_q = k * half_s if q_zero else np.sqrt(big_q)
            root_p = -k * half_c if p_zero else np.sqrt(big_p)
            q = 1 / k + 0 * phi if q_zero else half_s / np.sqrt(big_q)
            pp = -1 / k + 0 * phi if p_zero else half_c / np.sqrt(big_p)
            dq = 0 * phi if q_zero else half_c / (2 * np.sqrt(big_q)) - half_s * l0 * l1 * sin / big_q**1.5
            dpp = 0 * phi if p_zero else -half_s / (2 * np.sqrt(big_p)) + half_c * l0 * l1 * sin / big_p**1.5

            gamma = np.arctan2(-l1 * sin, l0 - l1 * cos)
            big_n = l3**2 + d2 - l2**2
            psi1 = np.arctan2(sigma * root_q * root_p, big_n)
            phi3 = np.pi + gamma - psi1
            bx, by = l1 * cos, l1 * sin
            cx, cy = l0 + l3 * np.cos(phi3), l3 * np.sin(phi3)
            phi2 = np.arctan2(cy - by, cx - bx)

            dgamma = l1 * (l1 - l0 * cos) / d2
            ddgamma = l0 * l1 * sin * (d2 - 2 * l1 * (l1 - l0 * cos)) / d2**2
            kk = l0 * l1 * (d2 + l2**2 - l3**2) / d2
            dkk = -2 * (l0 * l1) ** 2 * (l2**2 - l3**2) * sin / d2**2
            ratio = 2 * q * pp                       # = sin φ /√(PQ), signed along the branch
            dratio = 2 * (dq * pp + q * dpp)
            u31 = dgamma + sigma * kk * ratio
            du31 = ddgamma + sigma * (dkk * ratio + kk * dratio)

        e1, e2, e3 = np.exp(1j * phi), np.exp(1j * phi2), np.exp(1j * phi3)
        u21 = ((l3 * u31 * e3 - l1 * e1) / e2).real / l2
        du21 = ((l1 * e1 + l3 * (1j * du31 - u31**2) * e3) / e2).imag / l2
        v_s2 = 1j * l1 * e1 + 1j * a2 * l2 * u21 * e2
        a_s2 = -l1 * e1 + a2 * l2 * (1j * du21 - u21**2) * e2
        ordered = np.all(np.diff(phi_in) > 0) if phi_in.size > 1 else False
        ev = Evaluation(phi_in)
        ev.values = {
            "s": np.unwrap(phi3) if ordered and not limiter else phi3,
            "u31": u31, "du31": du31,
            "s2": np.unwrap(phi2) if ordered and not limiter else phi2,
            "u21": u21, "du21": du21,
            "chi21": np.abs(v_s2), "v_s2": point(v_s2.real, v_s2.imag), "a_s2": point(a_s2.real, a_s2.imag),
            "mu": np.arccos(np.clip(np.cos(phi3 - phi2), -1.0, 1.0)),
        }
        if "joints" in wanted:
            ev.joints = {"A": point(0 * phi, 0 * phi), "B": point(bx, by), "C": point(cx, cy),
                         "D": point(l0 + 0 * phi, 0 * phi),
                         "S2": point(bx + a2 * (cx - bx), by + a2 * (cy - by))}
        return ev

    # --- special positions --------------------------------------------------------
    def transmission_extremes(self, p):
        """cos μ = (l₂² + l₃² − d²)/(2l₂l₃) is extreme where d is: φ = 0 (d = |l₀ − l₁|) and φ = π."""
        l0, l1, l2, l3 = p["l0"], p["l1"], p["l2"], p["l3"]
        out = []
        for phi, d in ((0.0, abs(l0 - l1)), (np.pi, l0 + l1)):
            mu = np.arccos(np.clip((l2**2 + l3**2 - d**2) / (2 * l2 * l3), -1, 1))
            out.append((phi, float(min(mu, np.pi - mu))))
        return out

    def rocker_extremes(self, p) -> list[tuple[float, float]]:
        """Crank angles where u₃₁ = 0: A, B, C in line, AC = l₂ + l₁ (extended) or l₂ − l₁ (folded).

        In triangle ACD the angle at A is α = arccos((l₀² + AC² − l₃²)/(2l₀AC)); B lies on AC
        (φ = ±α) or on its extension beyond A (φ = π ± α).  Of these candidates the ones on the
        chosen branch are those where the computed C is at distance AC from A; a change point,
        where all four joints line up, is no extreme (u₃₁ ≠ 0 there) and drops out.
        """
        candidates, reach = self._extreme_candidates(p)
        if not candidates:
            return []
        ev = self.evaluate(p, np.array(candidates), {"joints"})
        return self._extremes(p, candidates, reach, np.hypot(*ev.joints["C"].T), ev.values["s"], ev.values["u31"])

    def _extreme_candidates(self, p) -> tuple[list[float], list[float]]:
        """The crank angles where A, B, C may line up (rocker_extremes), and AC at each."""
        l0, l1, l2, l3 = p["l0"], p["l1"], p["l2"], p["l3"]
        cycle = self.cycle(p)
        candidates, reach = [], []
        for ac, turn in ((l2 + l1, 0.0), (abs(l2 - l1), 0.0 if l2 < l1 else np.pi)):
            if ac == 0:
                continue   # l₁ = l₂ folded: C would sit on A, the triangle ACD has no angle at A
            cos_a = (l0**2 + ac**2 - l3**2) / (2 * l0 * ac)
            if abs(cos_a) > 1:
                continue   # that line-up cannot be assembled: the output rotates fully
            alpha = np.arccos(cos_a)
            for phi in (turn + alpha, turn - alpha):
                for lap in np.arange(0.0, cycle - 1e-9, 2 * np.pi):
                    candidates.append(wrap_angle(phi + lap, cycle))
                    reach.append(ac)
        return candidates, reach

    @staticmethod
    def _extremes(p, candidates, reach, ac_found, s, u31) -> list[tuple[float, float]]:
        """The candidates on the chosen branch (C at distance AC from A) where u₃₁ vanishes."""
        scale = p["l0"] + p["l1"] + p["l2"] + p["l3"]
        rows = zip(candidates, reach, ac_found, s, u31)
        return sorted((phi, float(s)) for phi, ac, found, s, u31 in rows
                      if abs(found - ac) <= 1e-9 * scale and abs(u31) < 1e-6)

    def resisting(self, p, load, phi, values, k):
        return four_bar_moment(p, load, phi, values, k)

    def special_positions(self, p, extremes: list[tuple[float, float]] | None = None):
        """``extremes``: rocker_extremes(p) if found already (special_positions_many)."""
        cycle = self.cycle(p)
        positions = []
        for cp in self.change_points(p):
            note = ("stroke limiter: the rocker hits it and rebounds, u₃₁ jumps" if p["limiter"]
                    else "the rocker passes through on the other branch")
            for phi in np.arange(cp, cp + cycle - 1e-9, 2 * np.pi):
                positions.append(SpecialPosition("change_point", wrap_angle(phi, cycle),
                                                 f"all four joints in line (change point); {note}"))
        for phi, s in self.rocker_extremes(p) if extremes is None else extremes:
            positions.append(SpecialPosition("rocker_extreme", phi,
                                             "rocker at an extreme position: crank and coupler in line, u₃₁ = 0", s))
        phi_mu, mu = min(self.transmission_extremes(p), key=lambda t: t[1])
        positions.append(SpecialPosition("min_transmission_angle", phi_mu,
                                         f"smallest transmission angle μ = {np.degrees(mu):.2f}°", mu))
        return sorted(positions, key=lambda sp: sp.phi)

    def special_positions_many(self, linkages: list[dict]) -> list[list[SpecialPosition]]:
        """special_positions of linkages of one ``branch``, their candidate extremes evaluated in one call: each
        candidate a row of its own (parameters and angles of shape (K, 1)), so that the rocker angle comes raw
        and is unwrapped per linkage as rocker_extremes' evaluation does (over its candidates when they ascend)."""
        found = [self._extreme_candidates(p) for p in linkages]
        owner = [m for m, (candidates, _) in enumerate(found) for _ in candidates]
        if not owner:
            return [self.special_positions(p, []) for p in linkages]
        stacked = {name: np.array([linkages[m][name] for m in owner], float)[:, None] for name in linkages[0]}
        phi = np.array([phi for candidates, _ in found for phi in candidates])[:, None]
        ev = self.evaluate(stacked, phi, {"joints"})
        reached, raw, u31 = np.hypot(*ev.joints["C"][:, 0, :].T), ev.values["s"][:, 0], ev.values["u31"][:, 0]
        positions, start = [], 0
        for p, (candidates, reach) in zip(linkages, found):
            rows = slice(start, start + len(candidates))
            start += len(candidates)
            ordered = len(candidates) > 1 and bool(np.all(np.diff(candidates) > 0))
            s = np.unwrap(raw[rows]) if ordered and not p["limiter"] else raw[rows]
            extremes = self._extremes(p, candidates, reach, reached[rows], s, u31[rows]) if candidates else []
            positions.append(self.special_positions(p, extremes))
        return positions

    def describe(self, p):
        l0, l1, l2, l3 = p["l0"], p["l1"], p["l2"], p["l3"]
        cls = grashof_class(l0, l1, l2, l3)
        info = {"grashof_class": cls, "lambda0": l0 / l1, "lambda2": l2 / l1, "lambda3": l3 / l1,
                "min_transmission_angle": min(m for _, m in self.transmission_extremes(p))}
        cp = self.change_point(p)
        if cp is not None:
            info["change_point"] = cp
            info["scheme"] = self.scheme(p)
        return info

    def scheme(self, p) -> int:
        """Textbook scheme of a change-point four-bar: 1 coupler longest, 2 rocker longest, 3 frame longest."""
        p0, q0 = self._p0_q0(p)
        if p0 == 0.0:
            return 3
        return 1 if p["l2"] > p["l3"] else 2
