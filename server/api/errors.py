"""HTTP 422 in FastAPI's own error format for errors the numeric core reports."""
from fastapi import HTTPException

from ..core.mechanisms import GeometryError

REQUEST_FIELDS = ("outputs", "phi", "n")


def unprocessable(error: GeometryError) -> HTTPException:
    """422 naming the field and the reason, like pydantic's validation errors, plus a code for translation."""
    if error.field.split(".")[0] in REQUEST_FIELDS:
        loc = ["body", *error.field.split(".")]
    else:
        loc = ["body", "params", error.field]
    return HTTPException(status_code=422, detail=[{
        "loc": loc, "msg": error.reason, "type": "geometry_error",
        "ctx": {"code": error.code, **error.context}}])
