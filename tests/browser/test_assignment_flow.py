"""The whole assignment flow in the browser: an instructor makes an assignment with per-student variants
from the flywheel scene; two students register by name (each sees their personal link once), get different
variants, one answers right and one wrong and each sees the matching feedback; the results page lists both and
its CSV agrees. Every response the student's page receives before submitting is searched for the correct answer.
A student's personal link opened in another browser (another device) continues their attempts; the instructor
uploads a roster, locks registration, makes a new link and deletes a row on the results page.
"""
from __future__ import annotations

import csv
import io
import json
import re

import httpx
import numpy as np
import pytest
from playwright.sync_api import TimeoutError as PlaywrightTimeout

from server.lessons.scenes import scenes
from server.lessons.requests import scene_request
from server.classroom.answers import question
from server.classroom.spec import AssignmentSpec
from server.classroom.names import normalise
from server.classroom.variants import plan
from server.lessons.markup import plain_label

from conftest import drag_slider, screenshot, server_log_tail

pytestmark = pytest.mark.browser
NUMBER = re.compile(r"-?\d+(?:[.,]\d+)?(?:[eE][-+]?\d+)?")
LEAK_RTOL = 1e-7        # a leaked answer would match to ~1e-15; a coincidence among ~10⁴ numbers at 1e-7 is ~1e-3


SEPARATOR = {"ru": ";", "uk": ";", "en": ","}           # where the language's spreadsheet splits the cells


def spreadsheet(text: str, lang: str) -> list[dict]:
    """The CSV's rows as a spreadsheet in the assignment's language reads them: split at its separator, each
    row keyed by the header's words."""
    return list(csv.DictReader(io.StringIO(text.lstrip("\ufeff"), newline=""), delimiter=SEPARATOR[lang]))


def numbers_in(text: str) -> np.ndarray:
    return np.array([float(m.replace(",", ".")) for m in NUMBER.findall(text)] or [np.nan])


def make_assignment(page) -> tuple[str, str, float]:
    """From the flywheel scene: ω_mean dragged on the scene, [δ] per student from 0.01 to 0.05 by 0.001."""
    page.goto("/scenes/flywheel?lang=en")
    page.wait_for_selector(".results:not(.busy) #panels figure")
    drag_slider(page, "#slider-omega_mean", 0.5)
    page.wait_for_timeout(400)                                   # the address (and the link) follow the slider
    omega = float(re.search(r"omega_mean=([\d.]+)", page.locator("#make-assignment").get_attribute("href")).group(1))
    page.click("#make-assignment")
    page.wait_for_load_state()
    assert float(page.locator('.slider-rule[data-slider="omega_mean"] [name="value"]').input_value()) == omega
    row = page.locator('.slider-rule[data-slider="delta"]')
    row.locator('[name="vary"]').check()
    row.locator('[name="vary_min"]').fill("0.01")
    row.locator('[name="vary_max"]').fill("0.05")
    row.locator('[name="vary_step"]').fill("0.001")
    page.fill("#attempts", "2")
    page.check("#reveal")
    page.fill("#title", "Flywheel lab")
    screenshot(page, "assignment_builder")
    page.click("#create-assignment")
    page.wait_for_selector("#assignment-links:not([hidden])")
    assert page.locator("#variants-count").inner_text().endswith("41")
    return (page.locator("#student-link").get_attribute("href"), page.locator("#results-link").get_attribute("href"),
            omega)


def correct_inertia(app_url: str, values: dict) -> float:
    """The answer as the flywheel endpoint gives it for the student's values (the test is not the student)."""
    scene = scenes()["flywheel"]
    body = scene_request(scene, scene.variants[0], values)
    return httpx.post(f"{app_url}/api/v1/flywheel?precision=full", json=body, timeout=30).json()["flywheel_inertia"]


