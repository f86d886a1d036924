"""A general mechanism's special positions as data: each carries its group's number (as in linkage.groups), the
group's kind, what it is (limit of assembly, dead position, smallest transmission angle, output reversal), the
link or slide that reverses, the angle φ, and a sentence in the request's language (content/i18n ru, uk, en);
the English ``description`` stays for scripts.  Checked against the description the core writes independently
of the fields (its "group k (KIND)" and "link n" / "slide name" words), and the ru/uk sentences against English
words leaking through."""
from __future__ import annotations

import copy
import re

import pytest
from fastapi.testclient import TestClient

from server.api.app import app
from server.core.structure.presets import presets
from server.core.structure.spec import KINDS

ENGLISH = re.compile(r"\b(group|link|slider|reverses|limit|dead|position|guide|slot)\b")


@pytest.fixture(scope="module")
def answers() -> dict:
    linkage = copy.deepcopy(presets()["shaping_machine"]["linkage"])
    linkage["groups"][1]["length"] = 0.01          # a rod too short: limits of assembly as well
    with TestClient(app) as client:
        return {lang: client.post(f"/api/v1/kinematics?lang={lang}",
                                  json={"mechanism": "general", "linkage": linkage, "outputs": ["special"],
                                        "n": 5}).json()["outputs"]["special"]
                for lang in ("en", "ru", "uk")}


def test_every_special_position_carries_its_fields(answers):
    special = answers["en"]
    assert {sp["kind"] for sp in special} >= {"limit_of_assembly", "smallest_determinant", "output_reversal"}
    for sp in special:
        assert sp["group_kind"] in KINDS and sp["description"].startswith(f"group {sp['group']}")
        if sp["kind"] == "output_reversal":
            subject = f"link {sp['link']}" if sp["link"] is not None else f"slide {sp['slide']}"
            assert (sp["link"] is None) != (sp["slide"] is None) and f": {subject} reverses" in sp["description"]
        else:
            assert sp["description"].startswith(f"group {sp['group']} ({sp['group_kind']})")
            assert sp["link"] is None and sp["slide"] is None


def test_texts_in_the_request_language(answers):
    en, ru, uk = answers["en"], answers["ru"], answers["uk"]
    assert len(en) == len(ru) == len(uk)
    for a, b, c in zip(en, ru, uk):
        assert a["phi"] == b["phi"] == c["phi"] and a["kind"] == b["kind"] == c["kind"]
        assert a["text"].startswith(f"group {a['group']}")
        assert b["text"].startswith(f"группа {a['group']}") and c["text"].startswith(f"група {a['group']}")
        assert not ENGLISH.search(b["text"]) and not ENGLISH.search(c["text"]), (b["text"], c["text"])
    slides = [sp for sp in ru if sp["slide"] == "E/ram"]
    assert slides and all("ползун E (направляющая ram)" in sp["text"] for sp in slides)
    values = [sp for sp in ru if sp["kind"] == "smallest_determinant"]
    assert values and all("," in sp["text"] or "= 1)" in sp["text"] for sp in values)     # decimal comma
