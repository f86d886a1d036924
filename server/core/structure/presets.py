"""The preset mechanisms of ``content/mechanisms/*.json``: name, title and source in ru/uk/en, the linkage."""
from __future__ import annotations

import json
from functools import cache
from ...paths import CONTENT

PRESETS_DIR = CONTENT / "mechanisms"


@cache
def presets() -> dict[str, dict]:
    """Every preset by name, in file-name order."""
    return {path.stem: json.loads(path.read_text(encoding="utf-8")) for path in sorted(PRESETS_DIR.glob("*.json"))}
