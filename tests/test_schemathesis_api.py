"""Hostile input's acceptance: schemathesis over the whole API (every operation of /api/v1/openapi.json, valid and
invalid requests), with a real assignment, its instructor token, a registered student's personal secret
(Authorization: Bearer) and another student's handle supplied in most cases, so that the requests reach past the
401s and 404s: no answer may be a 5xx, and every answer carries the security headers. (The instructor operations
may reset or delete the second student, never the first: their secret stays valid throughout.)

Each operation gets schemathesis's coverage phase (every boundary and wrong-type case its schema defines: about
20,000 in all, the same on every run) and its random cases: MDL_SCHEMATHESIS_CASES of them (default 250, about six
per operation; the acceptance run, below, is 5,000). One in-process session serves every case (its cookies cleared before
each, the environment's proxy settings not read): a session per case took half of the run's CPU.

    MDL_SCHEMATHESIS_CASES=5000 python3 -m pytest -q tests/test_schemathesis_api.py

The cases are spread over the operations (a parameterless GET has one case however many are asked, so the
others get more); the last test checks that at least that many were sent. Seeded (MDL_FUZZ_SEED) for
reproducibility; the data go to a pytest tmp directory.
"""
from __future__ import annotations

import faulthandler
import math
import os
import sys
from collections import Counter, defaultdict

import pytest
import schemathesis
from fastapi.testclient import TestClient
from hypothesis import HealthCheck, settings
from schemathesis.config import SchemathesisConfig
from schemathesis.python import asgi

from server.classroom import assignment_store
from server.api.app import create_app
from server.api.security import SECURITY_HEADERS

from openapi_document import openapi_document

CASES = int(os.environ.get("MDL_SCHEMATHESIS_CASES", "250"))
SEED = int(os.environ.get("MDL_FUZZ_SEED", "20269"))
OPENAPI = openapi_document()
OPERATIONS = sum(len(methods) for methods in OPENAPI["paths"].values())
SINGLE = sum(1 for path, methods in OPENAPI["paths"].items() for m, op in methods.items()
             if not op.get("parameters") and "requestBody" not in op)          # one distinct case each
PER_OPERATION = math.ceil(1.15 * (CASES - SINGLE) / (OPERATIONS - SINGLE))
CONFIG = SchemathesisConfig.from_dict({"seed": SEED, "generation": {"mode": "all", "max-examples": PER_OPERATION}})
schema = schemathesis.openapi.from_dict(OPENAPI, config=CONFIG)
QUIET = [HealthCheck.too_slow, HealthCheck.filter_too_much, HealthCheck.data_too_large,
         HealthCheck.function_scoped_fixture]
ASSIGNMENT = {"scene": "transfer-functions", "variant": "slider_crank", "title": "fuzz",
              "sliders": {"lambda": {"vary": {"min": 2.5, "max": 5.0}}},
              "questions": [{"id": "u31_max"}, {"id": "du31_min"}], "attempts": 3, "reveal_answers": True}
STUDENT, OTHER = "Fuzz Student", "Other Student"
sent = {"cases": 0, "supplied": 0}
answered: dict[str, Counter] = defaultdict(Counter)           # operation → status codes seen
tried: Counter = Counter()                                      # (method, path) → its cases so far


@pytest.fixture(scope="module")
def world(tmp_path_factory):
    """The app on its own data directory, an assignment, its results token, a student's secret and another
    student's handle (as the results list it)."""
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv("MDL_DATA_DIR", str(tmp_path_factory.mktemp("mdl-schemathesis")))
        assignment_store.store.cache_clear()
        app = create_app()
        client = TestClient(app)
        created = client.post("/api/v1/assignments", json=ASSIGNMENT)
        assert created.status_code == 201, created.text
        made = created.json()
        students = f"/api/v1/assignments/{made['id']}/students"
        registered = [client.post(students, json={"name": name}) for name in (STUDENT, OTHER)]
        assert [r.status_code for r in registered] == [201, 201], [r.text for r in registered]
        rows = client.get(f"/api/v1/assignments/{made['id']}/results/{made['results_token']}").json()["students"]
        session = asgi.get_client(app)    # one for every case (cookies cleared before each)
        session.trust_env = False           # nothing of this process's environment applies in-process
        yield {"app": app, "session": session, "assignment_id": made["id"], "token": made["results_token"],
               "secret": registered[0].json()["secret"],
               "student_id": next(row["id"] for row in rows if row["student"] == OTHER)}
        assignment_store.store.cache_clear()


@pytest.fixture(autouse=True)
def watchdog():
    faulthandler.dump_traceback_later(1800, exit=True, file=sys.__stderr__)
    yield
    faulthandler.cancel_dump_traceback_later()


def supply(case, world) -> None:
    """Three cases in four of each operation get the real assignment, token, student handle and the student's
    secret (the rest keep what was generated): counted per operation, so that which cases are supplied does not
    depend on the order the operations ran in."""
    turn = tried[case.method, case.path]
    tried[case.method, case.path] += 1
    if turn % 4 == 3 or not case.path_parameters:
        return
    for name in ("assignment_id", "token", "student_id"):
        if name in case.path_parameters:
            case.path_parameters[name] = world[name]
            sent["supplied"] += 1
    if "scene_id" in case.path_parameters:
        case.path_parameters["scene_id"] = "transfer-functions"
    if case.path.endswith("/submissions") and isinstance(case.body, dict) and turn % 2:
        case.body = {**case.body, "question": "u31_max"}         # a question of the assignment, the answer as drawn
        if "student" in case.body:
            case.body["student"] = STUDENT
    case.headers = {**(case.headers or {}), "Authorization": f"Bearer {world['secret']}"}


@schema.parametrize()
@settings(max_examples=PER_OPERATION, deadline=None, database=None, suppress_health_check=QUIET)
def test_no_answer_is_a_server_error_and_every_answer_carries_the_security_headers(case, world):
    supply(case, world)
    sent["cases"] += 1
    # a guard against a hang, not a measure of speed: a submission for a variant nobody has used yet computes its
    # answers in a heavy process, which a loaded machine may take tens of seconds to start and run
    world["session"].cookies.clear()
    response = case.call(session=world["session"], base_url="http://testserver", timeout=300)
    answered[f"{case.method} {case.path}"][response.status_code] += 1
    if case.path.endswith("/results/{token}/token") and response.status_code == 200:
        world["token"] = response.json()["results_token"]      # the instructor replaced the token: the old one ended
    where = f"{case.method} {case.formatted_path} → {response.status_code}"
    assert response.status_code < 500, where
    missing = [name for name, value in SECURITY_HEADERS.items() if response.headers.get(name) != [value]]
    assert not missing, f"{where}: missing {missing}"


def test_enough_cases_were_sent():
    """Runs after the operations above (file order): the acceptance counts cases, not operations."""
    assert sent["cases"] >= CASES, sent
    assert sent["supplied"] > 0
    print(f"\n{sent['cases']} cases, 0 × 5xx; status codes per operation:")
    for operation, codes in sorted(answered.items()):
        print(f"  {operation}: {dict(sorted(codes.items()))}")
    me = answered["GET /api/v1/assignments/{assignment_id}/me"]
    results = answered["GET /api/v1/assignments/{assignment_id}/results/{token}"]
    assert me[200] > 0 and results[200] > 0            # the secret and the token were supplied and accepted
