"""Elastic machine models as first-order systems y′ = f(t, y) with analytic Jacobians.

Two masses (Eremyants (1.20)–(1.21), (1.31)–(1.32); Drakunov–Tuleshova (1), (11) corrected):
    J₁ω̇₁ = M_д(ω₁) − F,                      F = c(φ₂)θ + bθ̇,  θ = φ₁ − φ₂ (the twist)
    J₂(φ₂)ω̇₂ = F − ½c′(φ₂)θ² − ½J₂′(φ₂)ω₂² − M_c(φ₂, ω₂)
Kinematic drive, a powerful motor φ₁ = ω t (1.22)–(1.23): only the mechanism moves; M_д = F.
Three masses (1.40)–(1.42):
    J₁ω̇₁ = M_д − F₁,  J₂ω̇₂ = F₁ − F₂,  J₃(φ₃)ω̇₃ = F₂ − ½c₂′θ₂² − ½J₃′ω₃² − M_c
    F₁ = c₁θ₁ + b₁θ̇₁, θ₁ = φ₁ − φ₂;   F₂ = c₂(φ₃)θ₂ + b₂θ̇₂, θ₂ = φ₂ − φ₃
The twists are state variables themselves: as differences of two growing angles they would
lose their digits (a 1e-5 rad twist between angles of 50 rad) to the tolerance of the angles.
Three work integrals ride along, W_in = ∫M_д ω₁dt, W_load = ∫M_c ω_out dt, W_diss = ∫Σbθ̇²dt,
so that W_in = ΔE + W_load + W_diss can be checked to the solver's tolerance.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .periodic_table import PeriodicTable


@dataclass
class MechanismSide:
    """J(φ) with J′, J″; c(φ) with c′, c″ (or a constant); M_c(φ) and the viscous S(φ), β."""

    inertia: PeriodicTable
    stiffness: PeriodicTable | float
    load: PeriodicTable
    sliding: PeriodicTable
    beta: float

    def stiff(self, phi: float) -> tuple[float, float, float]:
        """c, c′, c″ at φ: the reduced stiffness (Eremyants (1.24)–(1.29), (1.33)–(1.34); Drakunov–Tuleshova (2))
        from its table, or a constant c."""
        if isinstance(self.stiffness, PeriodicTable):
            return self.stiffness(phi)
        return self.stiffness, 0.0, 0.0

    def stiff_at(self, phi: np.ndarray) -> np.ndarray:
        """c at every φ of an array."""
        if isinstance(self.stiffness, PeriodicTable):
            return self.stiffness.evaluate(phi)[0]
        return np.full(np.shape(phi), float(self.stiffness))

    def fast(self, phi: float, omega: float, twist: float, force_of) -> tuple[float, float, float, float]:
        """The right-hand side's path: c(φ), the spring force F = force_of(c), ω̇ of the mechanism and M_c."""
        J, dJ = self.inertia.value_slope(phi)
        if isinstance(self.stiffness, PeriodicTable):
            c, dc = self.stiffness.value_slope(phi)
        else:
            c, dc = self.stiffness, 0.0
        m = self.load.value_slope(phi)[0]
        if self.beta:
            m += self.beta * omega * self.sliding.value_slope(phi)[0]
        force = force_of(c)
        return c, force, (force - 0.5 * dc * twist * twist - 0.5 * dJ * omega * omega - m) / J, m

    def resisting(self, phi: float, omega: float) -> tuple[float, float, float]:
        """M_c, ∂M_c/∂φ, ∂M_c/∂ω."""
        m, dm, _ = self.load(phi)
        s, ds, _ = self.sliding(phi)
        return m + self.beta * omega * s, dm + self.beta * omega * ds, self.beta * s

    def acceleration(self, phi: float, omega: float, twist: float, force: float):
        """ω̇ of the mechanism mass and its partial derivatives in φ, ω, θ, F."""
        J, dJ, ddJ = self.inertia(phi)
        c, dc, ddc = self.stiff(phi)
        mc, dmc_phi, dmc_w = self.resisting(phi, omega)
        numerator = force - 0.5 * dc * twist * twist - 0.5 * dJ * omega * omega - mc
        value = numerator / J
        d_phi = (-0.5 * ddc * twist * twist - 0.5 * ddJ * omega * omega - dmc_phi) / J - value * dJ / J
        return value, d_phi, (-dJ * omega - dmc_w) / J, -dc * twist / J, 1.0 / J


