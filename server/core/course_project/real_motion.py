"""The real motion of the crank in the steady regime with the flywheel fitted (Chaika–Vasylenko §3.4, the steady
regime's steps 9–16; Lecture 10 §10.3): ω₁(φ) and ε₁(φ) at any crank angle, from the energy equation, not read
off a grid.

The driving moment is constant and balances the cycle (the steady regime's step 9: A_P|cycle = A_c|cycle):

    M_д = (1/2π) ∫₀²π M_c dφ,      A(φ) = ∫₀^φ (M_д − M_c) dφ,      M_c = M_useful + M_T

(M_useful: the reduced moment of the useful loads and weights, power equality, Eremyants (1.5); M_T: the pairs'
dry friction of the static loads, as the machine's equation of motion takes it, dynamics/general_machine.py).
With group I's inertia I_I = J₁ + J_rotor i² + I_fly and J(φ) = I_I + J_II(φ) (Eremyants (1.3)):

    ω₁(φ)² = 2(T₀ + A(φ))/J(φ)                           Eremyants (1.10), the energy integral
    ε₁(φ) = (M_д − M_c(φ) − ½ J′(φ) ω₁²)/J(φ)            Eremyants (1.13)

with T₀ such that (ω_max + ω_min)/2 = ω₁ₘ (Lecture 10 (L3)), the extremes found where ω₁′ = 0 exactly
(Brent's method on M J − (T₀ + A) J′, the numerator of d(ω²)/dφ), T₀ by Newton's method: by the envelope
theorem d(ω²(φ*))/dT₀ = 2/J(φ*) at an extreme φ*.

A(φ) by composite Gauss–Legendre quadrature on PIECES uniform pieces of the turn split at the machine's kinks
(M_c is analytic between them: Machine.find_kinks), the rules of ORDER and 2·ORDER nodes on each piece; their
difference, summed over the turn, bounds the error of A (geometric convergence: the fine rule's own error is far
below it).  An angle between two piece ends takes the same two rules on [piece start, φ].
"""
from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from ..dynamics.general_machine import GeneralMachine
from ..mechanisms import GeometryError
from ..numerics import Numerics

TURN = 2 * np.pi
PIECES = 256               # uniform pieces of the turn for A(φ) (the kinks split them further)
ORDER = 8                  # Gauss–Legendre nodes of the coarse rule (the fine one: 2·ORDER)
NEWTON_STEPS = 50          # of T₀ at most (quadratic: ~5 are used)
LEVEL_TOLERANCE = 4e-16    # |ΔT₀|/T₀ that ends Newton's method on T₀

_coarse = np.polynomial.legendre.leggauss(ORDER)
_fine = np.polynomial.legendre.leggauss(2 * ORDER)


