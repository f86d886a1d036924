"""Students' names (server/classroom/names.py): which typed names are one student, which only look like another.

The hand cases are the classroom's reported ones ("IVAN  PETROV" spent "Ivan Petrov"'s attempts; "Пётр" and "Петр", a
Cyrillic "о" inside a Latin name made a second student who looks the same). The properties are checked with
hypothesis over names drawn from Latin, Cyrillic and Greek letters, digits and the punctuation of group codes.
"""
from __future__ import annotations

import unicodedata

import pytest
from hypothesis import given, settings, strategies as st

from server.classroom.names import (MAX_NAME, NameRefused, check_new, clean, confusables, look_alike, mixed_script,
                                    normalise, resembles, roster_names, script, skeleton, words)

LATIN = "abcdefghijklmnopqrstuvwxyz"
CYRILLIC = "абвгдеёжзийклмнопрстуфхцчшщъыьэюяєіїґ"
GREEK = "αβγδεζηθικλμνξοπρστυφχψω"
word_in = lambda letters: st.text(alphabet=letters + letters.upper(), min_size=1, max_size=12)
one_script_word = st.one_of(word_in(LATIN), word_in(CYRILLIC), word_in(GREEK))
names_of_words = st.lists(one_script_word, min_size=1, max_size=4).map(" ".join)


# --- one student: NFKC, case folding, whitespace, ё → е -----------------------------------------------------

@pytest.mark.parametrize("typed, same_as", [
    ("IVAN  PETROV", "Ivan Petrov"),
    ("  ivan\tpetrov ", "Ivan Petrov"),
    ("Ivan\u00a0Petrov", "Ivan Petrov"),            # no-break space
    ("ＩＶＡＮ ＰＥＴＲＯＶ", "Ivan Petrov"),           # fullwidth letters (NFKC)
    ("Пётр", "Петр"),
    ("ПЁТР", "петр"),
    ("Пе\u0308тр", "Петр"),                         # е + combining diaeresis composes to ё, then ё → е
    ("Iv\u200ban Petrov", "Ivan Petrov"),            # a zero-width space is not part of a name
    ("Straße", "STRASSE"),                           # full case folding
])
def test_names_that_are_one_student(typed, same_as):
    assert normalise(typed) == normalise(same_as)


@pytest.mark.parametrize("one, other", [("Ivan Petrov", "Ivan Petrova"), ("Ivan-Petrov", "Ivan Petrov"),
                                        ("Іван", "Иван"), ("Ганна", "Ґанна")])
def test_names_that_are_different_students(one, other):
    assert normalise(one) != normalise(other)


@given(names_of_words, st.sampled_from([str.upper, str.lower, str.title, lambda s: s]),
       st.lists(st.sampled_from([" ", "  ", "\t", "\u00a0", "\u2003"]), min_size=1, max_size=6))
def test_case_and_spacing_never_make_another_student(name, case, spaces):
    spaced = spaces[0] + (spaces[-1]).join(case(name).split(" ")) + spaces[-1]
    assert normalise(spaced) == normalise(name)


@given(st.text(max_size=60))
def test_the_key_is_stable_and_clean(text):
    key = normalise(text)
    assert normalise(key) == key                                  # idempotent
    assert key == key.strip() and "  " not in key and "ё" not in key
    assert not any(unicodedata.category(c)[0] == "C" for c in key)


# --- look-alikes across alphabets -----------------------------------------------------------------------------

def test_a_cyrillic_o_inside_a_latin_name_is_refused_saying_why():
    with pytest.raises(NameRefused) as refused:
        check_new("Ivan Petr\u043ev", [])                        # Cyrillic о
    assert refused.value.code == "name_mixed_scripts"
    assert refused.value.about == {"word": "Petr\u043ev", "letter": "\u043e", "script": "Cyrillic"}


