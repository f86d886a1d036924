"""Independent checks for the kinematics tests: positions read off the drawn joints, and their derivatives.

The numeric core returns joint coordinates for drawing the linkage.  Here the position of
the output link 3 and of the intermediate link 2 is measured on those joints with plain
geometry (a slider's x, a link's direction by atan2), never taken from the core's own
position functions, and then differentiated by central finite differences with one step of
Richardson extrapolation.  The tests compare those derivatives with the closed-form
transfer functions u₃₁, u′₃₁, u₂₁, u′₂₁.
"""
from __future__ import annotations

import numpy as np

from server.core.mechanisms import MECHANISMS

# (name of the measured quantity, True if it is an angle that may wrap by 2π)
MEASURED = {
    "sine": (("yoke x", False), ("block height on the slot", False)),
    "slider_crank": (("slider x", False), ("rod angle ψ", True)),
    "slotted_link": (("lever angle ψ", True), ("block travel along the lever", False)),
    "four_bar": (("rocker angle φ₃", True), ("coupler angle φ₂", True)),
}


def joints(mechanism: str, p: dict[str, float], phi) -> dict[str, np.ndarray]:
    """Joint coordinates (n, 2) drawn by the core at crank angles ``phi`` (rad)."""
    phi = np.atleast_1d(np.asarray(phi, float))
    return MECHANISMS[mechanism].evaluate(p, phi, {"joints"}).joints


def measured_positions(mechanism: str, p: dict[str, float], phi) -> tuple[np.ndarray, np.ndarray]:
    """(output link 3, intermediate link 2) positions measured on the joints, same sense as the core's s, s2.

    sine:          yoke x (m),                 block y on the crank pin (m)
    slider_crank:  slider x_B (m),             rod angle ψ, clockwise: B − A = l₂(cos ψ, −sin ψ)
    slotted_link:  lever angle ψ, clockwise from the upward vertical at C,   block travel l₀ + l₁ − |BC|
    four_bar:      rocker angle φ₃ = arg(C − D), coupler angle φ₂ = arg(C − B), counter-clockwise
    """
    j = joints(mechanism, p, phi)
    if mechanism == "sine":
        return j["yoke"][:, 0], j["A"][:, 1]
    if mechanism == "slider_crank":
        rod = j["B"] - j["A"]
        return j["B"][:, 0], np.arctan2(-rod[:, 1], rod[:, 0])
    if mechanism == "slotted_link":
        cb = j["B"] - j["C"]
        return np.arctan2(cb[:, 0], cb[:, 1]), p["l0"] + p["l1"] - np.hypot(cb[:, 0], cb[:, 1])
    if mechanism == "four_bar":
        dc, bc = j["C"] - j["D"], j["C"] - j["B"]
        return np.arctan2(dc[:, 1], dc[:, 0]), np.arctan2(bc[:, 1], bc[:, 0])
    raise KeyError(mechanism)


def _wrapped(delta: np.ndarray, is_angle: bool) -> np.ndarray:
    """A difference of two angles reduced to (−π, π]; lengths pass unchanged."""
    return np.angle(np.exp(1j * delta)) if is_angle else delta


def richardson_derivatives(position, phi: np.ndarray, h: float, is_angle: bool) -> tuple[np.ndarray, np.ndarray]:
    """First and second derivatives of ``position(phi)`` by central differences, Richardson-extrapolated.

    Central differences with steps h and h/2 have errors c₂h² + c₄h⁴ + …; the combination
    (4D(h/2) − D(h))/3 removes the h² term, leaving O(h⁴) truncation error.  Rounding adds
    about ε|s|/h to the first and ε|s|/h² to the second derivative (ε = 2.2e-16).
    """
    def central(step):
        s_plus, s_0, s_minus = position(phi + step), position(phi), position(phi - step)
        d1 = _wrapped(s_plus - s_minus, is_angle) / (2 * step)
        d2 = (_wrapped(s_plus - s_0, is_angle) - _wrapped(s_0 - s_minus, is_angle)) / step**2
        return d1, d2

    d1_h, d2_h = central(h)
    d1_half, d2_half = central(h / 2)
    return (4 * d1_half - d1_h) / 3, (4 * d2_half - d2_h) / 3


def fd_transfer_functions(mechanism: str, p: dict[str, float], phi: np.ndarray, h: float) -> dict[str, np.ndarray]:
    """u₃₁, u′₃₁, u₂₁, u′₂₁ by differentiating the positions measured on the joints."""
    (_, angle3), (_, angle2) = MEASURED[mechanism]
    u31, du31 = richardson_derivatives(lambda x: measured_positions(mechanism, p, x)[0], phi, h, angle3)
    u21, du21 = richardson_derivatives(lambda x: measured_positions(mechanism, p, x)[1], phi, h, angle2)
    return {"u31": u31, "du31": du31, "u21": u21, "du21": du21}
