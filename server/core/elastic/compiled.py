"""The elastic models' right-hand sides and Jacobians compiled with numba, on plain arrays.

The same formulas as models.py (two masses, kinematic drive, three masses) and periodic_table.py
(cubic Hermite on a uniform periodic grid), written once more without Python objects so that an
integrator loop compiled beside them (dop853.py, radau.py) calls them with no interpreter per step.
A model is (kind, p, tab): kind one of TWO_MASS, KINEMATIC, THREE_MASS, or RIGID (the rigid machine
J(φ)ω̇ + ½J′(φ)ω² = M_д(ω) − M_c(φ, ω) with the motor-side masses J_extra added at P_J1, states φ, ω;
right-hand side only, for the rigid start-up that the elastic scenes compare with); p the numbers at the P_*
indices; tab the tables' nodes, rows INERTIA, STIFFNESS, LOAD, SLIDING (values) each followed by
its node slopes times the spacing h.  The motor is dispatched on an integer kind (MOTOR_KINDS) with
the formulas of dynamics/motors.py, reduced to the crank as (i·M(iω), i²·M′(iω)) (report.reduced_torque).
tests/test_elastic_compiled.py checks every function here against the Python models to 1e-12.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

TWO_MASS, KINEMATIC, THREE_MASS, RIGID = 0, 1, 2, 3
MOTOR_KINDS = {"constant": 0, "linear": 1, "induction": 2, "kloss": 3}
(P_J1, P_J2, P_C1, P_B1, P_B, P_SPEED, P_BETA, P_C, P_STIFF_TABLE, P_PERIOD, P_H, P_N, P_MOTOR, P_I, P_M0,
 P_MB, P_MN, P_WN, P_WS, P_MMAX, P_SK) = range(21)
INERTIA, STIFFNESS, LOAD, SLIDING = 0, 2, 4, 6


@dataclass(frozen=True)
class CompiledModel:
    """The arrays the compiled functions read: kind, numbers p, tables tab (8 × (n + 1))."""

    kind: int
    p: np.ndarray
    tab: np.ndarray
    size: int


def pack(model, motor, gear_ratio: float) -> CompiledModel:
    """Arrays of a models.TwoMass / ThreeMass whose drive is `motor` behind the gear ratio i."""
    from .models import ThreeMass
    from .periodic_table import PeriodicTable
    side = model.side
    three = isinstance(model, ThreeMass)
    kind = THREE_MASS if three else (KINEMATIC if model.kinematic else TWO_MASS)
    table = isinstance(side.stiffness, PeriodicTable)
    stiffness = side.stiffness if table else side.inertia      # a placeholder row, never read
    tab = np.ascontiguousarray(np.stack([side.inertia.nodes, side.inertia.tangents, stiffness.nodes,
                                         stiffness.tangents, side.load.nodes, side.load.tangents,
                                         side.sliding.nodes, side.sliding.tangents]))
    p = np.zeros(21)
    p[P_J1] = model.J1
    p[P_J2] = model.J2 if three else 0.0
    p[P_C1] = model.c1 if three else 0.0
    p[P_B1] = model.b1 if three else 0.0
    p[P_B] = model.b2 if three else model.b
    p[P_SPEED] = model.drive.speed or 0.0
    p[P_BETA] = side.beta
    p[P_C] = 0.0 if table else side.stiffness
    p[P_STIFF_TABLE] = 1.0 if table else 0.0
    p[P_PERIOD], p[P_H], p[P_N] = side.inertia.period, side.inertia.h, side.inertia.n
    p[P_MOTOR] = MOTOR_KINDS[motor.kind]
    p[P_I] = gear_ratio
    p[P_M0], p[P_MB], p[P_MN], p[P_WN] = motor.M0, motor.b, motor.M_nominal, motor.omega_nominal
    p[P_WS], p[P_MMAX], p[P_SK] = motor.omega_sync, motor.M_max, motor.s_critical
    return CompiledModel(kind, p, tab, model.size)


def pack_rigid(side, J_extra: float, motor, gear_ratio: float) -> CompiledModel:
    """Arrays of the rigid machine: the mechanism side's tables (a models.MechanismSide), J_extra kg·m² turning
    with the crank, `motor` behind the gear ratio i."""
    tab = np.zeros((8, side.inertia.n + 1))
    tab[INERTIA], tab[INERTIA + 1] = side.inertia.nodes, side.inertia.tangents
    tab[LOAD], tab[LOAD + 1] = side.load.nodes, side.load.tangents
    tab[SLIDING], tab[SLIDING + 1] = side.sliding.nodes, side.sliding.tangents
    p = np.zeros(21)
    p[P_J1], p[P_BETA] = J_extra, side.beta
    p[P_PERIOD], p[P_H], p[P_N] = side.inertia.period, side.inertia.h, side.inertia.n
    p[P_MOTOR], p[P_I] = MOTOR_KINDS[motor.kind], gear_ratio
    p[P_M0], p[P_MB], p[P_MN], p[P_WN] = motor.M0, motor.b, motor.M_nominal, motor.omega_nominal
    p[P_WS], p[P_MMAX], p[P_SK] = motor.omega_sync, motor.M_max, motor.s_critical
    return CompiledModel(RIGID, p, np.ascontiguousarray(tab), 2)


@njit(cache=True)
def cell(p, phi):
    """Grid cell k and the position s ∈ [0, 1] in it of φ (k = −1 for a non-finite φ)."""
    if not math.isfinite(phi):
        return -1, 0.0
    x = (phi % p[P_PERIOD]) / p[P_H]
    n = int(p[P_N])
    k = min(int(x), n - 1)
    return k, x - k


@njit(cache=True)
def value_slope(tab, row, k, s, h):
    """f, f′ of the Hermite cell (the arrangement of PeriodicTable.value_slope)."""
    if k < 0:
        return math.nan, math.nan
    y0, y1, m0, m1 = tab[row, k], tab[row, k + 1], tab[row + 1, k], tab[row + 1, k + 1]
    s2 = s * s
    d = y0 - y1
    value = y0 + s * m0 + s2 * (-3 * d - 2 * m0 - m1) + s2 * s * (2 * d + m0 + m1)
    slope = (6 * s2 - 6 * s) * d + (3 * s2 - 4 * s + 1) * m0 + (3 * s2 - 2 * s) * m1
    return value, slope / h


@njit(cache=True)
def value_slope_curvature(tab, row, k, s, h):
    """f, f′, f″ of the Hermite cell (the arrangement of PeriodicTable.__call__)."""
    if k < 0:
        return math.nan, math.nan, math.nan
    y0, y1, m0, m1 = tab[row, k], tab[row, k + 1], tab[row + 1, k], tab[row + 1, k + 1]
    s2, s3 = s * s, s * s * s
    value = (2 * s3 - 3 * s2 + 1) * y0 + (s3 - 2 * s2 + s) * m0 + (-2 * s3 + 3 * s2) * y1 + (s3 - s2) * m1
    slope = (6 * s2 - 6 * s) * (y0 - y1) + (3 * s2 - 4 * s + 1) * m0 + (3 * s2 - 2 * s) * m1
    curvature = (12 * s - 6) * (y0 - y1) + (6 * s - 4) * m0 + (6 * s - 2) * m1
    return value, slope / h, curvature / (h * h)


@njit(cache=True)
def motor_torque(p, w):
    """(i·M(iω), i²·M′(iω)) at crank speed ω: constant, linear, induction (linearised), Kloss."""
    kind, i = int(p[P_MOTOR]), p[P_I]
    if kind == 0:
        return i * p[P_M0], 0.0
    if kind == 1:
        return i * (p[P_M0] - p[P_MB] * i * w), -i * i * p[P_MB]
    wm = i * w
    if kind == 2:
        slope = -p[P_MN] / (p[P_WS] - p[P_WN])
        return i * (slope * (wm - p[P_WS])), i * i * slope
    s, sk = (p[P_WS] - wm) / p[P_WS], p[P_SK]
    denominator = s * s + sk * sk
    torque = 2 * p[P_MMAX] * s * sk / denominator
    slope = -2 * p[P_MMAX] * sk * (sk * sk - s * s) / denominator**2 / p[P_WS]
    return i * torque, i * i * slope


@njit(cache=True)
def mechanism_fast(p, tab, phi, omega, twist, rate):
    """MechanismSide.fast with F = c(φ)θ + bθ̇: (F, ω̇ of the mechanism, M_c)."""
    k, s = cell(p, phi)
    h = p[P_H]
    J, dJ = value_slope(tab, INERTIA, k, s, h)
    if p[P_STIFF_TABLE] != 0.0:
        c, dc = value_slope(tab, STIFFNESS, k, s, h)
    else:
        c, dc = p[P_C], 0.0
    m = value_slope(tab, LOAD, k, s, h)[0]
    if p[P_BETA] != 0.0:
        m += p[P_BETA] * omega * value_slope(tab, SLIDING, k, s, h)[0]
    force = c * twist + p[P_B] * rate
    return force, (force - 0.5 * dc * twist * twist - 0.5 * dJ * omega * omega - m) / J, m


@njit(cache=True)
def rhs(kind, p, tab, t, y, out):
    """y′ = f(t, y) into out (models.TwoMass.rhs, ThreeMass.rhs; RIGID: φ′ = ω, ω′ = (M_д − M_c − ½J′ω²)/J)."""
    b = p[P_B]
    if kind == RIGID:
        phi, w = y[0], y[1]
        k, s = cell(p, phi)
        h = p[P_H]
        J, dJ = value_slope(tab, INERTIA, k, s, h)
        m = value_slope(tab, LOAD, k, s, h)[0]
        if p[P_BETA] != 0.0:
            m += p[P_BETA] * w * value_slope(tab, SLIDING, k, s, h)[0]
        out[0] = w
        out[1] = (motor_torque(p, w)[0] - m - 0.5 * dJ * w * w) / (J + p[P_J1])
        return
    if kind == THREE_MASS:
        phi3, w3, twist2, rate2, twist1, rate1 = y[0], y[1], y[2], y[3], y[4], y[5]
        w1 = w3 + rate2 + rate1
        f1 = p[P_C1] * twist1 + p[P_B1] * rate1
        f2, w3_dot, mc = mechanism_fast(p, tab, phi3, w3, twist2, rate2)
        w2_dot = (f1 - f2) / p[P_J2]
        torque = motor_torque(p, w1)[0]
        w1_dot = (torque - f1) / p[P_J1]
        out[0], out[1], out[2], out[3], out[4] = w3, w3_dot, rate2, w2_dot - w3_dot, rate1
        out[5], out[6], out[7] = w1_dot - w2_dot, torque * w1, mc * w3
        out[8] = p[P_B1] * rate1 * rate1 + b * rate2 * rate2
        return
    twist, rate = y[2], y[3]
    if kind == KINEMATIC:
        speed = p[P_SPEED]
        phi2, w2 = speed * t - twist, speed - rate
    else:
        phi2, w2 = y[0], y[1]
    force, w2_dot, mc = mechanism_fast(p, tab, phi2, w2, twist, rate)
    if kind == KINEMATIC:
        out[0], out[1], out[2], out[3] = 0.0, 0.0, rate, -w2_dot
        out[4], out[5], out[6] = force * p[P_SPEED], mc * w2, b * rate * rate
        return
    w1 = w2 + rate
    torque = motor_torque(p, w1)[0]
    out[0], out[1], out[2], out[3] = w2, w2_dot, rate, (torque - force) / p[P_J1] - w2_dot
    out[4], out[5], out[6] = torque * w1, mc * w2, b * rate * rate


@njit(cache=True)
def mechanism_derivatives(p, tab, phi, omega, twist, rate):
    """c, c′ and ω̇'s partial derivatives (MechanismSide.acceleration with F = cθ + bθ̇), M_c, ∂M_c/∂φ, ∂M_c/∂ω."""
    k, s = cell(p, phi)
    h = p[P_H]
    J, dJ, ddJ = value_slope_curvature(tab, INERTIA, k, s, h)
    if p[P_STIFF_TABLE] != 0.0:
        c, dc, ddc = value_slope_curvature(tab, STIFFNESS, k, s, h)
    else:
        c, dc, ddc = p[P_C], 0.0, 0.0
    m, dm, _ = value_slope_curvature(tab, LOAD, k, s, h)
    sl, dsl, _ = value_slope_curvature(tab, SLIDING, k, s, h)
    beta = p[P_BETA]
    mc, dmc_phi, dmc_w = m + beta * omega * sl, dm + beta * omega * dsl, beta * sl
    force = c * twist + p[P_B] * rate
    value = (force - 0.5 * dc * twist * twist - 0.5 * dJ * omega * omega - mc) / J
    a_phi = (-0.5 * ddc * twist * twist - 0.5 * ddJ * omega * omega - dmc_phi) / J - value * dJ / J
    a_w = (-dJ * omega - dmc_w) / J
    a_twist = -dc * twist / J
    a_force = 1.0 / J
    return c, dc, a_phi, a_w, a_twist, a_force, mc, dmc_phi, dmc_w


