"""HTTP 422 in FastAPI's own error format for errors the numeric core reports."""
from fastapi import Request
from fastapi.encoders import jsonable_encoder
from fastapi.exceptions import RequestValidationError
from fastapi.responses import JSONResponse

from ..core.mechanisms import GeometryError
from .json_safe import finite_or_none

REQUEST_FIELDS = ("outputs", "phi", "n", "motor", "inertias", "load", "compliances", "loads", "pairs")


async def geometry_error(request: Request, error: GeometryError) -> JSONResponse:
    """422 naming the field and the reason, like pydantic's validation errors, plus a code for translation;
    every route lets the core's GeometryError through to here."""
    if error.field.split(".")[0] in REQUEST_FIELDS:
        loc = ["body", *error.field.split(".")]
    else:
        loc = ["body", "params", error.field]
    return JSONResponse(status_code=422, content={"detail": [{
        "loc": loc, "msg": error.reason, "type": "geometry_error",
        "ctx": finite_or_none({"code": error.code, **error.context})}]})


async def validation_error(request: Request, error: RequestValidationError) -> JSONResponse:
    """FastAPI's own 422 body, with NaN/Infinity echoed from the request (``"input"``) sent as null.

    The default handler echoes the offending input; a body such as ``{"phi": [NaN]}`` (accepted by
    Python's JSON parser) would otherwise make the error response itself fail to serialise (HTTP 500).
    """
    return JSONResponse(status_code=422, content={"detail": finite_or_none(jsonable_encoder(error.errors()))})
