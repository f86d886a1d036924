"""The instructor's form in a real Chromium with a Russian locale: a number typed
with a decimal comma means what it says, ambiguous text is refused in the page's language before anything is
sent, each question says where the public pages show its answer, and an assignment with questions of the new
kinds (a value at an angle the student chooses, a prediction) works from the student's side: the angle field,
the plots locked until the prediction is closed, then open.
"""
from __future__ import annotations

import json
import re

import httpx
import numpy as np
import pytest

from conftest import interface_texts, screenshot

pytestmark = pytest.mark.browser
L1 = 0.1
RU = interface_texts("ru")


@pytest.fixture
def ru_page(chromium, app_url):
    context = chromium.new_context(base_url=app_url, viewport={"width": 1400, "height": 900}, locale="ru-RU")
    page = context.new_page()
    page.problems, page.posts = [], []
    page.on("console", lambda message: message.type == "error" and page.problems.append(message.text))
    page.on("pageerror", lambda error: page.problems.append(str(error)))
    page.on("request", lambda request: request.method == "POST" and page.posts.append(request.url))
    yield page
    context.close()


def open_builder(page) -> None:
    page.goto("/scenes/transfer-functions/assign?lang=ru&variant=slider_crank")
    page.wait_for_selector("#assignment-form")


def type_into(page, selector: str, text: str) -> None:
    """As a person types: select what is there, then the keys (fill() would bypass a number input's parser)."""
    page.click(selector, click_count=3)
    page.keyboard.press("Control+A")
    page.keyboard.type(text)


def lambda_field(page) -> str:
    return '.slider-rule[data-slider="lambda"] [name="value"]'


def test_a_number_input_in_a_russian_chromium_reads_a_decimal_comma_as_a_thousands_separator(ru_page):
    """The failure of point 11 as it was: <input type=number> takes "2,5" as 25 and calls it valid. Hence the
    form has no number inputs (checked below) and reads its fields itself."""
    ru_page.set_content('<input type="number" id="n" step="any">')
    ru_page.click("#n")
    ru_page.keyboard.type("2,5")
    assert ru_page.eval_on_selector("#n", "e => [e.value, e.validity.valid]") == ["25", True]


def test_a_decimal_comma_makes_the_value_it_says(ru_page, app_url):
    open_builder(ru_page)
    assert ru_page.locator('#assignment-form input[type="number"]').count() == 0
    assert ru_page.locator(lambda_field(ru_page)).input_value() == "3"
    tolerance = '[name="tolerance-u31_max"]'
    assert ru_page.locator(tolerance).input_value() == "1"
    type_into(ru_page, lambda_field(ru_page), "2,5")
    type_into(ru_page, tolerance, "1,5")
    ru_page.click("#create-assignment")
    ru_page.wait_for_selector("#assignment-links:not([hidden])")
    assignment_id = re.search(r"/assignments/([\w-]+)", ru_page.locator("#student-link").get_attribute("href")).group(1)
    secret = httpx.post(f"{app_url}/api/v1/assignments/{assignment_id}/students", json={"name": "Anyone"}).json()["secret"]
    variant = httpx.get(f"{app_url}/api/v1/assignments/{assignment_id}/me",
                        headers={"Authorization": f"Bearer {secret}"}).json()
    assert variant["values"]["lambda"] == 2.5
    assert variant["questions"][0]["tolerance"] == pytest.approx(0.015, rel=1e-12)
    assert not ru_page.problems


@pytest.mark.parametrize("text", ["1,234.5", "1.234,5", "2,5,1", "2,5 м", "двадцать"])
def test_ambiguous_or_wrong_numbers_are_refused_in_russian_and_nothing_is_sent(ru_page, text):
    open_builder(ru_page)
    type_into(ru_page, lambda_field(ru_page), text)
    ru_page.click("#create-assignment")
    error = ru_page.locator("#builder-error")
    error.filter(has_text=text).wait_for()
    words = RU["number_ambiguous"] if "," in text and "." in text or text.count(",") > 1 else RU["number_invalid"]
    assert words.replace("{text}", text) in error.inner_text()
    assert "λ" in error.inner_text() or "lambda" in error.inner_text().lower()        # the field, by its label
    assert ru_page.locator(lambda_field(ru_page)).get_attribute("aria-invalid") == "true"
    assert not [url for url in ru_page.posts if url.endswith("/api/v1/assignments")]
    type_into(ru_page, lambda_field(ru_page), "2,5")                  # mended: it goes
    ru_page.click("#create-assignment")
    ru_page.wait_for_selector("#assignment-links:not([hidden])")


