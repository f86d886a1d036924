"""Warnings, errors and numerics texts of the numeric core in the reader's language (content/i18n, keys
warn_*/err_*/num_*/study_*), with numbers as the page writes them: a decimal comma in Russian and Ukrainian
and a true minus sign (U+2212, never "−0") in every language.

A sentence the core says in English without a code (a solver's outcome set as plain text) is read back
with the English template of the same words (``num_message_*``, ``warn_*`` in content/i18n/en.json, whose
fields become the parts that vary) and said again with the reader's template: ``from_english``.
"""
from __future__ import annotations

import math
import re
import string
from functools import lru_cache

from ..core.mechanisms import Notice
from ..core.mechanisms.base import ranges_text
from ..lessons.numbers import (DECIMAL_COMMA, MINUS, NUMBER, POWER, SUBSCRIPTS, SUPERSCRIPTS,  # noqa: F401
                               ZERO, CommaFloat, ReadableFloat, signed)
from ..lessons.scenes import interface_texts

FIELD = re.compile(r"\{(\w+)(?:![rsa])?(?::[^{}]*)?\}")     # a placeholder of a template


def written(value, lang: str):
    """A number the core formatted already ("4.4e-16") as the page writes it; anything else as it is."""
    if not isinstance(value, str) or not NUMBER.match(value):
        return value
    return signed(value.replace(".", "," if lang in DECIMAL_COMMA else "."))


def localise_numerics(numerics: dict, lang: str) -> dict:
    """The method's description (and, for the elastic models, why it was chosen) in the reader's language."""
    texts = interface_texts(lang) if lang != "en" else {}
    local = dict(numerics)
    template = texts.get(f"num_{numerics.get('code')}")
    if template:
        local["method"] = template.format(method=numerics.get("method", ""))
    number = CommaFloat if lang in DECIMAL_COMMA else ReadableFloat
    code = numerics.get("message_code")
    # a routine message in every language (English too: numbers written out), or a warning's words
    message = interface_texts(lang).get(f"num_message_{code}") or texts.get(f"warn_{code}")
    if code and message:
        local["message"] = message.format(**filled(numerics.get("message_context", {}), lang))
    elif numerics.get("message"):
        local["message"] = from_english(numerics["message"], lang)
    why = interface_texts(lang).get(f"why_{numerics.get('code')}")      # English too: readable numbers
    if why and "why_context" in numerics:
        local["why"] = why.format(**{k: number(v) for k, v in numerics["why_context"].items()})
    return local


# The methods of a work–precision study as server/core/work_precision.py labels them, and their interface
# texts: study_method_<key> with the solver's name in {solver}; "ours" marks the app's own method.
STUDY_METHODS = [
    (re.compile(r"ours: Newton shooting"), "newton"),
    (re.compile(r"solve_ivp (?P<solver>\w+), cycles until periodic"), "cycles"),
    (re.compile(r"ours: compiled (?P<solver>\w+)"), "compiled"),
    (re.compile(r"(?P<solver>\w+)"), "scipy"),
]
OUR_METHODS = ("newton", "compiled")
SKIPPED_RUN = re.compile(r"(?P<method>.+) (?P<rtol>\d(?:\.\d+)?e[-+]\d+)")


def study_method(label: str, lang: str) -> tuple[str, bool]:
    """A study's method label in the reader's language, and whether it is the app's own method."""
    for pattern, key in STUDY_METHODS:
        found = pattern.fullmatch(label)
        if found:
            return interface_texts(lang)[f"study_method_{key}"].format(**found.groupdict()), key in OUR_METHODS
    return label, label.startswith("ours")


def skipped_run(text: str, lang: str) -> str:
    """"ours: compiled Radau 1e-05" → "наш: Radau (компилированный), rtol = 10⁻⁵"."""
    found = SKIPPED_RUN.fullmatch(text)
    if not found:
        return text
    rtol = written(found["rtol"], lang)
    return f"{study_method(found['method'], lang)[0]}, rtol = {rtol}"


def localise_study(study: dict, lang: str) -> dict:
    """The work–precision study in the reader's language: reference, quantity, each row's method (with
    ``ours`` true for the app's own method) and the runs left out."""
    texts = interface_texts(lang)              # English too: "rtol = 10⁻¹¹", not the core's "1e-11"
    local = dict(study)
    for field in ("reference", "quantity"):
        text = texts.get(f"study_{field}_{study.get(field + '_code')}")
        if text:
            local[field] = text
    local["rows"] = [row | dict(zip(("method", "ours"), study_method(row["method"], lang)))
                     for row in study.get("rows", [])]
    local["skipped"] = [skipped_run(text, lang) for text in study.get("skipped", [])]
    return local


