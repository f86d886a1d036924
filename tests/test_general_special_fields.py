"""A general mechanism's special positions as data: each carries its group's number (as in linkage.groups), the
group's kind and its name in the structural formula, what it is (limit of assembly, dead position, smallest
transmission angle, output reversal), the link or slide that reverses, the angle φ, and a sentence in the request's
language (content/i18n ru, uk, en) that names the group as the formula does and gives every value with its unit;
the English ``description`` stays for scripts.  Checked against the description the core writes independently
of the fields (its "group k (KIND)" and "link n" / "slide name" words), the names against the structural formula
of the same answer, and the ru/uk sentences against English words leaking through."""
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
                                  json={"mechanism": "general", "linkage": linkage, "outputs": ["special", "structure"],
                                        "n": 5}).json()["outputs"]
                for lang in ("en", "ru", "uk")}


def test_every_special_position_carries_its_fields(answers):
    special = answers["en"]["special"]
    names = answers["en"]["structure"]["formula"].split(" → ")[1:]
    assert {sp["kind"] for sp in special} >= {"limit_of_assembly", "smallest_determinant", "output_reversal"}
    for sp in special:
        assert sp["group_kind"] in KINDS and sp["description"].startswith(f"group {sp['group']}")
        assert sp["name"] == names[sp["group"]]
        assert (sp["assembles_after"] is None) == (sp["kind"] != "limit_of_assembly")
        if sp["kind"] == "output_reversal":
            subject = f"link {sp['link']}" if sp["link"] is not None else f"slide {sp['slide']}"
            assert (sp["link"] is None) != (sp["slide"] is None) and f": {subject} reverses" in sp["description"]
        else:
            assert sp["description"].startswith(f"group {sp['group']} ({sp['group_kind']})")
            assert sp["link"] is None and sp["slide"] is None


def test_texts_in_the_request_language(answers):
    en, ru, uk = (answers[lang]["special"] for lang in ("en", "ru", "uk"))
    assert len(en) == len(ru) == len(uk)
    for a, b, c in zip(en, ru, uk):
        assert a["phi"] == b["phi"] == c["phi"] and a["kind"] == b["kind"] == c["kind"]
        assert a["text"].startswith(f"group {a['name']}")
        assert b["text"].startswith(f"группа {a['name']}") and c["text"].startswith(f"група {a['name']}")
        assert not ENGLISH.search(b["text"]) and not ENGLISH.search(c["text"]), (b["text"], c["text"])
    slides = [sp for sp in ru if sp["slide"] == "E/ram" and sp["kind"] == "output_reversal"]
    # the ram's guide by its textbook name, the slider's extreme position with its unit
    assert slides and all(re.search(r"ползун E \(направляющая x–x\) меняет направление, крайнее положение "
                                    r"s = −?\d+,\d{3} м$", sp["text"]) for sp in slides), [sp["text"] for sp in slides]
    for sp in (sp for sp in ru if sp["link"] is not None):       # a link's extreme angle in degrees
        assert re.search(rf"θ{chr(0x2080 + sp['link'])} = \d+,\d°$", sp["text"]), sp["text"]
    values = [sp for sp in ru if sp["kind"] == "smallest_determinant"]
    assert values and all(re.search(r"на \d+,\d°$", sp["text"]) for sp in values)     # degrees, decimal comma
