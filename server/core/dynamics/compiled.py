"""The RK4-in-φ loop of the equation of motion compiled with numba: the same scalar arithmetic as the
reference loop in integrator.py, operation for operation, so the two agree to rounding.

    dT/dφ = M_φ(φ) + M_ω(ω, φ),  ω = √(2T/J(φ)),   dS/dφ = (∂M_ω/∂ω)/(J ω) · S     Eremyants (1.9), (1.13)

The speed-dependent moment i·M(iω) − β ω S(φ) (motors.py, Machine.speed_moment) is dispatched on a small
integer kind with its parameters in one float array (``speed_parameters``). Compiled code is cached on disk
(``cache=True``); ``warm_up`` compiles every signature the server uses, so no request waits for the JIT.
"""
from __future__ import annotations

import math
import time
from functools import lru_cache

import numpy as np
from numba import njit

from . import dop853
from .brent import brentq
from .speed_moment import (BETA, GEAR, INDUCTION, KLOSS, LINEAR, M0, M_MAX, M_NOMINAL,  # noqa: F401  (re-exported)
                           MOTOR_KINDS, NO_MOTOR, OMEGA_NOMINAL, OMEGA_SYNC, S_CRITICAL, SLOPE_B, speed_moment,
                           speed_parameters)

@njit(cache=True)
def _rate(J, base, sliding, speed, kind, p, j, T):
    """F(φ_j, T) and ∂F/∂T."""
    omega = math.sqrt(2.0 * T / J[j]) if T > 0.0 else 0.0
    if not speed:
        return base[j], 0.0
    moment, slope = speed_moment(kind, p, omega, sliding[j])
    return base[j] + moment, (slope / (J[j] * omega) if omega > 0.0 else 0.0)


@njit(cache=True)
def rk4_steps(phi, J, base, sliding, starts, speed, kind, p, T_nodes, t_nodes, first, steps):
    """Steps first … steps−1 of RK4 in φ, step k over the nodes starts[k] + 0, 1 (half step), 2, from
    T_nodes[first], t_nodes[first]; fills the following nodes. Returns (nodes filled, S, stall node index
    or −1). Stall detection and Simpson's t(φ) exactly as integrator.integrate's reference loop."""
    T, t, S = T_nodes[first], t_nodes[first], 1.0
    stall = -1
    count = first + 1
    for k in range(first, steps):
        j = starts[k]
        h = phi[j + 2] - phi[j]
        f1, g1 = _rate(J, base, sliding, speed, kind, p, j, T)
        f2, g2 = _rate(J, base, sliding, speed, kind, p, j + 1, T + 0.5 * h * f1)
        f3, g3 = _rate(J, base, sliding, speed, kind, p, j + 1, T + 0.5 * h * f2)
        f4, g4 = _rate(J, base, sliding, speed, kind, p, j + 2, T + h * f3)
        T_new = T + h * (f1 + 2 * f2 + 2 * f3 + f4) / 6
        if T_new <= 0.0 or min(T + 0.5 * h * f1, T + 0.5 * h * f2) < 0.0:
            stall = j
            break
        if T > 0.0 and 0.5 * (T + T_new) + h * (f1 - f4) / 8 <= 0.0:
            stall = j + 1
            break
        s1 = g1 * S
        s2 = g2 * (S + 0.5 * h * s1)
        s3 = g3 * (S + 0.5 * h * s2)
        s4 = g4 * (S + h * s3)
        S += h * (s1 + 2 * s2 + 2 * s3 + s4) / 6
        w0 = math.sqrt(2 * T / J[j])
        w1 = math.sqrt(2 * T_new / J[j + 2])
        if w0 == 0.0:
            t += 2 * h / w1
        else:
            T_mid = 0.5 * (T + T_new) + h * (f1 - f4) / 8
            w_half = math.sqrt(2 * max(T_mid, 0.0) / J[j + 1])
            t += h * (1 / w0 + 4 / w_half + 1 / w1) / 6
        T = T_new
        T_nodes[count] = T
        t_nodes[count] = t
        count += 1
    return count, S, stall


