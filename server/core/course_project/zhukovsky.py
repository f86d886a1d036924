"""Zhukovsky's lever: the balancing moment from the velocity plan turned by 90°, the check of the balancing moment
the groups give (Chaika–Vasylenko (3.2): the crank's equilibrium against a moment found otherwise), by virtual
power.

The velocity plan at the scale μ_v (m/s per mm) is turned by 90° counter-clockwise about its pole p: the image of
a point of velocity v = z′ω₁ lies at r = i v/μ_v (mm, complex x + iy from the pole).  Every force F_i is applied
at its point's image; its moment about the pole is

    m_i = r_i × F_i = Im(r̄_i F_i) = −F_i·v_i/μ_v    (N·mm; its arm h_i = m_i/|F_i|, mm)

A couple M_k on link k enters as the moment m_k = −M_k ω_k/μ_v: the textbook's pair of forces ±M_k/l at two
points of the link l apart, whose images lie ω_k l/μ_v apart on the plan, has exactly this moment (the couple
form is used here, for any link, a slider's too).  The lever is in equilibrium with the balancing moment M_b on
the crank (positive along ω₁), whose own lever moment is −M_b ω₁/μ_v:

    M_b = (μ_v/ω₁) Σ m_i = −(1/ω₁) Σ (F_i·v_i + M_k ω_k)            (virtual power: Σ P = 0)

The loads are the groups' (kinetostatics/groups/loads.py: the weights, the inertia forces and couples, the useful
loads), and with friction the pairs' friction loads of the groups' solution: a revolute pair's friction moment
z on link b and −z on link a (a couple of the relative rotation, m = −z (ω_b − ω_a)/μ_v), a prismatic pair's
friction force z u on b and −z u on a at the pair's point, each at the image of its own link's point there.
All arrays over the crank angles of the analysis: one lever per angle, vectorised.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..kinetostatics.groups.analysis import Approximation, GroupForces
from ..kinetostatics.groups.pairs import link_velocity
from ..kinetostatics.groups.report import label

FLOOR = 1e-12          # of the largest row's share of M_b: the scale of a zero balancing moment's difference


@dataclass(frozen=True)
class LeverRow:
    """One load on the lever, arrays over φ: its point on the mechanism (``at``, m), its image on the turned plan
    (``image``, mm from the pole; None for a couple), the force (N, complex) or couple (N·m), the arm about the
    pole (mm, counter-clockwise positive), the lever moment m (N·mm) and its share of M_b, μ_v m/ω₁ (N·m)."""

    name: str
    kind: str                     # gravity, inertia, useful, friction
    link: int
    at: np.ndarray | None
    image: np.ndarray | None
    force: np.ndarray | None
    couple: np.ndarray | None
    arm: np.ndarray | None
    moment: np.ndarray
    share: np.ndarray


@dataclass(frozen=True)
class Lever:
    rows: list[LeverRow]
    balancing: np.ndarray         # M_b along ω₁ from the lever, N·m
    mu_v: float


def turned(velocity: np.ndarray, mu_v: float) -> np.ndarray:
    """The image of a velocity on the plan turned by 90° counter-clockwise: i v/μ_v, mm."""
    return 1j * velocity / mu_v


def force_row(name: str, kind: str, link: int, z, velocity, force, omega, mu_v) -> LeverRow:
    """A force at the image of its point: m = Im(r̄F), h = m/|F| (0 where the force vanishes)."""
    image = turned(velocity, mu_v)
    moment = (np.conj(image) * force).imag
    size = np.abs(force)
    arm = np.divide(moment, size, out=np.zeros_like(moment), where=size > 0)
    return LeverRow(name, kind, link, z, image, force, None, arm, moment, mu_v * moment / omega)


def couple_row(name: str, kind: str, link: int, couple, turning, omega, mu_v) -> LeverRow:
    """A couple M on a link turning at ω_k = θ′ω₁: m = −M ω_k/μ_v."""
    moment = -couple * turning * omega / mu_v
    return LeverRow(name, kind, link, None, None, None, couple, None, moment, mu_v * moment / omega)


def lever(result: GroupForces, omega: np.ndarray, mu_v: float, row: Approximation | None = None) -> Lever:
    """Zhukovsky's lever at every angle of ``result`` with the crank's speed ``omega`` (rad/s, > 0, an array over
    the angles or one number) and the plan's scale ``mu_v``; ``row``: the friction loads of an approximation of
    the groups (the solution with friction, or None: the loads alone, without friction)."""
    omega = np.broadcast_to(np.asarray(omega, float), result.phi.shape)
    rows = []
    for load in result.loads:
        if load.force is not None:
            rows.append(force_row(load.name, load.kind, load.link, load.z, load.rate * omega, load.force, omega,
                                  mu_v))
        else:
            rows.append(couple_row(load.name, load.kind, load.link, load.moment, load.rate, omega, mu_v))
    if row is not None:
        rows += friction_rows(result, row, omega, mu_v)
    total = sum((r.moment for r in rows), np.zeros(result.phi.shape))
    return Lever(rows, mu_v * total / omega, mu_v)


def friction_rows(result: GroupForces, row: Approximation, omega: np.ndarray, mu_v: float) -> list[LeverRow]:
    """The pairs' friction loads of ``row`` on the lever (module docstring); pairs without friction left out."""
    rows = []
    for k, pair in enumerate(result.pairs):
        z = row.friction[k]
        if not np.any(z):
            continue
        name = label(pair.a, pair.b)
        if pair.kind == "R":
            rows.append(couple_row(f"M_f{name}", "friction", pair.b, z, pair.relative, omega, mu_v))
            continue
        for link, sign, who in ((pair.b, 1.0, name), (pair.a, -1.0, label(pair.b, pair.a))):
            velocity = link_velocity(result.comp, link, pair.z) * omega
            rows.append(force_row(f"F_f{who}", "friction", link, pair.z, velocity, sign * z * pair.u, omega, mu_v))
    return rows


def difference_percent(from_lever: np.ndarray, from_groups: np.ndarray, rows: list[LeverRow]) -> np.ndarray:
    """|M_b,lever − M_b,groups| / |M_b,groups| · 100 % (Chaika–Vasylenko (3.2)); a balancing moment near zero
    is measured against FLOOR of the largest share of a row instead (no division by zero)."""
    largest = np.max(np.abs([r.share for r in rows]), axis=0, initial=0.0) if rows else 0.0
    scale = np.maximum(np.abs(from_groups), np.maximum(FLOOR * largest, 1e-300))
    return 100 * np.abs(from_lever - from_groups) / scale


def at_angle(lever_: Lever, k: int) -> list[dict]:
    """The rows at angle index k, to draw and to list: point, image, force, arm, lever moment, share of M_b."""
    xy = lambda z: [float(np.real(z[k])), float(np.imag(z[k]))]
    out = []
    for r in lever_.rows:
        item = {"name": r.name, "kind": r.kind, "link": r.link, "moment": float(r.moment[k]),
                "share": float(r.share[k])}
        if r.force is not None:
            item |= {"at": xy(r.at), "image": xy(r.image), "force": xy(r.force), "arm": float(r.arm[k])}
        else:
            item["couple"] = float(r.couple[k])
        out.append(item)
    return out