@njit(cache=True)
def jac(kind, p, tab, t, y, out):
    """∂f/∂y into out (models.TwoMass.jac, ThreeMass.jac)."""
    out[:, :] = 0.0
    b = p[P_B]
    if kind == THREE_MASS:
        phi3, w3, twist2, rate2, rate1 = y[0], y[1], y[2], y[3], y[5]
        w1 = w3 + rate2 + rate1
        c2, dc2, a_phi, a_w, a_twist, a_force, mc, dmc_phi, dmc_w = mechanism_derivatives(p, tab, phi3, w3, twist2,
                                                                                          rate2)
        torque, slope = motor_torque(p, w1)
        J1, J2, c1, b1 = p[P_J1], p[P_J2], p[P_C1], p[P_B1]
        w3_row = (a_phi + a_force * dc2 * twist2, a_w, a_twist + a_force * c2, a_force * b, 0.0, 0.0)
        f2_row = (dc2 * twist2, 0.0, c2, b, 0.0, 0.0)
        f1_row = (0.0, 0.0, 0.0, 0.0, c1, b1)
        motor_row = (0.0, 1.0, 0.0, 1.0, 0.0, 1.0)
        out[0, 1] = out[2, 3] = out[4, 5] = 1.0
        for j in range(6):
            w2_j = (f1_row[j] - f2_row[j]) / J2
            w1_j = (slope * motor_row[j] - f1_row[j]) / J1
            out[1, j] = w3_row[j]
            out[3, j] = w2_j - w3_row[j]
            out[5, j] = w1_j - w2_j
            out[6, j] = (torque + slope * w1) * motor_row[j]
        out[7, 0], out[7, 1] = dmc_phi * w3, mc + dmc_w * w3
        out[8, 3], out[8, 5] = 2 * b * rate2, 2 * b1 * rate1
        return
    twist, rate = y[2], y[3]
    if kind == KINEMATIC:
        speed = p[P_SPEED]
        phi2, w2 = speed * t - twist, speed - rate
    else:
        phi2, w2 = y[0], y[1]
    c, dc, a_phi, a_w, a_twist, a_force, mc, dmc_phi, dmc_w = mechanism_derivatives(p, tab, phi2, w2, twist, rate)
    d_phi, d_w, d_twist, d_rate = a_phi + a_force * dc * twist, a_w, a_twist + a_force * c, a_force * b
    if kind == KINEMATIC:            # φ₂ = ωt − θ, ω₂ = ω − θ̇
        w1 = p[P_SPEED]
        out[2, 3] = 1.0
        out[3, 2] = d_phi - d_twist
        out[3, 3] = d_w - d_rate
        out[4, 2], out[4, 3] = (c - dc * twist) * w1, b * w1
        out[5, 2], out[5, 3] = -dmc_phi * w2, -(mc + dmc_w * w2)
        out[6, 3] = 2 * b * rate
        return
    w1 = w2 + rate
    torque, slope = motor_torque(p, w1)
    J1 = p[P_J1]
    out[0, 1] = 1.0
    out[1, 0], out[1, 1], out[1, 2], out[1, 3] = d_phi, d_w, d_twist, d_rate
    out[2, 3] = 1.0
    out[3, 0] = -dc * twist / J1 - d_phi
    out[3, 1] = slope / J1 - d_w
    out[3, 2] = -c / J1 - d_twist
    out[3, 3] = (slope - b) / J1 - d_rate
    out[4, 1] = out[4, 3] = torque + slope * w1
    out[5, 0], out[5, 1] = dmc_phi * w2, mc + dmc_w * w2
    out[6, 3] = 2 * b * rate


def rhs_of(model: CompiledModel):
    """f(t, y) as a Python callable returning a new array (for tests and the scipy reference path)."""
    def f(t, y):
        out = np.empty(model.size)
        rhs(model.kind, model.p, model.tab, float(t), np.ascontiguousarray(y, dtype=np.float64), out)
        return out
    return f


def jac_of(model: CompiledModel):
    """∂f/∂y(t, y) as a Python callable returning a new matrix."""
    def J(t, y):
        out = np.empty((model.size, model.size))
        jac(model.kind, model.p, model.tab, float(t), np.ascontiguousarray(y, dtype=np.float64), out)
        return out
    return J
