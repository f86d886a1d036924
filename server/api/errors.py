"""Error answers: HTTP 422 in FastAPI's own error format for errors the numeric core or validation reports, 503
with Retry-After when the classroom's database cannot be used now (a full disk, a server down), the classroom's
refusals (server/classroom/refusals.py: 404, 503 or 429 with Retry-After; a refused name's status, NAME_STATUS),
and a JSON 500 for anything the app did not expect (the security headers are added around them all by
security.py).

Whatever a request held is echoed back safely: the echo of a validation error is rebuilt without recursion
(``plain``), with bytes and strings made valid UTF-8, integers beyond 64 bits as floats, and objects as their
text, so that no body, however deep or odd, can make the error answer itself fail.
"""
import logging

from fastapi import Request
from fastapi.exceptions import RequestValidationError
from fastapi.responses import JSONResponse, Response

from ..classroom.refusals import Busy, NotFound, TooOften
from ..classroom.store import StoreUnavailable
from ..core.mechanisms import GeometryError
from .serialise import serialise

REQUEST_FIELDS = ("outputs", "phi", "n", "motor", "inertias", "load", "compliances", "loads", "pairs",
                  "linkage", "plan", "bearing", "masses", "pair_friction", "positions", "start", "output",
                  "chosen", "drawn")
SERVER_ERROR = "internal error: the server could not answer this request (it has been logged)"
STORE_RETRY_AFTER_S = 5
STORE_UNAVAILABLE = ("the classroom's database cannot be used just now (its disk is full, or its server is down or "
                     "restarting): nothing was saved by this request, or it was saved without the answer coming back; "
                     "try again in a few seconds")
NAME_STATUS = {"name_empty": 422, "name_too_long": 422, "name_mixed_scripts": 422,    # HTTP status of a refused name
               "name_confusable": 409, "name_taken": 409, "roster_locked": 403, "roster_name_needs_link": 403,
               "too_many_registrations": 429}


def unprocessable(content: dict) -> Response:
    """422 with every number as given (non-finite ones as null)."""
    return Response(serialise(content, digits=None), status_code=422, media_type="application/json")


def body_error(kind: str, msg: str, **ctx) -> dict:
    """One error about the request body as a whole, in FastAPI's format (loc ["body"])."""
    return {"loc": ["body"], "msg": msg, "type": kind, **({"ctx": ctx} if ctx else {})}


def _text(value: str) -> str:
    """The string as valid UTF-8: a lone surrogate (JSON's "\\ud800") becomes U+FFFD."""
    try:
        value.encode("utf-8")
        return value
    except UnicodeEncodeError:
        return value.encode("utf-16", "surrogatepass").decode("utf-16", "replace")


def _leaf(value):
    if value is None or isinstance(value, (bool, float)):
        return value
    if isinstance(value, int):                      # orjson writes 64-bit integers only
        if -2**63 <= value < 2**64:
            return value
        return float(value) if abs(value) < 2**1024 else None
    if isinstance(value, str):
        return _text(value)
    if isinstance(value, (bytes, bytearray)):
        return bytes(value).decode("utf-8", "replace")
    return _text(str(value))


def plain(value):
    """`value` as JSON data (dicts with text keys, lists, text, numbers, null), built with an explicit stack
    rather than recursion, so that its depth is bounded by memory, not by Python's recursion limit."""
    root: list = [None]
    stack = [(value, root, 0)]
    while stack:
        item, holder, key = stack.pop()
        if isinstance(item, dict):
            copy: dict = {}
            holder[key] = copy
            for name, member in item.items():
                name = _leaf(name) if isinstance(name, str) else _text(str(name))
                copy[name] = None
                stack.append((member, copy, name))
        elif isinstance(item, (list, tuple)):
            copy_list: list = [None] * len(item)
            holder[key] = copy_list
            stack.extend((member, copy_list, index) for index, member in enumerate(item))
        else:
            holder[key] = _leaf(item)
    return root[0]


async def geometry_error(request: Request, error: GeometryError) -> Response:
    """422 naming the field and the reason, like pydantic's validation errors, plus a code for translation;
    every route lets the core's GeometryError through to here."""
    if error.field.split(".")[0] in REQUEST_FIELDS:
        loc = ["body", *error.field.split(".")]
    else:
        loc = ["body", "params", error.field]
    return unprocessable({"detail": [{"loc": loc, "msg": error.reason, "type": "geometry_error",
                                      "ctx": {"code": error.code, **error.context}}]})


async def validation_error(request: Request, error: RequestValidationError) -> Response:
    """FastAPI's own 422 body, its echo of the request (``"input"``) made safe by ``plain``.

    The default handler echoes the offending input with jsonable_encoder: a body such as ``{"phi": [NaN]}``
    (accepted by Python's JSON parser), a non-UTF-8 body sent as text/plain, or a lone surrogate would otherwise
    make the error response itself fail to serialise (HTTP 500).
    """
    return unprocessable({"detail": plain(error.errors())})


async def server_error(request: Request, error: Exception) -> Response:
    """HTTP 500 as JSON in FastAPI's error format (Starlette's own is plain text); the traceback goes to the log
    (Starlette's ServerErrorMiddleware re-raises after answering)."""
    logging.getLogger("uvicorn.error").error("500 for %s %s: %r", request.method, request.url.path, error)
    content = {"detail": [{"loc": [], "msg": SERVER_ERROR, "type": "server_error"}]}
    return Response(serialise(content, digits=None), status_code=500, media_type="application/json")


async def store_unavailable(request: Request, error: StoreUnavailable) -> Response:
    """HTTP 503 with Retry-After and the reason in FastAPI's error format; one line in the log naming the
    database and its error, without a traceback (the cause is the database's, not the app's)."""
    logging.getLogger("uvicorn.error").warning("503 for %s %s: %s", request.method, request.url.path, error)
    content = {"detail": [{"loc": [], "msg": STORE_UNAVAILABLE, "type": "store_unavailable"}]}
    return Response(serialise(content, digits=None), status_code=503, media_type="application/json",
                    headers={"Retry-After": str(STORE_RETRY_AFTER_S), "Cache-Control": "no-store"})


async def not_found(request: Request, error: NotFound) -> Response:
    """HTTP 404 with the classroom's words for what is not there (``{"detail": "no such assignment"}``)."""
    return JSONResponse({"detail": error.what}, status_code=404)


async def busy(request: Request, error: Busy) -> Response:
    """HTTP 503 with Retry-After: the answers cannot be had now, nothing was counted."""
    return JSONResponse({"detail": [{"loc": [], "type": error.code, "msg": error.reason}]}, status_code=503,
                        headers={"Retry-After": str(error.retry_after)})


async def too_often(request: Request, error: TooOften) -> Response:
    """HTTP 429 with Retry-After and the limit: the client has done this too often in the window."""
    detail = {"loc": ["body"], "type": error.code, "ctx": {"limit": error.limit}, "msg": error.reason}
    return JSONResponse({"detail": [detail]}, status_code=429, headers={"Retry-After": str(error.retry_after)})