def watched_page(context):
    """A new page whose console errors are kept in page.problems and every response in page.bodies."""
    page = context.new_page()
    page.problems, page.bodies = [], []
    page.on("console", lambda message: message.type == "error" and page.problems.append(message.text))
    page.on("pageerror", lambda error: page.problems.append(str(error)))
    page.on("response", lambda response: page.bodies.append(response))
    return page


def open_as_student(context, student_url: str, name: str, lang: str = "en"):
    """The student's page after typing the name and going on from the personal link (kept in page.link);
    every response body it received is kept in page.bodies."""
    page = watched_page(context)
    page.goto(re.sub(r"lang=\w+", f"lang={lang}", student_url))
    page.fill("#student", name)
    page.click("button[type=submit]")
    page.wait_for_selector("#personal-link")
    page.link = page.locator("#personal-link").input_value()
    page.click("#continue")
    page.wait_for_selector("#questions .question")
    page.wait_for_timeout(500)
    return page


def own_variant(app_url: str, assignment_id: str, personal_link: str) -> dict:
    """The student's variant as the API gives it to the holder of their secret (the test, not the page)."""
    secret = re.search(r"/me/([\w-]+)", personal_link).group(1)
    return httpx.get(f"{app_url}/api/v1/assignments/{assignment_id}/me",
                     headers={"Authorization": f"Bearer {secret}"}).json()


def received_text(page) -> str:
    texts = [page.content()]
    for response in page.bodies:
        if response.request.resource_type in ("document", "fetch", "xhr"):
            try:
                texts.append(response.text())
            except Exception:                                    # a redirect has no body
                pass
    return "\n".join(texts)


def two_names_with_different_variants(assignment_id: str, spec: AssignmentSpec) -> tuple[str, str]:
    resolved = plan(spec, scenes())
    first = "Olena Kovalenko"
    for k in range(100):
        second = f"Taras Shevchenko {k}"
        if resolved.number_for(assignment_id, normalise(second)) != resolved.number_for(assignment_id,
                                                                                         normalise(first)):
            return first, second
    raise AssertionError("no second name with another variant")


def with_decimal_comma(x: float) -> str:
    """x to six significant digits with a decimal comma, as a student on the English page may type it, never with
    exactly three decimals: "10,582" there is refused as ambiguous (a thousands separator in English;
    decimal_input.js), so it is typed "10,5820" (.6g drops the trailing zero; 1 variant in 41 of this assignment
    hit it and waited for ✓ in vain)."""
    text = f"{x:.6g}".replace(".", ",")
    return text + "0" if re.search(r",\d{3}$", text) else text


def answer(page, value: str) -> str:
    """Type `value`, check it, and return the feedback once it says right or wrong; if it never does, fail with
    what the page showed instead, the submissions' statuses and the end of the server's log."""
    page.fill("#answer-flywheel_inertia", value)
    page.click("#question-flywheel_inertia button")
    feedback = page.locator("#feedback-flywheel_inertia")
    try:
        feedback.filter(has_text=re.compile("✓|✗")).wait_for()
    except PlaywrightTimeout:
        statuses = [r.status for r in page.bodies if r.url.endswith("/submissions")]
        origin = re.match(r"https?://[^/]+", page.url).group(0)
        raise AssertionError(f"no ✓ or ✗ for the answer {value}: the feedback reads {feedback.inner_text()!r}, "
                             f"the submissions were answered {statuses}, the page's problems {page.problems}; "
                             f"the server's log ends:\n{server_log_tail(origin)}") from None
    return feedback.inner_text()