def test_out_of_range_and_fractional_attempts_are_refused_in_russian(ru_page):
    open_builder(ru_page)
    type_into(ru_page, lambda_field(ru_page), "80,5")
    type_into(ru_page, "#attempts", "2,5")
    ru_page.click("#create-assignment")
    text = ru_page.locator("#builder-error").inner_text()
    assert "80,5 вне диапазона 1,05 … 8" in text and RU["number_not_whole"] in text
    assert not [url for url in ru_page.posts if url.endswith("/api/v1/assignments")]


def test_each_question_says_where_the_public_pages_show_its_answer(ru_page):
    open_builder(ru_page)
    picks = ru_page.locator(".question-pick")
    assert picks.count() == 5
    for i in range(picks.count()):
        notice = picks.nth(i).locator(".leak-notice")
        assert notice.is_visible()
        assert "Первая передаточная функция u₃₁" in notice.inner_text()          # the u₃₁ plot, by its title
    prediction = ru_page.locator('.question-pick[data-question="u31_max_prediction"] .kind-note').inner_text()
    assert "по-прежнему показывает" in prediction                      # honest: the public scene still shows it
    ru_page.locator('.question-pick[data-question="u31_at_angle"]').scroll_into_view_if_needed()
    screenshot(ru_page, "assignment_builder_ru")


def wait_for_plot(page, panel: str) -> None:
    page.wait_for_function("id => document.querySelector(`#panel-${id} .graph`)?.data?.length > 0", arg=panel)


def shown_scene(page) -> dict:
    """The scene the server embedded in the student's page."""
    return json.loads(page.locator("#scene-data").text_content().replace("<\\/", "</"))


def exact_u31(phi_degrees: float, lam: float) -> float:
    """u₃₁ of the central crank-slider from its geometry (φ = 0 at the inner dead centre)."""
    phi = np.radians(phi_degrees)
    return L1 * np.sin(phi) - L1 ** 2 * np.sin(phi) * np.cos(phi) / np.sqrt((lam * L1) ** 2 - (L1 * np.sin(phi)) ** 2)


def u31_max(lam: float) -> float:
    phi = np.linspace(0, 180, 1_800_001)                 # 1e-4° grid: the maximum to ~1e-12 relative
    return float(np.max(exact_u31(phi, lam)))


def make_in_builder(page, questions: list[str], angles: tuple[str, str, str] | None = None) -> str:
    """An assignment made in the Russian builder with these questions and one attempt; the students' link."""
    open_builder(page)
    for box in page.locator('input[name="question"]').all():
        box.set_checked(box.get_attribute("value") in questions)
    if angles:
        for part, text in zip(("min", "max", "step"), angles):
            type_into(page, f'[name="angle_{part}-u31_at_angle"]', text)
    type_into(page, "#attempts", "1")
    page.click("#create-assignment")
    page.wait_for_selector("#assignment-links:not([hidden])")
    return page.locator("#student-link").get_attribute("href")


def open_as_student(context, student_url: str, name: str):
    page = context.new_page()
    page.problems = []
    page.on("pageerror", lambda error: page.problems.append(str(error)))
    page.goto(student_url)
    page.fill("#student", name)
    page.click("button[type=submit]")
    page.wait_for_selector("#personal-link")          # shown once; then on to the scene
    page.click("#continue")
    page.wait_for_selector("#questions .question")
    return page


def student_lambda(page) -> float:
    return next(s["default"] for s in shown_scene(page)["variants"][0]["sliders"] if s["id"] == "lambda")


