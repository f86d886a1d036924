"""The page's markup of interface texts read on the server, as web/static/js/common/view/notation.js reads it:
"M_c0", "A_{P,k}", "R^{1/3}" (a run after "_" or "^" is a subscript or a superscript), "\\_" a plain
underscore. The templates render it with <sub>/<sup> (server/api/routers/pages.py); where only plain text can
stand (a CSV header, a title attribute) it is written as the page's aria-labels write it."""
from __future__ import annotations

import unicodedata

from .numbers import SUBSCRIPTS, SUPERSCRIPTS


def _lowers(char: str) -> bool:
    """A character of a run after "_" or "^": a letter, a decimal digit or a combining mark (\\p{L}, \\p{Nd},
    \\p{M} in web/static/js/common/view/notation.js)."""
    category = unicodedata.category(char)
    return category[0] in "LM" or category == "Nd"


def notation_parts(text: str) -> list[tuple[str, str]]:
    """text split into (run, shift) with shift "", "sub" or "sup": the markup of web/static/js/common/view/notation.js
    ("M_c0", "A_{P,k}", "R^{1/3}", "\\_" a plain underscore), read the same way."""
    parts, plain, i = [], "", 0
    while i < len(text):
        char = text[i]
        if char == "\\" and text[i + 1:i + 2] in ("_", "^"):
            plain, i = plain + text[i + 1], i + 2
            continue
        if char in "_^" and i > 0:
            if text[i + 1:i + 2] == "{" and "}" in text[i + 2:] and "{" not in text[i + 2:text.index("}", i + 2)]:
                end = text.index("}", i + 2)
                run, after = text[i + 2:end], end + 1
            else:
                end = i + 1
                while end < len(text) and _lowers(text[end]):
                    end += 1
                run, after = text[i + 1:end], end
            if run or after > i + 1:
                parts += [(plain, "")] if plain else []
                parts.append((run, "sub" if char == "_" else "sup"))
                plain, i = "", after
                continue
        plain, i = plain + char, i + 1
    return parts + ([(plain, "")] if plain else [])


def plain_label(text: str) -> str:
    """A label of the page's notation as plain text, the way the page names things where only plain text can
    stand (plainText of web/static/js/common/view/notation.js, its aria-labels): the markup dropped, the digits
    of a subscript or superscript written as Unicode glyphs, its letters as they are, for Unicode has no
    subscript of most letters (Cyrillic none): "u_31" → "u₃₁", "I_м" → "Iм", "M_с0^пр" → "Mс₀пр",
    "R^{1/3}" → "R¹/³", "solve\\_ivp" → "solve_ivp"."""
    return "".join(run.translate(SUBSCRIPTS if shift == "sub" else SUPERSCRIPTS) if shift else run
                   for run, shift in notation_parts(text))
