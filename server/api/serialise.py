"""Every computed answer leaves the server through here: numpy arrays written directly by orjson, no NaN or
infinity ever sent (null instead), floats at the precision a plot needs unless the client asks for all.

Plot precision (the default): each float of an array or a list (the curves: where the bytes are) is rounded to
PLOT_DIGITS = 7 significant digits,
x ↦ round(x·10ᵉ)·10⁻ᵉ with e = 6 − ⌊log₁₀|x|⌋ (vectorised over arrays; a relative change below 5·10⁻⁷,
about a thousandth of a pixel on a 2000-pixel plot), and orjson writes the shortest decimal that reads back
as that double, so 0.30000000000000004 goes out as 0.3. A single number (a field of an object: the cycle 4π,
ω_mean, δ, an error estimate) is sent whole, as it costs no bytes worth saving and a page may compute with it
(the 4π cycle's axis ends at 720°, not 719.99996°). ``?precision=full`` sends every float64 as it is
(shortest round-trip repr: 17 significant digits at most). Non-finite numbers become null in both modes,
as JSON has no NaN: orjson writes null for a non-finite float, scalar or array element; `_rounded` keeps
them non-finite, and `serialise` checks no other spelling can occur (tests/test_serialise.py).
"""
from __future__ import annotations

from typing import Literal

import numpy as np
import orjson
from fastapi import Request
from fastapi.responses import Response

from ..core.answer import POWERS_OF_TEN, Answer, significant  # noqa: F401  (re-exported: the endpoints' Answer)
from ..runtime import heavy
from ..runtime.response_cache import PARTIAL_HEADER, compressed  # noqa: F401  (the header the cache reads)

PLOT_DIGITS = 7
Precision = Literal["plot", "full"]
_OPTIONS = orjson.OPT_SERIALIZE_NUMPY


def _float_arrays(value, found: list) -> None:
    """The payload's float arrays, in the order _rebuilt meets them."""
    if isinstance(value, dict):
        for item in value.values():
            _float_arrays(item, found)
    elif isinstance(value, (list, tuple)):
        for item in value:
            _float_arrays(item, found)
    elif isinstance(value, np.ndarray) and value.dtype.kind == "f":
        found.append(value)


def _rebuilt(value, digits: int, arrays):
    """The payload with each float array taken from `arrays` (rounded, in walk order), each float rounded;
    arrays of other kinds, ints, strings and bools as they are."""
    if isinstance(value, dict):             # a field that is one number is sent whole
        return {key: item if isinstance(item, float) else _rebuilt(item, digits, arrays)
                for key, item in value.items()}
    if isinstance(value, (list, tuple)):
        return [_rebuilt(item, digits, arrays) for item in value]
    if isinstance(value, np.ndarray):
        if value.dtype.kind == "f":
            return next(arrays)
        return _rounded(value.tolist(), digits) if value.dtype.kind == "O" else value
    if isinstance(value, (float, np.floating)):       # np.float64 is a float; the decimal rounding is exact
        return float(f"{value:.{digits}g}")
    return value


def _rounded(payload, digits: int):
    """The payload with every float rounded to `digits` significant digits: all float arrays in one
    vectorised pass (one buffer, so the cost is per number, not per array)."""
    found: list[np.ndarray] = []
    _float_arrays(payload, found)
    if not found:
        return _rebuilt(payload, digits, iter(()))
    flat = significant(np.concatenate([a.ravel() for a in found]).astype(float, copy=False), digits)
    parts = np.split(flat, np.cumsum([a.size for a in found])[:-1])
    return _rebuilt(payload, digits, (part.reshape(a.shape) for part, a in zip(parts, found)))


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


def encoded(payload, digits: int | None, gzip_accepted: bool) -> tuple[bytes, bool]:
    """The payload's JSON, gzip-compressed when the client takes it and it gains (response_cache.compressed, as
    the cache would keep it); whether compressed."""
    raw = serialise(payload, digits)
    packed = compressed(raw) if gzip_accepted else None
    return (raw, False) if packed is None else (packed, True)


def encoded_response(body: bytes, packed: bool, partial: bool, headers: dict | None = None) -> Response:
    """The HTTP answer of a body `encoded` already (gzip-compressed or not), X-Partial: 1 when partial."""
    return Response(body, media_type="application/json", headers=(headers or {}) | (
        {PARTIAL_HEADER: "1"} if partial else {}) | ({"Content-Encoding": "gzip", "Vary": "Accept-Encoding"}
                                                      if packed else {}))


def answer_encoded(function, request, lang: str, precision: Precision, gzip_accepted: bool) -> tuple[bytes, bool, bool]:
    """function(request, lang)'s answer as sent (run in a heavy process): `encoded` at `precision`; whether
    compressed; whether partial."""
    answer = function(request, lang)
    return (*encoded(answer.payload, PLOT_DIGITS if precision == "plot" else None, gzip_accepted), answer.partial)


async def respond_apart(http: Request, function, request, lang: str, precision: Precision = "plot") -> Response:
    """The HTTP answer of function(request, lang) computed in a heavy process, and serialised and compressed
    there as well: an elastic machine's answer is 0.2 MB of JSON whose serialising and compressing (about 5 ms)
    would hold the worker's event loop, and every answer waiting in it, as long."""
    gzip_accepted = "gzip" in http.headers.get("accept-encoding", "")
    return encoded_response(*await heavy.submit(answer_encoded, function, request, lang, precision, gzip_accepted))
