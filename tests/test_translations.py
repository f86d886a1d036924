"""Every string in the reader's language and in the textbooks' notation.

- The API's texts for every scene and variant in Russian and Ukrainian (warnings, numerics, the work–precision
  study) hold no English sentence of the app's own (content/i18n/en.json).
- Sentences the core says only in English (a solver's outcome) are said again in the reader's language.
- Numbers in sentences: a true minus sign U+2212, never "−0", powers of ten written out.
- One alphabet per symbol per language: M_д, M_с, P_с, A_с in ru/uk (Cyrillic д, с, as the textbooks write
  them), M_d, M_c, A_d, A_c in en; no "_" or "^" that the notation markup leaves on screen.
- The Jinja filter `notation`: subscripts as <sub>, everything else escaped.
"""
from __future__ import annotations

import re
import string
from pathlib import Path

import pytest
from fastapi.testclient import TestClient

from server.api.app import app
from server.api.messages import from_english, localise_study, signed, skipped_run
from server.api.routers.pages import decimal, notation
from server.lessons.markup import notation_parts
from server.core.elastic.simulate import work_bound_message
from server.lessons.requests import scene_request
from server.lessons.scenes import interface_texts, scene_documents, scenes

REPO = Path(__file__).resolve().parents[1]
LANGUAGES = ("ru", "uk")
WORD = re.compile(r"[A-Za-z][A-Za-z'’-]+")
FIELD = re.compile(r"\{[^{}]*\}")


def english_fragments(lang: str) -> set[str]:
    """The English sentences of the app's own strings that a page in lang must not show: every piece
    between placeholders of an en value with at least three English words, unless lang's value of the same
    key holds it too (a formula, a solver's name)."""
    english, other = interface_texts("en"), interface_texts(lang)
    fragments = set()
    for key, text in english.items():
        for piece in FIELD.split(text):
            piece = " ".join(piece.split()).strip(" ,.;:()")
            if len(WORD.findall(piece)) >= 3 and piece not in other.get(key, ""):
                fragments.add(piece)
    return fragments


def english_in(text: str, lang: str) -> list[str]:
    flat = " ".join(text.split())
    return sorted(fragment for fragment in english_fragments(lang) if fragment in flat)


def texts_of(value) -> list[str]:
    """Every string of an API answer that the page shows in words (not numbers, keys or ids)."""
    if isinstance(value, dict):
        found = []
        for key, item in value.items():
            if key in ("warnings", "message", "method", "why", "reference", "quantity", "skipped") or \
                    isinstance(item, (dict, list)):
                found += texts_of(item)
        return found
    if isinstance(value, list):
        return [text for item in value for text in texts_of(item)]
    return [value] if isinstance(value, str) else []


client = TestClient(app)
CASES = [(scene.id, variant.id) for scene in scenes().values() if scene.kind != "kinematics"
         for variant in scene.variants]


@pytest.mark.parametrize("scene_id, variant_id", CASES)
@pytest.mark.parametrize("lang", LANGUAGES)
def test_api_answers_of_every_scene_hold_no_english_sentence(scene_id, variant_id, lang):
    scene = scenes()[scene_id]
    variant = next(v for v in scene.variants if v.id == variant_id)
    answer = client.post(f"/api/v1/{scene.endpoint}?lang={lang}", json=scene_request(scene, variant))
    assert answer.status_code == 200, answer.text
    assert english_in("\n".join(texts_of(answer.json())), lang) == []      # some answers say nothing in words


@pytest.mark.parametrize("lang", LANGUAGES)
def test_a_stall_and_a_study_are_told_in_the_readers_language(lang):
    """Outcomes the default set-ups do not reach: a start-up that stalls, and the live work–precision study."""
    scene = scenes()["equation-of-motion"]
    variant = next(v for v in scene.variants if v.id == "linear")
    body = scene_request(scene, variant)
    stall = body | {"motor": {"kind": "linear", "M0": 10, "b": 0.3}}
    words = texts_of(client.post(f"/api/v1/motion?lang={lang}", json=stall).json())
    assert any("φ =" in text for text in words) and english_in("\n".join(words), lang) == []
    study = client.post(f"/api/v1/work-precision/motion?lang={lang}", json=body).json()["study"]
    assert study["rows"] and sum(row["ours"] for row in study["rows"]) >= 1
    words = texts_of(study) + [row["method"] for row in study["rows"]]
    assert english_in("\n".join(words), lang) == []
    assert not any("ours" in text or "solve_ivp" in text for text in words)


