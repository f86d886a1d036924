"""A computing endpoint's Answer from the core's result and notices: the numerics, study and warnings in the
reader's language, and whether a time or work bound cut the computation short (sent as X-Partial); what an
endpoint body is asked (the keys read, a preview's accuracy) and a refusal kept as a batch member's answer."""
from __future__ import annotations

from collections.abc import Collection

from ..core.dynamics.motors import Motor
from ..core.mechanisms import GeometryError
from .messages import localise_numerics, localise_study, translate
from .serialise import Answer

Reads = Collection[str] | None      # the answer's top-level keys a caller reads; None: every one
# A family member's accuracy (server/families/family.py, PREVIEW): the error allowed as a fraction of each drawn
# curve's span, where the endpoint's own tolerance would be far tighter than a preview needs; None: the exact
# answer, computed exactly as without it. Only the family asks for it, and only for PREVIEW_AWARE endpoints.
Preview = float | None

# The core's words when a bound stopped a computation with a partial result (server/core/dynamics/motion.py:
# "stopped at the time budget …"; server/core/elastic/simulate.py and the start from rest: "… the work bound").
PARTIAL_MARKERS = ("time budget", "work bound")


def payload(result: dict, notices, lang: str) -> dict:
    """The answer's body: numerics and study in the reader's language, the warnings once each, in order."""
    warnings = dict.fromkeys(translate(n, lang) for n in notices)
    if isinstance(result.get("study"), dict):
        result["study"] = localise_study(result["study"], lang)
    for holder in (result, result.get("startup") or {}):
        if isinstance(holder.get("numerics"), dict):
            holder["numerics"] = localise_numerics(holder["numerics"], lang)
    return result | {"warnings": list(warnings)}


def cut_short(result: dict, notices) -> bool:
    """Whether a time or work bound stopped part of the computation: the core says so in the message of a
    numerics dict (the answer's, the start-up's) or in a warning, in English before translation."""
    texts = [notice.text for notice in notices]
    for holder in (result, result.get("startup") or {}):
        if isinstance(holder.get("numerics"), dict):
            texts.append(str(holder["numerics"].get("message", "")))
    return any(marker in text for text in texts for marker in PARTIAL_MARKERS)


def answer(result: dict, notices, lang: str) -> Answer:
    partial = cut_short(result, notices)               # before the texts are translated
    return Answer(payload(result, notices, lang), partial)


def refused_or(compute_one) -> Answer | GeometryError:
    """The answer of compute_one(), or the GeometryError it raised (a member refused where the route says 422)."""
    try:
        return compute_one()
    except GeometryError as error:
        return error


def motor_of(motor) -> Motor:
    """The core's Motor of a request's motor (a machine's motor, a gas force's indicator diagram)."""
    return Motor(**{**motor.model_dump(), "expansion": tuple(motor.expansion), "compression": tuple(motor.compression),
                    "table_phi": tuple(motor.table_phi or ()), "table_moment": tuple(motor.table_moment or ())})
