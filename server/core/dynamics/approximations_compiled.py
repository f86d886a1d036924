"""The steps of Lecture 10 §10.10 (successive_approximations.py) compiled with numba: the same loop, the same
sums in the same order (the trapezoid rule summed node after node, as numpy's cumsum does) and Brent's method
as scipy's brentq (brent.brentq, its port), so the laws agree with the plain loop to rounding.

Each step costs two root searches over the cycle's 2049 nodes: the shift c of the mean speed that makes the
cycle's work zero and the level T₀ of the energy equation (L4) whose cycle mean of ω is the one asked for.
In numpy each evaluation is a dozen array passes; here it is one loop, with no array made.
"""
from __future__ import annotations

import math
import time
from functools import lru_cache

import numpy as np
from numba import njit

from .brent import brentq
from .speed_moment import KLOSS, speed_moment

RUNNING, CONVERGED, NO_BALANCE, STOPS, ROOT_FAILED = 0, 1, 2, 3, 4   # how the loop ended
BALANCE, ENERGY = 0, 1                                                # the two functions Brent's method solves
ROWS = 4                                                              # ω_max, ω_min, mean M_д, change
QUADRATIC = 0.1             # a Newton step d leaves ~d²/(the bracket's width) (f″/f′ on its scale): below xtol
NEWTON_STEPS = 12           # more: Newton's method gives way to Brent's (never met on the scenes' machines)
BRENT_ITERATIONS = 100      # scipy's brentq default


@njit(cache=True)
def _cycle_mean(values, phi):
    """(1/Φ)∫ values dφ: cumulative_trapezoid's last value, summed in its order."""
    total = 0.0
    for j in range(phi.size - 1):
        total += 0.5 * (phi[j + 1] - phi[j]) * (values[j + 1] + values[j])
    return total / (phi[-1] - phi[0])


@njit(cache=True)
def _balance(shift, omega, phi, net_phi, sliding, kind, p):
    """The cycle mean of M_д,φ − M_с,φ + M(ω + c): zero where A_д = A_с over the cycle."""
    total, previous = 0.0, 0.0
    for j in range(phi.size):
        value = net_phi[j] + speed_moment(kind, p, omega[j] + shift, sliding[j])[0]
        if j > 0:
            total += 0.5 * (phi[j] - phi[j - 1]) * (value + previous)
        previous = value
    return total / (phi[-1] - phi[0])


@njit(cache=True)
def _energy_excess(T0, work, J, phi, mean):
    """The cycle mean of ω = √(2(T₀ + A)/I), less the mean asked for (successive_approximations.energy_law)."""
    total, previous = 0.0, 0.0
    for j in range(phi.size):
        value = math.sqrt(max(2 * (T0 + work[j]) / J[j], 0.0))
        if j > 0:
            total += 0.5 * (phi[j] - phi[j - 1]) * (value + previous)
        previous = value
    return total / (phi[-1] - phi[0]) - mean


@njit(cache=True)
def _balance_slope(shift, omega, phi, net_phi, sliding, kind, p):
    """_balance and its derivative in c, the cycle mean of ∂M/∂ω(ω + c), in one pass."""
    total, previous, total_slope, previous_slope = 0.0, 0.0, 0.0, 0.0
    for j in range(phi.size):
        moment, slope = speed_moment(kind, p, omega[j] + shift, sliding[j])
        value = net_phi[j] + moment
        if j > 0:
            half = 0.5 * (phi[j] - phi[j - 1])
            total += half * (value + previous)
            total_slope += half * (slope + previous_slope)
        previous, previous_slope = value, slope
    span = phi[-1] - phi[0]
    return total / span, total_slope / span


@njit(cache=True)
def _energy_slope(T0, work, J, phi, mean):
    """_energy_excess and its derivative in T₀, the cycle mean of 1/(I ω), in one pass."""
    total, previous, total_slope, previous_slope = 0.0, 0.0, 0.0, 0.0
    for j in range(phi.size):
        value = math.sqrt(max(2 * (T0 + work[j]) / J[j], 0.0))
        slope = 1.0 / (J[j] * value) if value > 0.0 else 0.0
        if j > 0:
            half = 0.5 * (phi[j] - phi[j - 1])
            total += half * (value + previous)
            total_slope += half * (slope + previous_slope)
        previous, previous_slope = value, slope
    span = phi[-1] - phi[0]
    return total / span - mean, total_slope / span


@njit(cache=True)
def _newton(which, guess, xa, xb, f_a, xtol, rtol, omega, phi, net_phi, sliding, kind, p, work, J, mean):
    """Newton's method on _value(which, ·) from ``guess``, kept inside the bracket [xa, xb] whose ends have
    values of opposite signs (f_a the value at xa < xb; a step that would leave it bisects instead); stops when
    a step is below xtol + rtol·|x|, Brent's tolerance, or when the error it leaves, d² times the curvature
    on the bracket's scale, is (QUADRATIC). (root, status): status 1 when NEWTON_STEPS did not reach it."""
    low, high, f_low = xa, xb, f_a
    x = min(max(guess, low), high)
    for _ in range(NEWTON_STEPS):
        if which == BALANCE:
            f, slope = _balance_slope(x, omega, phi, net_phi, sliding, kind, p)
        else:
            f, slope = _energy_slope(x, work, J, phi, mean)
        if f == 0.0:
            return x, 0
        if (f < 0) == (f_low < 0):
            low = x
        else:
            high = x
        step = -f / slope if slope != 0.0 else np.inf
        target = x + step
        newton = low < target < high
        if not newton:                          # not finite, or out of the bracket: bisect
            target = 0.5 * (low + high)
            step = target - x
        x = target
        if abs(step) <= xtol + rtol * abs(x) or (newton and step * step <= QUADRATIC * xtol * (xb - xa)):
            return x, 0
    return x, 1


