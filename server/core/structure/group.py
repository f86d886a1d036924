"""What every class-II structural (Assur) group hands back, and the terms of its velocity and acceleration plans.

A group of two links and three lower pairs (Chaika–Vasylenko §3.1, Fig. 3.3; Artobolevsky's kinds: 1 RRR,
2 RRP, 3 RPR, 4 PRP, 5 RPP) is solved from its outer elements (joints and guides already placed) for its
inner joint or slide, on one assembly branch σ = ±1.  Its first and second analogs come from the loop closure
differentiated once and twice: two real linear equations for two unknowns each time (state.solve_pair), with
the same matrix as the position's Jacobian, whose determinant vanishes at the group's dead positions.

The plan terms are the textbook's vector equations (velocity plan: v_C = v_B + v_CB; acceleration plan:
a_C = a_B + a^n_CB + a^τ_CB; with a moving guide a_B3 = a_B2 + a^k_B3B2 + a^r_B3B2, a^k = 2ω × v_r),
written as analogs: a velocity term is V ω₁, an acceleration term A ω₁² + V ε₁.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from .state import Angle, Point


@dataclass(frozen=True)
class Slide:
    """A slider's displacement s along its guide (m) with s′, s″."""

    s: np.ndarray
    d1: np.ndarray
    d2: np.ndarray


@dataclass(frozen=True)
class Term:
    """One vector of a plan: its label (pb, bc, n_CB, τ_CB, k_B3B2 …), what it is, and its analogs:
    velocity = v ω₁; acceleration = a ω₁² + v ε₁ (v = 0 for the normal and Coriolis terms)."""

    name: str
    kind: str          # absolute, rotation, sliding, normal, tangential, coriolis, relative
    v: np.ndarray
    a: np.ndarray


Chain = tuple[str, list[Term]]               # (target point, the terms whose sum is its velocity/acceleration)


@dataclass(frozen=True)
class Plan:
    """A group's plan equations, and the plan targets that are no joint (B₃: the lever's point under B)."""

    velocity: list[Chain]
    acceleration: list[Chain]
    coincident: dict[str, Point] = field(default_factory=dict)


@dataclass
class GroupSolution:
    """A group's new joints, its links (origin point and angle), its slides, where it closes, and its plan
    (built only when asked: ``plan()``; the kinematics over the turn does not need it)."""

    kind: str
    joints: dict[str, Point]
    links: dict[int, tuple[Point, Angle]]
    slides: dict[str, Slide]
    closes: np.ndarray                        # the closure has a real solution at these φ
    determinant: np.ndarray                   # Jacobian determinant / its scale: 0 at a dead position
    plan: Callable[[], Plan]
    undetermined: np.ndarray | None = None    # angles where the closure leaves a link's angle free (RPR, B ≡ D)
    margins: dict | None = None               # {edge: (f, f′)}: gap to the edge of closure (change_points.py)


@dataclass(frozen=True)
class Singular:
    """How a group is solved near its change points (change_points.py): ``flip`` multiplies its σ (the
    assembly continued through each), ``near`` marks the neighbourhoods (the loop's radicand there is taken
    ≥ 0: the flattened loop, whatever the round-off), and ``fill`` gives the analogs there: a function of a
    pair (x′, x″) returning the limit of the continuing motion, or None for undefined (NaN)."""

    flip: np.ndarray | float = 1.0
    near: np.ndarray | None = None
    fill: Callable | None = None

    def radicand(self, value: np.ndarray) -> np.ndarray:
        return value if self.near is None else np.where(self.near, np.maximum(value, 0.0), value)

    def analogs(self, *pairs):
        """Each pair (x′, x″) of the group's analogs, the limit or NaN within the neighbourhoods."""
        if self.near is None or not np.any(self.near):
            return pairs
        if self.fill is not None:
            return tuple(self.fill(d1, d2) for d1, d2 in pairs)
        return tuple((np.where(self.near, np.nan, d1), np.where(self.near, np.nan, d2)) for d1, d2 in pairs)


REGULAR = Singular()


def carried(origin: Point, angle: Angle, z: np.ndarray) -> Point:
    """The point of a link that is at z now (z moves with the link): z′ = z′_O + iθ′(z − z_O),
    z″ = z″_O + (iθ″ − θ′²)(z − z_O)."""
    r = z - origin.z
    return Point(z, origin.d1 + 1j * angle.d1 * r, origin.d2 + (1j * angle.d2 - angle.d1**2) * r)


def absolute(label: str, p: Point) -> tuple[Term, Term]:
    """pb on the velocity plan and πb on the acceleration plan."""
    return Term("p" + label, "absolute", p.d1, np.zeros_like(p.d1)), Term("π" + label, "absolute", p.d1, p.d2)


def rotation(a: str, b: str, start: np.ndarray, end: np.ndarray, angle: Angle) -> tuple[Term, list[Term]]:
    """Relative motion of B about A on one link, r = z_B − z_A: v_BA = iθ′r ⊥ AB (vector ab);
    a^n_BA = −θ′²r along BA, a^τ_BA = iθ″r ⊥ AB (+ iθ′r ε₁)."""
    r = end - start
    zero = np.zeros_like(r)
    return (Term(a.lower() + b.lower(), "rotation", 1j * angle.d1 * r, zero),
            [Term(f"n_{b}{a}", "normal", zero, -angle.d1**2 * r),
             Term(f"τ_{b}{a}", "tangential", 1j * angle.d1 * r, 1j * angle.d2 * r)])


def sliding(on: str, along: str, slide: Slide, unit: np.ndarray, guide: Angle) -> tuple[Term, list[Term]]:
    """A slider ``on`` relative to the guide's point ``along`` under it: v_r = s′u (along the guide);
    a^k = 2iθ′_g s′u (Coriolis, ⊥ guide, zero on a guide that does not turn), a^r = s″u (+ s′u ε₁)."""
    zero = np.zeros_like(unit)
    v_rel = slide.d1 * unit
    return (Term(f"{along.lower()}{on.lower()}", "sliding", v_rel, zero),
            [Term(f"k_{on}{along}", "coriolis", zero, 2j * guide.d1 * v_rel),
             Term(f"r_{on}{along}", "relative", v_rel, slide.d2 * unit)])


def chains(target: str, base: Point, label: str, steps: list[tuple[Term, list[Term]]]):
    """The velocity and the acceleration equation that reach ``target`` from the known point ``base``."""
    pv, pa = absolute(label, base)
    return (target, [pv] + [v for v, _ in steps]), (target, [pa] + [t for _, acc in steps for t in acc])
