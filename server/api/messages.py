"""Warnings and errors of the numeric core in the reader's language (content/i18n, keys warn_*/err_*)."""
from __future__ import annotations

from ..core.mechanisms import Notice
from .content import interface_texts


def translate(notice: Notice, lang: str) -> str:
    """The notice in ``lang``; English text of the core when the language has no template for it."""
    if lang == "en":
        return notice.text
    template = interface_texts(lang).get(f"warn_{notice.code}")
    if template is None:
        return notice.text
    return template.format(**notice.context)
