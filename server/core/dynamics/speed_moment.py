"""The speed-dependent moment of the equation of motion, compiled: i·M(iω) − β ω S(φ) (motors.py,
Machine.speed_moment) dispatched on a small integer kind with its parameters in one float array
(``speed_parameters``), shared by the RK4 loop (compiled.py) and DOP853 leaving rest (dop853.py)."""
from __future__ import annotations

import numpy as np
from numba import njit

NO_MOTOR, LINEAR, INDUCTION, KLOSS = 0, 1, 2, 3          # speed characteristics of motors.py (others: NO_MOTOR)
MOTOR_KINDS = {"linear": LINEAR, "induction": INDUCTION, "kloss": KLOSS}
# parameter vector: i, β, M₀, b, M_н, ω_н, ω_с, M_к, s_к
GEAR, BETA, M0, SLOPE_B, M_NOMINAL, OMEGA_NOMINAL, OMEGA_SYNC, M_MAX, S_CRITICAL = range(9)


def speed_parameters(machine) -> tuple[bool, int, np.ndarray]:
    """(speed dependent?, motor kind code, parameter vector) of a Machine for the compiled loop."""
    motor = machine.motor
    kind = MOTOR_KINDS.get(motor.kind, NO_MOTOR)
    params = np.array([machine.inertias.gear_ratio, machine.load.beta, motor.M0, motor.b, motor.M_nominal,
                       motor.omega_nominal, motor.omega_sync, motor.M_max, motor.s_critical], dtype=np.float64)
    return bool(machine.speed_dependent), kind, params


@njit(cache=True)
def speed_moment(kind, p, omega, sliding):
    """ω-dependent moment and ∂/∂ω: i·M(iω) − β ω S(φ); Machine.speed_moment and Motor.torque written out."""
    i = p[GEAR]
    moment = -p[BETA] * omega * sliding
    slope = -p[BETA] * sliding
    if kind == NO_MOTOR:
        return moment, slope
    w = i * omega
    if kind == LINEAR:                      # M = M₀ − b ω_m
        torque = p[M0] - p[SLOPE_B] * w
        torque_slope = -p[SLOPE_B] + 0 * w
    elif kind == INDUCTION:                 # M = M_н (ω_с − ω_m)/(ω_с − ω_н)
        linear = -p[M_NOMINAL] / (p[OMEGA_SYNC] - p[OMEGA_NOMINAL])
        torque = linear * (w - p[OMEGA_SYNC])
        torque_slope = linear + 0 * w
    else:                                   # Kloss: M = 2M_к/(s/s_к + s_к/s)
        s = (p[OMEGA_SYNC] - w) / p[OMEGA_SYNC]
        sk = p[S_CRITICAL]
        denominator = s * s + sk * sk
        torque = 2 * p[M_MAX] * s * sk / denominator
        torque_slope = -2 * p[M_MAX] * sk * (sk * sk - s * s) / denominator**2 / p[OMEGA_SYNC]
    moment += i * torque
    slope += i * i * torque_slope
    return moment, slope