@pytest.mark.parametrize("lang", LANGUAGES)
def test_a_machine_that_cannot_move_says_why_in_its_numerics_too(lang):
    """The numerics' outcome of a motion ended by a warning (a jam on the lever pivot) is that warning's
    sentence in the reader's language (Numerics.tell), as in the list of warnings."""
    body = {"mechanism": "slotted_link", "params": {"l0": 0.1, "l1": 0.1}, "inertias": {"J1": 0.5, "J3": 0.1},
            "load": {"force": 20, "f": 0.2}, "motor": {"kind": "linear", "M0": 60, "b": 0.3},
            "outputs": ["steady", "startup"]}
    data = client.post(f"/api/v1/motion?lang={lang}", json=body).json()
    messages = [data[key]["numerics"]["message"] for key in ("steady", "startup") if key in data] + \
        [data["numerics"]["message"]] * ("numerics" in data)
    assert messages and all(message and message in data["warnings"] for message in messages)


@pytest.mark.parametrize("lang", LANGUAGES)
def test_core_outcomes_without_a_code_are_said_again_in_the_readers_language(lang):
    """The sentences the core builds in English (elastic/simulate.py, dynamics/motion.py) match an English
    template, and come back in lang with their numbers written the reader's way."""
    texts = interface_texts(lang)
    cut = from_english(work_bound_message(1.25, 2.0), lang)
    assert cut == texts["num_message_work_bound"].replace("{t:.4g}", "1,25").replace("{t_end:.4g}", "2")
    stopped = from_english("the solver stopped at t = -0.5 s: the state diverged", lang)
    assert "−0,5" in stopped and texts["num_reason_diverged"] in stopped
    rtol = from_english("the tolerance rtol = 1e-06 was not reached within 65536 steps per revolution", lang)
    assert "10⁻⁶" in rtol and "65536" in rtol and english_in(rtol, lang) == []
    assert from_english("words no template has", lang) == "words no template has"


def test_every_english_outcome_template_has_the_same_fields_in_every_language():
    for key in interface_texts("en"):
        if key.startswith(("num_message_", "num_reason_", "study_method_")):
            fields = [{f for _, f, _, _ in string.Formatter().parse(interface_texts(lang)[key]) if f}
                      for lang in ("ru", "uk", "en")]
            assert fields[0] == fields[1] == fields[2], key


def test_study_methods_and_skipped_runs_are_named_in_the_readers_language():
    study = {"rows": [{"method": "ours: Newton shooting", "rtol": 1e-3},
                      {"method": "solve_ivp LSODA, cycles until periodic", "rtol": 1e-3},
                      {"method": "ours: compiled Radau", "rtol": 1e-3}, {"method": "RK45", "rtol": 1e-3}],
             "skipped": ["DOP853 1e-05", "ours: compiled Radau 1e-07"]}
    local = localise_study(study, "ru")
    assert [row["ours"] for row in local["rows"]] == [True, False, True, False]
    assert [row["method"] for row in local["rows"]] == [
        "наш: метод стрельбы Ньютона", "SciPy LSODA, циклы до периодичности", "наш: Radau, компилированный",
        "SciPy RK45"]
    assert local["skipped"] == ["SciPy DOP853, rtol = 10⁻⁵", "наш: Radau, компилированный, rtol = 10⁻⁷"]
    assert skipped_run("DOP853 2.5e-04", "uk") == "SciPy DOP853, rtol = 2,5·10⁻⁴"


@pytest.mark.parametrize("text, written", [
    ("-2.5", "−2.5"), ("-0", "0"), ("-0.00", "0.00"), ("-0,0", "0,0"), ("12", "12"), ("1e-05", "10⁻⁵"),
    ("-1e-05", "−10⁻⁵"), ("1.5e-05", "1.5·10⁻⁵"), ("-2.5e+06", "−2.5·10⁶"), ("0e+00", "0")])
def test_numbers_in_sentences_have_a_true_minus_and_no_signed_zero(text, written):
    assert signed(text) == written


@pytest.mark.parametrize("value, lang, written", [
    (-1.5e-7, "ru", "−1,5·10⁻⁷"), (-0.0, "uk", "0"), (-3.25, "ru", "−3,25"), (2.5, "en", "2.5"), ("—", "ru", "—")])
def test_the_pages_decimal_filter_writes_numbers_the_readers_way(value, lang, written):
    assert decimal(value, lang) == written


def displayed_strings():
    """(where, language, text) of every interface text: content/i18n and the scenes (not their questions)."""
    def walk(value, where, lang=None):
        if isinstance(value, dict):
            for key, item in value.items():
                if key != "questions":
                    yield from walk(item, f"{where}.{key}", key if key in ("ru", "uk", "en") else lang)
        elif isinstance(value, list):
            for i, item in enumerate(value):
                yield from walk(item, f"{where}[{i}]", lang)
        elif isinstance(value, str) and lang:
            yield where, lang, value
    for name, document in scene_documents().items():      # shared sliders (content/sliders.json) where used
        yield from walk(document, name)
    for lang in ("ru", "uk", "en"):
        for key, text in interface_texts(lang).items():
            yield key, lang, text


