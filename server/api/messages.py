"""Warnings and errors of the numeric core in the reader's language (content/i18n, keys warn_*/err_*)."""
from __future__ import annotations

import math

from ..core.mechanisms import Notice
from ..core.mechanisms.base import ranges_text
from ..lessons.scenes import interface_texts

DECIMAL_COMMA = ("ru", "uk")


class ReadableFloat(float):
    """A number for sentences: 'g' formats keep ordinary numbers out of exponent notation (12100, not
    1.21e+04), and Russian and Ukrainian texts get a decimal comma."""

    decimal = "."

    def __format__(self, spec: str) -> str:
        value = float(self)
        if spec.endswith("g") and 1e-4 <= abs(value) < 1e9:
            digits = int(spec[1:-1] or 6) - 1 - math.floor(math.log10(abs(value)))
            text = f"{round(value, digits):.0f}" if digits <= 0 else f"{value:.{digits}f}".rstrip("0").rstrip(".")
        else:
            text = format(value, spec)
        return text.replace(".", self.decimal)


class CommaFloat(ReadableFloat):
    decimal = ","


def localise_numerics(numerics: dict, lang: str) -> dict:
    """The method's description (and, for the elastic models, why it was chosen) in the reader's language."""
    texts = interface_texts(lang) if lang != "en" else {}
    local = dict(numerics)
    template = texts.get(f"num_{numerics.get('code')}")
    if template:
        local["method"] = template.format(method=numerics.get("method", ""))
    number = CommaFloat if lang in DECIMAL_COMMA else ReadableFloat
    message = texts.get(f"num_message_{numerics.get('message_code')}")
    if message:
        local["message"] = message.format(**{k: number(v) if isinstance(v, float) else v
                                             for k, v in numerics.get("message_context", {}).items()})
    why = interface_texts(lang).get(f"why_{numerics.get('code')}")      # English too: readable numbers
    if why and "why_context" in numerics:
        local["why"] = why.format(**{k: number(v) for k, v in numerics["why_context"].items()})
    return local


def localise_study(study: dict, lang: str) -> dict:
    """The work–precision study's reference and quantity in the reader's language."""
    texts = interface_texts(lang) if lang != "en" else {}
    local = dict(study)
    for field in ("reference", "quantity"):
        text = texts.get(f"study_{field}_{study.get(field + '_code')}")
        if text:
            local[field] = text
    return local


def translate(notice: Notice, lang: str) -> str:
    """The notice in ``lang``; English text of the core when the language has no template for it."""
    if lang == "en":
        return notice.text
    template = interface_texts(lang).get(f"warn_{notice.code}")
    if template is None:
        return notice.text
    decimal = "," if lang in DECIMAL_COMMA else "."
    number = CommaFloat if decimal == "," else ReadableFloat
    context = {key: number(value) if isinstance(value, float) else
               ranges_text(value, decimal) if key == "ranges" else value
               for key, value in notice.context.items()}
    return template.format(**context)
