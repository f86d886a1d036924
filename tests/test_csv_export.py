"""The instructor's CSV files: no formula whatever separator the spreadsheet splits at, and the conventions and
words of the assignment's language.

1. Names such as "Ivan Petrov;=1+1" and "Ira;=cmd|' /C calc'!A0" once went out unquoted, so a ru/uk
   spreadsheet splitting at ";" saw a cell "=1+1". Now, read back with csv.reader at "," ";" and a tab, no cell
   begins with = + - @ TAB CR, except a negative number the app wrote.
2. ru and uk write ";" and a decimal comma, en "," and a decimal point; every number reads back exactly.
3. The results' columns are headed in words of the assignment's language: the sliders by their labels
   (λ = l₂/l₁), the questions by theirs, not by internal keys.
"""
from __future__ import annotations

import csv
import io
import re

import pytest
from fastapi.testclient import TestClient

from server.classroom import assignment_store
from server.api.app import app
from server.api.csv_export import csv_attachment

API = "/api/v1/assignments"
HOSTILE = ["Ivan Petrov;=1+1", "Ira;=cmd|' /C calc'!A0", "Oleh,+SUM(A1)", "Petro\t@A1", "=HYPERLINK(\"x\")",
           "-1", "Anna\";=1", "Mark\n=2", "@x;-y,+z\t=w", "Олена;;=1"]
FORMULA = ("=", "+", "-", "@", "\t", "\r")
CRANK = {"scene": "transfer-functions", "variant": "slider_crank",
         "sliders": {"lambda": {"vary": {"min": 2.5, "max": 5.0}}},
         "questions": [{"id": "u31_max"}, {"id": "du31_min"}], "attempts": 3}


def cells(text: str, delimiter: str) -> list[str]:
    return [cell for row in csv.reader(io.StringIO(text.lstrip("\ufeff"), newline=""), delimiter=delimiter)
            for cell in row]


def assert_no_formula(text: str, negative_numbers: list[str]) -> None:
    """Read with each separator: a cell may begin with a formula character only as a negative number written
    by the app (which a mismatched reader may glue to the next cell)."""
    for delimiter in (",", ";", "\t"):
        for cell in cells(text, delimiter):
            if cell.startswith(FORMULA):
                assert cell.startswith("-") and any(cell.startswith(n) for n in negative_numbers), \
                    f"read at {delimiter!r}: {cell!r}"


@pytest.mark.parametrize("lang", ["ru", "uk", "en"])
def test_no_cell_begins_a_formula_whatever_the_separator(lang):
    rows = [[name, 3, -1.5, 2.25e-5, None, True] for name in HOSTILE]
    text = csv_attachment(["student", "variant", "answer", "correct", "empty", "right"], rows, "t.csv",
                          lang).body.decode("utf-8")
    written = ["-1,5"] if lang in ("ru", "uk") else ["-1.5"]
    assert_no_formula(text, written)
    read = list(csv.reader(io.StringIO(text.lstrip("\ufeff"), newline=""), delimiter=";" if lang != "en" else ","))
    for row, name in zip(read[1:], HOSTILE):                # the separator of the file: the name, neutralised
        assert row[0].replace("'", "") == name.replace("'", "") and not row[0].startswith(FORMULA)
        assert float(row[2].replace(",", ".")) == -1.5 and float(row[3].replace(",", ".")) == 2.25e-5
        assert row[4] == "" and row[5] == "1"


@pytest.mark.parametrize("lang, delimiter, decimal", [("ru", ";", ","), ("uk", ";", ","), ("en", ",", ".")])
def test_the_separator_and_the_decimal_mark_are_the_languages(lang, delimiter, decimal):
    text = csv_attachment(["a", "b"], [[0.1 + 0.2, -7]], "t.csv", lang).body.decode("utf-8")
    line = text.lstrip("\ufeff").splitlines()[1]
    assert line == f'"0{decimal}30000000000000004"{delimiter}"-7"'
    row = list(csv.reader(io.StringIO(text.lstrip("\ufeff")), delimiter=delimiter))[1]
    assert float(row[0].replace(decimal, ".")) == 0.1 + 0.2                # every digit (repr)


# --- through the API -----------------------------------------------------------------------------------------

@pytest.fixture()
def client(tmp_path, monkeypatch):
    monkeypatch.setenv("MDL_DATA_DIR", str(tmp_path))
    monkeypatch.delenv("MDL_DATABASE_URL", raising=False)
    assignment_store.store.cache_clear()
    yield TestClient(app)
    assignment_store.store.cache_clear()


