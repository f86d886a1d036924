"""Every warning and error the core can raise has a Russian and a Ukrainian text whose placeholders it fills."""
import re
import string
from pathlib import Path

import pytest

from server.lessons.scenes import interface_texts

SOURCES = list(Path(__file__).resolve().parents[1].joinpath("server").rglob("*.py"))
CODE = re.compile(r'(?:Notice|NoMotion)\(\s*f?"([a-z_]+)(\{[^"]*\})?"')
SNAKE = re.compile(r'"([a-z0-9]+(?:_[a-z0-9]+)+)"')


def codes(pattern):
    found = set()
    for path in SOURCES:
        for match in pattern.finditer(path.read_text(encoding="utf-8")):
            found.add(match.group(1))
    return found


def notice_codes():
    found = set()
    for code in codes(CODE):
        found |= {code + "speeds", code + "slows"} if code.endswith("_") else {code}
    return found


@pytest.mark.parametrize("lang", ["ru", "uk", "en"])
def test_every_notice_has_a_translation(lang):
    texts = interface_texts(lang)
    missing = sorted(code for code in notice_codes() if f"warn_{code}" not in texts)
    assert not missing


def test_templates_use_the_same_placeholders_in_every_language():
    for key in interface_texts("en"):
        if key.startswith(("warn_", "err_")):
            fields = [{f for _, f, _, _ in string.Formatter().parse(interface_texts(lang)[key]) if f}
                      for lang in ("ru", "uk", "en")]
            assert fields[0] == fields[1] == fields[2], key


def geometry_error_codes():
    """Codes of GeometryError(field, reason, code, …): the snake_case literals after the field."""
    found = set()
    for path in SOURCES:
        text = path.read_text(encoding="utf-8")
        for start in (m.end() for m in re.finditer(r"GeometryError\(", text)):
            depth, end = 1, start
            while depth:
                depth += {"(": 1, ")": -1}.get(text[end], 0)
                end += 1
            literals = SNAKE.findall(text[start:end])
            found |= set(literals[1:] if text[start:end].lstrip().startswith('"' + literals[0]) else literals) if literals else set()
    return found


def test_geometry_errors_with_codes_are_translated():
    texts = interface_texts("ru")
    generic = {"negative_length", "out_of_range", "unknown_param", "not_finite", "not_integer"}
    missing = sorted(c for c in geometry_error_codes() - generic if f"err_{c}" not in texts)
    assert not missing