@njit(cache=True)
def rk4_cycles(phi, J, base, sliding, starts, speed, kind, p, T0, t0, steps, cycles, rtol, settle, T_out, t_out,
               counts, S_out, stalls):
    """Whole cycles of rk4_steps one after another, each from the last one's end (row n of T_out, t_out, counts,
    S_out, stalls: cycle n's nodes, nodes filled, S and stall node), until a stall, until the cycle-start energy
    settles (``settle``: |T_end − T_start| ≤ rtol·T_end, motion._cycles' test) or ``cycles`` cycles; returns the
    cycles run. The start-up's cycles without a Python call each (motion._cycles)."""
    T, t = T0, t0
    for n in range(cycles):
        T_out[n, 0] = T
        t_out[n, 0] = t
        count, S, stall = rk4_steps(phi, J, base, sliding, starts, speed, kind, p, T_out[n], t_out[n], 0, steps)
        counts[n], S_out[n], stalls[n] = count, S, stall
        if stall >= 0:
            return n + 1
        T_end = T_out[n, count - 1]
        if settle and abs(T_end - T) <= rtol * T_end:
            return n + 1
        T, t = T_end, t_out[n, count - 1]
    return cycles


@njit(cache=True, error_model="numpy")
def _periodic_omega(work, total, T0):
    """ω = √(2(T₀ + A)/I) with numpy's rules: x/0 = ±inf, √(negative) = NaN."""
    return np.sqrt(2 * (T0 + work) / total)


@njit(cache=True, error_model="numpy")
def _refined(work, total, T0, k, sign):
    """The parabola through sample k and its periodic neighbours when it bends the right way (flywheel._extreme)."""
    n = work.size - 1
    left = _periodic_omega(work[(k - 1) % n], total[(k - 1) % n], T0)
    mid = _periodic_omega(work[k], total[k], T0)
    right = _periodic_omega(work[(k + 1) % n], total[(k + 1) % n], T0)
    curvature = left - 2 * mid + right
    return mid - (right - left) ** 2 / (8 * curvature) if curvature * sign < 0 else mid


@njit(cache=True, error_model="numpy")
def _first_with_speed(work, total, T0, last, q_bound, above, speed):
    """The first sample up to ``last`` whose ω equals ``speed``; only samples whose ω² lies within 1e-15 of
    it (``q_bound``: the side given by ``above``) can, as √ rounds at most two neighbouring doubles to one."""
    for i in range(last + 1):
        q = 2 * (T0 + work[i]) / total[i]
        if (q >= q_bound if above else q <= q_bound) and np.sqrt(q) == speed:
            return i
    return last


@njit(cache=True, error_model="numpy")
def mean_of_extremes(work, total, T0):
    """(ω_max + ω_min)/2 of ω(φ) = √(2(T₀ + A(φ))/I(φ)), both extremes refined by a parabola: what
    flywheel.periodic_speed solves for, with the arithmetic of its numpy version (_extreme of the array)
    element for element, without the array: the first largest and smallest samples of the open cycle (a NaN
    counts as both, as in numpy's argmax). The scan compares ω² = 2(T₀ + A)/I (√ is monotone) and takes the
    square root only to find the first sample whose ω ties with the extreme."""
    n = work.size - 1
    q_max, q_min, k_max, k_min = -np.inf, np.inf, 0, 0
    for i in range(n):
        q = 2 * (T0 + work[i]) / total[i]
        if not q >= 0.0:                       # ω is NaN here: numpy's argmax stops at the first NaN
            return 0.5 * (_refined(work, total, T0, i, 1.0) + _refined(work, total, T0, i, -1.0))
        if q > q_max:
            q_max, k_max = q, i
        if q < q_min:
            q_min, k_min = q, i
    k_max = _first_with_speed(work, total, T0, k_max, q_max * (1 - 1e-15), True, np.sqrt(q_max))
    k_min = _first_with_speed(work, total, T0, k_min, q_min * (1 + 1e-15), False, np.sqrt(q_min))
    return 0.5 * (_refined(work, total, T0, k_max, 1.0) + _refined(work, total, T0, k_min, -1.0))


