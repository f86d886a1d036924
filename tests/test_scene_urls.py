"""One URL style for the scenes: every id lowercase words joined by hyphens; a former id (/scenes/flywheel_analysis)
redirects permanently to the current one with the query kept, for the page, the builder and the API, and an
assignment made with a former id still finds its scene."""
from __future__ import annotations

import re

import pytest
from fastapi.testclient import TestClient

from server.api.app import app
from server.lessons.scenes import scenes

FORMER = {"flywheel_analysis": "flywheel-analysis", "induction_motor": "induction-motor"}


@pytest.fixture(scope="module")
def client():
    with TestClient(app) as client:
        yield client


def test_every_scene_id_is_hyphenated_lowercase():
    assert all(re.fullmatch(r"[a-z0-9]+(-[a-z0-9]+)*", scene_id) for scene_id in scenes())
    for old, new in FORMER.items():
        assert old not in list(scenes()) and scenes()[old].id == new and scenes().get(old).id == new


@pytest.mark.parametrize("old,new", FORMER.items())
def test_a_former_address_redirects(client, old, new):
    page = client.get(f"/scenes/{old}?lang=uk", follow_redirects=False)
    assert page.status_code == 301 and page.headers["location"] == f"/scenes/{new}?lang=uk"
    assert client.get(page.headers["location"]).status_code == 200
    api = client.get(f"/api/v1/scenes/{old}", follow_redirects=False)
    assert api.status_code == 301 and api.headers["location"] == f"/api/v1/scenes/{new}"
    assert client.get(api.headers["location"]).json()["id"] == new


def test_the_builder_of_a_former_id_redirects(client):
    scene = next(s for s in scenes().values() if s.former_ids)
    old = scene.former_ids[0]
    page = client.get(f"/scenes/{old}/assign?lang=en", follow_redirects=False)
    assert page.status_code == 301 and page.headers["location"] == f"/scenes/{scene.id}/assign?lang=en"


def test_the_current_ids_answer_directly(client):
    for scene_id in scenes():
        assert client.get(f"/scenes/{scene_id}?lang=ru", follow_redirects=False).status_code == 200, scene_id