def test_a_question_at_an_angle_the_student_chooses(ru_page):
    student_url = make_in_builder(ru_page, ["u31_at_angle"], ("20", "160", "10"))
    page = open_as_student(ru_page.context, student_url, "Олеся Українка")
    lam = student_lambda(page)
    assert page.locator("#angle-u31_at_angle").is_visible()
    assert "от 20° до 160° через 10°" in page.locator("#question-u31_at_angle .angle-hint").inner_text()
    wait_for_plot(page, "position")
    assert page.locator("#panel-u31").count() == 0 and "u31" not in shown_scene(page)["outputs"]
    page.fill("#angle-u31_at_angle", "35")                               # off the grid: refused on the page
    page.fill("#answer-u31_at_angle", "0,05")
    page.click("#question-u31_at_angle button")
    assert "через 10°" in page.locator("#feedback-u31_at_angle").inner_text()
    page.fill("#angle-u31_at_angle", "40")
    page.fill("#answer-u31_at_angle", f"{exact_u31(40, lam) * 1.002:.6f}".replace(".", ","))
    page.click("#question-u31_at_angle button")
    page.locator("#feedback-u31_at_angle").filter(has_text="✓").wait_for()
    assert page.locator("#angle-u31_at_angle").is_disabled()
    screenshot(page, "assignment_student_angle_ru")
    assert not page.problems


def test_a_prediction_opens_its_plot_once_answered(ru_page):
    student_url = make_in_builder(ru_page, ["u31_max_prediction"])
    page = open_as_student(ru_page.context, student_url, "Іван Франко")
    lam = student_lambda(page)
    assert page.locator("#question-u31_max_prediction .prediction-hint").is_visible()
    wait_for_plot(page, "du31")
    assert page.locator("#panel-u31").count() == 0 and "u31" not in shown_scene(page)["outputs"]
    screenshot(page, "assignment_student_prediction_ru")
    page.fill("#answer-u31_max_prediction", f"{u31_max(lam) * 1.01:.6f}".replace(".", ","))
    with page.expect_event("load"):                     # the page asks again: the plots open
        page.click("#question-u31_max_prediction button")
    page.wait_for_selector("#questions .question.right")
    assert "u31" in shown_scene(page)["outputs"]
    wait_for_plot(page, "u31")
    page.locator("#question-u31_max_prediction").scroll_into_view_if_needed()
    screenshot(page, "assignment_student_ru")
    assert not page.problems


PARSED = [("2,5", "ru", 2.5), ("2,5", "uk", 2.5), ("2.5", "ru", 2.5), ("2,5", "en", 2.5), ("1 234,5", "ru", 1234.5),
          ("−0,5", "uk", -0.5), ("1,234", "ru", 1.234), ("1e-3", "en", 0.001),
          ("1,234", "en", "ambiguous"), ("1,234.5", "ru", "ambiguous"), ("1.234,5", "uk", "ambiguous"),
          ("2,5,1", "ru", "ambiguous"), ("1.2.3", "en", "ambiguous"), ("0x10", "en", "invalid"),
          ("Infinity", "en", "invalid"), ("2,5 м", "ru", "invalid"), ("  ", "ru", "empty")]


def test_the_page_parser_reads_each_language_as_documented(ru_page):
    """decimal_input.js as the browser runs it (the module the builder and the answer fields import)."""
    open_builder(ru_page)
    module = re.search(r'src="([^"]*/js/)classroom/view/assignment_builder\.js"', ru_page.content()).group(1) + "common/model/decimal_input.js"
    results = ru_page.evaluate("""async ([url, cases]) => {
        const { parseDecimal } = await import(url);
        return cases.map(([text, lang]) => parseDecimal(text, lang));
    }""", [module, [[text, lang] for text, lang, _ in PARSED]])
    for (text, lang, expected), got in zip(PARSED, results):
        assert got == ({"error": expected} if isinstance(expected, str) else {"value": expected}), (text, lang, got)


def test_the_builder_says_when_another_question_keeps_a_predictions_plots_closed(ru_page):
    open_builder(ru_page)
    conflict = ru_page.locator("#conflict-u31_max_prediction")
    ru_page.check('input[name="question"][value="u31_max_prediction"]')          # u31_max is picked by default
    assert conflict.is_visible() and "Наибольшее значение передаточной функции u₃₁" in conflict.inner_text()
    ru_page.uncheck('input[name="question"][value="u31_max"]')
    assert conflict.is_hidden()
    ru_page.check('input[name="question"][value="u31_at_angle"]')               # it hides u₃₁ too
    assert conflict.is_visible()
    ru_page.uncheck('input[name="question"][value="u31_at_angle"]')
    ru_page.check('input[name="question"][value="du31_min"]')                   # hides u₃₁ as well (its plots)
    assert conflict.is_visible()