@pytest.mark.parametrize("latin_look_alike", list("aeopcxy"))
def test_latin_look_alikes_in_a_cyrillic_name_are_refused(latin_look_alike):
    name = "Петр" + latin_look_alike + "в"
    with pytest.raises(NameRefused) as refused:
        check_new(name, [])
    assert refused.value.code == "name_mixed_scripts" and refused.value.about["script"] == "Latin"


@pytest.mark.parametrize("new, existing", [
    ("Рорa", None),                                  # mixed: refused before any comparison
    ("Рора", "Popa"),                                # all Cyrillic, reads as the Latin name
    ("ВОВА", "Boba"),                                # capitals: В looks like B
    ("КМ-З1 Сох", "KM-31 Cox"),                      # Cyrillic З for the digit 3, and a Cyrillic word
    ("Τοm", None),                                   # Greek Τ, ο beside a Latin m: mixed
    ("ΚΑΤΕ", "Kate"),                                # all Greek capitals
    ("АННА", "Ahha"),                                # the same in capitals
])
def test_look_alikes_of_registered_names_are_refused_naming_the_name(new, existing):
    with pytest.raises(NameRefused) as refused:
        check_new(new, [existing] if existing else [])
    if existing:
        assert refused.value.code == "name_confusable" and refused.value.about == {"resembles": existing}
        assert existing in refused.value.reason


@pytest.mark.parametrize("name, existing", [
    ("Ivan Петренко", []),                           # two words, each in one alphabet
    ("KM-21/1 Ivanov", []),
    ("Олег", ["Oleg"]),                              # л and г have no Latin look-alike here
    ("Анна", ["Anna"]),                              # н looks like H (as a capital), not like n
    ("Ali", ["All"]),                                # Latin letters stand for themselves
    ("O'Brien", []),
    ("Ольга Ковальчук-Шевченко", ["Ольга Ковальчук"]),
    ("山田 太郎", []),
    ("やまだ たろう", []),
])
def test_legitimate_names_are_accepted(name, existing):
    assert check_new(name, existing) == clean(name)


@given(st.text(alphabet=LATIN, min_size=2, max_size=12), st.data())
def test_swapping_latin_letters_for_cyrillic_look_alikes_is_always_caught(word, data):
    """A Latin name with any of its letters replaced by a Cyrillic letter that looks like it: refused, whether
    alone (mixed alphabets) or, all replaced, beside the Latin original (a look-alike)."""
    swappable = {prototype: cyr for cyr, prototype in sorted(confusables().items())
                 if script(cyr) == "CYRILLIC" and cyr.islower() and prototype in LATIN}
    places = [i for i, c in enumerate(word) if c in swappable]
    if not places:
        return
    chosen = data.draw(st.sets(st.sampled_from(places), min_size=1))
    spoof = "".join(swappable[c] if i in chosen else c for i, c in enumerate(word))
    with pytest.raises(NameRefused):
        check_new(spoof, [word])
    if len(places) == len(word):                       # every letter swapped: one alphabet, a pure look-alike
        assert look_alike(spoof, word)
        assert resembles(spoof, [word]) == word


@given(names_of_words)
@settings(max_examples=200)
def test_a_name_never_resembles_itself_or_its_own_spelling(name):
    assert resembles(name, [name, name.upper(), " " + name.lower()]) is None
    assert not look_alike(name, name)


# --- look-alikes within one alphabet, other alphabets, characters that show nothing ----------------------------

@pytest.mark.parametrize("typed, registered", [
    ("lvan Petrov", "Ivan Petrov"),                  # a Latin small l for the capital I
    ("Iv\u0251n Petrov", "Ivan Petrov"),             # U+0251 LATIN SMALL LETTER ALPHA
    ("1van Petrov", "Ivan Petrov"),                  # the digit 1
    ("Ivan Petr0v", "Ivan Petrov"),                  # the digit 0
    ("Marina Ivanova", "Rnarina Ivanova"),           # m and rn
    ("\u13a0\u13aa\u13d9\u13ac Smith", "Dave Smith"),  # Cherokee ᎠᎪᏙᎬ
    ("KM-2l/l Ivanov", "KM-21/1 Ivanov"),
])
def test_look_alikes_by_the_full_confusables_table_are_refused(typed, registered):
    with pytest.raises(NameRefused) as refused:
        check_new(typed, [registered])
    assert refused.value.code == "name_confusable" and refused.value.about == {"resembles": registered}


