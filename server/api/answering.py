"""A computing endpoint's Answer from the core's result and notices: the numerics, study and warnings in the
reader's language, and whether a time or work bound cut the computation short (sent as X-Partial)."""
from __future__ import annotations

from .messages import localise_numerics, localise_study, translate
from .serialise import Answer

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
