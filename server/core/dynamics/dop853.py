"""Leaving rest in time, compiled: scipy's DOP853 with its events, written out for numba.

    φ̇ = ω,   J(φ) ω̇ = M(φ) + M_ω(ω, φ) − ½ J′(φ) ω²                         Eremyants (1.13)

The same method as integrator.leave_rest's reference call of ``solve_ivp(method="DOP853", events=...)``
(Hairer, Nørsett & Wanner, Solving ODE I, §II.5 and §II.10; scipy.integrate._ivp.rk.DOP853): scipy's
coefficients, its initial step (select_initial_step), error norm (the 5th- and 3rd-order estimates
combined), step-size control (safety 0.9, factor 0.2…10, exponent −1/8), its 7th-order dense output, and
its event handling (a sign change over an accepted step, the root of the event on the dense output by
Brent's method to 4ε, a terminal event ending the run). The right-hand side comes from the Chebyshev table
of integrator.RestTable (barycentric formula, Berrut & Trefethen 2004 (5.4)) and the motor kernel of
compiled.py. Where the table does not apply (a stage outside [a, b]) the run reports it and the caller uses
the reference path.
"""
from __future__ import annotations

import math
import time

import numpy as np
from numba import njit, objmode
from scipy.integrate._ivp import dop853_coefficients as dop

from .speed_moment import speed_moment

STAGES = 12
A = np.ascontiguousarray(dop.A, dtype=np.float64)                 # 16 × 16, rows 13–15: dense-output stages
B = np.ascontiguousarray(dop.B, dtype=np.float64)
C = np.ascontiguousarray(dop.C, dtype=np.float64)
E3 = np.ascontiguousarray(dop.E3, dtype=np.float64)
E5 = np.ascontiguousarray(dop.E5, dtype=np.float64)
D = np.ascontiguousarray(dop.D, dtype=np.float64)
SAFETY, MIN_FACTOR, MAX_FACTOR = 0.9, 0.2, 10.0
ERROR_EXPONENT = -1.0 / 8.0                    # −1/(error estimator order 7 + 1)
EVENT_TOL = 4 * np.finfo(float).eps            # solve_ivp's xtol = rtol of Brent's method for events
BRENT_ITERATIONS = 100
CLOCK_EVERY = 16                               # steps between looks at the wall clock

DONE, OFF_TABLE, OUT_OF_TIME = 0, 1, 2          # outcomes of leave_rest


@njit(cache=True)
def _table_at(nodes, weights, values, phi, out):
    """J, J′, M(φ), S(φ) at φ from the barycentric interpolant through the Chebyshev nodes."""
    for j in range(nodes.size):
        if phi == nodes[j]:
            for c in range(4):
                out[c] = values[j, c]
            return
    total = 0.0
    for c in range(4):
        out[c] = 0.0
    for j in range(nodes.size):
        term = weights[j] / (phi - nodes[j])
        total += term
        for c in range(4):
            out[c] += term * values[j, c]
    for c in range(4):
        out[c] /= total


@njit(cache=True)
def _rhs(y, table, speed, kind, p, work, out):
    """(φ̇, ω̇); returns False when φ is outside the table's interval."""
    nodes, weights, values, a, b = table
    if not (a <= y[0] <= b):
        return False
    _table_at(nodes, weights, values, y[0], work)
    J, dJ, moment, sliding = work[0], work[1], work[2], work[3]
    if speed:
        moment += speed_moment(kind, p, y[1], sliding)[0]
    out[0] = y[1]
    out[1] = (moment - 0.5 * dJ * y[1] ** 2) / J
    return True


@njit(cache=True)
def _spacing(t):
    """nextafter(t, +∞) − t for t ≥ 0 (the least step scipy allows is ten of these)."""
    if t == 0.0:
        return 5e-324
    mantissa, exponent = math.frexp(t)
    return math.ldexp(1.0, exponent - 53) if exponent - 53 >= -1074 else 5e-324


