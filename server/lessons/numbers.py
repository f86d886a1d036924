"""Numbers as the page writes them in a sentence: a decimal comma in Russian and Ukrainian, a true minus sign
(U+2212, never "−0") and powers of ten written out, in every language."""
from __future__ import annotations

import math
import re

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
        return signed(text.replace(".", self.decimal))


class CommaFloat(ReadableFloat):
    decimal = ","


MINUS = "\u2212"
SUPERSCRIPTS = str.maketrans("-0123456789", "⁻⁰¹²³⁴⁵⁶⁷⁸⁹")
SUBSCRIPTS = str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉")
ZERO = re.compile(r"^-(?=[0.,]*(?:$|[^0-9.,]))")      # "-0", "-0.00", "-0e+00": a zero keeps no sign
POWER = re.compile(r"e([-+]?\d+)$")
NUMBER = re.compile(r"^-?\d+(?:\.\d+)?(?:e[-+]?\d+)?$")      # a number as Python writes it


def signed(text: str) -> str:
    """A formatted number as the page writes it: a true minus sign ("-2.5" → "−2.5"), a zero without one
    ("-0.0" → "0.0") and a power of ten written out ("1.5e-05" → "1.5·10⁻⁵", "1e+06" → "10⁶")."""
    power = POWER.search(text)
    if power:
        exponent = str(int(power[1])).translate(SUPERSCRIPTS)
        mantissa = text[:power.start()]
        if float(mantissa.replace(",", ".")) == 0:
            return "0"
        text = f"10{exponent}" if mantissa.lstrip("-") == "1" else f"{mantissa}·10{exponent}"
        text = "-" + text if mantissa.startswith("-") and text.startswith("10") else text
    return MINUS + text[1:] if text.startswith("-") and not ZERO.match(text) else ZERO.sub("", text)
