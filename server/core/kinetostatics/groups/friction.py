"""Friction in every pair of a general mechanism (Chaika–Vasylenko (3.3)) and its equilibrium.

The friction loads z_p (a moment in a revolute pair, a force along the line of a prismatic pair, on link b of
the pair, against the relative motion) follow from the reactions:
    revolute:   z_p = −sgn(θ′_b − θ′_a) f_p r_p |R_p|        (the friction circle ρ = f·r)
    prismatic:  z_p = −sgn(s′) f_p |N_p|
and the reactions are affine in z (equilibrium.Influence), so the equilibrium with friction is the fixed point
z = G(z).  The textbook's successive approximations are the iteration z ← G(z) from z = 0 (approximation 1
without friction), stopped when the relative change of the reactions is below ε_R (design step 17(d)).

As for the crank-slider (kinetostatics/equilibrium.py), the answer is the fixed point solved directly by
Newton's method with the generalised Jacobian J = ∂G/∂z (|N| and |R| are piecewise smooth), each step taking
the Newton point or the textbook's step, whichever leaves the smaller change of the reactions (the Newton point
wherever the change it leaves is within ε_R of its reactions: there the two differ by rounding alone, and a
textbook step taken on rounding would bound its error by q/(1 − q), infinite where q ≥ 1); the error left
after a Newton correction is bounded by that correction, after a textbook step by q/(1 − q) of it (q the
spectral radius of J, the series' ratio).  Self-locking is decided as the crank-slider's solve decides it
where its direct solve goes astray: the equilibrium the mechanism reaches as its friction grows from zero
(continuation in the share s of the friction, det(I − sJ) > 0 along it, det = 1 at s = 0) must exist up to
s = 1; where that branch folds (det(I − J) reaches 0) or no equilibrium continues it, the reactions it needs
grow without bound: no driving moment moves the mechanism there.  As in the crank-slider's solve, an equilibrium
that Newton's method does not reach from the previous share's within NEWTON_CAP steps is taken as not
continuing the branch (on these piecewise-smooth equations Newton converges in a few steps where a root
continues the branch).  A jam — friction loads that sustain themselves whatever the load, the crank-slider's
rod inside the guide's friction angle (f₃₄|tan ψ′| ≥ 1) — is found as the branch ending for the loads or for
the loads reversed; it is looked for only where the bound ρ(A) ≥ 1 (``bound_ratio``) allows one.  For the
crank-slider this gives exactly the dedicated solve's locked angles (tests/test_group_forces_crank_slider.py).
The time budget is a work bound only: the angles it leaves are reported unconverged, in words, never decided
locked by it.  ``solve`` runs these decisions angle by angle in compiled code (compiled.py); ``solve_reference``,
all angles at once in numpy, is the reference it is tested against (tests/test_group_friction_compiled.py).
"""
from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from . import compiled
from .compiled import CONTINUATION, NEWTON_CAP       # shares of the continuation; Newton steps per solve
from .equilibrium import Influence
from .pairs import KinematicPair



@dataclass(frozen=True)
class PairFriction:
    """f and the journal radius r (m) of one pair (r unused for a prismatic pair); β, its viscous friction
    (N·m·s revolute, N·s/m prismatic), enters the equation of motion (dynamics/general_machine.py)."""

    f: float = 0.0
    r: float = 0.0
    beta: float = 0.0


