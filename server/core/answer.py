"""A computed answer before it is written out: the payload and whether a time or work bound cut it short,
and the rounding to significant digits that every answer's floats go through (decimal-exact while 10^|k| is)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

with np.errstate(over="ignore"):
    POWERS_OF_TEN = 10.0 ** np.arange(400)             # 10ᵏ, exact up to 10²²; past 10³⁰⁸ infinite


@dataclass(frozen=True)
class Answer:
    """A computing endpoint's answer before serialisation: the payload (dicts, lists, numbers, numpy arrays)
    and whether a time or work bound cut the computation short (sent as the header X-Partial: 1; such an
    answer is not cached, since computing it again may get further)."""

    payload: dict
    partial: bool = False


def significant(x: np.ndarray, digits: int) -> np.ndarray:
    """x rounded to `digits` significant digits, element-wise; 0, ±inf and NaN unchanged.

    x·10ᵏ is rounded to an integer and scaled back, k = digits − 1 − ⌊log₁₀|x|⌋, with 10^|k| from a table:
    for k < 0 it divides by 10^|k| rather than multiplying by the inexact 10ᵏ, so while 10^|k| is exact
    (|k| ≤ 22, i.e. 10⁻¹⁶ ≤ |x| < 10²⁸) the result is the double nearest to the decimal, whose shortest
    repr is the decimal itself; beyond, the last bit may differ (still rounded, a longer repr)."""
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        exponent = np.log10(np.abs(x))
        np.floor(exponent, out=exponent)
        np.subtract(digits - 1, exponent, out=exponent)
        exponent[~np.isfinite(exponent)] = 0.0            # 0, ±inf, NaN: scaled by 1, left as they are
        k = np.clip(exponent.astype(np.int64), 1 - POWERS_OF_TEN.size, POWERS_OF_TEN.size - 1)
        up, down = POWERS_OF_TEN[np.maximum(k, 0)], POWERS_OF_TEN[np.maximum(-k, 0)]
        rounded = x * up
        rounded /= down
        np.round(rounded, out=rounded)
        rounded /= up
        rounded *= down
    lost = ~np.isfinite(rounded)                            # subnormals (10ᵏ overflows): sent as they are
    rounded[lost] = x[lost]
    return rounded