@pytest.mark.parametrize("blank", ["\u2800", "\u1160", "\u115f", "\u3164", "\uffa0", "\ufe00", "\ufe0f", "\u034f",
                                   "\u00ad", "\u200d", "\u2060", "\U000e0041", "\U000e0100"])
def test_characters_that_show_nothing_are_dropped_so_the_name_is_the_registered_one(blank):
    typed = f"Iv{blank}an Pe{blank}trov{blank}"
    assert clean(typed) == "Ivan Petrov" and normalise(typed) == normalise("Ivan Petrov")
    with pytest.raises(NameRefused) as refused:
        check_new(blank * 3, [])
    assert refused.value.code == "name_empty"


def test_ivan_typed_with_cyrillic_letters_is_refused_and_real_names_stay_apart():
    with pytest.raises(NameRefused):
        check_new("I\u0432\u0430\u043d Petrov", ["Ivan Petrov"])          # Iван: a word in two alphabets
    assert skeleton("\u0406van") == skeleton("Ivan")                      # Ukrainian І reads as the Latin I
    for one, other in [("Петров", "Петрова"), ("Іван", "Иван"), ("Олена", "Олеся"), ("Ганна", "Ґанна"),
                       ("Ali", "All"), ("Анна", "Anna"), ("Ярослав", "Ярослава"), ("Юлія", "Юлия")]:
        assert resembles(one, [other]) is None and check_new(one, [other]) == one


def test_the_table_is_all_of_unicodes_confusables():
    table = confusables()
    assert len(table) > 6000
    assert table["\u0430"] == "a" and table["I"] == "l" and table["m"] == "rn" and table["0"] == "O"
    assert table["\u13a0"] == "D"


def test_words_and_scripts():
    assert words("KM-21/1 Ivanov") == ["KM", "Ivanov"]
    assert words("d'Artagnan") == ["d", "Artagnan"]
    assert script("я") == "CYRILLIC" and script("1") is None and script("\u0301") is None
    assert mixed_script("Ivan Петров") is None and mixed_script("Іvan").letter == "І"


def test_empty_and_long_names_are_refused():
    for empty in ("", "   ", "\u200b", "\t\r\n"):
        with pytest.raises(NameRefused) as refused:
            check_new(empty, [])
        assert refused.value.code == "name_empty"
    with pytest.raises(NameRefused) as refused:
        check_new("x" * (MAX_NAME + 1), [])
    assert refused.value.code == "name_too_long"


# --- rosters ----------------------------------------------------------------------------------------------

def test_a_roster_of_lines_keeps_commas_in_names_and_drops_repeats():
    roster = roster_names("\ufeffIvanov, Petr\nSmith, John\n\nIVANOV,  PETR\n=HYPERLINK(\"x\")\n")
    assert roster.names == ["Ivanov, Petr", "Smith, John", '=HYPERLINK("x")'] and roster.refused == []


def test_a_roster_table_takes_the_named_column():
    semicolons = roster_names("Группа;ФИО;Email\nКМ-21;Иванов Иван;a@b\nКМ-21;Пётр Сидоров;c@d\n")
    assert semicolons.names == ["Иванов Иван", "Пётр Сидоров"]
    commas = roster_names('id,name\n1,"Ivanov, Petr"\n2,Smith\n3,\n')
    assert commas.names == ["Ivanov, Petr", "Smith"] and commas.refused == [("3,", "no name in this line")]
    tabs = roster_names("Ivanov\tKM-21\nPetrov\tKM-22\n")                # no header: the first column
    assert tabs.names == ["Ivanov", "Petrov"]
