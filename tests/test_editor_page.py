"""The editor's page (/editor): served in every language with that language's interface texts and every preset
of content/mechanisms (title and source in the page's language, the linkage as the API takes it); linked
from the start page."""
from __future__ import annotations

import html
import json
import re

import pytest
from fastapi.testclient import TestClient

from server.api.app import app
from server.core.structure.presets import presets


@pytest.fixture(scope="module")
def client() -> TestClient:
    with TestClient(app) as c:
        yield c


def embedded(page: str, element_id: str):
    match = re.search(rf'<script type="application/json" id="{element_id}">(.*?)</script>', page, re.S)
    return json.loads(match.group(1).replace("<\\/", "</"))


@pytest.mark.parametrize("lang", ["ru", "uk", "en"])
def test_the_editor_page_carries_its_texts_and_the_presets(client, lang):
    answer = client.get(f"/editor?lang={lang}")
    assert answer.status_code == 200
    page = answer.text
    texts = embedded(page, "interface-texts")
    assert f"<h1>{html.escape(texts['editor_title'])}</h1>" in page and f'<html lang="{lang}">' in page
    shown = embedded(page, "editor-presets")
    assert [p["name"] for p in shown] == list(presets())
    for item in shown:
        preset = presets()[item["name"]]
        assert item["title"] == preset["title"][lang] and item["source"] == preset["source"][lang]
        assert item["linkage"] == preset["linkage"]
    assert '/js/editor/main.js"' in page and "/vendor/plotly/" in page


def test_the_start_page_links_to_the_editor(client):
    assert 'href="/editor?lang=uk"' in client.get("/?lang=uk").text
