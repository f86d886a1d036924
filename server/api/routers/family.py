"""POST /api/v1/family: a slider's family of answers (server/families/family.py), computed in the heavy process."""
from __future__ import annotations

import asyncio
import math
from typing import Any, Literal

import orjson
from fastapi import APIRouter, Request
from fastapi.responses import Response
from pydantic import BaseModel, ConfigDict, Field, ValidationInfo, field_validator

from ...runtime import heavy
from ...runtime.admission import server_timing
from ...families import family
from ..endpoints import ENDPOINTS
from ..family_batch import member_batch
from ...runtime.response_cache import cache_key, canonical_json
from ..schemas import Language
from ..serialise import encoded, encoded_response
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
                              "inside the range at its ends) for the numbers all 4 hold, 0 the nearer member's "
                              "answer whole (a coarse family's interval not shown within the tolerance) "
                              "(server/families/family.py)")
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
    # previews' lane, ahead of the full families queued in theirs (which then compute those 9 again: their memo is
    # in another process), and beside the answers' lane, so that an elastic answer never waits for it. Previews
    # go in the order asked, so that none waits longer than those asked before it (the page aborts the ones its
    # student has given up, which then leave the queue); refinements newest first (heavy.LaneQueue). A family
    # comes back as bytes, gzip-compressed when the client takes it: it is up to 2 MB of JSON, whose serialising
    # and compressing (tens of ms) would hold the worker's event loop.
    # When the worker is busy (heavy.busy: answers or previews wait for their lane, or a refinement is under way) a
    # full family is not refined: the answer is the coarse family (numerics.stage "coarse", marked no-store so
    # that the cache keeps it apart from the full family the same question gets on spare CPU). While previews
    # queue (heavy.crowded) a coarse family takes the lean start (family.LEAN_MEMBERS).
    gzip_accepted = "gzip" in http.headers.get("accept-encoding", "")
    body = request.model_dump()
    unrefined = request.stage == "full" and heavy.busy()
    if unrefined:
        body["stage"] = "coarse"
        kept = coarse_in_cache(http, body, gzip_accepted)
        if kept is not None:
            return kept
    lane = "previews" if body["stage"] == "coarse" else "families"
    lean = body["stage"] == "coarse" and heavy.crowded()
    work = (family_body, body, lang, gzip_accepted, lean)
    heavy.TIMING.set(timing := {})           # filled when this request's own job ran (not one it joined)
    refinement = lane == "families"
    encoded_body, packed, partial = await _in_flight.join(work, lambda: heavy.submit(*work, lane=lane,
                                                                                        newest_first=refinement))
    headers = ({"Cache-Control": "no-store"} if unrefined else {}) | (
        {"Server-Timing": server_timing(timing)} if timing else {})
    return encoded_response(encoded_body, packed, partial, headers)


def coarse_in_cache(http: Request, body: dict, gzip_accepted: bool) -> Response | None:
    """The coarse family of the same question from the response cache (this worker's, or the shared layer), as
    the answer to a full one the busy worker does not refine (no-store: not kept as the full family); or None."""
    cache = getattr(http.app.state, "response_cache", None)
    if cache is None or not cache.enabled:
        return None
    key = cache_key(http.scope["path"], http.scope.get("query_string", b"").decode("latin-1"),
                    canonical_json(family.shared(body)))
    found = cache.get(key) or cache.get_shared(key)
    if found is None:
        return None
    start = found.message_start(gzip_accepted, b"hit")
    headers = {name.decode("latin-1"): value.decode("latin-1") for name, value in start["headers"]
               if name.lower() not in (b"content-length", b"x-cache")}
    return Response(found.body_for(gzip_accepted), headers=headers | {"Cache-Control": "no-store"})


class InFlight:
    """The families being computed in this worker, by question: a second student asking the same family while
    it is computed waits for the same computation instead of starting another (a class grabs the same slider at
    the same defaults). The computation is cancelled (and so leaves its lane, or stops: heavy.LaneQueue) only
    when every student waiting for it has gone."""

    def __init__(self):
        self.running: dict[bytes, tuple[asyncio.Future, list[int]]] = {}

    async def join(self, work: tuple, start):
        _, body, lang, gzip_accepted, _ = work
        key = orjson.dumps([family.shared(body), lang, gzip_accepted], option=orjson.OPT_SORT_KEYS)
        if key not in self.running:
            task = asyncio.ensure_future(start())
            self.running[key] = (task, [0])
            task.add_done_callback(lambda _, key=key, task=task: self._forget(key, task))
        task, waiting = self.running[key]
        waiting[0] += 1
        try:
            return await asyncio.shield(task)
        except asyncio.CancelledError:
            if task.done() or waiting[0] > 1:
                raise
            if self.running.get(key, (None,))[0] is task:
                del self.running[key]          # a student asking again now starts it anew
            task.cancel()
            raise
        finally:
            waiting[0] -= 1

    def _forget(self, key: bytes, task: asyncio.Future) -> None:
        if self.running.get(key, (None,))[0] is task:
            del self.running[key]
        if not task.cancelled():
            task.exception()            # retrieved: an error reaches every waiting route, not the loop's log


_in_flight = InFlight()


def family_body(body: dict, lang: str, gzip_accepted: bool, lean: bool = False) -> tuple[bytes, bool, bool]:
    """The family's answer as sent (run in the heavy process): its JSON (the family rounds its floats to
    family.SIGNIFICANT digits itself: serialised as they are), gzip-compressed when the client takes it and it
    gains (response_cache.compressed, as the cache would keep it); whether compressed; whether partial.
    ``lean``: a coarse family of family.LEAN_MEMBERS start members."""
    answer, partial = family_answer(body, lang, lean)
    return (*encoded(answer, None, gzip_accepted), partial)


def family_answer(body: dict, lang: str, lean: bool = False) -> tuple[dict, bool]:
    """The family's answer and whether it is partial (run in the heavy process)."""
    vary = [family.Vary(item["path"], item["factor"]) for item in body["vary"]]
    counts = {"computed": 0}
    fields = body.get("fields")
    members = member_batch(body["endpoint"], body["request"], vary, lang, counts, fields)
    answer, partial = family.build(members, body["min"], body["max"], body["log"], lang, body.get("stage", "full"),
                                   pack=body.get("packed", False), lean=lean)
    answer["numerics"]["computed"] = counts["computed"]
    return answer, partial
