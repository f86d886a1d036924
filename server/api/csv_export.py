"""CSV files for spreadsheets (the results, the students' personal links), with formula injection neutralised.

A spreadsheet reads a cell that begins with = + - @ as a formula ("=HYPERLINK(…)", "+cmd|' /C calc'!A0"), and
drops a leading tab or carriage return before doing so ("\\t=1+1" becomes "=1+1"). Per OWASP's CSV Injection
advice, every text cell that begins with one of = + - @ TAB CR gets a leading apostrophe, which the
spreadsheet shows as text. Numbers the app writes itself (a negative answer, -1.5) stay numbers: only text
cells (names, toggles, links) are prefixed, never an int or float.
"""
from __future__ import annotations

import csv
import io
from collections.abc import Iterable

from fastapi.responses import Response

FORMULA_STARTS = ("=", "+", "-", "@", "\t", "\r")


def safe_cell(value) -> str | int | float:
    """The cell as written: numbers unchanged (floats in their shortest round-trip form), None empty, text
    prefixed with ' when a spreadsheet would read it as a formula."""
    if value is None:
        return ""
    if isinstance(value, bool):
        return int(value)
    if isinstance(value, (int, float)):
        return value if isinstance(value, int) else repr(value)
    text = str(value)
    return "'" + text if text.startswith(FORMULA_STARTS) else text


def csv_attachment(header: list[str], rows: Iterable[list], filename: str) -> Response:
    """A CSV download (UTF-8 with a BOM, so that spreadsheets read it as UTF-8), every cell through safe_cell."""
    out = io.StringIO()
    writer = csv.writer(out)
    writer.writerow([safe_cell(cell) for cell in header])
    for row in rows:
        writer.writerow([safe_cell(cell) for cell in row])
    return Response("\ufeff" + out.getvalue(), media_type="text/csv; charset=utf-8",
                    headers={"Content-Disposition": f'attachment; filename="{filename}"'})