def test_assignment_from_making_to_results(chromium, app_url, browser_page):
    instructor = browser_page
    student_url, results_url, omega = make_assignment(instructor)
    assignment_id = re.search(r"/assignments/([\w-]+)", student_url).group(1)
    spec = AssignmentSpec.model_validate({
        "scene": "flywheel", "variant": "rig", "sliders": {"delta": {"vary": {"min": 0.01, "max": 0.05}, "step": 0.001},
                                                        "omega_mean": {"value": omega}},
        "questions": [{"id": "flywheel_inertia"}], "attempts": 2})
    right_name, wrong_name = two_names_with_different_variants(assignment_id, spec)

    students = {}
    for name in (right_name, wrong_name):
        context = chromium.new_context(base_url=app_url, viewport={"width": 1400, "height": 900})   # a browser each
        page = open_as_student(context, student_url, name)
        variant = own_variant(app_url, assignment_id, page.link)
        assert variant["values"]["omega_mean"] == omega
        correct = correct_inertia(app_url, variant["values"])
        seen = numbers_in(received_text(page))
        assert not np.any(np.isclose(seen, correct, rtol=LEAK_RTOL, atol=0)), f"{name}: the answer reached the page"
        assert page.locator("#slider-delta").is_disabled()
        assert "flywheel" not in json.dumps([r.url for r in page.bodies if "/api/v1/flywheel" in r.url])
        students[name] = (page, variant, correct)
    assert students[right_name][1]["variant"] != students[wrong_name][1]["variant"]
    assert students[right_name][1]["values"]["delta"] != students[wrong_name][1]["values"]["delta"]

    page, _, correct = students[right_name]
    feedback = answer(page, with_decimal_comma(correct * 1.01))                 # within 2 %, decimal comma
    assert "✓" in feedback and "right" in feedback
    assert page.locator("#answer-flywheel_inertia").is_disabled()
    shown = float(page.locator("#correct-flywheel_inertia").inner_text().split(":")[1].split()[0].replace(",", "."))
    assert shown == pytest.approx(correct, rel=1e-5)
    screenshot(page, "assignment_student_right")

    page, _, correct = students[wrong_name]
    feedback = answer(page, f"{correct * 1.1:.6g}")
    assert "✗" in feedback and "attempts left: 1" in feedback
    assert page.locator("#correct-flywheel_inertia").inner_text() == ""          # not closed: no answer shown
    screenshot(page, "assignment_student_wrong")
    for name, (page, _, _) in students.items():
        assert page.problems == [], (name, page.problems)

    instructor.goto(results_url.replace("lang=ru", "lang=en"))
    rows = instructor.locator("#results tbody tr")
    assert rows.count() == 2
    table = {rows.nth(i).locator("td").nth(0).inner_text(): rows.nth(i).inner_text() for i in range(2)}
    assert "✓" in table[right_name] and "1 / 1" in table[right_name]
    assert "✗" in table[wrong_name] and "0 / 1" in table[wrong_name]
    assert f"Correct answer: {students[wrong_name][2]:.6g}" in table[wrong_name]     # the instructor sees it
    assert "Correct answer" not in table[right_name]
    screenshot(instructor, "assignment_results")
    header = instructor.locator("#results thead th", has_text="Moment of inertia")    # "I_fl" as the scene writes it
    assert header.locator("sub").inner_text() == "fl" and "_" not in header.inner_text()
    assert "_" not in header.get_attribute("title")
    scroll_box = instructor.locator(".table-wrap")                 # the wide table's scroll box: reached and named
    assert scroll_box.get_attribute("tabindex") == "0" and scroll_box.get_attribute("role") == "region"
    assert scroll_box.get_attribute("aria-label") == "Results"
    assert "lang=en" in results_url                               # the assignment's language: its CSV's words
    exported = httpx.get(app_url + instructor.locator("#csv").get_attribute("href")).text
    exported_rows = {row["Student"]: row for row in spreadsheet(exported, "en")}
    assert set(exported_rows) == {right_name, wrong_name}
    inertia = plain_label(question(scenes()["flywheel"], "flywheel_inertia").label["en"])   # the CSV's plain text
    for name, (_, variant, _) in students.items():
        row = exported_rows[name]
        assert int(row["Variant"]) == variant["variant"] and float(row["[δ]"]) == variant["values"]["delta"]
        assert row["Score"] == ("1" if name == right_name else "0")
        assert float(row[f"{inertia}: Correct answer"]) == pytest.approx(students[name][2], rel=1e-9)
        assert f"{variant['variant']}" in table[name]
    assert instructor.problems == []

    page, _, correct = students[wrong_name]
    page.reload()                                                  # the cookie: straight back to the scene
    page.wait_for_selector("#questions .question")
    assert "attempts left: 1" in page.locator("#feedback-flywheel_inertia").inner_text()
    other_device = chromium.new_context(base_url=app_url, viewport={"width": 1400, "height": 900}, locale="ru-RU")
    phone = watched_page(other_device)
    phone.goto(page.link.replace("lang=en", "lang=ru"))            # the personal link, on another device
    phone.wait_for_selector("#questions .question")
    assert wrong_name in phone.locator(".assignment-who").inner_text()
    assert "1" in phone.locator("#feedback-flywheel_inertia").inner_text()          # the same attempts
    phone.fill("#answer-flywheel_inertia", f"{correct:.6g}".replace(".", ","))
    phone.click("#question-flywheel_inertia button")              # the feedback shows ✗ already: wait for ✓
    phone.locator("#feedback-flywheel_inertia").filter(has_text="✓").wait_for()
    screenshot(phone, "assignment_student_other_device_ru")
    assert phone.problems == []
    instructor.reload()
    row = instructor.locator("#results tbody tr", has_text=wrong_name)
    assert "✓" in row.inner_text() and "1 / 1" in row.inner_text()
    for page, _, _ in students.values():
        page.context.close()
    other_device.close()