@njit(cache=True, error_model="numpy")
def _mean_error(T0, work, total, omega_mean):
    return mean_of_extremes(work, total, T0) - omega_mean


@njit(cache=True, error_model="numpy")
def periodic_level(work, total, omega_mean, xa, xb, xtol, rtol, iterations):
    """T₀ with ½(ω_max + ω_min) = ω_m on [xa, xb] (flywheel.periodic_speed): Brent's method, scipy's brentq
    ported line for line (brent.brentq), so that the root is the very double scipy finds.
    Returns (root, status): status 0 converged, 1 no convergence within ``iterations`` (scipy's RuntimeError),
    2 a NaN value of the function (scipy's ValueError), 3 no sign change on the bracket (scipy's ValueError)."""
    return brentq(_mean_error, (work, total, omega_mean), xa, xb, xtol, rtol, iterations)


@njit(cache=True, error_model="numpy")
def _vertex(values, sign):
    """numerics.parabola_extremum(values, sign) of a closed periodic grid, its arithmetic element for element:
    the first largest of sign·y over the open cycle (a NaN counts as largest, as in numpy's argmax), refined by
    the parabola through it and its periodic neighbours when that bends the right way."""
    n = values.size - 1
    k = 0
    best = sign * values[0]
    if not math.isnan(best):
        for i in range(1, n):
            y = sign * values[i]
            if math.isnan(y):
                k = i
                break
            if y > best:
                best, k = y, i
    left, mid, right = sign * values[(k - 1) % n], sign * values[k], sign * values[(k + 1) % n]
    curvature = left - 2 * mid + right
    top = mid - (right - left) ** 2 / (8 * curvature) if curvature < 0 else mid
    return sign * top


@njit(cache=True, error_model="numpy")
def speed_extremes(omega):
    """(ω_max, ω_min) of ω(φ) on a closed grid, each as numerics.parabola_extremum finds it."""
    return _vertex(omega, 1.0), _vertex(omega, -1.0)


@lru_cache(maxsize=1)
def warm_up() -> float:
    """Compile (or load from the disk cache) every signature the server calls: the RK4 loop here and
    DOP853 leaving rest (dop853.py); returns the seconds the first call took (later calls: at once).
    The server calls it at start; the computations with a wall-clock budget call it before their clock
    starts, so the JIT never eats a budget."""
    started = time.perf_counter()
    nodes = np.linspace(1.0, 2.0, 9)
    params = np.array([2.0, 0.1, 10.0, 0.1, 10.0, 90.0, 100.0, 20.0, 0.1])
    starts = 2 * np.arange(4, dtype=np.int64)
    for kind in (NO_MOTOR, LINEAR, INDUCTION, KLOSS):
        T_nodes, t_nodes = np.zeros(5), np.zeros(5)
        T_nodes[0] = 1.0
        for speed in (False, True):
            rk4_steps(nodes, nodes, nodes, nodes, starts, speed, kind, params, T_nodes, t_nodes, 0, 4)
    rk4_cycles(nodes, nodes, nodes, nodes, starts, True, LINEAR, params, 1.0, 0.0, 4, 2, 1e-6, True,
               np.zeros((2, 5)), np.zeros((2, 5)), np.zeros(2, np.int64), np.zeros(2), np.zeros(2, np.int64))
    mean_of_extremes(nodes, nodes, 1.0)
    periodic_level(nodes, nodes, 1.0, 0.0, 1.0, 1e-12, 1e-12, 100)
    speed_extremes(nodes)
    dop853.warm_up()
    return time.perf_counter() - started
