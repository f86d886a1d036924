"""Where the app's own files are: the pages (web/), the lessons as data (content/), the measured tables
(bench/results/) and the classroom's database (data/).

In a source checkout they are the repository's top-level folders. ``pip install .`` maps the first three into
the package (pyproject.toml, ``[tool.setuptools.package-dir]``: ``server/web``, ``server/content``,
``server/bench_results``), so an installed app finds them beside its code. The database then defaults to
``./data`` in the directory the server is started from (``MDL_DATA_DIR`` names another).
"""
from __future__ import annotations

import hashlib
from collections.abc import Iterable
from pathlib import Path

PACKAGE = Path(__file__).resolve().parent
CHECKOUT = PACKAGE.parent
IS_CHECKOUT = (CHECKOUT / "pyproject.toml").is_file() and (CHECKOUT / "web").is_dir()


def _folder(installed: str, *in_checkout: str) -> Path:
    inside = PACKAGE / installed
    return inside if inside.is_dir() else CHECKOUT.joinpath(*in_checkout)


WEB = _folder("web", "web")
CONTENT = _folder("content", "content")
BENCH_RESULTS = _folder("bench_results", "bench", "results")


def default_data_dir() -> Path:
    """data/ of the checkout, or of the working directory for an installed app."""
    return CHECKOUT / "data" if IS_CHECKOUT else Path.cwd() / "data"


def files_digest(files: Iterable[tuple[str, Path]]) -> bytes:
    """SHA-256 over each (name, file): its name and bytes, each followed by a NUL, in name order."""
    digest = hashlib.sha256()
    for name, path in sorted(files):
        digest.update(name.encode() + b"\0" + path.read_bytes() + b"\0")
    return digest.digest()