@dataclass
class FrictionMap:
    """Per friction pair p: the reaction coordinates affine in z, r_p(z) = base_p + Σ_q z_q ∂r_p/∂z_q
    (R: (R_x, R_y); P: (N, 0)), and the coefficient −sgn(relative) f_p ρ_p.  The slopes are kept angle first,
    ``lever[n, p, k, q]`` = ∂(r_p)_k/∂z_q at angle n, so that r(z) is one batched matrix product per angle."""

    base: np.ndarray          # (K, N, 2)
    lever: np.ndarray         # (N, K, 2, K)
    coefficient: np.ndarray   # (K, N)

    @property
    def slope(self) -> np.ndarray:
        """(K, K, N, 2): [p, q, n, k] = ∂(r_p)_k/∂z_q (a view of ``lever``)."""
        return self.lever.transpose(1, 3, 0, 2)

    def take(self, where: np.ndarray) -> "FrictionMap":
        """The map at the angles ``where`` only."""
        return FrictionMap(self.base[:, where], self.lever[where], self.coefficient[:, where])

    def moved(self, dz: np.ndarray) -> np.ndarray:
        """(K, N, 2): the change Σ_q (∂r_p/∂z_q) dz_q of the reactions that a change dz of the friction loads
        makes."""
        n, K = self.lever.shape[:2]
        product = np.matmul(self.lever.reshape(n, 2 * K, K), dz.T[:, :, None])
        return product.reshape(n, K, 2).transpose(1, 0, 2)

    def change(self, dz: np.ndarray) -> np.ndarray:
        """The largest change of a reaction that a change dz of the friction loads makes, per angle."""
        return np.abs(self.moved(dz)).max(axis=(0, 2))

    def reactions(self, z: np.ndarray) -> np.ndarray:
        """r_p(z) = r_p(0) + Σ_q (∂r_p/∂z_q) z_q: the reactions are linear in the friction loads z."""
        return self.base + self.moved(z)

    def apply(self, z: np.ndarray) -> np.ndarray:
        """G(z): the friction loads (3.3) from the reactions the friction loads z give."""
        r = self.reactions(z)
        return self.coefficient * np.hypot(r[..., 0], r[..., 1])

    def evaluate(self, z: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """G(z), J = ∂G/∂z (K, K, N) and the reactions r_p(z)."""
        r = self.reactions(z)
        norm = np.hypot(r[..., 0], r[..., 1])
        unit = np.where(norm[..., None] > 0, r / np.where(norm > 0, norm, 1.0)[..., None], 0.0)
        G = self.coefficient * norm
        J = self.coefficient[:, None] * np.matmul(unit.transpose(1, 0, 2)[:, :, None, :],
                                                  self.lever)[:, :, 0, :].transpose(1, 2, 0)
        return G, J, r


def friction_map(influence: Influence, locate: list[tuple[int, int] | None], pairs: list[KinematicPair],
                 coefficients: list[PairFriction]) -> FrictionMap:
    """``locate[p]``: (group, pair index) of friction pair p, None for the crank's pivot."""
    n = influence.crank.shape[1]
    K = len(pairs)
    if K == 0:                                 # no friction anywhere
        return FrictionMap(np.zeros((0, n, 2)), np.zeros((n, 0, 2, 0)), np.zeros((0, n)))
    base, lever = np.zeros((K, n, 2)), np.zeros((n, K, 2, K))
    for p, where in enumerate(locate):
        if where is None:                      # the crank's pivot: R₀₁
            for k, part in enumerate((influence.crank.real, influence.crank.imag)):
                base[p, :, k], lever[:, p, k] = part[0], part[1:].T
            continue
        x = influence.group_unknowns[where[0]].transpose(1, 2, 0)[:, 2 * where[1]:2 * where[1] + 2]   # (N, 2, C)
        used = 2 if pairs[p].kind == "R" else 1                          # P: (N, 0)
        base[p, :, :used], lever[:, p, :used] = x[:, :used, 0], x[:, :used, 1:]
    return FrictionMap(base, lever, friction_coefficients(pairs, coefficients))


def friction_coefficients(pairs: list[KinematicPair], coefficients: list[PairFriction]) -> np.ndarray:
    """(K, N): −sgn(relative) f_p ρ_p of every friction pair, ρ_p = r_p (revolute) or 1 (prismatic) (3.3)."""
    return np.stack([-np.sign(pair.relative) * c.f * (c.r if pair.kind == "R" else 1.0)
                     for pair, c in zip(pairs, coefficients)])


@dataclass
class Solved:
    z: np.ndarray                 # (K, N)
    ratio: np.ndarray             # q: spectral radius of J at z (the textbook series' ratio); NaN if not asked
    locked: np.ndarray
    converged: np.ndarray
    error: np.ndarray
    iterations: int


def spectral_radius(J: np.ndarray) -> np.ndarray:
    """max |λ| of J[:, :, n] for every angle."""
    matrices = np.nan_to_num(np.moveaxis(J, -1, 0), nan=0.0, posinf=0.0, neginf=0.0)
    return np.abs(np.linalg.eigvals(matrices)).max(axis=-1) if matrices.shape[-1] else np.zeros(J.shape[-1])


def newton_step(J: np.ndarray, residual: np.ndarray) -> np.ndarray:
    """Δ with (I − J)Δ = G(z) − z at every angle; NaN where I − J is singular."""
    K, n = residual.shape
    A = np.eye(K)[None] - np.moveaxis(J, -1, 0)
    det = np.linalg.det(A)
    ok = np.isfinite(det) & (np.abs(det) > 1e-14)
    step = np.full((n, K), np.nan)
    if ok.any():
        step[ok] = np.linalg.solve(A[ok], residual.T[ok][..., None])[..., 0]
    return step.T


def determinant(J: np.ndarray) -> np.ndarray:
    """det(I − J) at every angle: zero where the friction equilibrium z = G(z) has no unique solution."""
    return np.linalg.det(np.eye(J.shape[0])[None] - np.moveaxis(J, -1, 0))


def bound_ratio(fmap: FrictionMap) -> np.ndarray:
    """ρ(A), A_pq = |c_p|·‖∂r_p/∂z_q‖: |G(z) − G(0)| ≤ A|z| entrywise, so where ρ(A) < 1 no nonzero friction
    loads sustain themselves without a load (z = tH(z), t ≤ 1, needs ρ(A) ≥ 1, Collatz–Wielandt): no jam.
    Where the bound ρ(A) ≤ min(‖A‖∞, ‖A‖₁) is below 1 that bound is returned instead (the decision ≥ 1 is
    the same; the eigenvalues are computed only where it is not)."""
    A = np.abs(fmap.coefficient)[:, None] * np.hypot(fmap.slope[..., 0], fmap.slope[..., 1])
    bound = np.minimum(A.sum(axis=1).max(axis=0), A.sum(axis=0).max(axis=0))
    ratio = bound.copy()
    where = ~(bound < 1)
    if where.any():
        ratio[where] = spectral_radius(A[:, :, where])
    return ratio


def solve(fmap: FrictionMap, tolerance: float, budget: float | None = None, jams: bool = True,
          ratios: bool = True) -> Solved:
    """z = G(z) at every angle, compiled (groups/compiled.py): the decisions of ``solve_reference``, angle by
    angle, equal to it to rounding; ``budget`` is looked at between blocks of angles.  The series' ratio q at
    the answer is computed afterwards for all the angles that do not lock at once (NaN where they lock)."""
    K, n = fmap.coefficient.shape
    if K == 0:                                 # without friction the first approximation is the equilibrium
        none = np.zeros(n, bool)
        return Solved(np.zeros((0, n)), np.zeros(n), none, np.ones(n, bool), np.zeros(n), 0)
    deadline = time.perf_counter() + (budget if budget is not None else np.inf)
    z, locked, converged, error, iterations = compiled.solve(fmap.base, fmap.lever, fmap.coefficient, tolerance,
                                                             deadline, jams)
    todo = np.isfinite(fmap.base).all(axis=(0, 2)) & np.isfinite(fmap.lever).all(axis=(1, 2, 3))
    ratio = np.where(todo, np.nan, 0.0)
    if ratios and (todo & ~locked).any():     # q at the answer, all angles at once (as the reference's)
        free = todo & ~locked
        _, J, _ = fmap.take(free).evaluate(z[:, free])
        ratio[free] = spectral_radius(J)
    return Solved(z, ratio, locked, converged, error, iterations)


def solve_reference(fmap: FrictionMap, tolerance: float, budget: float | None = None, jams: bool = True,
                    ratios: bool = True) -> Solved:
    """The reference: z = G(z) at every angle at once in numpy (module docstring); ``budget``: a wall-clock bound (s), the angles it leaves are
    reported unconverged, never locked; ``jams``: look for jams (False: a caller that only locates the
    equilibrium's corners, where a jam's angles are decided by another solve); ``ratios``: the series' ratio q
    at the answer (False: a caller that reads only z, the decisions and the error; ``ratio`` is NaN then).

    The equilibrium is first solved directly.  Where that lands on a root with det(I − J) ≤ 0 or does not
    converge, the branch is followed from zero friction (continuation); where it folds or ends, the mechanism
    locks.  A jam, friction loads that sustain themselves whatever the load (the crank-slider's rod inside the
    guide's friction angle), shows as the branch ending for the loads or for the loads reversed (for one guide
    the jam's sign decides which): so where ρ(A) ≥ 1 (bound_ratio) the branch is followed for the reversed
    loads too, and the mechanism locks where either ends."""
    K, n = fmap.coefficient.shape
    if K == 0:                                 # without friction the first approximation is the equilibrium
        none = np.zeros(n, bool)
        return Solved(np.zeros((0, n)), np.zeros(n), none, np.ones(n, bool), np.zeros(n), 0)
    iterations = 0
    deadline = time.perf_counter() + (budget if budget is not None else np.inf)

    def iterate(m, z, share, todo):
        """Newton (or the textbook's step) on z = share·G(z) at the angles ``todo``, from z."""
        z, error = z.copy(), np.where(todo, np.inf, 0.0)
        det, ratio, steps = np.ones(n), np.zeros(n), 0
        if todo.any():
            sub = m.take(todo)
            z_sub, error[todo], det[todo], ratio[todo], steps = newton(sub, z[:, todo], share)
            z[:, todo] = z_sub
        return z, error, det, ratio, steps

    def newton(m, z, share):
        """Each step on the angles still above ε_R only (the others keep their z)."""
        n_sub = z.shape[1]
        error = np.full(n_sub, np.inf)
        steps = 0
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
            while steps < NEWTON_CAP and time.perf_counter() < deadline:
                active = np.flatnonzero(~(error <= tolerance) & np.isfinite(z).all(0))
                if not active.size:
                    break
                steps += 1
                here = m.take(active)
                za = z[:, active]
                G, J, _ = here.evaluate(za)
                G, J = share * G, share * J
                step = newton_step(J, G - za)
                usable = np.isfinite(step).all(0)
                candidates = [za + np.where(usable, step, 0.0), G]
                left = [here.change(share * here.apply(c) - c) for c in candidates]
                settled = left[0] <= tolerance * np.abs(here.reactions(candidates[0])).max(axis=(0, 2))
                better = usable & ((left[0] <= np.where(np.isfinite(left[1]), left[1], np.inf)) | settled)
                chosen = np.where(better, candidates[0], candidates[1])
                q = np.zeros(better.size)              # the series' ratio, needed where the textbook's step was taken
                if (~better).any():
                    q[~better] = spectral_radius(J[:, :, ~better])
                scale = np.abs(here.reactions(chosen)).max(axis=(0, 2))
                moved = here.change(chosen - za) / np.where(scale > 0, scale, 1.0)
                z[:, active] = chosen
                estimate = np.where(better, moved, np.where(q < 1, moved * q / (1 - q), np.inf))
                error[active] = np.where(np.isfinite(estimate), estimate, np.inf)
        G, J, _ = m.evaluate(z)
        return z, error, determinant(share * J), spectral_radius(share * J) if ratios else np.full(n_sub, np.nan), \
            steps

    def follow(m, todo):
        """The branch from zero friction in CONTINUATION shares; where it is lost (folds or ends)."""
        nonlocal iterations
        z, lost = np.zeros((K, n)), np.zeros(n, bool)
        error, ratio = np.full(n, np.inf), np.zeros(n)
        for share in np.linspace(0, 1, CONTINUATION + 1)[1:]:
            z, error, det, ratio, steps = iterate(m, z, share, todo & ~lost)
            iterations += steps
            if time.perf_counter() >= deadline:             # out of time: undecided, not lost
                return z, np.where(lost, error, np.inf), ratio, lost, todo & ~lost
            lost |= todo & ~((error <= tolerance) & (det > 0))
        return z, error, ratio, lost, np.zeros(n, bool)

    todo = np.isfinite(fmap.base).all(axis=(0, 2)) & np.isfinite(fmap.lever).all(axis=(1, 2, 3))
    z, error, det, ratio, iterations = iterate(fmap, np.zeros((K, n)), 1.0, todo)
    astray = todo & ~((error <= tolerance) & (det > 0))
    locked = np.zeros(n, bool)
    if astray.any():
        followed, f_error, f_ratio, lost, _ = follow(fmap, astray)
        kept = astray & ~lost
        z = np.where(kept, followed, z)
        error, ratio = np.where(kept, f_error, error), np.where(kept, f_ratio, ratio)
        locked |= lost
    suspect = todo & ~locked & (bound_ratio(fmap) >= 1) if jams else np.zeros(n, bool)
    if suspect.any():
        _, _, _, jammed, undecided = follow(FrictionMap(-fmap.base, fmap.lever, fmap.coefficient), suspect)
        locked |= jammed
        error = np.where(undecided, np.inf, error)         # out of time before the jam was decided
    converged = todo & ~locked & (error <= tolerance)
    return Solved(z, ratio, locked, converged, error, iterations)
