"""The friction equilibrium z = G(z) of friction.py solved angle by angle in compiled code (numba).

The same decisions as the numpy reference ``friction.solve_reference``, in the same order, for one angle at a
time (each angle's solve there never reads another angle's): Newton's method on z = s·G(z) with the
generalised Jacobian, each step taking the Newton point or the textbook's step z ← s·G(z), whichever leaves
the smaller change of the reactions; the error left after a Newton correction bounded by that correction, after
a textbook step by q/(1 − q) of it (q the spectral radius of s·J); where the direct solve (s = 1) does not
reach a root with det(I − J) > 0, the branch followed from zero friction in CONTINUATION shares, the angle
locking where it is lost; where the bound ρ(A) ≥ 1 allows a jam, the branch followed for the loads reversed
too.  Only the arithmetic differs: a K × K LU with partial pivoting of its own for det(I − s·J) and the Newton
step (LAPACK's in the reference), so the two agree to rounding (tests/test_group_friction_compiled.py).

The wall-clock budget is checked between blocks of angles (BLOCK): the angles it leaves are reported
unconverged, never locked (a work bound only).  ``certified_normals`` proves, without the solve, where the
prismatic pairs' normal forces keep their frictionless signs (for bracketing M_T's corners).
"""
from __future__ import annotations

import time

import numpy as np
from numba import njit

from . import influence
from .dense import i_minus, lu, lu_solve, norm, spectral_radius

NEWTON_CAP = 40           # Newton steps per solve (friction.py's module docstring)
CONTINUATION = 32         # shares of the friction switched on from zero where the direct solve went astray
BLOCK = 256               # angles between two looks at the clock (≲ 0.1 s even where every angle is followed)
SINGULAR_DET = 1e-14      # |det(I − J)| at or below which the Newton step is not taken (as the reference's)
POWER_STEPS = 50          # power steps on the jam bound's matrix before its eigenvalues are computed


@njit(cache=True)
def _product(L, z, out):
    """out_j = Σ_q L[q, j] z_q, summed in the order of q (j = 2p + k: the k-th coordinate of pair p)."""
    for j in range(out.size):
        out[j] = 0.0
    for q in range(z.size):
        zq = z[q]
        for j in range(out.size):
            out[j] += L[q, j] * zq


@njit(cache=True)
def _reactions(base, L, z, out):
    """r_p(z) = base_p + Σ_q (∂r_p/∂z_q) z_q, flat (2K,)."""
    _product(L, z, out)
    for j in range(out.size):
        out[j] = base[j] + out[j]


@njit(cache=True)
def _change(L, dz, work):
    """max_{p,k} |Σ_q (∂r_p/∂z_q)_k dz_q|: NaN if any is NaN (as numpy's max)."""
    _product(L, dz, work)
    return _largest(work)


@njit(cache=True)
def _largest(r):
    """max_j |r_j|, NaN if any is NaN (as numpy's max)."""
    big = 0.0
    for j in range(r.size):
        a = abs(r[j])
        if a != a:
            return np.nan
        if a > big:
            big = a
    return big


@njit(cache=True)
def _apply(base, L, coef, z, share, r, out):
    """out = share·G(z) (3.3), r the reactions at z."""
    _reactions(base, L, z, r)
    for p in range(z.size):
        out[p] = share * (coef[p] * norm(r[2 * p], r[2 * p + 1]))


@njit(cache=True)
def _jacobian(L, coef, share, r, G, J):
    """G = share·G(z) and J = share·∂G/∂z from the reactions r at z (friction.FrictionMap.evaluate)."""
    K = G.size
    for p in range(K):
        length = norm(r[2 * p], r[2 * p + 1])
        u0, u1 = 0.0, 0.0
        if length > 0:
            u0, u1 = r[2 * p] / length, r[2 * p + 1] / length
        G[p] = share * (coef[p] * length)
        for q in range(K):
            J[p, q] = share * (coef[p] * (u0 * L[q, 2 * p] + u1 * L[q, 2 * p + 1]))


