"""A scene's variant names a mechanism preset of content/mechanisms instead of copying its linkage and masses
(server/lessons/scene_files.py), and a slider may set an item of a list ("masses.forces.0.working") in the
lesson model (server/lessons/requests.py), in a family's members (server/families/family.py) and on the page
(tests/browser/test_request_body_parity.py checks the page's twin against the lesson model)."""
from __future__ import annotations

import json

import pytest
from fastapi.testclient import TestClient

from server.runtime import heavy
from server.families import family
from server.api.app import app
from server.lessons.requests import path_value, scene_request, set_path
from server.lessons.scene_files import ContentError, resolved_scene
from server.lessons.scenes import CONTENT_DIR, scenes

PRESET = json.loads((CONTENT_DIR / "mechanisms" / "shaping_machine.json").read_text(encoding="utf-8"))
SIX_BAR_VARIANTS = [("equation-of-motion", "shaping"), ("equation-of-motion", "whitworth"),
                    ("flywheel", "shaping"), ("forces-friction", "shaping")]


def variant(scene_id: str, variant_id: str):
    return next(v for v in scenes()[scene_id].variants if v.id == variant_id)


def test_the_request_takes_the_presets_linkage_and_masses_with_the_variants_own_keys_merged():
    forces = variant("forces-friction", "shaping")
    assert forces.mechanism == "general" and forces.request["linkage"] == PRESET["linkage"]
    masses = forces.request["masses"]
    assert masses == PRESET["dynamics"]["masses"] | {"friction": 0.1, "pair_radius": 0.02}   # merged, not replaced
    flywheel = variant("flywheel", "shaping")
    assert flywheel.request["motor"] == PRESET["dynamics"]["flywheel"]["motor"]
    assert flywheel.request["delta"] == PRESET["dynamics"]["flywheel"]["delta"]
    whitworth = variant("equation-of-motion", "whitworth")          # extends the shaping machine's variant
    assert whitworth.request["linkage"] != variant("equation-of-motion", "shaping").request["linkage"]
    assert whitworth.request["rtol"] == 1e-8


def test_the_scene_file_names_the_preset_and_copies_nothing_of_it():
    for name in ("equation_of_motion", "flywheel", "forces_friction"):
        text = (CONTENT_DIR / "scenes" / f"{name}.json").read_text(encoding="utf-8")
        assert '"linkage": "linkage"' in text and '"groups"' not in text


@pytest.mark.parametrize("reference, reason", [
    ({"name": "no_such_mechanism", "request": {"linkage": "linkage"}}, "no file of content/mechanisms"),
    ({"name": "shaping_machine", "request": {"masses": "dynamics.mass"}}, "has no 'dynamics.mass'"),
])
def test_a_preset_reference_to_nothing_is_refused_naming_the_file_and_variant(reference, reason):
    raw = {"variants": [{"id": "six", "preset": reference, "request": {}}]}
    with pytest.raises(ContentError, match=rf"s\.json: variant six: .*{reason}"):
        resolved_scene(raw, "s.json", {}, {"shaping_machine": PRESET})


@pytest.mark.parametrize("address, reason", [
    ({"request": {"masses": "d.mass"}, "example": "shaping_machine"}, "the address has no 'd.mass'"),
    ({"request": {"linkage": "m"}, "example": "no_such_mechanism"}, "address example 'no_such_mechanism'"),
])
def test_an_address_reference_to_nothing_is_refused_naming_the_file_and_variant(address, reason):
    """A variant that takes its mechanism from the page address is resolved with its example preset's documents
    (m: the linkage, d: its dynamics): a path they lack, or an example that is no preset, is refused."""
    raw = {"variants": [{"id": "own", "address": address, "request": {}}]}
    with pytest.raises(ContentError, match=rf"s\.json: variant own: {reason}"):
        resolved_scene(raw, "s.json", {}, {"shaping_machine": PRESET})


def test_a_dotted_path_indexes_a_list():
    body = {"masses": {"forces": [{"working": 1.0}, {"working": 2.0}]}}
    set_path(body, "masses.forces.1.working", 5.0)
    assert body == {"masses": {"forces": [{"working": 1.0}, {"working": 5.0}]}}
    assert path_value(body, "masses.forces.1.working") == 5.0
    set_path(body, "load.f", 0.1)                                 # objects on the way are still made
    assert body["load"] == {"f": 0.1}


def test_the_ram_force_slider_sets_the_presets_force():
    scene = scenes()["equation-of-motion"]
    body = scene_request(scene, variant("equation-of-motion", "shaping"), {"P": 4000})
    assert body["masses"]["forces"][0]["working"] == 4000
    assert body["masses"]["forces"][0]["k"] == PRESET["dynamics"]["masses"]["forces"][0]["k"]


def test_a_family_member_sets_a_list_item_and_leaves_the_request_as_it_was():
    request = scene_request(scenes()["forces-friction"], variant("forces-friction", "shaping"))
    member = family.member_body(request, [family.Vary("masses.forces.0.working", 1.0)], 1234.0)
    assert member["masses"]["forces"][0]["working"] == 1234.0
    assert request["masses"]["forces"][0]["working"] == 3000                 # shared parts never written
    assert family.path_exists(request, "masses.forces.0.working")
    assert not family.path_exists(request, "masses.forces.3.working")


@pytest.fixture(scope="module")
def client():
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(heavy, "HEAVY_PROCESSES", 0)
        patch.setattr(family, "TIME_BUDGET_S", 1e9)         # complete families on any machine
        yield TestClient(app)


def test_the_family_of_the_ram_force_moves_the_balancing_moment(client):
    """The page's preview of the P slider: members with the force set through the list, each a full answer whose
    useful work grows with P (the ram's work over a cycle is linear in P: checked against the two ends)."""
    request = scene_request(scenes()["forces-friction"], variant("forces-friction", "shaping")) | {"n": 73}
    answer = client.post("/api/v1/family", json={
        "endpoint": "forces", "request": request, "vary": [{"path": "masses.forces.0.working", "factor": 1.0}],
        "min": 1000, "max": 5000, "log": False})
    assert answer.status_code == 200, answer.text[:400]
    data = answer.json()
    works = [member["work_useful"] for member in data["answers"]]
    values = data["values"]
    slope = (works[-1] - works[0]) / (values[-1] - values[0])
    assert slope > 0
    for value, work in zip(values, works):
        # linear in P, to the digits a family sends (5 significant: 5e-5 each of the three numbers compared)
        assert work == pytest.approx(works[0] + slope * (value - values[0]), rel=2e-4)