def test_kinematics_assignment_page_never_asks_for_the_answer(chromium, app_url):
    """u₃₁max asked: the student's page requests kinematics without u₃₁ and u′₃₁, and shows no such plot."""
    created = httpx.post(f"{app_url}/api/v1/assignments", json={
        "scene": "transfer-functions", "variant": "slider_crank", "lang": "en",
        "sliders": {"lambda": {"vary": {"min": 2.5, "max": 5.0}, "free": {"min": 2.0, "max": 6.0}}},
        "questions": [{"id": "u31_max"}]}).json()
    context = chromium.new_context(base_url=app_url, viewport={"width": 1400, "height": 900})
    page = open_as_student(context, created["student_url"], "Ivan Franko")
    page.wait_for_selector("#plots figure")
    variant = own_variant(app_url, created["id"], page.link)
    requests = [r.request.post_data_json for r in page.bodies if r.url.split("?")[0].endswith("/api/v1/kinematics")]
    assert requests and all(not {"u31", "du31"} & set(body["outputs"]) for body in requests)
    assert page.locator("#slider-lambda").is_enabled()                        # free within 2 … 6
    drag_slider(page, "#slider-lambda", 0.9)
    page.wait_for_timeout(600)
    last = [r for r in page.bodies if r.url.split("?")[0].endswith("/api/v1/kinematics")][-1]
    assert last.request.post_data_json["params"]["l2"] != pytest.approx(variant["values"]["lambda"] * 0.1)
    assert "u31" not in last.json()["outputs"]
    page.click("#back-to-variant")
    page.wait_for_load_state()
    assert f"λ = l₂/l₁ = {variant['values']['lambda']:.2f}" in page.locator("#controls").inner_text()
    assert page.problems == []
    screenshot(page, "assignment_student_kinematics")
    context.close()


