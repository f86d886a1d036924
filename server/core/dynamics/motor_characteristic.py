"""The induction motor's reduced static characteristic M_д(ω₁) and the stability of an operating point
(Lecture 10 §10.9, Fig. 10.14).

Reduced to the crank by power equality, a motor torque M(ω_m) at ω_m = iω₁ gives M_д(ω₁) = i·M(iω₁).
The full curve is Kloss's formula (a standard addition, not in the lecture):

    M = 2M_к/(s/s_к + s_к/s),   s = (ω_с − ω_m)/ω_с,

with the points of Fig. 10.14: a (ω₁ = 0, the starting torque M_дп), b (the critical speed
ω₁к = ω_с(1 − s_к)/i, M_дmax = iM_к) and d (the synchronous speed ω₁с = ω_с/i, no torque).  bd is the
stable branch, ab the unstable one.  An operating point ω* is where M_д(ω*) = M_с(ω*); it is stable when

    dM_д/dω₁ < dM_с/dω₁   at ω*                                            Lecture 10 §10.9, Fig. 10.14

(a small rise of speed makes the resistance win and brings the speed back).  Above M_дmax there is no
operating point: the motor stalls.  Linearised through an operating point (ω₁н, M_дн) and ω₁с:

    M_д = b₁* + k₁* ω₁,  b₁* = M_дн ω₁с/(ω₁с − ω₁н),  k₁* = −M_дн/(ω₁с − ω₁н)       Lecture 10 (L30)

The print has b₁* = M_дн ω₁/(ω₁с − ω₁н) (ω₁ for ω₁с): ``linearised`` gives both, and the torque each
gives at ω₁с (zero only for the corrected form).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from .motors import Motor


@dataclass(frozen=True)
class OperatingPoint:
    """A root of M_д(ω) = M_с(ω) on one branch: speed (rad/s), moment (N·m), both slopes (N·m·s/rad)."""

    omega: float
    moment: float
    drive_slope: float
    load_slope: float
    branch: str                 # "stable" (bd) or "unstable" (ab)

    @property
    def stable(self) -> bool:
        """The criterion of Lecture 10 §10.9, Fig. 10.14: dM_д/dω < dM_с/dω."""
        return self.drive_slope < self.load_slope


def reduced_torque(motor: Motor, gear_ratio: float, omega):
    """M_д(ω₁) = i·M(iω₁) and dM_д/dω₁ = i²·M′(iω₁), reduced to the crank (power equality, Eremyants (1.17))."""
    torque, slope = motor.torque(gear_ratio * np.asarray(omega, float))
    return gear_ratio * torque, gear_ratio**2 * slope


def critical_speed(motor: Motor, gear_ratio: float) -> float:
    """ω₁к, point b of Fig. 10.14, where the stable branch ends: ω_с(1 − s_к)/i (Kloss); 0 for the linearised
    characteristic (L30), which is the stable branch alone."""
    if motor.kind == "kloss":
        return motor.omega_sync * (1 - motor.s_critical) / gear_ratio
    return 0.0


def characteristic(motor: Motor, gear_ratio: float, points: int = 241, extra=()) -> dict:
    """The curve from ω₁ = 0 to ω₁с on ``points`` speeds and the ``extra`` ones (operating points), with the
    branch of each point and the marked points a (start), b (maximum) and d (synchronous)."""
    sync = motor.omega_sync / gear_ratio
    knee = critical_speed(motor, gear_ratio)
    omega = np.unique(np.concatenate([np.linspace(0.0, sync, points), [knee], list(extra)]))
    moment, slope = reduced_torque(motor, gear_ratio, omega)
    start = float(reduced_torque(motor, gear_ratio, 0.0)[0])
    peak = float(reduced_torque(motor, gear_ratio, knee)[0])
    return {"omega": omega, "moment": moment, "slope": slope,
            "stable": np.where(omega >= knee, moment, np.nan), "unstable": np.where(omega <= knee, moment, np.nan),
            "start": {"omega": 0.0, "moment": start}, "maximum": {"omega": knee, "moment": peak},
            "synchronous": {"omega": sync, "moment": 0.0}}


def operating_points(motor: Motor, gear_ratio: float, load: float, load_slope: float = 0.0) -> list[OperatingPoint]:
    """Every root of M_д(ω) = load + load_slope·ω in (0, ω₁с): at most one on each branch (both monotone,
    the load's slope ≥ 0); none above M_дmax (stall)."""
    sync = motor.omega_sync / gear_ratio
    knee = critical_speed(motor, gear_ratio)

    def excess(w):
        return float(reduced_torque(motor, gear_ratio, w)[0]) - load - load_slope * w

    found = []
    for low, high, branch in ((knee, sync, "stable"), (0.0, knee, "unstable")):
        if high > low and excess(low) * excess(high) < 0:
            w = brentq(excess, low, high, xtol=1e-13 * sync, rtol=1e-14)
            moment, slope = reduced_torque(motor, gear_ratio, w)
            found.append(OperatingPoint(w, float(moment), float(slope), load_slope, branch))
    return found


def linearised(motor: Motor, gear_ratio: float, point: OperatingPoint) -> dict:
    """(L30) through the operating point taken as nominal, corrected and as printed: b₁*, k₁* and the torque
    each gives at ω₁с."""
    sync = motor.omega_sync / gear_ratio
    k = -point.moment / (sync - point.omega)
    corrected, printed = point.moment * sync / (sync - point.omega), point.moment * point.omega / (sync - point.omega)
    return {"k": k, "b": corrected, "b_printed": printed,
            "at_sync": corrected + k * sync, "at_sync_printed": printed + k * sync,
            "omega": np.array([0.0, sync]), "moment": np.array([corrected, corrected + k * sync])}
