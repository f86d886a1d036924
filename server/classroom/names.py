"""Students' names: when two typed names are the same student, and when a new name only looks like another.

A name is kept as typed, cleaned (``clean``); it is compared by its key (``normalise``): Unicode NFKC, case
folding, whitespace collapsed, ё → е, so "IVAN  PETROV" is "Ivan Petrov" and "Пётр" is "Петр". Two names
whose keys differ can still look the same on the results page: "Ivan" with a Cyrillic "а", or "Рора" typed
in Cyrillic beside a Latin "Popa". Such a name is refused, saying which name it resembles:

- a word (a run of letters) may not mix alphabets (``mixed_script``): "Ivаn" with the Cyrillic "а" is refused
  even when nobody is called Ivan yet; a name of several words each in one alphabet ("Ivan Петренко") is fine;
- a name is refused when its skeleton matches an existing name's (``resembles``): the skeleton of Unicode
  Technical Standard #39 (every character replaced by the prototype it can be mistaken for, all of
  confusables.txt: Cyrillic "а" → "a", Cherokee "Ꭰ" → "D", and within one alphabet "I" → "l", "m" → "rn",
  "0" → "O"), compared case-folded, so "lvan Petrov" (a Latin l) is refused beside "Ivan Petrov", and
  "ᎠᎪᏙᎬ Smith" beside "Dave Smith". Distinct letters stay distinct: "Петров" and "Петрова", "Іван" and "Иван".

Characters that show nothing (``IGNORABLE_RANGES``: zero-width and bidi marks, variation selectors, the
combining grapheme joiner, Hangul fillers, the Braille blank) are dropped from a name as typed (``clean``).
"""
from __future__ import annotations

import bisect
import csv
import io
import unicodedata
from collections import Counter
from collections.abc import Iterable
from dataclasses import dataclass, field
from functools import lru_cache

from .confusables_table import TABLE as CONFUSABLES

MAX_NAME = 80
MAX_ROSTER = 2000                 # names in one roster upload

# Characters that show nothing, dropped from a name: Unicode's Default_Ignorable_Code_Point (DerivedCoreProperties,
# Unicode 15: soft hyphen, combining grapheme joiner, Hangul fillers, variation selectors, tags, …) and blanks
# that are not classed so, U+2800 BRAILLE PATTERN BLANK and U+FFFC OBJECT REPLACEMENT CHARACTER.
IGNORABLE_RANGES = ((0x00AD, 0x00AD), (0x034F, 0x034F), (0x061C, 0x061C), (0x115F, 0x1160), (0x17B4, 0x17B5),
                    (0x180B, 0x180F), (0x200B, 0x200F), (0x202A, 0x202E), (0x2060, 0x206F), (0x2800, 0x2800),
                    (0x3164, 0x3164), (0xFE00, 0xFE0F), (0xFEFF, 0xFEFF), (0xFFA0, 0xFFA0), (0xFFF0, 0xFFF8),
                    (0xFFFC, 0xFFFC), (0x1BCA0, 0x1BCA3), (0x1D173, 0x1D17A), (0xE0000, 0xE0FFF))
# Scripts that one word may legitimately combine (Japanese writes kanji and kana together).
SCRIPT_FAMILIES = {"HIRAGANA": "JAPANESE", "KATAKANA": "JAPANESE", "CJK": "JAPANESE"}
ROSTER_HEADERS = {"name", "names", "student", "students", "full name", "имя", "фио", "студент", "ім'я", "піб",
                  "ім’я"}


class NameRefused(ValueError):
    """A name that cannot be registered: a code for the pages, the reason in English, and what it refers to."""

    def __init__(self, code: str, reason: str, **about: str):
        super().__init__(reason)
        self.code, self.reason, self.about = code, reason, about


_IGNORABLE_STARTS = [start for start, _ in IGNORABLE_RANGES]


def invisible(c: str) -> bool:
    """A character that shows nothing in a name: a control or format character, an unassigned or private one,
    a lone surrogate (category C), or one of ``IGNORABLE_RANGES``."""
    code = ord(c)
    k = bisect.bisect_right(_IGNORABLE_STARTS, code) - 1
    return unicodedata.category(c)[0] == "C" or (k >= 0 and code <= IGNORABLE_RANGES[k][1])


def clean(name: str) -> str:
    """The name as shown: NFKC, characters that show nothing removed (``invisible``: zero-width spaces, bidi
    marks, variation selectors, Hangul fillers, the Braille blank), every run of whitespace one space, no space
    at the ends."""
    text = unicodedata.normalize("NFKC", "".join(c for c in name if c.isspace() or not invisible(c)))
    kept = "".join(" " if c.isspace() else c for c in text if c.isspace() or not invisible(c))
    return " ".join(kept.split())


def normalise(name: str) -> str:
    """The key that identifies a student: the cleaned name, case-folded (NFKC again after folding), ё → е."""
    folded = unicodedata.normalize("NFKC", clean(name).casefold())
    return folded.replace("ё", "е")


def script(letter: str) -> str | None:
    """The alphabet of a letter from its Unicode name (LATIN, CYRILLIC, GREEK, …); None for marks and
    modifier letters, which take the script of the letter they stand with."""
    if unicodedata.category(letter)[0] != "L":
        return None
    first = unicodedata.name(letter, "UNKNOWN").split()[0]
    return None if first == "MODIFIER" else SCRIPT_FAMILIES.get(first, first)


