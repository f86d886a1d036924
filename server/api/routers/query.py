"""The query parameters every computing endpoint takes."""
from fastapi import Query

from ..serialise import PLOT_DIGITS

LANG = Query("en", description="language of the warnings and numerics texts: ru, uk or en")
PRECISION = Query("plot", description=(
    f"plot (default): every float rounded to {PLOT_DIGITS} significant digits, enough for any plot or table "
    "(a relative change below 5·10⁻⁷); full: every float as computed (float64 in its shortest round-trip form), "
    "for scripts that need all the digits"))
