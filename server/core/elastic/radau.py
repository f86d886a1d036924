"""scipy's Radau IIA (scipy/integrate/_ivp/radau.py) ported into one compiled loop, for the stiff machines.

Radau IIA of order 5 (Hairer, Wanner, Solving ODE II, §IV.8) as scipy implements it: the same
constants (scipy's C, E, T, TI, P, μ), simplified Newton iterations on the transformed 3-stage
system with one real and one complex LU of (μ/h·I − J) (at most 6 iterations, the same convergence
rate test and tolerance max(10ε/rtol, min(0.03, √rtol))), the same error estimate (one more
solve, and a second one after a rejection), the same step-size prediction (the two-step
formula of predict_factor, safety 0.9·13/(12 + iterations)), the same rule for refreshing the
Jacobian (iterations > 2 and rate > 1e-3) and the same cubic collocation polynomial for the
starting guess and the samples.  The LU is a plain partial-pivoting one (n ≤ 9), not LAPACK's
getrf: equal in exact arithmetic, it differs from scipy's only in rounding.

One call integrates one chunk [t0, t_bound] from a fresh start and fills its samples, as dop853.chunk.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit
from scipy.integrate._ivp import radau as reference

from .compiled import jac, rhs
from .dop853 import FINISHED, TOO_SMALL_STEP, WORK_BOUND, initial_step

C = np.ascontiguousarray(reference.C)
E = np.ascontiguousarray(reference.E)
T = np.ascontiguousarray(reference.T)
TI = np.ascontiguousarray(reference.TI)
P = np.ascontiguousarray(reference.P)
MU_REAL = float(reference.MU_REAL)
MU_COMPLEX = complex(reference.MU_COMPLEX)
NEWTON_MAXITER = 6
MIN_FACTOR, MAX_FACTOR = 0.2, 10.0
EPS = float(np.finfo(float).eps)


@njit(cache=True)
def lu_factor(a, pivots):
    """In-place LU with partial pivoting (rows swapped by pivots), real or complex."""
    n = a.shape[0]
    for k in range(n):
        best, largest = k, abs(a[k, k])
        for i in range(k + 1, n):
            if abs(a[i, k]) > largest:
                best, largest = i, abs(a[i, k])
        pivots[k] = best
        if best != k:
            for j in range(n):
                a[k, j], a[best, j] = a[best, j], a[k, j]
        if a[k, k] != 0:
            for i in range(k + 1, n):
                a[i, k] /= a[k, k]
                for j in range(k + 1, n):
                    a[i, j] -= a[i, k] * a[k, j]


@njit(cache=True)
def lu_solve(lu, pivots, b):
    """x with LU x = b (the factors of lu_factor), returned as a new array."""
    n = lu.shape[0]
    x = b.copy()
    for k in range(n):
        if pivots[k] != k:
            x[k], x[pivots[k]] = x[pivots[k]], x[k]
    for i in range(n):
        for j in range(i):
            x[i] -= lu[i, j] * x[j]
    for i in range(n - 1, -1, -1):
        for j in range(i + 1, n):
            x[i] -= lu[i, j] * x[j]
        x[i] /= lu[i, i]
    return x


@njit(cache=True)
def factorise(J, h, lu_real, piv_real, lu_complex, piv_complex):
    """LU of μ_real/h·I − J and μ_complex/h·I − J."""
    n = J.shape[0]
    for i in range(n):
        for j in range(n):
            lu_real[i, j] = -J[i, j]
            lu_complex[i, j] = -J[i, j]
        lu_real[i, i] += MU_REAL / h
        lu_complex[i, i] += MU_COMPLEX / h
    lu_factor(lu_real, piv_real)
    lu_factor(lu_complex, piv_complex)


@njit(cache=True)
def collocation(kind, p, tab, t, y, h, Z0, scale, tol, lu_real, piv_real, lu_complex, piv_complex, Z, F, work):
    """solve_collocation_system: (converged, iterations, rate (−1: none), RHS calls); Z is the result."""
    n = y.size
    m_real, m_complex = MU_REAL / h, MU_COMPLEX / h
    W = np.zeros((3, n))
    for r in range(3):
        for i in range(n):
            total = 0.0
            for q in range(3):
                total += TI[r, q] * Z0[q, i]
            W[r, i] = total
    Z[:, :] = Z0
    dW = np.empty((3, n))
    f_real, f_complex = np.empty(n), np.empty(n, dtype=np.complex128)
    dW_norm_old, rate, converged, nfev, k = -1.0, -1.0, False, 0, 0
    for k in range(NEWTON_MAXITER):
        finite = True
        for r in range(3):
            for i in range(n):
                work[i] = y[i] + Z[r, i]
            rhs(kind, p, tab, t + C[r] * h, work, F[r])
            for i in range(n):
                finite = finite and math.isfinite(F[r, i])
        nfev += 3
        if not finite:
            break
        for i in range(n):
            f_real[i] = F[0, i] * TI[0, 0] + F[1, i] * TI[0, 1] + F[2, i] * TI[0, 2] - m_real * W[0, i]
            f_complex[i] = (F[0, i] * (TI[1, 0] + 1j * TI[2, 0]) + F[1, i] * (TI[1, 1] + 1j * TI[2, 1])
                            + F[2, i] * (TI[1, 2] + 1j * TI[2, 2]) - m_complex * (W[1, i] + 1j * W[2, i]))
        dW_real = lu_solve(lu_real, piv_real, f_real)
        dW_complex = lu_solve(lu_complex, piv_complex, f_complex)
        total = 0.0
        for i in range(n):
            dW[0, i], dW[1, i], dW[2, i] = dW_real[i], dW_complex[i].real, dW_complex[i].imag
            for r in range(3):
                total += (dW[r, i] / scale[i]) ** 2
        dW_norm = math.sqrt(total) / math.sqrt(3 * n)
        if dW_norm_old >= 0:
            rate = dW_norm / dW_norm_old
        if rate >= 0 and (rate >= 1 or rate ** (NEWTON_MAXITER - k) / (1 - rate) * dW_norm > tol):
            break
        for i in range(n):
            for r in range(3):
                W[r, i] += dW[r, i]
            for r in range(3):
                Z[r, i] = T[r, 0] * W[0, i] + T[r, 1] * W[1, i] + T[r, 2] * W[2, i]
        if dW_norm == 0 or (rate >= 0 and rate / (1 - rate) * dW_norm < tol):
            converged = True
            break
        dW_norm_old = dW_norm
    return converged, k + 1, rate, nfev


@njit(cache=True)
def predict_factor(h_abs, h_abs_old, error_norm, error_norm_old):
    """Hairer II §IV.8's step-size prediction (h_abs_old < 0 or error_norm_old < 0: none yet)."""
    if error_norm_old < 0 or h_abs_old < 0 or error_norm == 0:
        multiplier = 1.0
    else:
        multiplier = h_abs / h_abs_old * (error_norm_old / error_norm) ** 0.25
    if error_norm == 0:
        return math.inf
    return min(1.0, multiplier) * error_norm ** -0.25


