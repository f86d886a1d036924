"""The kinematic state of a linkage being composed: joints, links and guides over an array of crank angles.

Everything is vectorised over φ (arrays of shape (N,)).  A point is its position z = x + iy with the first
and second transfer functions (analogs) z′ = dz/dφ, z″ = d²z/dφ² (Eremyants §2.1: velocities v = z′ω₁,
accelerations a = z″ω₁² + z′ε₁).  A link carries its angle θ with θ′, θ″.  A guide is a straight line fixed
on a link: a point P on it and its direction θ_g = θ_link + α, so u = e^{iθ_g}, u′ = iθ′_g u,
u″ = (iθ″_g − θ′_g²)u.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Point:
    """Position z and its analogs z′, z″ (complex arrays over φ)."""

    z: np.ndarray
    d1: np.ndarray
    d2: np.ndarray


@dataclass(frozen=True)
class Angle:
    """A link's angle θ (rad, counter-clockwise from +x) and its analogs θ′, θ″."""

    th: np.ndarray
    d1: np.ndarray
    d2: np.ndarray

    def unit(self) -> np.ndarray:
        """e^{iθ}: the unit vector at the angle."""
        return np.exp(1j * self.th)

    def shifted(self, alpha: float) -> "Angle":
        """θ + α with the same analogs θ′, θ″."""
        return Angle(self.th + alpha, self.d1, self.d2)


@dataclass(frozen=True)
class Guide:
    """A straight guide: a point P on it and its direction (the angle of the link that carries it plus α)."""

    point: Point
    angle: Angle
    link: int


def fixed_point(x: float, y: float, n: int) -> Point:
    """A point of the frame: z = x + iy at every angle, z′ = z″ = 0."""
    zero = np.zeros(n, complex)
    return Point(np.full(n, complex(x, y)), zero, zero)


def fixed_angle(theta: float, n: int) -> Angle:
    """An angle of the frame: θ at every angle, θ′ = θ″ = 0."""
    zero = np.zeros(n)
    return Angle(np.full(n, float(theta)), zero, zero)


def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """z-component of the vector product a × b of complex-coded plane vectors: Im(ā b)."""
    return (np.conj(a) * b).imag


def solve_pair(c1: np.ndarray, c2: np.ndarray, rhs: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Real x₁, x₂ with x₁c₁ + x₂c₂ = rhs (two scalar equations of a plane vector), by Cramer's rule:
    x₁ = (rhs × c₂)/(c₁ × c₂), x₂ = (c₁ × rhs)/(c₁ × c₂).  The determinant c₁ × c₂ vanishes at the group's
    singular (dead) position; there the result is inf/nan, which the caller reports in words."""
    det = cross(c1, c2)
    with np.errstate(divide="ignore", invalid="ignore"):
        return cross(rhs, c2) / det, cross(c1, rhs) / det


def on_link(origin: Point, angle: Angle, offset: complex) -> Point:
    """A point fixed on a link: z = z_O + w e^{iθ} with w = along + i·across in the link's frame;
    z′ = z′_O + iθ′ w e^{iθ}, z″ = z″_O + (iθ″ − θ′²) w e^{iθ} (rigid-body kinematics)."""
    rotated = offset * angle.unit()
    return Point(origin.z + rotated, origin.d1 + 1j * angle.d1 * rotated,
                 origin.d2 + (1j * angle.d2 - angle.d1**2) * rotated)
