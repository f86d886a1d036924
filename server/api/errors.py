"""HTTP 422 in FastAPI's own error format for errors the numeric core reports."""
from fastapi import Request
from fastapi.encoders import jsonable_encoder
from fastapi.exceptions import RequestValidationError
from fastapi.responses import Response

from ..core.mechanisms import GeometryError
from .serialise import serialise

REQUEST_FIELDS = ("outputs", "phi", "n", "motor", "inertias", "load", "compliances", "loads", "pairs",
                  "linkage", "plan")


def _unprocessable(content: dict) -> Response:
    """422 with every number as given (non-finite ones as null)."""
    return Response(serialise(content, digits=None), status_code=422, media_type="application/json")


async def geometry_error(request: Request, error: GeometryError) -> Response:
    """422 naming the field and the reason, like pydantic's validation errors, plus a code for translation;
    every route lets the core's GeometryError through to here."""
    if error.field.split(".")[0] in REQUEST_FIELDS:
        loc = ["body", *error.field.split(".")]
    else:
        loc = ["body", "params", error.field]
    return _unprocessable({"detail": [{"loc": loc, "msg": error.reason, "type": "geometry_error",
                                       "ctx": {"code": error.code, **error.context}}]})


async def validation_error(request: Request, error: RequestValidationError) -> Response:
    """FastAPI's own 422 body, with NaN/Infinity echoed from the request (``"input"``) sent as null.

    The default handler echoes the offending input; a body such as ``{"phi": [NaN]}`` (accepted by
    Python's JSON parser) would otherwise make the error response itself fail to serialise (HTTP 500).
    """
    return _unprocessable({"detail": jsonable_encoder(error.errors())})
