"""Students' names: when two typed names are the same student, and when a new name only looks like another.

A name is kept as typed, cleaned (``clean``); it is compared by its key (``normalise``): Unicode NFKC, case
folding, whitespace collapsed, ё → е, so "IVAN  PETROV" is "Ivan Petrov" and "Пётр" is "Петр". Two names
whose keys differ can still look the same on the results page: "Ivan" with a Cyrillic "а", or "Рора" typed
in Cyrillic beside a Latin "Popa". Such a name is refused, saying which name it resembles:

- a word (a run of letters) may not mix alphabets (``mixed_script``): "Ivаn" with the Cyrillic "а" is refused
  even when nobody is called Ivan yet; a name of several words each in one alphabet ("Ivan Петренко") is fine;
- a name is refused when its skeleton matches an existing name's (``resembles``): each letter is replaced by the
  Latin letters (or digits) it can be mistaken for, per Unicode Technical Standard #39, confusables.txt.
"""
from __future__ import annotations

import csv
import io
import unicodedata
from collections import Counter
from collections.abc import Iterable
from dataclasses import dataclass, field

MAX_NAME = 80
MAX_ROSTER = 2000                 # names in one roster upload

# Look-alikes across alphabets, from Unicode TR39 confusables.txt (https://www.unicode.org/Public/security/latest/
# confusables.txt): the "MA" entries whose source is a Cyrillic or Greek letter and whose prototype is one ASCII
# letter or digit, e.g. "0430 ; 0061 ; MA # ( а → a ) CYRILLIC SMALL LETTER A → LATIN SMALL LETTER A". Keys are
# compared case-folded, so each lowercase letter lists the prototypes of its own entry and of its capital's
# ("і" → i from U+0456, and l from U+0406 "І"; "н" → h from U+041D "Н"). Latin letters stand for themselves:
# names in one alphabet are told apart by their keys (Latin I and l, or 0 and O, are not folded together).
LOOK_ALIKES: dict[str, str] = {
    # Cyrillic
    "а": "a", "б": "6", "в": "b", "г": "r", "е": "e", "з": "3", "к": "k", "м": "m", "н": "h", "о": "o",
    "р": "p", "с": "c", "т": "t", "у": "y", "х": "x", "ь": "b", "ѕ": "s", "і": "il", "ј": "j", "ѡ": "w",
    "ѵ": "v", "ү": "y", "һ": "h", "ҽ": "e", "ӏ": "il", "ԁ": "d", "ԍ": "g", "ԛ": "q", "ԝ": "w",
    # Greek
    "α": "a", "β": "b", "γ": "y", "ε": "e", "ζ": "z", "η": "h", "ι": "il", "κ": "k", "μ": "m", "ν": "vn",
    "ο": "o", "ρ": "p", "σ": "o", "τ": "t", "υ": "uy", "χ": "x", "ϲ": "c", "ϳ": "j",
}
# Scripts that one word may legitimately combine (Japanese writes kanji and kana together).
SCRIPT_FAMILIES = {"HIRAGANA": "JAPANESE", "KATAKANA": "JAPANESE", "CJK": "JAPANESE"}
ROSTER_HEADERS = {"name", "names", "student", "students", "full name", "имя", "фио", "студент", "ім'я", "піб",
                  "ім’я"}


class NameRefused(ValueError):
    """A name that cannot be registered: a code for the pages, the reason in English, and what it refers to."""

    def __init__(self, code: str, reason: str, **about: str):
        super().__init__(reason)
        self.code, self.reason, self.about = code, reason, about


def clean(name: str) -> str:
    """The name as shown: NFKC, control and invisible characters (zero-width spaces, bidi marks, lone
    surrogates) removed, every run of whitespace one space, no space at the ends."""
    text = unicodedata.normalize("NFKC", name)
    kept = "".join(" " if c.isspace() else c for c in text if c.isspace() or unicodedata.category(c)[0] != "C")
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


def skeleton(key: str) -> tuple[str, ...]:
    """For each character of a key, the characters it can be taken for: itself, and its Latin look-alikes."""
    return tuple(c + LOOK_ALIKES.get(c, "") for c in key)


def look_alike(key: str, other: str) -> bool:
    """Two different keys that can be read as the same: at every place, some character both can be taken for."""
    if key == other or len(key) != len(other):
        return False
    return all(set(a) & set(b) for a, b in zip(skeleton(key), skeleton(other)))


def resembles(name: str, existing: Iterable[str]) -> str | None:
    """The first existing name (as shown) that ``name`` looks like without being it, or None."""
    key = normalise(name)
    return next((shown for shown in existing if look_alike(key, normalise(shown))), None)


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