@njit(cache=True)
def _norm(x0, x1):
    """scipy's RMS norm of a 2-vector."""
    return math.sqrt(x0 * x0 + x1 * x1) / math.sqrt(2.0)


@njit(cache=True)
def _dense(F, y_old, t_old, h, t, out):
    """scipy's Dop853DenseOutput at t."""
    x = (t - t_old) / h
    for c in range(2):
        value = 0.0
        for i in range(F.shape[0]):
            value += F[F.shape[0] - 1 - i, c]
            value *= x if i % 2 == 0 else 1 - x
        out[c] = value + y_old[c]


@njit(cache=True)
def _event(index, y, nodes_phi):
    """Event functions: φ − φ_k for the step nodes (index < count), ω for the stall (the last index)."""
    return y[1] if index == nodes_phi.size else y[0] - nodes_phi[index]


@njit(cache=True)
def _event_root(index, nodes_phi, F, y_old, t_old, t_new, h, y):
    """Brent's method (scipy's brentq) for the event's zero on the dense output between t_old and t_new."""
    xpre, xcur = t_old, t_new
    _dense(F, y_old, t_old, h, xpre, y)
    fpre = _event(index, y, nodes_phi)
    _dense(F, y_old, t_old, h, xcur, y)
    fcur = _event(index, y, nodes_phi)
    if fpre == 0.0:
        return xpre
    if fcur == 0.0:
        return xcur
    xblk, fblk, spre, scur = 0.0, 0.0, 0.0, 0.0
    for _ in range(BRENT_ITERATIONS):
        if fpre != 0.0 and fcur != 0.0 and (fpre < 0.0) != (fcur < 0.0):
            xblk, fblk = xpre, fpre
            spre = scur = xcur - xpre
        if abs(fblk) < abs(fcur):
            xpre, xcur, xblk = xcur, xblk, xcur
            fpre, fcur, fblk = fcur, fblk, fcur
        delta = (EVENT_TOL + EVENT_TOL * abs(xcur)) / 2
        sbis = (xblk - xcur) / 2
        if fcur == 0.0 or abs(sbis) < delta:
            return xcur
        if abs(spre) > delta and abs(fcur) < abs(fpre):
            if xpre == xblk:                                   # secant
                stry = -fcur * (xcur - xpre) / (fcur - fpre)
            else:                                              # inverse quadratic
                dpre = (fpre - fcur) / (xpre - xcur)
                dblk = (fblk - fcur) / (xblk - xcur)
                stry = -fcur * (fblk * dblk - fpre * dpre) / (dblk * dpre * (fblk - fpre))
            if 2 * abs(stry) < min(abs(spre), 3 * abs(sbis) - delta):
                spre, scur = scur, stry
            else:
                spre, scur = sbis, sbis
        else:
            spre, scur = sbis, sbis
        xpre, fpre = xcur, fcur
        xcur += scur if abs(scur) > delta else (delta if sbis > 0 else -delta)
        _dense(F, y_old, t_old, h, xcur, y)
        fcur = _event(index, y, nodes_phi)
    return xcur


