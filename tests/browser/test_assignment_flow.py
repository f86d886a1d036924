"""The whole assignment flow in the browser: an instructor makes an assignment with per-student variants
from the flywheel scene; two students with different names get different variants, one answers right and
one wrong and each sees the matching feedback; the results page lists both and its CSV agrees. Every
response the student's page receives before submitting is searched for the correct answer.
"""
from __future__ import annotations

import csv
import io
import json
import re

import httpx
import numpy as np
import pytest

from server.lessons.scenes import scenes
from server.lessons.requests import scene_request
from server.classroom.spec import AssignmentSpec
from server.classroom.variants import plan, student_key

from conftest import drag_slider, screenshot

pytestmark = pytest.mark.browser
NUMBER = re.compile(r"-?\d+(?:[.,]\d+)?(?:[eE][-+]?\d+)?")
LEAK_RTOL = 1e-7        # a leaked answer would match to ~1e-15; a coincidence among ~10⁴ numbers at 1e-7 is ~1e-3


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


def open_as_student(context, student_url: str, name: str):
    """The student's page after typing the name; every response body it received is kept in page.bodies."""
    page = context.new_page()
    page.problems, page.bodies = [], []
    page.on("console", lambda message: message.type == "error" and page.problems.append(message.text))
    page.on("pageerror", lambda error: page.problems.append(str(error)))
    page.on("response", lambda response: page.bodies.append(response))
    page.goto(student_url.replace("lang=ru", "lang=en"))
    page.fill("#student", name)
    page.click("button[type=submit]")
    page.wait_for_selector("#questions .question")
    page.wait_for_timeout(500)
    return page


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
        if resolved.number_for(assignment_id, student_key(second)) != resolved.number_for(assignment_id,
                                                                                           student_key(first)):
            return first, second
    raise AssertionError("no second name with another variant")


def answer(page, value: str) -> str:
    page.fill("#answer-flywheel_inertia", value)
    page.click("#question-flywheel_inertia button")
    page.locator("#feedback-flywheel_inertia").filter(has_text=re.compile("✓|✗")).wait_for()
    return page.locator("#feedback-flywheel_inertia").inner_text()


def test_assignment_from_making_to_results(chromium, app_url, browser_page):
    instructor = browser_page
    student_url, results_url, omega = make_assignment(instructor)
    assignment_id = re.search(r"/assignments/([\w-]+)", student_url).group(1)
    spec = AssignmentSpec.model_validate({
        "scene": "flywheel", "variant": "rig", "sliders": {"delta": {"vary": {"min": 0.01, "max": 0.05}, "step": 0.001},
                                                        "omega_mean": {"value": omega}},
        "questions": [{"id": "flywheel_inertia"}], "attempts": 2})
    right_name, wrong_name = two_names_with_different_variants(assignment_id, spec)

    context = chromium.new_context(base_url=app_url, viewport={"width": 1400, "height": 900})
    students = {}
    for name in (right_name, wrong_name):
        page = open_as_student(context, student_url, name)
        variant = httpx.get(f"{app_url}/api/v1/assignments/{assignment_id}/students/{name}").json()
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
    feedback = answer(page, f"{correct * 1.01:.6g}".replace(".", ","))           # within 2 %, decimal comma
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
    exported = httpx.get(app_url + instructor.locator("#csv").get_attribute("href")).text.lstrip("\ufeff")
    exported_rows = {row["student"]: row for row in csv.DictReader(io.StringIO(exported))}
    assert set(exported_rows) == {right_name, wrong_name}
    for name, (_, variant, _) in students.items():
        row = exported_rows[name]
        assert int(row["variant"]) == variant["variant"] and float(row["delta"]) == variant["values"]["delta"]
        assert row["score"] == ("1" if name == right_name else "0")
        assert float(row["flywheel_inertia correct"]) == pytest.approx(students[name][2], rel=1e-9)
        assert f"{variant['variant']}" in table[name]
    assert instructor.problems == []
    context.close()


def test_kinematics_assignment_page_never_asks_for_the_answer(chromium, app_url):
    """u₃₁max asked: the student's page requests kinematics without u₃₁ and u′₃₁, and shows no such plot."""
    created = httpx.post(f"{app_url}/api/v1/assignments", json={
        "scene": "transfer-functions", "variant": "slider_crank", "lang": "en",
        "sliders": {"lambda": {"vary": {"min": 2.5, "max": 5.0}, "free": {"min": 2.0, "max": 6.0}}},
        "questions": [{"id": "u31_max"}]}).json()
    context = chromium.new_context(base_url=app_url, viewport={"width": 1400, "height": 900})
    page = open_as_student(context, created["student_url"], "Ivan Franko")
    page.wait_for_selector("#plots figure")
    requests = [r.request.post_data_json for r in page.bodies if r.url.split("?")[0].endswith("/api/v1/kinematics")]
    assert requests and all(not {"u31", "du31"} & set(body["outputs"]) for body in requests)
    assert page.locator("#slider-lambda").is_enabled()                        # free within 2 … 6
    drag_slider(page, "#slider-lambda", 0.9)
    page.wait_for_timeout(600)
    variant = httpx.get(f"{app_url}/api/v1/assignments/{created['id']}/students/Ivan Franko").json()
    last = [r for r in page.bodies if r.url.split("?")[0].endswith("/api/v1/kinematics")][-1]
    assert last.request.post_data_json["params"]["l2"] != pytest.approx(variant["values"]["lambda"] * 0.1)
    assert "u31" not in last.json()["outputs"]
    page.click("#back-to-variant")
    page.wait_for_load_state()
    assert f"λ = l₂/l₁ = {variant['values']['lambda']:.2f}" in page.locator("#controls").inner_text()
    assert page.problems == []
    screenshot(page, "assignment_student_kinematics")
    context.close()
