"""Every message of the app said with its values: web/static/js/common/view/messages.js (messageText, errorReason,
run in Node) fills every format field of every text of content/i18n in en, ru and uk, and says each exactly as the
server's own renderer does (server/api/messages.py: str.format over `filled`, written independently in Python);
an API error's context fills its err_ text; a group's number becomes its name in the structural formula where
the page knows the groups, and is counted from 1 where it does not; a missing value leaves "…", never the field.
"""
from __future__ import annotations

import json
import re
import shutil
import subprocess
from pathlib import Path

import pytest

from server.api.messages import filled
from server.lessons.scenes import interface_texts

MODULE = Path(__file__).resolve().parents[1] / "web" / "static" / "js" / "common" / "view" / "messages.js"
LANGUAGES = ("en", "ru", "uk")
FIELD = re.compile(r"(?<![_^\\])\{(\w+)(?::[^{}]*)?\}")       # a format field, not a subscript's braces
NODE = shutil.which("node") or shutil.which("nodejs")
pytestmark = pytest.mark.skipif(NODE is None, reason="Node is not installed")
SCRIPT = """
const cases = JSON.parse(require("fs").readFileSync(0, "utf8"));
import(process.argv[1]).then((m) => {
  const out = cases.map(({ call, args }) => m[call](...args));
  process.stdout.write(JSON.stringify(out));
});
"""


def run(cases: list[tuple[str, list]]) -> list:
    done = subprocess.run([NODE, "-e", SCRIPT, MODULE.as_uri()], text=True, capture_output=True, check=True,
                          timeout=60, input=json.dumps([{"call": call, "args": args} for call, args in cases]))
    return json.loads(done.stdout)


def sample(name: str):
    """A value for a field: crank-angle ranges in degrees, a group already named, a number otherwise (a
    negative one and one whose last digits a format must round)."""
    return {"ranges": [[10.0, 20.54], [300.26, 360.0]], "group": "II₂(4,5)"}.get(name, -1234.5678)


def test_every_field_of_every_message_is_filled_as_the_server_fills_it():
    cases, expected = [], []
    for lang in LANGUAGES:
        for key, text in interface_texts(lang).items():
            names = set(FIELD.findall(text))
            if not names:
                continue
            values = {name: sample(name) for name in names}
            cases.append(("messageText", [text, values, {"lang": lang}]))
            expected.append((lang, key, text.format(**filled(values, lang))))
    assert len(cases) > 300                         # every language's texts with fields
    for said, (lang, key, server) in zip(run(cases), expected):
        assert not FIELD.search(said), (lang, key, said)
        assert said == server, (lang, key)


def test_an_error_is_said_with_its_context_and_the_groups_by_name():
    ru = interface_texts("ru")
    error = {"code": "crank_not_full_turn", "message": "the crank cannot turn fully", "ctx": {
        "code": "crank_not_full_turn", "group": 1, "ranges": [[143.9012, 221.2231]]}}
    named, counted, missing, unknown = run([
        ("errorReason", [error, ru, {"lang": "ru", "groups": ["II₁(2,3)", "II₂(4,5)"]}]),
        ("errorReason", [error, ru, {"lang": "ru"}]),
        ("errorReason", [error | {"ctx": {}}, ru, {"lang": "ru"}]),
        ("errorReason", [{"code": "no_such_code", "message": "the server's words", "ctx": {}}, ru, {"lang": "ru"}])])
    assert named == ("Кривошип не проворачивается полностью: группа II₂(4,5) не собирается при φ = 143,9°–221,2°; "
                     "машине нужен весь оборот.")
    assert "группа 2 не собирается" in counted            # the second group, counted as a student counts
    assert "{" not in missing and "группа … не собирается" in missing
    assert unknown == "the server's words"
