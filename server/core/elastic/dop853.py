"""scipy's DOP853 (scipy/integrate/_ivp/rk.py, common.py) ported line for line into one compiled loop.

Dormand–Prince 8(5,3) (Hairer, Nørsett, Wanner, Solving ODE I, §II.10): the same coefficients
(scipy's dop853_coefficients), the same error norm ‖err₅‖²|h| / √((‖err₅‖² + 0.01‖err₃‖²)·n) with
scale = atol + max(|y|, |y_new|)·rtol, the same step-size control (safety 0.9, factors 0.2 … 10,
exponent −1/8, no growth right after a rejection), the same initial step (select_initial_step,
error estimator order 7) and the same 7th-order dense output for the samples.  It calls the elastic
right-hand side compiled.rhs directly: numba caches no function passed in as an argument (it
recompiles in every process), so the loop is written for this model family.

One call integrates one chunk [t0, t_bound] from a fresh start, as one solve_ivp call does, and
fills the samples of the chunk (each from the step that ends at or after it, OdeSolution's rule);
it stops when the right-hand side has been called more than max_evaluations times.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit
from scipy.integrate._ivp import dop853_coefficients as coefficients

from .compiled import rhs

STAGES = coefficients.N_STAGES                 # 12
A = np.ascontiguousarray(coefficients.A)        # 16 × 16, rows 13–15 for the dense output
C = np.ascontiguousarray(coefficients.C)
B = np.ascontiguousarray(coefficients.B)
E3 = np.ascontiguousarray(coefficients.E3)
E5 = np.ascontiguousarray(coefficients.E5)
D = np.ascontiguousarray(coefficients.D)
SAFETY, MIN_FACTOR, MAX_FACTOR = 0.9, 0.2, 10.0
ERROR_EXPONENT = -1.0 / 8.0                     # −1/(error estimator order + 1)
FINISHED, WORK_BOUND, TOO_SMALL_STEP = 0, 1, 2


@njit(cache=True)
def rms(x):
    """‖x‖/√n (common.norm)."""
    total = 0.0
    for value in x:
        total += value * value
    return math.sqrt(total) / math.sqrt(x.size)


@njit(cache=True)
def initial_step(kind, p, tab, t0, y0, f0, t_bound, rtol, atol, order, f1):
    """common.select_initial_step (Hairer I, §II.4); f1 is scratch for its one extra evaluation."""
    interval = abs(t_bound - t0)
    if interval == 0.0:
        return 0.0
    scale = atol + np.abs(y0) * rtol
    d0, d1 = rms(y0 / scale), rms(f0 / scale)
    h0 = 1e-6 if d0 < 1e-5 or d1 < 1e-5 else 0.01 * d0 / d1
    h0 = min(h0, interval)
    rhs(kind, p, tab, t0 + h0, y0 + h0 * f0, f1)
    d2 = rms((f1 - f0) / scale) / h0
    if d1 <= 1e-15 and d2 <= 1e-15:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / max(d1, d2)) ** (1 / (order + 1))
    return min(100 * h0, h1, interval)


@njit(cache=True)
def stage_state(K, s, a, y, h, out):
    """out = y + (Σ_{j<s} a_j K_j)·h: the state at which stage s is evaluated."""
    n = y.size
    for i in range(n):
        total = 0.0
        for j in range(s):
            total += K[j, i] * a[j]
        out[i] = y[i] + total * h


@njit(cache=True)
def chunk(kind, p, tab, t0, t_bound, y0, rtol, atol, samples, out, max_evaluations):
    """Integrate [t0, t_bound] from y0; out[:, m] = y(samples[m]).
    Returns (status, y at the end, accepted steps, rejected steps, RHS calls)."""
    n = y0.size
    K = np.empty((16, n))
    y, y_new, f, work = y0.copy(), np.empty(n), np.empty(n), np.empty(n)
    rhs(kind, p, tab, t0, y, f)
    h_abs = initial_step(kind, p, tab, t0, y, f, t_bound, rtol, atol, 7, work)
    nfev, accepted, rejected, sample = 2, 0, 0, 0
    t = t0
    F = np.empty((7, n))
    while t < t_bound:
        min_step = 10 * abs(np.nextafter(t, np.inf) - t)
        if h_abs < min_step:
            h_abs = min_step
        step_rejected = False
        while True:
            if h_abs < min_step:
                return TOO_SMALL_STEP, y, accepted, rejected, nfev
            t_new = t + h_abs
            if t_new > t_bound:
                t_new = t_bound
            h = t_new - t
            h_abs = abs(h)
            K[0] = f
            for s in range(1, STAGES):
                stage_state(K, s, A[s], y, h, work)
                rhs(kind, p, tab, t + C[s] * h, work, K[s])
            for i in range(n):
                total = 0.0
                for j in range(STAGES):
                    total += K[j, i] * B[j]
                y_new[i] = y[i] + h * total
            rhs(kind, p, tab, t + h, y_new, K[STAGES])
            nfev += STAGES
            err5, err3 = 0.0, 0.0
            for i in range(n):
                scale = atol[i] + max(abs(y[i]), abs(y_new[i])) * rtol
                e5, e3 = 0.0, 0.0
                for j in range(STAGES + 1):
                    e5 += K[j, i] * E5[j]
                    e3 += K[j, i] * E3[j]
                err5 += (e5 / scale) ** 2
                err3 += (e3 / scale) ** 2
            if err5 == 0.0 and err3 == 0.0:
                error_norm = 0.0
            else:
                error_norm = abs(h) * err5 / math.sqrt((err5 + 0.01 * err3) * n)
            if nfev > max_evaluations:
                return WORK_BOUND, y, accepted, rejected, nfev
            if error_norm < 1:
                if error_norm == 0:
                    factor = MAX_FACTOR
                else:
                    factor = SAFETY * error_norm ** ERROR_EXPONENT
                    factor = factor if factor < MAX_FACTOR else MAX_FACTOR
                if step_rejected and factor > 1.0:
                    factor = 1.0
                h_abs *= factor
                break
            factor = SAFETY * error_norm ** ERROR_EXPONENT       # Python's max(0.2, x): 0.2 unless x > 0.2
            h_abs *= factor if factor > MIN_FACTOR else MIN_FACTOR
            step_rejected = True
            rejected += 1
        accepted += 1
        if sample < samples.size and (samples[sample] <= t_new or t_new == t_bound):
            for s in range(STAGES + 1, 16):                       # the dense output's three extra stages
                stage_state(K, s, A[s], y, h, work)
                rhs(kind, p, tab, t + C[s] * h, work, K[s])
            nfev += 16 - STAGES - 1
            for i in range(n):
                delta = y_new[i] - y[i]
                F[0, i] = delta
                F[1, i] = h * K[0, i] - delta
                F[2, i] = 2 * delta - h * (K[STAGES, i] + K[0, i])
                for r in range(4):
                    total = 0.0
                    for j in range(16):
                        total += D[r, j] * K[j, i]
                    F[3 + r, i] = h * total
            while sample < samples.size and (samples[sample] <= t_new or t_new == t_bound):
                x = (samples[sample] - t) / h
                for i in range(n):
                    value = 0.0
                    for r in range(7):
                        value += F[6 - r, i]
                        value *= x if r % 2 == 0 else 1 - x
                    out[i, sample] = value + y[i]
                sample += 1
        t = t_new
        y[:] = y_new
        f[:] = K[STAGES]
    return FINISHED, y, accepted, rejected, nfev