@dataclass
class Drive:
    """Motor reduced to the crank side: torque(ω) → (M, dM/dω); or a prescribed speed."""

    torque: object
    speed: float | None = None


class TwoMass:
    """States: φ₂, ω₂, θ, θ̇, W_in, W_load, W_diss (φ₂, ω₂ from θ for a kinematic drive)."""

    def __init__(self, J1: float, side: MechanismSide, damping: float, drive: Drive):
        self.J1, self.side, self.b, self.drive = J1, side, damping, drive
        self.kinematic = drive.speed is not None
        self.size = 7

    def mechanism_state(self, t: float, y) -> tuple[float, float]:
        """φ₂, ω₂."""
        if self.kinematic:
            return self.drive.speed * t - y[2], self.drive.speed - y[3]
        return y[0], y[1]

    def rhs(self, t: float, y) -> list[float]:
        """y′ of the two masses, Eremyants (1.20)–(1.21), (1.31)–(1.32), Drakunov–Tuleshova (1), (11) corrected
        (module docstring); for a kinematic drive (1.22)–(1.23) only the mechanism moves."""
        phi2, w2 = self.mechanism_state(t, y)
        twist, rate = y[2], y[3]
        c, force, w2_dot, mc = self.side.fast(phi2, w2, twist, lambda c: c * twist + self.b * rate)
        if self.kinematic:
            w1 = self.drive.speed
            return [0.0, 0.0, rate, -w2_dot, force * w1, mc * w2, self.b * rate * rate]
        w1 = w2 + rate
        torque = self.drive.torque(w1)[0]
        return [w2, w2_dot, rate, (torque - force) / self.J1 - w2_dot, torque * w1, mc * w2, self.b * rate * rate]

    def jac(self, t: float, y) -> np.ndarray:
        """∂f/∂y of ``rhs``, analytic (the same equations differentiated)."""
        phi2, w2 = self.mechanism_state(t, y)
        twist, rate = y[2], y[3]
        c, dc, _ = self.side.stiff(phi2)
        force = c * twist + self.b * rate
        a, a_phi, a_w, a_twist, a_force = self.side.acceleration(phi2, w2, twist, force)
        mc, dmc_phi, dmc_w = self.side.resisting(phi2, w2)
        # total derivatives of ω̇₂ through F = c(φ₂)θ + bθ̇
        dA = {"phi": a_phi + a_force * dc * twist, "w": a_w, "twist": a_twist + a_force * c, "rate": a_force * self.b}
        jac = np.zeros((7, 7))
        if self.kinematic:     # φ₂ = ωt − θ, ω₂ = ω − θ̇
            w1 = self.drive.speed
            jac[2, 3] = 1.0
            jac[3, 2] = dA["phi"] - dA["twist"]
            jac[3, 3] = dA["w"] - dA["rate"]
            jac[4, 2], jac[4, 3] = (c - dc * twist) * w1, self.b * w1
            jac[5, 2], jac[5, 3] = -dmc_phi * w2, -(mc + dmc_w * w2)
            jac[6, 3] = 2 * self.b * rate
            return jac
        w1 = w2 + rate
        torque, slope = self.drive.torque(w1)
        jac[0, 1] = 1.0
        jac[1, 0], jac[1, 1], jac[1, 2], jac[1, 3] = dA["phi"], dA["w"], dA["twist"], dA["rate"]
        jac[2, 3] = 1.0
        jac[3, 0] = -dc * twist / self.J1 - dA["phi"]
        jac[3, 1] = slope / self.J1 - dA["w"]
        jac[3, 2] = -c / self.J1 - dA["twist"]
        jac[3, 3] = (slope - self.b) / self.J1 - dA["rate"]
        jac[4, 1] = jac[4, 3] = torque + slope * w1
        jac[5, 0], jac[5, 1] = dmc_phi * w2, mc + dmc_w * w2
        jac[6, 3] = 2 * self.b * rate
        return jac

    def energy(self, t: np.ndarray, y: np.ndarray) -> np.ndarray:
        """Kinetic plus elastic energy, J, at the times t of the states y (columns)."""
        phi2, w2 = self.mechanism_state(t, y)
        motor = 0.0 if self.kinematic else 0.5 * self.J1 * (w2 + y[3]) ** 2
        return motor + 0.5 * self.side.inertia.evaluate(phi2)[0] * w2 * w2 + 0.5 * self.side.stiff_at(phi2) * y[2] ** 2

    def motor_state(self, t, y) -> tuple:
        """φ₁, ω₁ of the motor side (scalars or arrays over the columns of y)."""
        phi2, w2 = self.mechanism_state(t, y)
        return phi2 + y[2], w2 + y[3]