@njit(cache=True)
def error_norm_of(error, y, y_new, atol, rtol):
    """RMS of errorᵢ/(atolᵢ + rtol·max(|yᵢ|, |y_newᵢ|)): scipy's Radau error norm."""
    total = 0.0
    for i in range(y.size):
        total += (error[i] / (atol[i] + max(abs(y[i]), abs(y_new[i])) * rtol)) ** 2
    return math.sqrt(total) / math.sqrt(y.size)


@njit(cache=True)
def chunk(kind, p, tab, t0, t_bound, y0, rtol, atol, samples, out, max_evaluations):
    """Integrate [t0, t_bound] from y0; out[:, m] = y(samples[m]).
    Returns (status, y at the end, accepted, rejected, RHS calls, Jacobians, LU decompositions)."""
    n = y0.size
    y, y_new, f, work = y0.copy(), np.empty(n), np.empty(n), np.empty(n)
    rhs(kind, p, tab, t0, y, f)
    stored_h = initial_step(kind, p, tab, t0, y, f, t_bound, rtol, atol, 3, work)
    nfev, njev, nlu, accepted, rejected, sample = 2, 1, 0, 0, 0, 0
    stored_h_old, stored_error_old = -1.0, -1.0
    newton_tol = max(10 * EPS / rtol, min(0.03, rtol ** 0.5))
    J = np.empty((n, n))
    jac(kind, p, tab, t0, y, J)
    current_jac, have_lu, have_sol = True, False, False
    lu_real, lu_complex = np.empty((n, n)), np.empty((n, n), dtype=np.complex128)
    piv_real, piv_complex = np.empty(n, dtype=np.int64), np.empty(n, dtype=np.int64)
    Z, Z0, F, Q = np.empty((3, n)), np.zeros((3, n)), np.empty((3, n)), np.zeros((n, 3))
    scale, ZE = np.empty(n), np.empty(n)
    sol_t, sol_h = t0, 1.0
    sol_y = y.copy()
    t = t0
    while t < t_bound:
        min_step = 10 * abs(np.nextafter(t, np.inf) - t)
        h_abs, h_abs_old, error_norm_old = stored_h, stored_h_old, stored_error_old
        if stored_h < min_step:
            h_abs, h_abs_old, error_norm_old = min_step, -1.0, -1.0
        step_rejected = False
        while True:
            if h_abs < min_step:
                return TOO_SMALL_STEP, y, accepted, rejected, nfev, njev, nlu
            t_new = t + h_abs
            if t_new > t_bound:
                t_new = t_bound
            h = t_new - t
            h_abs = abs(h)
            for r in range(3):
                if have_sol:              # the previous step's collocation polynomial, extrapolated
                    x = (t + h * C[r] - sol_t) / sol_h
                    for i in range(n):
                        Z0[r, i] = Q[i, 0] * x + Q[i, 1] * x * x + Q[i, 2] * x * x * x + sol_y[i] - y[i]
                else:
                    Z0[r, :] = 0.0
            for i in range(n):
                scale[i] = atol[i] + abs(y[i]) * rtol
            converged, iterations, rate = False, 0, -1.0
            while not converged:
                if not have_lu:
                    factorise(J, h, lu_real, piv_real, lu_complex, piv_complex)
                    nlu += 2
                    have_lu = True
                converged, iterations, rate, calls = collocation(kind, p, tab, t, y, h, Z0, scale, newton_tol,
                                                                 lu_real, piv_real, lu_complex, piv_complex, Z, F,
                                                                 work)
                nfev += calls
                if not converged:
                    if current_jac:
                        break
                    jac(kind, p, tab, t, y, J)
                    njev += 1
                    current_jac, have_lu = True, False
            if nfev > max_evaluations:
                return WORK_BOUND, y, accepted, rejected, nfev, njev, nlu
            if not converged:
                h_abs *= 0.5
                have_lu = False
                continue
            for i in range(n):
                y_new[i] = y[i] + Z[2, i]
                ZE[i] = (Z[0, i] * E[0] + Z[1, i] * E[1] + Z[2, i] * E[2]) / h
                work[i] = f[i] + ZE[i]
            error = lu_solve(lu_real, piv_real, work)
            error_norm = error_norm_of(error, y, y_new, atol, rtol)
            safety = 0.9 * (2 * NEWTON_MAXITER + 1) / (2 * NEWTON_MAXITER + iterations)
            if step_rejected and error_norm > 1:
                rhs(kind, p, tab, t, y + error, work)
                nfev += 1
                error = lu_solve(lu_real, piv_real, work + ZE)
                error_norm = error_norm_of(error, y, y_new, atol, rtol)
            if error_norm > 1:
                factor = safety * predict_factor(h_abs, h_abs_old, error_norm, error_norm_old)
                h_abs *= factor if factor > MIN_FACTOR else MIN_FACTOR
                have_lu = False
                step_rejected = True
                rejected += 1
            else:
                break
        recompute_jac = iterations > 2 and rate > 1e-3
        factor = safety * predict_factor(h_abs, h_abs_old, error_norm, error_norm_old)
        factor = factor if factor < MAX_FACTOR else MAX_FACTOR
        if not recompute_jac and factor < 1.2:
            factor = 1.0
        else:
            have_lu = False
        rhs(kind, p, tab, t_new, y_new, f)
        nfev += 1
        if recompute_jac:
            jac(kind, p, tab, t_new, y_new, J)
            njev += 1
            current_jac = True
        else:
            current_jac = False
        stored_h_old, stored_error_old = stored_h, error_norm
        stored_h = h_abs * factor
        for i in range(n):                # Q = Zᵀ P: y(t_old + x h) = y_old + Q (x, x², x³)
            for q in range(3):
                Q[i, q] = Z[0, i] * P[0, q] + Z[1, i] * P[1, q] + Z[2, i] * P[2, q]
        sol_t, sol_h, have_sol = t, t_new - t, True
        sol_y[:] = y
        accepted += 1
        while sample < samples.size and (samples[sample] <= t_new or t_new == t_bound):
            x = (samples[sample] - sol_t) / sol_h
            for i in range(n):
                out[i, sample] = Q[i, 0] * x + Q[i, 1] * x * x + Q[i, 2] * x * x * x + sol_y[i]
            sample += 1
        t = t_new
        y[:] = y_new
    return FINISHED, y, accepted, rejected, nfev, njev, nlu