@njit(cache=True)
def _newton(base, L, coef, z, share, tolerance, w):
    """Newton (or the textbook's step) on z = share·G(z) from z (in place): (error, det(I − share·J), steps),
    friction.solve_reference's ``newton`` for one angle."""
    r, r0, r1, work, G, J, A, piv, step, c0, c1, t = w
    K = z.size
    error = np.inf
    steps = 0
    _reactions(base, L, z, r)
    while steps < NEWTON_CAP:
        if error <= tolerance:
            break
        finite = True
        for p in range(K):
            if not np.isfinite(z[p]):
                finite = False
        if not finite:
            break
        steps += 1
        _jacobian(L, coef, share, r, G, J)
        i_minus(J, A)
        det = lu(A, piv)
        usable = np.isfinite(det) and abs(det) > SINGULAR_DET
        if usable:
            for p in range(K):
                step[p] = G[p] - z[p]
            lu_solve(A, piv, step)
            for p in range(K):
                if not np.isfinite(step[p]):
                    usable = False
        for p in range(K):
            c0[p] = z[p] + step[p] if usable else z[p]
            c1[p] = G[p]
        _apply(base, L, coef, c0, share, r0, t)
        for p in range(K):
            t[p] -= c0[p]
        left0 = _change(L, t, work)
        better = usable and left0 <= tolerance * _largest(r0)     # settled: the textbook's step is not needed
        if not better:
            _apply(base, L, coef, c1, share, r1, t)
            for p in range(K):
                t[p] -= c1[p]
            left1 = _change(L, t, work)
            better = usable and left0 <= (left1 if np.isfinite(left1) else np.inf)
        q = 0.0
        if not better:
            q = spectral_radius(J)
        for p in range(K):
            chosen = c0[p] if better else c1[p]
            t[p] = chosen - z[p]
            z[p] = chosen
        r[:] = r0 if better else r1                  # the reactions at the new z
        scale = _largest(r)
        moved = _change(L, t, work) / (scale if scale > 0 else 1.0)
        if better:
            estimate = moved
        elif q < 1:
            estimate = moved * q / (1 - q)
        else:
            estimate = np.inf
        error = estimate if np.isfinite(estimate) else np.inf
    _jacobian(L, coef, share, r, G, J)
    i_minus(J, A)
    det = lu(A, piv)
    return error, det, steps


@njit(cache=True)
def _follow(base, L, coef, shares, tolerance, w, z, steps_out):
    """The branch from zero friction over ``shares``: (lost, error) at the last share; z in place."""
    for p in range(z.size):
        z[p] = 0.0
    error = np.inf
    for s in range(shares.size):
        error, det, steps = _newton(base, L, coef, z, shares[s], tolerance, w)
        steps_out[s] = steps
        if not (error <= tolerance and det > 0):
            return True, error
    return False, error


@njit(cache=True)
def _jam_bound(L, coef, A, x, y):
    """friction.bound_ratio at one angle (its entries finite), for the decision ρ(A) ≥ 1 only: min(‖A‖∞, ‖A‖₁)
    where it is below 1; else the Collatz–Wielandt bounds min_i (Ax)_i/x_i ≤ ρ(A) ≤ max_i (Ax)_i/x_i of a
    nonnegative A at x > 0 (Horn & Johnson, Matrix Analysis, 8.1.26), x from power steps, until one of them
    decides; where none does within POWER_STEPS, ρ(A) itself (the eigenvalues, as the reference)."""
    K = coef.size
    for p in range(K):
        for q in range(K):
            A[p, q] = abs(coef[p]) * norm(L[q, 2 * p], L[q, 2 * p + 1])
    bound = min(A.sum(axis=1).max(), A.sum(axis=0).max())
    if bound < 1:
        return bound
    for p in range(K):
        x[p] = 1.0
    for _ in range(POWER_STEPS):
        low, high, top = np.inf, 0.0, 0.0
        for p in range(K):
            s = 0.0
            for q in range(K):
                s += A[p, q] * x[q]
            y[p] = s
            low, high, top = min(low, s / x[p]), max(high, s / x[p]), max(top, s)
        if high < 1 or low >= 1:
            return high if high < 1 else low
        if not top > 0:
            break
        for p in range(K):
            x[p] = y[p] / top
            if not x[p] > 0:                      # a zero entry: the bounds need x > 0
                return spectral_radius(A)
    return spectral_radius(A)


@njit(cache=True)
def solve_block(base, lever, coef, tolerance, jams, shares, first, last,
                z, locked, converged, error, direct_steps, follow_steps, jam_steps):
    """Angles first … last − 1 (base (N, K, 2), lever (N, K, 2, K), coef (N, K)); the outputs in place."""
    K = coef.shape[1]
    w = (np.empty(2 * K), np.empty(2 * K), np.empty(2 * K), np.empty(2 * K), np.empty(K), np.empty((K, K)),
         np.empty((K, K)), np.empty(K, np.int64), np.zeros(K), np.empty(K), np.empty(K), np.empty(K))
    followed, b, reversed_base, L = np.empty(K), np.empty(2 * K), np.empty(2 * K), np.empty((K, 2 * K))
    bound, x, y = np.empty((K, K)), np.empty(K), np.empty(K)
    for n in range(first, last):
        todo = True
        for p in range(K):
            for k in range(2):
                b[2 * p + k] = base[n, p, k]
                if not np.isfinite(base[n, p, k]):
                    todo = False
                for q in range(K):
                    L[q, 2 * p + k] = lever[n, p, k, q]
                    if not np.isfinite(lever[n, p, k, q]):
                        todo = False
        if not todo:
            continue
        c = coef[n]
        zn = z[n]
        for p in range(K):
            zn[p] = 0.0
        e, det, steps = _newton(b, L, c, zn, 1.0, tolerance, w)
        direct_steps[n] = steps
        error[n] = e
        if not (e <= tolerance and det > 0):                   # astray: follow the branch from zero friction
            lost, fe = _follow(b, L, c, shares, tolerance, w, followed, follow_steps[n])
            if lost:
                locked[n] = True
            else:
                zn[:] = followed
                error[n] = fe
        if jams and not locked[n] and _jam_bound(L, c, bound, x, y) >= 1:
            for j in range(2 * K):
                reversed_base[j] = -b[j]
            jammed, _ = _follow(reversed_base, L, c, shares, tolerance, w, followed, jam_steps[n])
            locked[n] = jammed
        converged[n] = not locked[n] and error[n] <= tolerance


