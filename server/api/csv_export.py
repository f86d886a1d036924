"""CSV files for spreadsheets (the results, the students' personal links): formula injection neutralised, in
the instructor's language and conventions.

A spreadsheet reads a cell that begins with = + - @ as a formula ("=HYPERLINK(…)", "+cmd|' /C calc'!A0"), and
drops a leading tab or carriage return before doing so ("\\t=1+1" becomes "=1+1"). Which characters split the
cells is the reader's choice, not the file's: a ru/uk spreadsheet splits at ";", another at "," or a tab, and
a text cell such as "Ivan Petrov;=1+1" read with ";" becomes two cells, the second a formula. So every text
cell is quoted, and a formula character is neutralised with a leading apostrophe (OWASP's CSV Injection
advice; the spreadsheet shows it as text) wherever a cell could begin, whatever the separator: at the start
of the text and after every separator, quote or line break in it. Numbers the app writes itself (a negative
answer, -1.5) stay numbers: never prefixed.

Conventions by language: ru and uk write ";" between cells and a decimal comma (1,5), as their spreadsheets
read them; en writes "," and a decimal point. The results' columns are headed in words of the assignment's
language: the students, the sliders by their labels (λ = l₂/l₁), the questions by theirs, as plain text
(plain_label): a spreadsheet shows no subscript, so the page's markup must not reach it.
"""
from __future__ import annotations

import csv
import io
import re
from collections.abc import Iterable

from fastapi.responses import Response

from ..classroom.variants import Plan
from ..lessons.scenes import interface_texts
from ..classroom.answers import question
from ..lessons.markup import plain_label
from .schemas_assignments import ResultRow

FORMULA_STARTS = ("=", "+", "-", "@", "\t", "\r")
# a formula character where a reader may start a cell: the text's start, or after a separator, quote or line break
_CELL_START_FORMULA = re.compile(r'(^|[,;\t\r\n"])([=+\-@\t\r])')
SEPARATOR = {"ru": ";", "uk": ";", "en": ","}
DECIMAL = {"ru": ",", "uk": ",", "en": "."}
# the results' columns, in content/i18n's words where it has them
WORDS = {"student": "assignment_student", "variant": "assignment_variant", "attempts": "assignment_answers",
         "right": "assignment_right", "correct": "assignment_correct_value", "score": "assignment_score",
         "first_seen": "assignment_first_seen", "last_submission": "assignment_last"}
ANSWER = {"ru": "ответ", "uk": "відповідь", "en": "answer"}
LINK = {"ru": "Личная ссылка", "uk": "Особисте посилання", "en": "Personal link"}


def neutralised(text: str) -> str:
    """The text with an apostrophe before every formula character that could begin a cell."""
    return _CELL_START_FORMULA.sub(lambda m: m.group(1) + "'" + m.group(2), text)


def safe_cell(value, lang: str = "en") -> str:
    """The cell as written: numbers unchanged in their shortest round-trip form (with the language's decimal
    separator), None empty, text neutralised."""
    if value is None:
        return ""
    if isinstance(value, bool):
        return str(int(value))
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        return repr(value).replace(".", DECIMAL.get(lang, "."))
    return neutralised(str(value))


def csv_attachment(header: list[str], rows: Iterable[list], filename: str, lang: str = "en") -> Response:
    """A CSV download in the language's conventions (UTF-8 with a BOM, so that spreadsheets read it as UTF-8),
    every cell quoted and through safe_cell."""
    out = io.StringIO()
    writer = csv.writer(out, delimiter=SEPARATOR.get(lang, ","), quoting=csv.QUOTE_ALL)
    writer.writerow([neutralised(str(cell)) for cell in header])
    for row in rows:
        writer.writerow([safe_cell(cell, lang) for cell in row])
    return Response("\ufeff" + out.getvalue(), media_type="text/csv; charset=utf-8",
                    headers={"Content-Disposition": f'attachment; filename="{filename}"'})


def parameter_label(resolved: Plan, key: str, lang: str) -> str:
    """A slider's or a toggle's label in the language, as plain text; the key itself for a value no control
    shows."""
    for control in [*resolved.variant.sliders, *resolved.variant.toggles]:
        if control.id == key:
            return plain_label(control.label.get(lang) or control.label.get("en") or key)
    return key


def results_table(resolved: Plan, rows: Iterable[ResultRow], lang: str) -> tuple[list[str], list[list]]:
    """The results' header, in words of the language, and one row per student."""
    words = interface_texts(lang)
    word = {name: words.get(key, name) for name, key in WORDS.items()}
    questions = [pick.id for pick in resolved.spec.questions]
    labels = {q: plain_label(question(resolved.scene, q).label.get(lang, q)) for q in questions}
    parameters = list(resolved.values(0))
    header = [word["student"], word["variant"], *[parameter_label(resolved, p, lang) for p in parameters],
              *[f"{labels[q]}: {part}" for q in questions
                for part in (word["attempts"], word["right"], ANSWER.get(lang, "answer"), word["correct"])],
              word["score"], word["attempts"], word["first_seen"], word["last_submission"]]
    body = [[row.student, row.variant, *[row.values.get(p) for p in parameters],
             *[v for q in questions for v in (row.questions[q]["attempts"], int(row.questions[q]["right"]),
                                              row.questions[q]["answer"], row.questions[q]["correct"])],
             row.score, row.attempts, row.first_seen, row.last_submission] for row in rows]
    return header, body


def results_csv(resolved: Plan, rows: Iterable[ResultRow], filename: str) -> Response:
    """The instructor's results as CSV in the assignment's language and conventions."""
    lang = resolved.spec.lang
    header, body = results_table(resolved, rows, lang)
    return csv_attachment(header, body, filename, lang)


def links_csv(resolved: Plan, rows: Iterable[list], filename: str) -> Response:
    """The students' personal links (name, variant, link) as CSV in the assignment's language and conventions."""
    lang = resolved.spec.lang
    words = interface_texts(lang)
    header = [words.get("assignment_student", "student"), words.get("assignment_variant", "variant"),
              LINK.get(lang, LINK["en"])]
    return csv_attachment(header, rows, filename, lang)