def words(name: str) -> list[str]:
    """The runs of letters (with their marks) in a name: "KM-21/1 Ivanov" → ["KM", "Ivanov"]."""
    found, current = [], ""
    for c in name:
        if unicodedata.category(c)[0] in "LM":
            current += c
        elif current:
            found.append(current)
            current = ""
    return found + ([current] if current else [])


@dataclass(frozen=True)
class MixedWord:
    word: str
    letter: str          # the first letter outside the word's main alphabet
    script: str          # that letter's alphabet
    main: str            # the alphabet most of the word's letters are in


def mixed_script(name: str) -> MixedWord | None:
    """The first word of the name that mixes alphabets, or None."""
    for word in words(name):
        scripts = [(c, script(c)) for c in word if script(c)]
        counts = Counter(s for _, s in scripts)
        if len(counts) > 1:
            main = counts.most_common(1)[0][0]
            letter, other = next((c, s) for c, s in scripts if s != main)
            return MixedWord(word, letter, other.capitalize(), main.capitalize())
    return None


@lru_cache(maxsize=1)
def confusables() -> dict[str, str]:
    """Unicode TR39 confusables, every entry (confusables_table.py, made by confusables_build.py): a character →
    its prototype, "а" (Cyrillic) → "a", "I" → "l", "m" → "rn", "0" → "O"."""
    table = {}
    for line in CONFUSABLES.splitlines():
        if line:
            source, *prototype = line.split()
            table[chr(int(source, 16))] = "".join(chr(int(code, 16)) for code in prototype)
    return table


def skeleton(text: str) -> str:
    """The TR39 skeleton: NFD, every character replaced by its prototype, NFD again."""
    table = confusables()
    return unicodedata.normalize("NFD", "".join(table.get(c, c) for c in unicodedata.normalize("NFD", text)))


@lru_cache(maxsize=16384)
def look(name: str) -> frozenset[str]:
    """How a name can be read, case aside: the case-folded skeletons of the name as typed and of its case-folded
    form (the capital "I" reads as "l", the small "m" as "rn")."""
    shown = clean(name)
    return frozenset(skeleton(skeleton(form).casefold()) for form in (shown, shown.casefold()))


def look_alike(name: str, other: str) -> bool:
    """Two names of different students (different keys) that can be read as the same."""
    return normalise(name) != normalise(other) and not look(name).isdisjoint(look(other))


def resembles(name: str, existing: Iterable[str]) -> str | None:
    """The first existing name (as shown) that ``name`` looks like without being it, or None."""
    key, seen = normalise(name), look(name)
    return next((shown for shown in existing if not seen.isdisjoint(look(shown)) and normalise(shown) != key), None)


def check_new(name: str, existing: Iterable[str]) -> str:
    """The cleaned name if it may be registered beside the existing names; NameRefused saying why not."""
    shown = clean(name)
    if not normalise(shown):
        raise NameRefused("name_empty", "type a name or a number")
    if len(shown) > MAX_NAME:
        raise NameRefused("name_too_long", f"at most {MAX_NAME} characters")
    mixed = mixed_script(shown)
    if mixed:
        raise NameRefused("name_mixed_scripts",
                          f"the word '{mixed.word}' mixes alphabets: '{mixed.letter}' is {mixed.script}, the rest "
                          f"{mixed.main}; type each word in one alphabet",
                          word=mixed.word, letter=mixed.letter, script=mixed.script)
    similar = resembles(shown, existing)
    if similar is not None:
        raise NameRefused("name_confusable", f"'{shown}' looks like the name '{similar}' already registered; if that "
                                             f"is you, open your personal link or ask the instructor",
                          resembles=similar)
    return shown


@dataclass
class Roster:
    """Names read from an uploaded roster, and the lines that could not be read as a name."""

    names: list[str] = field(default_factory=list)
    refused: list[tuple[str, str]] = field(default_factory=list)     # (line as given, reason)


def roster_names(text: str) -> Roster:
    """A roster as the instructor pastes or uploads it: one name per line, or a table whose column headed
    name / student / ФИО / ПІБ (any case) holds the names. Columns are split at tabs or semicolons (what
    spreadsheets save), or at commas when such a header names the column; without a header a comma belongs to
    the name ("Ivanov, Petr"), and the first column of a tab or semicolon table holds the names. A header line
    is skipped, empty lines are ignored, the same name twice counts once."""
    lines = [line for line in text.replace("\ufeff", "").splitlines() if line.strip()]
    delimiter = next((d for d in ("\t", ";", ",") if lines and d in lines[0]), None)
    rows = [row for row in csv.reader(io.StringIO("\n".join(lines)), delimiter=delimiter) if row] if delimiter \
        else [[line] for line in lines]
    header = rows[0] if rows else []
    column = next((i for i, cell in enumerate(header) if normalise(cell) in ROSTER_HEADERS), None)
    if column is not None:
        rows = rows[1:]
    elif delimiter == ",":
        rows, column = [[line] for line in lines], 0
    else:
        column = 0
    roster, seen = Roster(), set()
    for row in rows[:MAX_ROSTER]:
        given = row[column] if column < len(row) else ""
        shown = clean(given)
        if not normalise(shown):
            roster.refused.append(((delimiter or "").join(row), "no name in this line"))
        elif len(shown) > MAX_NAME:
            roster.refused.append((shown, f"longer than {MAX_NAME} characters"))
        elif normalise(shown) not in seen:
            seen.add(normalise(shown))
            roster.names.append(shown)
    if len(rows) > MAX_ROSTER:
        roster.refused.append((f"{len(rows) - MAX_ROSTER} more lines", f"at most {MAX_ROSTER} names at once"))
    return roster
