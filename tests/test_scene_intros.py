"""A scene opens with a short task-oriented text (what to drag, what to watch); the sources' details (equations,
misprints, conventions) are folded below it in a <details> the reader opens (scene.details, scene.html)."""
from __future__ import annotations

import re

import pytest
from fastapi.testclient import TestClient

from server.api.app import app
from server.lessons.scenes import interface_texts, scenes

client = TestClient(app)
FOLDED = {"wear": ("ISNKPKPM", "(4.24)"), "angular-acceleration": ("−0,0565", "(4)"),
          "bearings": ("(2.11)", "(2.19)"), "elastic-four-bar": ("(8)", "10⁷"),
          "induction-motor": ("b₁*", "§10.10"), "friction-influence": ("(3.30)", "(4.24)")}
SHORT = 420        # characters: two or three lines of the intro's width


@pytest.mark.parametrize("scene_id", sorted(FOLDED))
@pytest.mark.parametrize("lang", ["ru", "uk", "en"])
def test_the_intro_says_what_to_do_and_folds_the_sources_details(scene_id, lang):
    scene = scenes()[scene_id]
    text, details = scene.text[lang], scene.details[lang]
    assert len(text) <= SHORT and len(details) > 2 * len(text)
    assert re.search(r"(?i)двига|поворачива|рухай|поверта|drag|turn", text)            # what to drag
    assert not re.search(r"напечатан|надрукован|printed|\(\d\.\d+\)", text)          # no misprint notes up front
    page = client.get(f"/scenes/{scene_id}?lang={lang}").text
    intro = page.split('<section class="intro">', 1)[1].split("</section>", 1)[0]
    shown, folded = intro.split('<details class="intro-details"', 1)
    folded = folded.split("</details>", 1)[0]
    assert interface_texts(lang)["intro_details"] in folded
    marks = FOLDED[scene_id]
    assert all(mark.replace("−0,0565", "0565") in folded for mark in marks)
    assert not any(mark.replace("−0,0565", "0565") in shown for mark in marks)