@njit(cache=True)
def leave_rest(nodes, weights, values, a, b, speed, kind, p, nodes_phi, t_bound, rtol, atol, deadline,
               t_first, omega_first):
    """Integrate from rest at the table's start (φ = a, ω = 0, t = 0) towards t_bound. The table: J, J′,
    M(φ), S(φ) at the Chebyshev ``nodes`` of [a, b] with barycentric ``weights``; the motor: ``speed``,
    ``kind``, ``p`` of compiled.speed_parameters. Events: passing each of ``nodes_phi`` (the step nodes after
    the start; the last one terminal) and the stall (ω falling through 0, terminal). Fills t_first[k],
    omega_first[k] at the first passing of node k (NaN if it is not passed) and returns DONE, OFF_TABLE or
    OUT_OF_TIME (the wall clock passed ``deadline``, on time.perf_counter's scale)."""
    table = (nodes, weights, values, a, b)
    count = nodes_phi.size
    events = count + 1
    work = np.empty(4)
    y = np.array([a, 0.0])
    f = np.empty(2)
    K = np.empty((16, 2))
    F = np.empty((7, 2))
    stage_y = np.empty(2)
    stage_f = np.empty(2)
    y_new = np.empty(2)
    probe = np.empty(2)
    g = np.empty(events)
    g_new = np.empty(events)
    fired = np.zeros(events, dtype=np.int64)
    roots = np.empty(events)
    active = np.empty(events, dtype=np.int64)
    e5, e3 = np.zeros(2), np.zeros(2)
    t_first[:] = np.nan
    omega_first[:] = np.nan
    y[0] = a                                           # φ₀: the start of the table, at rest
    if not _rhs(y, table, speed, kind, p, work, f):
        return OFF_TABLE
    for e in range(events):
        g[e] = _event(e, y, nodes_phi)
    # select_initial_step (order 7)
    t = 0.0
    scale0 = atol + abs(y[0]) * rtol
    scale1 = atol + abs(y[1]) * rtol
    d0 = _norm(y[0] / scale0, y[1] / scale1)
    d1 = _norm(f[0] / scale0, f[1] / scale1)
    h0 = 1e-6 if d0 < 1e-5 or d1 < 1e-5 else 0.01 * d0 / d1
    h0 = min(h0, abs(t_bound - t))
    stage_y[0] = y[0] + h0 * f[0]
    stage_y[1] = y[1] + h0 * f[1]
    if not _rhs(stage_y, table, speed, kind, p, work, stage_f):
        return OFF_TABLE
    d2 = _norm((stage_f[0] - f[0]) / scale0, (stage_f[1] - f[1]) / scale1) / h0
    if d1 <= 1e-15 and d2 <= 1e-15:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / max(d1, d2)) ** (1.0 / 8.0)
    h_abs = min(100 * h0, h1, abs(t_bound - t))
    steps = 0
    while True:
        steps += 1
        if steps % CLOCK_EVERY == 1:                   # from the first step on: warm_up runs this block too
            with objmode(now="float64"):
                now = time.perf_counter()
            if now > deadline:
                return OUT_OF_TIME
        # one accepted step (RungeKutta._step_impl)
        min_step = 10 * _spacing(t)
        if h_abs < min_step:
            h_abs = min_step
        rejected = False
        while True:
            if h_abs < min_step:
                return DONE                                   # scipy: the step became too small, the run fails
            t_new = t + h_abs
            if t_new - t_bound > 0:
                t_new = t_bound
            h = t_new - t
            h_abs = abs(h)
            K[0, 0], K[0, 1] = f[0], f[1]
            for s in range(1, STAGES):
                for c in range(2):
                    dy = 0.0
                    for r in range(s):
                        dy += K[r, c] * A[s, r]
                    stage_y[c] = y[c] + dy * h
                if not _rhs(stage_y, table, speed, kind, p, work, stage_f):
                    return OFF_TABLE
                K[s, 0], K[s, 1] = stage_f[0], stage_f[1]
            for c in range(2):
                total = 0.0
                for r in range(STAGES):
                    total += K[r, c] * B[r]
                y_new[c] = y[c] + h * total
            if not _rhs(y_new, table, speed, kind, p, work, stage_f):
                return OFF_TABLE
            K[STAGES, 0], K[STAGES, 1] = stage_f[0], stage_f[1]
            e5[:] = 0.0
            e3[:] = 0.0
            for c in range(2):
                scale = atol + max(abs(y[c]), abs(y_new[c])) * rtol
                for r in range(STAGES + 1):
                    e5[c] += K[r, c] * E5[r]
                    e3[c] += K[r, c] * E3[r]
                e5[c] /= scale
                e3[c] /= scale
            e5_norm_2 = math.sqrt(e5[0] * e5[0] + e5[1] * e5[1]) ** 2
            e3_norm_2 = math.sqrt(e3[0] * e3[0] + e3[1] * e3[1]) ** 2
            if e5_norm_2 == 0 and e3_norm_2 == 0:
                error_norm = 0.0
            else:
                error_norm = abs(h) * e5_norm_2 / math.sqrt((e5_norm_2 + 0.01 * e3_norm_2) * 2)
            if error_norm < 1:
                factor = MAX_FACTOR if error_norm == 0 else min(MAX_FACTOR, SAFETY * error_norm ** ERROR_EXPONENT)
                if rejected:
                    factor = min(1.0, factor)
                h_abs *= factor
                break
            h_abs *= max(MIN_FACTOR, SAFETY * error_norm ** ERROR_EXPONENT)
            rejected = True
        t_old = t
        y_old0, y_old1 = y[0], y[1]
        t = t_new
        finished = t - t_bound >= 0
        # events of this step (solve_ivp: find_active_events, handle_events)
        for e in range(events):
            g_new[e] = _event(e, y_new, nodes_phi)
        n_active = 0
        for e in range(events):
            up = g[e] <= 0 and g_new[e] >= 0
            down = g[e] >= 0 and g_new[e] <= 0
            if (down if e == count else (up or down)):
                active[n_active] = e
                n_active += 1
        terminate = False
        if n_active > 0:
            # dense output: the three extra stages and the interpolant's coefficients
            y[0], y[1] = y_old0, y_old1
            for s in range(STAGES + 1, 16):
                for c in range(2):
                    dy = 0.0
                    for r in range(s):
                        dy += K[r, c] * A[s, r]
                    stage_y[c] = y[c] + dy * h
                if not _rhs(stage_y, table, speed, kind, p, work, stage_f):
                    return OFF_TABLE
                K[s, 0], K[s, 1] = stage_f[0], stage_f[1]
            for c in range(2):
                delta_y = y_new[c] - y[c]
                F[0, c] = delta_y
                F[1, c] = h * K[0, c] - delta_y
                F[2, c] = 2 * delta_y - h * (K[STAGES, c] + K[0, c])
                for i in range(4):
                    total = 0.0
                    for r in range(16):
                        total += D[i, r] * K[r, c]
                    F[3 + i, c] = h * total
            limit = n_active
            for i in range(n_active):
                e = active[i]
                fired[e] += 1
                roots[i] = _event_root(e, nodes_phi, F, y, t_old, t, h, probe)
            for i in range(n_active):
                if (active[i] == count - 1 or active[i] == count) and fired[active[i]] >= 1:
                    terminate = True
            if terminate:                       # in time order, up to the first terminal event
                order = np.argsort(roots[:n_active])
                sorted_active = active[:n_active][order].copy()
                sorted_roots = roots[:n_active][order].copy()
                for i in range(n_active):
                    active[i], roots[i] = sorted_active[i], sorted_roots[i]
                for i in range(n_active):
                    if active[i] == count - 1 or active[i] == count:
                        limit = i + 1
                        break
            for i in range(limit):
                e = active[i]
                if e < count and np.isnan(t_first[e]):
                    _dense(F, y, t_old, h, roots[i], probe)
                    t_first[e] = roots[i]
                    omega_first[e] = probe[1]
        for e in range(events):
            g[e] = g_new[e]
        if terminate or finished:
            return DONE
        y[0], y[1] = y_new[0], y_new[1]
        f[0], f[1] = K[STAGES, 0], K[STAGES, 1]


def warm_up() -> None:
    """Compile leave_rest (or load it from the disk cache): one run of a constant-inertia machine."""
    nodes = np.cos(np.pi * np.arange(5) / 4) * 0.5 + 0.5
    weights = np.array([0.5, -1.0, 1.0, -1.0, 0.5])
    values = np.ones((5, 4))
    params = np.array([2.0, 0.1, 10.0, 0.1, 10.0, 90.0, 100.0, 20.0, 0.1])
    leave_rest(nodes, weights, values, 0.0, 1.0, True, 1, params, np.array([0.1, 0.2]), 10.0, 1e-11, 1e-14,
               time.perf_counter() + 10.0, np.empty(2), np.empty(2))