@njit(cache=True)
def _value(x, which, omega, phi, net_phi, sliding, kind, p, work, J, mean):
    """_balance at the shift x (BALANCE) or _energy_excess at the level x (ENERGY): what Brent's method solves."""
    if which == BALANCE:
        return _balance(x, omega, phi, net_phi, sliding, kind, p)
    return _energy_excess(x, work, J, phi, mean)


@njit(cache=True)
def approximation_steps(phi, J, net_phi, sliding, kind, p, omega_operating, knee, sync, tol, limit,
                        laws, moments, rows):
    """The loop of successive_approximations: fills laws[k], moments[k] (ω^(k+1)(φ), M_д^(k+1)(φ)) and
    rows[k] (ROWS) step by step; returns (steps done, how it ended: RUNNING, CONVERGED, NO_BALANCE, STOPS or
    ROOT_FAILED, the step where it stopped)."""
    n = phi.size
    omega = np.full(n, omega_operating)
    shifted = np.empty(n)
    driving = np.empty(n)
    work = np.empty(n)
    J_max = J.max()
    T0 = 0.0
    for step in range(1, limit + 1):
        level = _cycle_mean(omega, phi)
        low, high = knee - level, sync - level
        f_low = _balance(low, omega, phi, net_phi, sliding, kind, p)
        if f_low * _balance(high, omega, phi, net_phi, sliding, kind, p) > 0:
            return step - 1, NO_BALANCE, step
        shift, status = _newton(BALANCE, 0.0, low, high, f_low, 1e-14 * omega_operating, 1e-15, omega, phi, net_phi,
                                sliding, kind, p, work, J, 0.0)
        if status != 0:
            shift, status = brentq(_value, (BALANCE, omega, phi, net_phi, sliding, kind, p, work, J, 0.0), low, high,
                                   1e-14 * omega_operating, 1e-15, BRENT_ITERATIONS)
        if status != 0:
            return step - 1, ROOT_FAILED, step
        for j in range(n):
            shifted[j] = omega[j] + shift
            driving[j] = speed_moment(kind, p, shifted[j], sliding[j])[0]
        total = 0.0
        work[0] = 0.0
        for j in range(n - 1):
            total += 0.5 * (phi[j + 1] - phi[j]) * ((net_phi[j + 1] + driving[j + 1]) + (net_phi[j] + driving[j]))
            work[j + 1] = total
        mean = level + shift
        lowest = -work[0]
        for j in range(n):
            lowest = max(lowest, -work[j])
        f_low = _energy_excess(lowest, work, J, phi, mean)
        if f_low > 0:
            return step - 1, STOPS, step
        top = lowest + 0.5 * J_max * (2 * mean) ** 2 + 1.0
        guess = T0 if step > 1 else 0.5 * _cycle_mean(J, phi) * mean * mean
        T0, status = _newton(ENERGY, guess, lowest, top, f_low, 1e-15 * top, 1e-15, omega, phi, net_phi, sliding,
                             kind, p, work, J, mean)
        if status != 0:
            T0, status = brentq(_value, (ENERGY, omega, phi, net_phi, sliding, kind, p, work, J, mean), lowest, top,
                                1e-15 * top, 1e-15, BRENT_ITERATIONS)
        if status != 0:
            return step - 1, ROOT_FAILED, step
        new = laws[step - 1]
        largest, total, w_max, w_min = 0.0, 0.0, -np.inf, np.inf
        for j in range(n):
            new[j] = math.sqrt(max(2 * (T0 + work[j]) / J[j], 0.0))
            largest = max(largest, abs(new[j] - omega[j]))
            total += new[j]
            w_max, w_min = max(w_max, new[j]), min(w_min, new[j])
        moments[step - 1, :] = driving
        change = largest / (total / n)
        rows[step - 1, 0], rows[step - 1, 1] = w_max, w_min
        rows[step - 1, 2], rows[step - 1, 3] = _cycle_mean(driving, phi), change
        omega = new.copy()
        if change < tol and step > 1:
            return step, CONVERGED, step
    return limit, RUNNING, limit


@lru_cache(maxsize=1)
def warm_up() -> float:
    """Compile (or load from the disk cache) the loop's one signature; the seconds it took."""
    started = time.perf_counter()
    phi = np.linspace(0.0, 2 * np.pi, 9)
    ones = np.ones(9)
    params = np.array([1.0, 0.0, 0.0, 0.0, 10.0, 90.0, 100.0, 20.0, 0.1])
    approximation_steps(phi, ones, -ones, 0 * ones, KLOSS, params, 95.0, 90.0, 100.0, 1e-8, 2,
                        np.empty((2, 9)), np.empty((2, 9)), np.empty((2, ROWS)))
    return time.perf_counter() - started
