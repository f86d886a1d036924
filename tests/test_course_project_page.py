"""The course project's page (/project): served in every language with that language's interface texts, its
sections' headings and the presets driven by a crank (title and source in the page's language, the linkage and
the dynamics as the API takes them); linked from the start page and from the editor."""
from __future__ import annotations

import html
import json
import re

import pytest
from fastapi.testclient import TestClient

from server.api.app import app
from server.core.structure.presets import presets
from server.lessons.scenes import interface_texts

SECTIONS = ["project_report_title", "project_structure", "project_kinematics", "project_dynamics",
            "project_kinetostatics", "project_equations", "project_sheets"]


@pytest.fixture(scope="module")
def client() -> TestClient:
    with TestClient(app) as c:
        yield c


def embedded(page: str, element_id: str):
    match = re.search(rf'<script type="application/json" id="{element_id}">(.*?)</script>', page, re.S)
    return json.loads(match.group(1).replace("<\\/", "</"))


@pytest.mark.parametrize("lang", ["ru", "uk", "en"])
def test_the_project_page_carries_its_texts_sections_and_presets(client, lang):
    answer = client.get(f"/project?lang={lang}")
    assert answer.status_code == 200
    page = answer.text
    texts = embedded(page, "interface-texts")
    assert texts == interface_texts(lang)
    assert f'<html lang="{lang}">' in page and f"<h1>{html.escape(texts['project_title'])}</h1>" in page
    for key in SECTIONS:                               # every section's heading, in the page's language
        assert html.escape(texts[key]) in page, key
    shown = embedded(page, "project-presets")
    cranked = [name for name, p in presets().items() if p["linkage"]["input"].get("kind", "crank") == "crank"]
    assert [p["name"] for p in shown] == cranked and "shaping_machine" in cranked
    for item in shown:
        preset = presets()[item["name"]]
        assert item["title"] == preset["title"][lang] and item["source"] == preset["source"][lang]
        assert item["linkage"] == preset["linkage"] and item["dynamics"] == preset.get("dynamics")
    assert '/js/course_project/main.js"' in page and "/css/course_project.css" in page


def test_an_unknown_language_falls_back_and_the_page_still_renders(client):
    answer = client.get("/project?lang=xx")
    assert answer.status_code == 200 and 'id="project-report"' in answer.text


def test_the_start_page_and_the_editor_link_to_the_project(client):
    assert 'href="/project?lang=uk"' in client.get("/?lang=uk").text
    editor = client.get("/editor?lang=ru").text
    assert 'id="editor-course-project"' in editor and html.escape(interface_texts("ru")["editor_course_project"]) in editor