STRINGS = list(displayed_strings())
LATIN_IN_RU = re.compile(r"(?<![A-Za-z])[MPA]_c(?![A-Za-z])|_d(?![A-Za-z])")   # M_c, P_c, M_c0; M_d, φ_d
CYRILLIC_SUBSCRIPT = re.compile(r"_\{?[^}\s]*[а-яёіїєґ]", re.IGNORECASE)


def test_one_alphabet_per_symbol_per_language():
    """ru/uk write the resisting moment, force and work with a Cyrillic с (M_с, P_с, A_с) beside the driving
    M_д, A_д (the motor's φ_д, I_д too); en writes every subscript in Latin letters (M_d, M_c, ω_mean)."""
    latin = [(where, text) for where, lang, text in STRINGS if lang != "en" and LATIN_IN_RU.search(text)]
    cyrillic = [(where, text) for where, lang, text in STRINGS if lang == "en" and CYRILLIC_SUBSCRIPT.search(text)]
    assert latin == [] and cyrillic == []
    ru = "\n".join(text for _, lang, text in STRINGS if lang == "ru")
    assert "M_с" in ru and "M_д" in ru and "A_с" in ru and "P_с" in ru


def test_no_markup_is_left_on_screen():
    """Once read as notation, no "_" or "^" is left in any interface text (placeholders filled first)."""
    left = []
    for where, lang, text in STRINGS:
        shown = FIELD.sub("1", text) if where.startswith(("warn_", "num_", "err_", "why_", "study_")) else text
        plain = "".join(run for run, shift in notation_parts(shown) if not shift)
        if "_" in plain or "^" in plain:
            left.append((where, lang, text))
    assert left == []


@pytest.mark.parametrize("text, html", [
    ("M_c0 = 1", "M<sub>c0</sub> = 1"),
    ("A_{P,k}, Дж", "A<sub>P,k</sub>, Дж"),
    ("ω_ср²", "ω<sub>ср</sub>²"),
    ("c_n ∝ R^{1/3}", "c<sub>n</sub> ∝ R<sup>1/3</sup>"),
    ("(f tg ψ)^i", "(f tg ψ)<sup>i</sup>"),
    ("φ̇_d − φ̇₁", "φ̇<sub>d</sub> − φ̇₁"),
    ("solve\\_ivp", "solve_ivp"),
    ("x_", "x_"),
    ("<b>a_1</b> & b", "&lt;b&gt;a<sub>1</sub>&lt;/b&gt; &amp; b"),
    ("p_{<i>}", "p<sub>&lt;i&gt;</sub>"),
])
def test_the_jinja_filter_writes_subscripts_and_escapes_the_rest(text, html):
    assert str(notation(text)) == html


def test_scene_pages_show_subscripts_and_no_raw_underscore():
    page = client.get("/scenes/flywheel?lang=ru").text
    intro = page.split('<section class="intro">')[1].split("</section>")[0]
    assert "ω<sub>max</sub>" in intro and "_" not in intro
    start = client.get("/?lang=ru").text
    assert "M<sub>с</sub><sup>пр</sup>(φ)" in start          # the reduced moment with the books' superscript


@pytest.mark.parametrize("lang", ["ru", "uk", "en"])
def test_the_measurements_page_is_a_page_of_the_app(lang):
    page = client.get(f"/measurements?lang={lang}")
    assert page.status_code == 200
    assert interface_texts(lang)["measurements_title"] in page.text
    assert "<table>" in page.text and page.text.count('<div class="graph" role="img"') == 6    # drawn by the page
    assert client.get("/bench-results/wp_steady_cycle.png").status_code == 200    # the bench's own, for its readers


@pytest.mark.parametrize("lang", LANGUAGES)
def test_the_measurements_page_speaks_the_readers_language(lang):
    """/measurements in ru/uk: its headings, references, figure captions, the fastest-method sentences, the
    tables' heads and our methods' names in the reader's words (content/i18n, measurements_*), no English
    sentence of the app's own, numbers with a decimal comma; only solver names (SciPy's RK45 …) stay."""
    html = client.get(f"/measurements?lang={lang}").text
    article = html.split('<article class="measurements"', 1)[1].split("</article>", 1)[0]
    text = re.sub(r"<[^>]+>", " ", article)
    texts = interface_texts(lang)
    assert english_in(text, lang) == []
    for english in ("Reference", "Fastest", "ours", "interactive", "run time", "tolerance", "Elastic", "Flywheel",
                    "method", "error", "seed", "solve_ivp"):
        assert english not in text, english
    for key in ("steady_cycle", "flywheel", "elastic_belt", "elastic_stiff", "elastic_linkage", "elastic_four_bar"):
        assert str(notation(texts[f"measurements_study_{key}"])) in article, key
    assert texts["measurements_figure"] in article and texts["numerics_rtol"] != "Допуск rtol"
    assert "<th>" + texts["measurements_column_run_time"] + "</th>" in article
    assert not re.search(r"\d\.\d", text.replace("RK45", ""))         # a decimal comma in every number
    assert english_in(html, lang) == []