def class_with_hostile_names(client, lang: str) -> tuple[dict, list[str]]:
    created = client.post(API, json={**CRANK, "lang": lang})
    assert created.status_code == 201, created.text
    created = created.json()
    registered = []
    for name in ["Ivan Petrov;=1+1", "Ira;=cmd|' /C calc'!A0", "Oleh,+SUM(A1)", "Nina;-2+3"]:
        answer = TestClient(app).post(f"{API}/{created['id']}/students", json={"name": name})
        if answer.status_code == 201:
            registered.append(name)
            sent = client.post(f"{API}/{created['id']}/submissions", json={"question": "du31_min", "answer": -1.5},
                               headers={"Authorization": f"Bearer {answer.json()['secret']}"})
            assert sent.status_code == 200, sent.text
    assert "Ivan Petrov;=1+1" in registered and "Ira;=cmd|' /C calc'!A0" in registered
    return created, registered


@pytest.mark.parametrize("lang", ["ru", "uk", "en"])
def test_the_results_and_links_csv_hold_no_formula_for_any_separator(client, lang):
    created, registered = class_with_hostile_names(client, lang)
    instructor = f"{API}/{created['id']}/results/{created['results_token']}"
    results = client.get(f"{instructor}/csv")
    links = client.post(f"{instructor}/links")
    assert results.status_code == links.status_code == 200
    negative = [n for n in re.findall(r'"(-[^"]*)"', results.text)]          # the numbers the app wrote
    assert negative and all(re.fullmatch(r"-\d[\d.,e+-]*", n) for n in negative), negative
    assert_no_formula(results.text, negative)
    assert_no_formula(links.text, [])
    delimiter = ";" if lang in ("ru", "uk") else ","
    names = [row[0] for row in csv.reader(io.StringIO(results.text.lstrip("\ufeff")), delimiter=delimiter)][1:]
    assert sorted(n.replace("'", "") for n in names) == sorted(n.replace("'", "") for n in registered)


WORDS = {"ru": ("Студент", "Вариант", "Наибольшее значение передаточной функции u₃₁", "Ответов", "Верно"),
         "uk": ("Студент", "Варіант", "Найбільше значення передаточної функції u₃₁", "Відповідей", "Правильно"),
         "en": ("Student", "Variant", "Maximum of the transfer function u₃₁", "Answers", "Score")}


@pytest.mark.parametrize("lang", ["ru", "uk", "en"])
def test_the_results_csv_is_headed_in_words_of_the_assignments_language(client, lang):
    created, _ = class_with_hostile_names(client, lang)
    text = client.get(f"{API}/{created['id']}/results/{created['results_token']}/csv").text.lstrip("\ufeff")
    delimiter, decimal = (";", ",") if lang in ("ru", "uk") else (",", ".")
    header, *rows = list(csv.reader(io.StringIO(text), delimiter=delimiter))
    student, variant, question, attempts, score = WORDS[lang]
    assert header[:2] == [student, variant]
    assert "λ = l₂/l₁" in header and "lambda" not in header and "u31_max attempts" not in header
    assert any(h.startswith(question) and h.endswith(f": {attempts}") for h in header), header
    assert score in header
    lam = header.index("λ = l₂/l₁")
    for row in rows:
        assert len(row) == len(header)
        assert 2.5 <= float(row[lam].replace(decimal, ".")) <= 5.0
        if decimal == ",":
            assert "." not in row[lam]


# the questions whose labels carry the page's markup (I_м, M_с0^пр, ω_{1ср}): a spreadsheet shows none of it
MARKED_UP = [("flywheel", "rig", "flywheel_inertia", {"ru": "Iм", "uk": "Iм", "en": "I"}),
             ("resisting-moment", "sine", "mc0", {"ru": "Mс₀пр", "uk": "Mс₀", "en": "M"}),
             ("equation-of-motion", "linear", "omega_mean", {"ru": "ω₁ср", "uk": "ω₁ср", "en": "ω₁"})]


@pytest.mark.parametrize("lang", ["ru", "uk", "en"])
@pytest.mark.parametrize("scene, variant, question, plain", MARKED_UP, ids=[m[0] for m in MARKED_UP])
def test_the_results_csv_writes_the_labels_as_plain_text(client, lang, scene, variant, question, plain):
    """No header cell holds the page's markup ("_x", "^x", "_{…}"): a label reads as the page's plain text
    (aria-labels), the digits of a subscript or superscript as Unicode glyphs, its letters as they are."""
    spec = {"scene": scene, "variant": variant, "questions": [{"id": question}], "lang": lang}
    created = client.post(API, json=spec)
    assert created.status_code == 201, created.text
    created = created.json()
    text = client.get(f"{API}/{created['id']}/results/{created['results_token']}/csv").text.lstrip("\ufeff")
    header = next(csv.reader(io.StringIO(text), delimiter=";" if lang in ("ru", "uk") else ","))
    assert [cell for cell in header if "_" in cell or "^" in cell] == [], header
    assert any(plain[lang] in cell for cell in header), header
