"""POST /api/v1/family: a slider's family of answers (server/families/family.py), computed in the heavy process."""
from __future__ import annotations

import math
from typing import Any, Literal

from fastapi import APIRouter, Request
from fastapi.responses import Response
from pydantic import BaseModel, ConfigDict, Field, ValidationInfo, field_validator

from ...runtime import heavy
from ...families import family
from ..endpoints import ENDPOINTS
from ..family_batch import member_batch
from ...runtime.response_cache import compressed
from ..schemas import Language
from ..serialise import PARTIAL_HEADER, serialise
from .query import LANG

heavy.preload(__name__)     # family_body runs in the lanes

router = APIRouter(tags=["family"])
# A family answers a page's dragged slider; the course project is computed whole on /project and its scene's page
# has no slider to drag, so it has none (a family of course projects would cost seconds of CPU).
WITHOUT_FAMILY = ("course-project",)
Endpoint = Literal[tuple(endpoint for endpoint in ENDPOINTS if endpoint not in WITHOUT_FAMILY)]


class VaryItem(BaseModel):
    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    path: str = Field(min_length=1, max_length=200, description="dotted path of a number in `request`, "
                                                                "e.g. params.l2")
    factor: float = Field(1.0, allow_inf_nan=False, description="the path is set to value × factor (the "
                                                                "slider's units to SI and its scale)")


class FamilyRequest(BaseModel):
    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)
    endpoint: Endpoint = Field(description="the computing endpoint whose answers make the family")
    request: dict[str, Any] = Field(description="the endpoint's body exactly as the page sends it")
    vary: list[VaryItem] = Field(min_length=1, max_length=8, description="the paths the slider sets")
    log: bool = Field(False, description="members spaced (and interpolated) in log(value); needs min > 0")
    min: float = Field(allow_inf_nan=False, description="the slider's lowest value, in its shown units")
    max: float = Field(allow_inf_nan=False, description="the slider's highest value, in its shown units")
    stage: Literal[family.STAGES] = Field("full", description='"coarse": the 9 start members at once, unrefined '
                                          '(asked first, on the grab); "full": refined to the tolerance')
    fields: list[str] | None = Field(
        None, min_length=1, max_length=family.MAX_FIELDS,
        description="dotted paths of the answer's leaves a preview draws (e.g. \"t\", \"modal.stiffness\"): each "
                    "member is pruned to those subtrees and the interpolation error covers them alone. A path a "
                    "member does not hold is left out of it (an answer's shape depends on the values and on "
                    "`outputs`). Absent: the whole answers")
    packed: bool = Field(False, description="send the family packed: arrays equal in every member once, in "
                         "`shared`; every float array of a quantity with a span as {exp10: e, order: n, deltas: [...]}, "
                         "the integers round(x/10^e) as differences of order n along the first axis (order 1 keeps "
                         "null where x is null), 10^e ≤ 1e-4 of the quantity's span (server/families/family.py, Packed)")


    @field_validator("fields")
    @classmethod
    def dotted_paths(cls, fields: list[str] | None) -> list[str] | None:
        for index, path in enumerate(fields or []):
            if not family.FIELD.fullmatch(path):
                raise ValueError(f"fields[{index}]: {path[:80]!r} is not a dotted path of an answer's keys "
                                 "(letters, digits and _, joined by dots, at most 8 deep)")
        return fields

    @field_validator("vary")
    @classmethod
    def paths_in_request(cls, vary: list[VaryItem], info: ValidationInfo) -> list[VaryItem]:
        request = info.data.get("request")
        if request is not None:
            for index, item in enumerate(vary):
                if not family.path_exists(request, item.path):
                    raise ValueError(f"vary[{index}].path: {item.path!r} is not a number in request")
        return vary

    @field_validator("min")
    @classmethod
    def positive_for_log(cls, low: float, info: ValidationInfo) -> float:
        if info.data.get("log") and low <= 0:
            raise ValueError("a log-spaced family needs min > 0")
        return low

    @field_validator("max")
    @classmethod
    def above_min(cls, high: float, info: ValidationInfo) -> float:
        low = info.data.get("min")
        if low is not None and not high > low:
            raise ValueError("max must be greater than min")
        if low is not None and not math.isfinite(high - low):
            raise ValueError("max − min must be a finite number")
        return high