def solve(base: np.ndarray, lever: np.ndarray, coefficient: np.ndarray, tolerance: float,
          deadline: float = np.inf, jams: bool = True):
    """z = G(z) at every angle (base (K, N, 2), lever (N, K, 2, K), coefficient (K, N), as friction.FrictionMap):
    (z (K, N), locked, converged, error, iterations) as friction.solve_reference's, the angles the deadline
    (time.perf_counter()) leaves unconverged (error ∞)."""
    K, n = coefficient.shape
    b = np.ascontiguousarray(base.transpose(1, 0, 2))
    c = np.ascontiguousarray(coefficient.T)
    shares = np.linspace(0, 1, CONTINUATION + 1)[1:]
    z, error = np.zeros((n, K)), np.zeros(n)
    locked, converged = np.zeros(n, bool), np.zeros(n, bool)
    direct = np.zeros(n, np.int64)
    follow, jam = np.zeros((n, shares.size), np.int64), np.zeros((n, shares.size), np.int64)
    for first in range(0, n, BLOCK):
        if time.perf_counter() >= deadline:                   # the work bound: unconverged, never locked
            error[first:] = np.inf
            break
        solve_block(b, np.ascontiguousarray(lever), c, tolerance, jams, shares, first, min(first + BLOCK, n),
                    z, locked, converged, error, direct, follow, jam)
    iterations = int(direct.max(initial=0) + follow.max(axis=0, initial=0).sum() + jam.max(axis=0, initial=0).sum())
    return z.T.copy(), locked, converged, error, iterations


@njit(cache=True)
def certified_normals(base, lever, coef, rows):
    """Where the sign of each prismatic pair's normal force with friction (pair rows ``rows``) is that of its
    normal force without, proved without solving (base (N, K, 2), lever (N, K, 2, K), coef (N, K)).

    With A_pq = |c_p|·‖∂r_p/∂z_q‖ and b_p = |c_p|·‖r_p(0)‖ the friction loads of any equilibrium satisfy
    |z| ≤ b + A|z| (3.3 and the triangle inequality).  A w > 0 with (I − A)w ≥ b proves ρ(A) < 1
    (Collatz–Wielandt: the equilibrium is unique and never locks, friction.bound_ratio) and |z| ≤ w ((I − A)⁻¹ ≥ 0);
    so |N(z) − N(0)| ≤ Σ_q |∂N/∂z_q| w_q =: δ, and where |N(0)| > δ (with a margin for ε_R and rounding) N(z) has
    the sign of N(0).  w is (I − A)⁻¹b, checked as above."""
    n, K = coef.shape
    ok = np.zeros(n, np.bool_)
    A, M, piv, b, w = np.empty((K, K)), np.empty((K, K)), np.empty(K, np.int64), np.empty(K), np.empty(K)
    for k in range(n):
        finite = True
        for p in range(K):
            for j in range(2):
                if not np.isfinite(base[k, p, j]):
                    finite = False
                for q in range(K):
                    if not np.isfinite(lever[k, p, j, q]):
                        finite = False
        if not finite:
            continue
        scale = 0.0
        for p in range(K):
            b[p] = abs(coef[k, p]) * norm(base[k, p, 0], base[k, p, 1])
            scale = max(scale, norm(base[k, p, 0], base[k, p, 1]))
            for q in range(K):
                A[p, q] = abs(coef[k, p]) * norm(lever[k, p, 0, q], lever[k, p, 1, q])
        top = b.max()
        for p in range(K):
            b[p] += 1e-12 * top + 1e-300                   # b > 0: the check below is then strict
        i_minus(A, M)
        if not lu(M, piv) > 0:
            continue
        w[:] = b
        lu_solve(M, piv, w)
        proved = True
        for p in range(K):
            left = w[p]
            for q in range(K):
                left -= A[p, q] * w[q]
            if not (w[p] > 0 and left >= b[p] * (1 - 1e-12)):
                proved = False
        if not proved:
            continue
        for row in rows:
            delta = 0.0
            for q in range(K):
                delta += abs(lever[k, row, 0, q]) * w[q]
            if not abs(base[k, row, 0]) > delta * (1 + 1e-9) + 1e-9 * scale:
                proved = False
        ok[k] = proved
    return ok


def warm_up() -> float:
    """Compile (or load from the disk cache) the friction solve, the sign proof and the groups' pass; seconds."""
    started = time.perf_counter()
    certified_normals(np.ones((2, 2, 2)), np.zeros((2, 2, 2, 2)), np.full((2, 2), 0.1), np.array([1]))
    influence.warm_up()
    lever = np.zeros((2, 2, 2, 2))
    lever[:, 0, 0, 1] = lever[:, 1, 0, 0] = 0.5
    base = np.ones((2, 2, 2))
    solve(base, lever, np.full((2, 2), 0.1), 1e-12)
    return time.perf_counter() - started
