"""Every computed answer leaves the server through here: numpy arrays written directly by orjson, no NaN or
infinity ever sent (null instead), floats at the precision a plot needs unless the client asks for all.

Plot precision (the default): each float is rounded to PLOT_DIGITS = 7 significant digits,
x ↦ round(x·10ᵉ)·10⁻ᵉ with e = 6 − ⌊log₁₀|x|⌋ (vectorised over arrays; a relative change below 5·10⁻⁷,
about a thousandth of a pixel on a 2000-pixel plot), and orjson writes the shortest decimal that reads back
as that double, so 0.30000000000000004 goes out as 0.3. ``?precision=full`` sends every float64 as it is
(shortest round-trip repr: 17 significant digits at most). Non-finite numbers become null in both modes,
as JSON has no NaN: orjson writes null for a non-finite float, scalar or array element; `_rounded` keeps
them non-finite, and `serialise` checks no other spelling can occur (tests/test_serialise.py).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np
import orjson
from fastapi.responses import Response

PLOT_DIGITS = 7
Precision = Literal["plot", "full"]
PARTIAL_HEADER = "X-Partial"
_OPTIONS = orjson.OPT_SERIALIZE_NUMPY


@dataclass(frozen=True)
class Answer:
    """A computing endpoint's answer before serialisation: the payload (dicts, lists, numbers, numpy arrays)
    and whether a time or work bound cut the computation short (sent as the header X-Partial: 1; such an
    answer is not cached, since computing it again may get further)."""

    payload: dict
    partial: bool = False


def _significant(x: np.ndarray, digits: int) -> np.ndarray:
    """x rounded to `digits` significant digits, element-wise; 0, ±inf and NaN unchanged.

    The integer is scaled back by an exact power of ten (10ᵏ is exact for |k| ≤ 22): dividing by 10ᵏ rather
    than multiplying by the inexact 10⁻ᵏ gives the double nearest to the decimal, whose shortest repr is
    the decimal itself. Beyond 10²² (|x| < 10⁻¹⁶ or > 10²⁸) the last bit may differ: still rounded, a
    longer repr."""
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        exponent = (digits - 1) - np.floor(np.log10(np.abs(x)))
        exponent = np.where(np.isfinite(exponent), exponent, 0.0)
        up = np.where(exponent >= 0, 10.0 ** np.abs(exponent), 1.0)
        down = np.where(exponent < 0, 10.0 ** np.abs(exponent), 1.0)
        rounded = np.round(x * up / down) / up * down
    return np.where(np.isfinite(rounded), rounded, x)       # subnormals (10ᵉ overflows) are sent as they are


def _rounded(value, digits: int):
    """The payload with its floats rounded; arrays of other kinds, ints, strings and bools as they are."""
    if isinstance(value, dict):
        return {key: _rounded(item, digits) for key, item in value.items()}
    if isinstance(value, (list, tuple)):
        return [_rounded(item, digits) for item in value]
    if isinstance(value, np.ndarray):
        if value.dtype.kind == "f":
            return _significant(value.astype(float), digits)
        return _rounded(value.tolist(), digits) if value.dtype.kind == "O" else value
    if isinstance(value, (float, np.floating)):       # np.float64 is a float; the decimal rounding is exact
        return float(f"{value:.{digits}g}")
    return value


def _fallback(value):
    """What orjson does not write itself: arrays that are not C-contiguous (slices with a step: copied), and
    contiguous ones of a kind it does not know (objects, float16: as lists)."""
    if isinstance(value, np.ndarray):
        return value.tolist() if value.flags.c_contiguous else np.ascontiguousarray(value)
    if isinstance(value, np.generic):
        return value.item()
    raise TypeError(f"{type(value).__name__} is not JSON")


def _wide_ints_as_floats(value):
    """Integers beyond 64 bits (orjson writes no others), e.g. echoed from a request in a 422, as floats."""
    if isinstance(value, dict):
        return {key: _wide_ints_as_floats(item) for key, item in value.items()}
    if isinstance(value, (list, tuple)):
        return [_wide_ints_as_floats(item) for item in value]
    if isinstance(value, int) and not isinstance(value, bool) and not -2**63 <= value < 2**64:
        return float(value) if abs(value) < 2**1024 else None
    return value


def serialise(payload, digits: int | None = PLOT_DIGITS) -> bytes:
    """The payload as JSON bytes: floats to `digits` significant digits (None: all), non-finite as null."""
    data = payload if digits is None else _rounded(payload, digits)
    try:
        return orjson.dumps(data, default=_fallback, option=_OPTIONS)
    except orjson.JSONEncodeError:
        return orjson.dumps(_wide_ints_as_floats(data), default=_fallback, option=_OPTIONS)


def respond(answer: Answer, precision: Precision = "plot") -> Response:
    """The HTTP answer: JSON at the requested precision, X-Partial: 1 when the answer is partial."""
    headers = {PARTIAL_HEADER: "1"} if answer.partial else None
    return Response(serialise(answer.payload, PLOT_DIGITS if precision == "plot" else None),
                    media_type="application/json", headers=headers)