class FamilyNumerics(BaseModel):
    method: str
    stage: Literal[family.STAGES] = Field(description="the request's stage: coarse (unrefined) or full")
    points: int = Field(description="members in the family")
    checked: int = Field(description="values computed exactly (each one a member)")
    computed: int = Field(description="of those, computed for this family (the rest from the process's memo)")
    runtime_ms: float
    message: str = Field(description="in words: the cap or the time budget that stopped the family, partial members")


class FamilyResponse(BaseModel):
    values: list[float] = Field(description="the members' slider values, ascending, min and max included")
    orders: list[int] = Field(description="each interval's rule (len(values) − 1 of them): 1 linear between "
                              "its two members, 3 Lagrange's cubic through the 4 members k − 1 … k + 2 (moved "
                              "inside the range at its ends) for the numbers all 4 hold (server/families/family.py)")
    shared: dict | None = Field(None, description="only when `packed`: the arrays equal in every "
                                "answered member, sent once; each member's answer is `shared` merged with its own, "
                                "object by object")
    answers: list[dict | None] = Field(description="the endpoint's answer at each value (pruned to `fields` when "
                                       "given; packed, without the `shared` arrays, when `packed`); null where refused")
    errors: list[dict | None] = Field(description="{code, message} of a refused value, else null")
    interpolation_error: float | None = Field(description="largest estimated |interpolation − exact| / span "
                                                          "over the intervals (linear: h²·|f''|/8, f'' from "
                                                          "neighbours, or a step the neighbours' slopes do not "
                                                          "explain; cubic: max|Π(v − vᵢ)|·|f[5 members]|; an "
                                                          "interval left above the tolerance: its bound; "
                                                          "packed: plus 5e-5, what packing may move a value)")
    tolerance: float = Field(description="the target: 0.5 % of each plotted quantity's span over the family")
    numerics: FamilyNumerics


@router.post("/family", summary="A slider's family: the endpoint's answer at values across the slider's range, "
                                "spaced so that interpolation (linear or cubic by interval) is within 0.5 % of each "
                                "quantity's span",
             responses={200: {"model": FamilyResponse,
                              "description": "the family; header X-Partial: 1 when cut short by a work bound"},
                        422: {"description": "invalid input: the field and the reason"}})
async def family_route(request: FamilyRequest, http: Request, lang: Language = LANG) -> Response:
    # The coarse stage is the preview a student is waiting for while dragging (9 members): it runs in the
    # answers' lane, ahead of the full families queued in theirs (which then compute those 9 again: their memo is
    # in another process). In either lane a family goes after the answers waiting there, and the newest family
    # first (heavy.LaneQueue). It comes back as bytes, gzip-compressed when the client takes it: a family is up
    # to 2 MB of JSON, whose serialising and compressing (tens of ms) would hold the worker's event loop.
    lane = "answers" if request.stage == "coarse" else "families"
    gzip_accepted = "gzip" in http.headers.get("accept-encoding", "")
    body, encoded, partial = await heavy.submit(family_body, request.model_dump(), lang, gzip_accepted, lane=lane,
                                                newest_first=True)
    headers = ({PARTIAL_HEADER: "1"} if partial else {}) | (
        {"Content-Encoding": "gzip", "Vary": "Accept-Encoding"} if encoded else {})
    return Response(body, media_type="application/json", headers=headers)


def family_body(body: dict, lang: str, gzip_accepted: bool) -> tuple[bytes, bool, bool]:
    """The family's answer as sent (run in the heavy process): its JSON (the family rounds its floats to
    family.SIGNIFICANT digits itself: serialised as they are), gzip-compressed when the client takes it and it
    gains (response_cache.compressed, as the cache would keep it); whether compressed; whether partial."""
    answer, partial = family_answer(body, lang)
    raw = serialise(answer, None)
    packed = compressed(raw) if gzip_accepted else None
    return (raw, False, partial) if packed is None else (packed, True, partial)


def family_answer(body: dict, lang: str) -> tuple[dict, bool]:
    """The family's answer and whether it is partial (run in the heavy process)."""
    vary = [family.Vary(item["path"], item["factor"]) for item in body["vary"]]
    counts = {"computed": 0}
    fields = body.get("fields")
    members = member_batch(body["endpoint"], body["request"], vary, lang, counts, fields)
    answer, partial = family.build(members, body["min"], body["max"], body["log"], lang, body.get("stage", "full"),
                                   pack=body.get("packed", False))
    answer["numerics"]["computed"] = counts["computed"]
    return answer, partial