@lru_cache(maxsize=None)
def english_sentences() -> list[tuple[re.Pattern, str]]:
    """Every English template of a numerics outcome or warning as a pattern whose groups are its fields,
    with its key; the longest first, so that a template never matches the start of a longer one's text."""
    sentences = []
    for key, text in interface_texts("en").items():
        if not key.startswith(("num_message_", "warn_", "num_reason_")):
            continue
        pattern, names = "", set()
        for literal, name, _, _ in string.Formatter().parse(text):
            pattern += re.escape(literal)
            if name is not None:
                pattern += f"(?P={name})" if name in names else f"(?P<{name}>.+?)"
                names.add(name)
        sentences.append((re.compile(pattern), key))
    return sorted(sentences, key=lambda item: -len(item[0].pattern))


def from_english(text: str, lang: str) -> str:
    """text, an English sentence of the core, in lang: said with lang's template of the same key, the parts
    that vary copied over (numbers with lang's decimal separator and minus sign, an English reason that has
    a template of its own translated too); text itself when no template matches."""
    for pattern, key in english_sentences():
        found = pattern.fullmatch(text)
        if found is None:
            continue
        parts = {name: written(value, lang) if NUMBER.match(value) else from_english(value, lang)
                 for name, value in found.groupdict().items()}
        return FIELD.sub(lambda field: parts[field[1]], interface_texts(lang)[key])
    return text


def translate(notice: Notice, lang: str) -> str:
    """The notice in ``lang``; English text of the core when the language has no template for it."""
    if lang == "en":
        return notice.text
    template = interface_texts(lang).get(f"warn_{notice.code}")
    if template is None:
        return notice.text
    return template.format(**filled(notice.context, lang))


def special_text(special: dict, lang: str) -> str:
    """A general mechanism's special position (its fields: kind, group, name, group_kind, link or slide, value)
    as a sentence in ``lang``, the group by its name in the structural formula: "group II₂(2,3) RRP: limit of
    assembly", "group II₂(4,5) RRP: slider E (guide x–x) reverses, an extreme position s = 0.181 m".  A slide is
    named as the core names it, its guide by its label in ``lang`` (guide_label_*): "E/ram" is the slider E on
    the guide ram, "B/slot" the block at B in its slot (RPP), an RPR group's slide ("s23") as it is.  Every
    value with its unit: a link's angle θ in degrees, a slide's s in metres, the angle between the group's links
    at its closest to a dead position in degrees."""
    texts = interface_texts(lang)
    number = CommaFloat if lang in DECIMAL_COMMA else ReadableFloat
    what, value = "", special.get("value")
    if special.get("link") is not None:
        what = f"{texts['editor_link']} {special['link']}"
        if value is not None:
            value = f"θ{str(special['link']).translate(SUBSCRIPTS)} = {number(math.degrees(value) % 360):.1f}°"
    elif special.get("slide") is not None:
        joint, _, guide = special["slide"].partition("/")
        where = "" if not guide else (f" {texts['editor_in_slot']}" if guide == "slot"
                                      else f" ({texts['editor_guide_word']} {texts.get(f'guide_label_{guide}', guide)})")
        what = f"{texts['editor_slide']} {joint}{where}"
        if value is not None:
            value = f"s = {number(value):.3f} {texts['units_m']}"
    elif value is not None:           # |sin| of the angle between the group's links
        value = f"{number(math.degrees(math.asin(min(value, 1.0)))):.1f}°"
    return texts[f"editor_sp_{special['kind']}"].format(group=special.get("name") or special["group"],
                                                         kind=special["group_kind"], what=what, value=value or "")


def filled(context: dict, lang: str) -> dict:
    """A template's context as lang writes it: floats and numbers formatted already ("4.4e-16") with its
    decimal separator and minus sign, angle ranges as "57,0°–133,0°"."""
    decimal = "," if lang in DECIMAL_COMMA else "."
    number = CommaFloat if decimal == "," else ReadableFloat
    return {key: number(value) if isinstance(value, float) else
            ranges_text(value, decimal) if key == "ranges" else written(value, lang)
            for key, value in context.items()}