class ThreeMass:
    """States: φ₃, ω₃, θ₂, θ̇₂, θ₁, θ̇₁, W_in, W_load, W_diss."""

    size = 9

    def __init__(self, J1: float, J2: float, c1: float, b1: float, side: MechanismSide, b2: float, drive: Drive):
        self.J1, self.J2, self.c1, self.b1, self.side, self.b2, self.drive = J1, J2, c1, b1, side, b2, drive

    def rhs(self, t: float, y) -> list[float]:
        """y′ of the three masses, Eremyants (1.40)–(1.42) (module docstring)."""
        phi3, w3, twist2, rate2, twist1, rate1 = y[:6]
        w1 = w3 + rate2 + rate1
        f1 = self.c1 * twist1 + self.b1 * rate1
        _, f2, w3_dot, mc = self.side.fast(phi3, w3, twist2, lambda c: c * twist2 + self.b2 * rate2)
        w2_dot = (f1 - f2) / self.J2
        torque = self.drive.torque(w1)[0]
        w1_dot = (torque - f1) / self.J1
        return [w3, w3_dot, rate2, w2_dot - w3_dot, rate1, w1_dot - w2_dot,
                torque * w1, mc * w3, self.b1 * rate1 * rate1 + self.b2 * rate2 * rate2]

    def jac(self, t: float, y) -> np.ndarray:
        """∂f/∂y of ``rhs``, analytic (the same equations differentiated)."""
        phi3, w3, twist2, rate2, twist1, rate1 = y[:6]
        w1 = w3 + rate2 + rate1
        c2, dc2, _ = self.side.stiff(phi3)
        f2 = c2 * twist2 + self.b2 * rate2
        a, a_phi, a_w, a_twist, a_force = self.side.acceleration(phi3, w3, twist2, f2)
        mc, dmc_phi, dmc_w = self.side.resisting(phi3, w3)
        torque, slope = self.drive.torque(w1)
        # rows of ω̇₃, ω̇₂, ω̇₁ over the states φ₃, ω₃, θ₂, θ̇₂, θ₁, θ̇₁
        w3_row = np.array([a_phi + a_force * dc2 * twist2, a_w, a_twist + a_force * c2, a_force * self.b2, 0, 0])
        f2_row = np.array([dc2 * twist2, 0, c2, self.b2, 0, 0])
        f1_row = np.array([0, 0, 0, 0, self.c1, self.b1])
        w2_row = (f1_row - f2_row) / self.J2
        w1_row = (slope * np.array([0, 1, 0, 1, 0, 1]) - f1_row) / self.J1
        jac = np.zeros((9, 9))
        jac[0, 1] = jac[2, 3] = jac[4, 5] = 1.0
        jac[1, :6] = w3_row
        jac[3, :6] = w2_row - w3_row
        jac[5, :6] = w1_row - w2_row
        jac[6, :6] = (torque + slope * w1) * np.array([0, 1, 0, 1, 0, 1])
        jac[7, 0], jac[7, 1] = dmc_phi * w3, mc + dmc_w * w3
        jac[8, 3], jac[8, 5] = 2 * self.b2 * rate2, 2 * self.b1 * rate1
        return jac

    def energy(self, t: np.ndarray, y: np.ndarray) -> np.ndarray:
        """Kinetic plus elastic energy, J, at the times t of the states y (columns)."""
        phi3, w3, twist2, rate2, twist1, rate1 = y[:6]
        w2, w1 = w3 + rate2, w3 + rate2 + rate1
        return (0.5 * self.J1 * w1 * w1 + 0.5 * self.J2 * w2 * w2 + 0.5 * self.side.inertia.evaluate(phi3)[0] * w3 * w3
                + 0.5 * self.c1 * twist1 * twist1 + 0.5 * self.side.stiff_at(phi3) * twist2 * twist2)

    def motor_state(self, t, y) -> tuple:
        """φ₁, ω₁ of the motor side (scalars or arrays over the columns of y)."""
        return y[0] + y[2] + y[4], y[1] + y[3] + y[5]
