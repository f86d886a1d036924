"""One notation per quantity (tests/notation.json, the one list): every scene's texts and the interface texts, read
as the pages show them (server/api/routers/pages.notation_parts: a subscript as _{…}, a superscript as ^{…}), never
write a quantity in another form than the list's — the flywheel I_м (not J_м), the crank's mean speed ω_1ср (not
ω_ср, ω₁ср), the main bearing's R₁₄ (not R₄₁), the reduced moments and group inertias with the books' ^пр (ru) /
^зв (uk), a Cyrillic с in M_с0. The printed forms of errata are quotes of a book and keep its spelling. The table of
the symbols each scene uses goes to test-artifacts/notation_table.json."""
from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from server.lessons.markup import notation_parts
from server.lessons.scenes import interface_texts, scene_documents

REPO = Path(__file__).resolve().parents[1]
NOTATION = json.loads((REPO / "tests" / "notation.json").read_text(encoding="utf-8"))["quantities"]
QUOTES = ("erratum_printed", "erratum_why", "project_eq_gutyar_printed", "project_eq_wittenbauer_printed")
LANGUAGES = ("ru", "uk", "en")


def shown(text: str) -> str:
    """text as the page shows it, read back into markup: "M_с0^пр" → "M_{с0}^{пр}"."""
    return "".join(run if not shift else ("_" if shift == "sub" else "^") + "{" + run + "}"
                   for run, shift in notation_parts(text))


def other_forms(text: str, lang: str, scene_id: str | None) -> list[str]:
    """The spellings of a quantity in text that the list does not allow (quantity: the spelling)."""
    found = []
    for entry in NOTATION:
        if scene_id in entry.get("except", ()):
            continue
        for pattern in entry["not"][lang]:
            found += [f"{entry['quantity']}: {m.group(0)}" for m in re.finditer(pattern, text)]
    return found


def scene_strings(document, lang: str, where: str = ""):
    """(where, text) of every string of a scene document in lang (its questions included)."""
    if isinstance(document, dict):
        for key, value in document.items():
            if key == lang and isinstance(value, str):
                yield where, value
            else:
                yield from scene_strings(value, lang, f"{where}.{key}")
    elif isinstance(document, list):
        for i, value in enumerate(document):
            yield from scene_strings(value, lang, f"{where}[{i}]")


def test_the_list_gives_every_quantity_a_form_in_each_language_that_it_does_not_forbid():
    for entry in NOTATION:
        for lang in LANGUAGES:
            assert not other_forms(entry["forms"][lang], lang, None), entry["quantity"]


@pytest.mark.parametrize("lang", LANGUAGES)
def test_every_scene_writes_each_quantity_in_the_lists_form(lang):
    wrong, table = [], {}
    for name, document in scene_documents().items():
        scene_id = document["id"]
        used = set()
        for where, text in scene_strings(document, lang):
            if any(part in where for part in ("errata", "printed")):
                continue
            markup = shown(text)
            wrong += [f"{name}{where}: {found}" for found in other_forms(markup, lang, scene_id)]
            used |= {entry["quantity"] for entry in NOTATION if entry["forms"][lang] in markup}
        table[scene_id] = sorted(used)
    artifacts = REPO / "test-artifacts"
    artifacts.mkdir(exist_ok=True)
    (artifacts / f"notation_table_{lang}.json").write_text(json.dumps(table, ensure_ascii=False, indent=1), "utf-8")
    assert wrong == []
    assert sum(map(len, table.values())) >= 10          # the forms are found, not only the other forms missed


@pytest.mark.parametrize("lang", LANGUAGES)
def test_the_interface_texts_write_each_quantity_in_the_lists_form(lang):
    wrong = [f"{key}: {found}" for key, text in interface_texts(lang).items() if not key.startswith(QUOTES)
             for found in other_forms(shown(text), lang, None)
             if not key.startswith(("elastic_", "warn_elastic")) or "M_" not in found]
    assert wrong == []
