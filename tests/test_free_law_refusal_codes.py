"""A refused free law M_P(φ₁) (motor.table_phi, motor.table_moment) keeps pydantic's HTTP 422, field path, type
and words, and adds what the page needs to say it in the reader's language (content/i18n err_<code>): the code,
the point's row (from 1), the bound in the editor's units (degrees for an angle, N·m for a moment); its text in
every language fills from that context."""
import math

import pytest
from fastapi.testclient import TestClient

from server.api.app import app
from server.lessons.scenes import interface_texts

client = TestClient(app)
MACHINE = {"mechanism": "slider_crank", "params": {"l1": 0.1, "l2": 0.4}, "inertias": {"J1": 0.5},
           "outputs": ["steady"]}


def refusals(phi, moment) -> list[dict]:
    response = client.post("/api/v1/motion?lang=ru", json=MACHINE | {
        "motor": {"kind": "table", "table_phi": phi, "table_moment": moment}})
    assert response.status_code == 422
    return response.json()["detail"]


def test_an_angle_beyond_the_turn_names_its_point_and_the_bound_in_degrees():
    [error] = refusals([0.0, 1.0, 7.0], [1.0, 2.0, 3.0])
    assert error["loc"] == ["body", "motor", "table_phi", 2] and error["type"] == "less_than"
    assert error["msg"] == f"Input should be less than {2 * math.pi}"
    assert error["ctx"] == {"lt": 2 * math.pi, "code": "free_law_angle", "point": 3, "min": 0.0, "max": 360.0}


def test_a_negative_angle_and_a_moment_too_large_name_their_points():
    angle, moment = refusals([0.0, -1.0], [1.0, -2e7])
    assert angle["loc"] == ["body", "motor", "table_phi", 1] and angle["type"] == "greater_than_equal"
    assert angle["ctx"] == {"ge": 0.0, "code": "free_law_angle", "point": 2, "min": 0.0, "max": 360.0}
    assert moment["loc"] == ["body", "motor", "table_moment", 1] and moment["type"] == "greater_than_equal"
    assert moment["ctx"] == {"ge": -1e7, "code": "free_law_moment", "point": 2, "min": -1e7, "max": 1e7}


def test_angles_not_increasing_name_the_point_and_the_previous_angle():
    [error] = refusals([0.0, math.radians(30.5), math.radians(20)], [1.0, 2.0, 3.0])
    assert error["loc"] == ["body", "motor", "table_phi"] and error["type"] == "value_error"
    assert error["ctx"]["code"] == "free_law_increasing" and error["ctx"]["point"] == 3
    assert error["ctx"]["previous"] == 2 and error["ctx"]["bound"] == pytest.approx(30.5, abs=1e-9)


def test_a_table_of_one_point_is_said_by_the_allowed_count():
    errors = refusals([0.0], [1.0])
    assert [e["loc"][-1] for e in errors] == ["table_phi", "table_moment"]
    assert all(e["type"] == "too_short" and e["ctx"]["code"] == "free_law_points"
               and (e["ctx"]["min"], e["ctx"]["max"]) == (2, 361) for e in errors)


def test_other_refusals_of_the_table_are_pydantics_own():
    [error] = refusals([0.0, "NaN"], [1.0, 2.0])
    assert error["type"] == "finite_number" and "ctx" not in error


@pytest.mark.parametrize("lang", ["ru", "uk", "en"])
@pytest.mark.parametrize("phi, moment", [([0.0, 7.0], [1.0, 2.0]), ([0.0, 1.0], [1.0, 2e8]),
                                         ([0.0, 1.0, 0.5], [1.0, 2.0, 3.0]), ([0.0], [1.0])])
def test_every_code_has_a_text_its_context_fills(lang, phi, moment):
    for error in refusals(phi, moment):
        text = interface_texts(lang)[f"err_{error['ctx']['code']}"].format(**error["ctx"])
        assert "{" not in text and str(error["ctx"].get("point", "")) in text