@dataclass(frozen=True)
class Resistance:
    """∫₀^φ M_useful dφ and ∫₀^φ M_T dφ at the ends of the quadrature's pieces over one turn (``cumulative``,
    (2, P + 1), N·m·rad), the pieces' ends (``edges``), the error bound of both integrals (``error``) and the sum
    of the pieces' |integrals| (``magnitude``, J: ∫|M_c| dφ where no piece holds a change of sign)."""

    machine: GeneralMachine
    edges: np.ndarray
    cumulative: np.ndarray
    error: float
    magnitude: float

    @property
    def driving_moment(self) -> float:
        """M_д = (1/2π) ∫₀²π M_c dφ, N·m: the constant driving moment of the steady regime."""
        return float(self.cumulative[:, -1].sum()) / TURN

    @property
    def useful_work(self) -> float:
        """∫₀²π M_useful dφ, J: the work of the useful loads (the weights' is zero over the turn)."""
        return float(self.cumulative[0, -1])

    @property
    def friction_work(self) -> float:
        """∫₀²π M_T dφ, J: the work the pairs' dry friction takes over the turn."""
        return float(self.cumulative[1, -1])

    def moments(self, phi: np.ndarray) -> np.ndarray:
        """(M_useful, M_T, J, J′) at ``phi`` from the machine's tables (4, N)."""
        tables = self.machine.tables(np.asarray(phi, float))
        return np.stack([tables.useful, tables.dry, tables.J, tables.dJ])

    def integrals(self, phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(∫₀^ψ M_useful, ∫₀^ψ M_T) at ψ = φ mod 2π (2, N), and the bound of their error (N,)."""
        psi = np.mod(np.asarray(phi, float).ravel(), TURN)
        piece = np.clip(np.searchsorted(self.edges, psi, side="right") - 1, 0, self.edges.size - 2)
        start = self.edges[piece]
        fine, difference = partial_rules(lambda x: self.moments(x)[:2], start, psi)
        return self.cumulative[:, piece] + fine, np.abs(difference).sum(axis=0)


def partial_rules(function, low: np.ndarray, high: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """∫ from low to high of each row of ``function`` by the Gauss–Legendre rule of 2·ORDER nodes (m, N), and the
    coarse rule's difference from it (m, N), all intervals at once."""
    half, mid = 0.5 * (high - low), 0.5 * (high + low)
    t = np.concatenate([_coarse[0], _fine[0]])
    values = function((mid[:, None] + half[:, None] * t[None, :]).ravel())
    values = values.reshape(values.shape[0], low.size, t.size)
    coarse = half * (values[:, :, :ORDER] @ _coarse[1])
    fine = half * (values[:, :, ORDER:] @ _fine[1])
    return fine, coarse - fine


def resistance(machine: GeneralMachine) -> Resistance:
    """The integrals of M_useful and M_T over the turn (``Resistance``), GeometryError where M_c is not finite
    somewhere (self-locking with the friction given: no motion)."""
    kinks = np.asarray(machine.kinks())
    edges = np.unique(np.concatenate([np.linspace(0.0, TURN, PIECES + 1), kinks[(kinks > 0) & (kinks < TURN)]]))
    probe = Resistance(machine, edges, np.zeros((2, edges.size)), 0.0, 0.0)
    fine, difference = partial_rules(lambda x: probe.moments(x)[:2], edges[:-1], edges[1:])
    if not np.isfinite(fine).all():
        raise GeometryError("masses.friction", "the mechanism locks itself somewhere in the turn with this "
                            "friction (the friction moment grows without bound): there is no steady motion",
                            "project_self_locking")
    cumulative = np.concatenate([np.zeros((2, 1)), np.cumsum(fine, axis=1)], axis=1)
    scale = np.abs(fine).sum()
    error = float(np.abs(difference).sum()) + 64 * np.finfo(float).eps * scale
    return Resistance(machine, edges, cumulative, error, float(scale))


@dataclass(frozen=True)
class RealMotion:
    """The steady motion with the flywheel: ω₁(φ), ε₁(φ) at any angle (module docstring)."""

    resistance: Resistance
    flywheel_inertia: float      # I_fly added to the crank's shaft, kg·m²
    omega_mean: float            # ω₁ₘ = (ω_max + ω_min)/2, rad/s
    level: float                 # T₀, J: the kinetic energy at φ = 0 is T₀ (A(0) = 0)
    extremes: tuple[float, float, float, float]   # φ_max, ω_max, φ_min, ω_min
    iterations: int              # Newton's steps on T₀
    numerics: Numerics

    @property
    def driving_moment(self) -> float:
        return self.resistance.driving_moment

    @property
    def delta(self) -> float:
        """δ = (ω_max − ω_min)/ω₁ₘ achieved (Lecture 10 (L3))."""
        return (self.extremes[1] - self.extremes[3]) / self.omega_mean

    def state(self, phi: np.ndarray) -> dict[str, np.ndarray]:
        """At the crank angles ``phi``: A (J), J with the flywheel and J′ (kg·m², kg·m²/rad), M_д − M_c (N·m),
        ω₁ (rad/s), ε₁ (rad/s²)."""
        phi = np.asarray(phi, float)
        work = self.work(phi)
        useful, dry, inertia, slope = self.resistance.moments(phi)
        inertia = inertia + self.flywheel_inertia
        moment = self.driving_moment - useful - dry
        omega = np.sqrt(2 * (self.level + work) / inertia)
        return {"work": work, "J": inertia, "dJ": slope, "moment": moment, "omega": omega,
                "epsilon": (moment - 0.5 * slope * omega**2) / inertia}

    def work(self, phi: np.ndarray) -> np.ndarray:
        """A(φ) = M_д ψ − ∫₀^ψ M_c dφ, ψ = φ mod 2π (periodic: A(2π) = 0)."""
        phi = np.asarray(phi, float)
        integrals, _ = self.resistance.integrals(phi)
        return (self.driving_moment * np.mod(phi.ravel(), TURN) - integrals.sum(axis=0)).reshape(phi.shape)


def real_motion(resisting: Resistance, flywheel_inertia: float, omega_mean: float) -> RealMotion:
    """The real motion with group I's inertia raised by ``flywheel_inertia`` at the mean speed ``omega_mean``
    (module docstring): T₀ by Newton's method on (ω_max + ω_min)/2 = ω₁ₘ with the extremes refined exactly."""
    started = time.perf_counter()
    edges = resisting.edges[:-1]
    probe = RealMotion(resisting, flywheel_inertia, omega_mean, 0.0, (0.0,) * 4, 0, Numerics(""))
    work = probe.work(edges)
    inertia = resisting.moments(edges)[2] + flywheel_inertia
    floor = float(-work.min())
    level = max(0.5 * omega_mean**2 * float(inertia.mean()) - float(work.mean()), floor + 1e-9 * abs(floor) + 1e-300)
    steps = 0
    for exact in (False, True):         # the pieces' ends first (cheap), then the extremes refined exactly
        for step in range(1, NEWTON_STEPS + 1):
            found = speed_extremes(probe, level, work, inertia, exact)
            (_, w_max, j_max), (_, w_min, j_min) = found
            change = (0.5 * (w_max + w_min) - omega_mean) / (0.5 * (1 / (j_max * w_max) + 1 / (j_min * w_min)))
            following = level - change
            if following <= floor:                     # the speed would reach zero: halve the way to the floor
                following = 0.5 * (level + floor)
            done = abs(following - level) <= LEVEL_TOLERANCE * abs(level)
            level = following
            if done:
                break
        steps += step
    found = speed_extremes(probe, level, work, inertia)
    (phi_max, w_max, _), (phi_min, w_min, _) = found
    relative = resisting.error / max(float(inertia.min()) * w_min**2, 1e-300)    # δω/ω ≈ δA/(J ω²)
    numerics = Numerics(
        method="A(φ) by composite Gauss–Legendre quadrature between the kinks of M_c (rules of "
               f"{ORDER} and {2 * ORDER} nodes on each of {edges.size} pieces, their difference the error bound); "
               "ω₁² = 2(T₀ + A)/J at each angle; T₀ by Newton's method on (ω_max + ω_min)/2 = ω₁ₘ with the extremes "
               "found by Brent's method where dω₁/dφ = 0", code="project_real_motion", steps=int(edges.size),
        iterations=steps, converged=step < NEWTON_STEPS, error_estimate=relative,
        runtime_ms=1e3 * (time.perf_counter() - started))
    return RealMotion(resisting, flywheel_inertia, omega_mean, level, (phi_max, w_max, phi_min, w_min), steps,
                      numerics)


def speed_extremes(motion: RealMotion, level: float, work: np.ndarray, inertia: np.ndarray, exact: bool = True):
    """((φ, ω, J) at ω_max, (φ, ω, J) at ω_min) for T₀ = ``level``: the best piece end, then (``exact``) the root
    of g = (M_д − M_c) J − (T₀ + A) J′ (the numerator of d(ω²)/dφ) between its neighbours by Brent's method,
    where g changes sign there (else the piece end itself: a corner of ω)."""
    edges = motion.resistance.edges
    squares = 2 * (level + work) / inertia
    count = squares.size
    if not exact:
        return [(float(edges[k]), float(np.sqrt(squares[k])), float(inertia[k]))
                for k in (int(np.argmax(squares)), int(np.argmin(squares)))]

    def slope(phi: float) -> float:
        state = motion.resistance.moments(np.array([phi]))
        a = float(motion.work(np.array([phi]))[0])
        moment = motion.driving_moment - state[0, 0] - state[1, 0]
        return moment * (state[2, 0] + motion.flywheel_inertia) - (level + a) * state[3, 0]

    out = []
    for sign in (1, -1):
        k = int(np.argmax(sign * squares))
        low = edges[k - 1] if k > 0 else edges[count - 1] - TURN
        high = edges[k + 1]
        phi = float(edges[k])
        g_low, g_high = slope(low), slope(high)
        if sign * g_low > 0 > sign * g_high:
            phi = brentq(slope, low, high, xtol=1e-15, rtol=4 * np.finfo(float).eps)
        state = motion.resistance.moments(np.array([phi]))
        j = float(state[2, 0]) + motion.flywheel_inertia
        w = float(np.sqrt(2 * (level + motion.work(np.array([phi]))[0]) / j))
        out.append((float(np.mod(phi, TURN)), w, j))
    return out