def test_roster_lock_new_link_and_delete_on_the_results_page(chromium, app_url, browser_page):
    """In Russian: the instructor pastes a roster (one look-alike line is refused, naming why), locks
    registration; a name not on it is refused, and so is a roster name typed (it enters only by its personal
    link); the instructor downloads the links, the student opens theirs, the instructor makes them a new link,
    deletes another's row, and replaces the results link itself (the old one stops working)."""
    created = httpx.post(f"{app_url}/api/v1/assignments", json={
        "scene": "flywheel", "variant": "rig", "lang": "ru", "questions": [{"id": "flywheel_inertia"}],
        "sliders": {"delta": {"vary": {"min": 0.01, "max": 0.05}, "step": 0.001}}}, timeout=60).json()
    instructor = browser_page
    instructor.on("dialog", lambda dialog: dialog.accept())
    instructor.goto(created["results_url"])
    instructor.fill("#roster-names", "ФИО;Группа\nИванов Иван;КМ-21/1\nПетренко Олена;КМ-21/1\nIvanоv Petr;КМ-21/2\n")
    instructor.click("#roster-add")
    instructor.locator("#results tbody tr").nth(1).wait_for()
    outcome = instructor.locator("#roster-outcome").inner_text()
    assert "Добавлены (2)" in outcome and "Не приняты (1)" in outcome and "Ivanоv Petr" in outcome
    assert instructor.locator("#results tbody tr").count() == 2
    instructor.click("#roster-lock")
    instructor.locator("#registration-state", has_text="только имена из списка").wait_for()

    student = chromium.new_context(base_url=app_url, viewport={"width": 1400, "height": 900}, locale="ru-RU")
    page = watched_page(student)
    page.goto(created["student_url"])
    page.fill("#student", "Сидоров Петр")
    page.click("button[type=submit]")
    assert "Регистрация открыта только для имён из списка" in page.locator("#name-error").inner_text()
    assert page.problems == ["Failed to load resource: the server responded with a status of 403 (Forbidden)"]
    page.problems.clear()                                      # the refusal's status, as Chromium logs it
    page.fill("#student", "иванов  иван")
    page.click("button[type=submit]")
    assert "есть в списке преподавателя" in page.locator("#name-error").inner_text()
    assert page.problems == ["Failed to load resource: the server responded with a status of 403 (Forbidden)"]
    page.problems.clear()

    instructor.reload()
    with instructor.expect_download() as download:
        instructor.click("#links-new")                         # neither has a link yet
    links = spreadsheet(open(download.value.path(), encoding="utf-8").read(), "ru")    # a ru spreadsheet: ";"
    assert sorted(row["Студент"] for row in links) == ["Иванов Иван", "Петренко Олена"]
    page.goto(next(row["Личная ссылка"] for row in links if row["Студент"] == "Иванов Иван"))
    page.wait_for_selector("#questions .question")
    assert page.problems == []
    ivanov = instructor.locator("#results tbody tr", has_text="Иванов Иван")
    ivanov.locator("button.new-link").click()
    new_link = ivanov.locator(".shown-link").input_value()
    assert "/me/" in new_link
    page.reload()                                              # the old secret in the cookie no longer works
    assert "больше не действует" in page.locator("#name-error").inner_text()
    page.goto(new_link)
    page.wait_for_selector("#questions .question")
    instructor.locator("#results tbody tr", has_text="Петренко Олена").locator("button.delete-student").click()
    instructor.locator("#results tbody tr", has_text="Петренко Олена").wait_for(state="detached")
    assert instructor.locator("#results tbody tr").count() == 1
    screenshot(instructor, "assignment_results_roster_ru")
    assert instructor.problems == []

    old_url = instructor.url
    instructor.click("#replace-results-link")                 # the confirm dialog is accepted
    instructor.locator("#new-results-link").wait_for()
    new_url = instructor.locator("#new-results-url").input_value()
    assert new_url != old_url and "/results/" in new_url and instructor.url == new_url
    assert httpx.get(old_url).status_code == 404 and httpx.get(new_url).status_code == 200
    instructor.locator("#results tbody tr", has_text="Иванов Иван").locator("button.new-link").click()   # the page
    assert "/me/" in instructor.locator("#results tbody tr", has_text="Иванов Иван").locator(".shown-link").input_value()
    assert instructor.locator("#csv").get_attribute("href").startswith(
        f"/api/v1/assignments/{created['id']}/results/{new_url.split('/results/')[1].split('?')[0]}/")
    screenshot(instructor, "assignment_results_link_replaced_ru")
    assert instructor.problems == []
    student.close()
