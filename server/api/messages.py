"""Warnings and errors of the numeric core in the reader's language (content/i18n, keys warn_*/err_*)."""
from __future__ import annotations

from ..core.mechanisms import Notice
from ..core.mechanisms.base import ranges_text
from .content import interface_texts

DECIMAL_COMMA = ("ru", "uk")


class CommaFloat(float):
    """A number that prints with a decimal comma, as Russian and Ukrainian texts write it."""

    def __format__(self, spec: str) -> str:
        return format(float(self), spec).replace(".", ",")


def localise_numerics(numerics: dict, lang: str) -> dict:
    """The method's description (and, for the elastic models, why it was chosen) in the reader's language."""
    texts = interface_texts(lang) if lang != "en" else {}
    local = dict(numerics)
    template = texts.get(f"num_{numerics.get('code')}")
    if template:
        local["method"] = template.format(method=numerics.get("method", ""))
    message = texts.get(f"num_message_{numerics.get('message_code')}")
    if message:
        local["message"] = message.format(**numerics.get("message_context", {}))
    why = texts.get(f"why_{numerics.get('code')}")
    if why and "why_context" in numerics:
        context = {k: CommaFloat(v) if lang in DECIMAL_COMMA else v for k, v in numerics["why_context"].items()}
        local["why"] = why.format(**context)
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
    context = {key: CommaFloat(value) if isinstance(value, float) and decimal == "," else
               ranges_text(value, decimal) if key == "ranges" else value
               for key, value in notice.context.items()}
    return template.format(**context)
