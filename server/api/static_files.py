"""Our static files and plotly.js on versioned URLs, cached by browsers for a year; the old URLs revalidated.

``/static/<version>/js/api.js`` where the version is a hash of every file name and content under web/static,
taken at start-up: a changed file gives a new version, hence new URLs, so a browser may keep what it has
fetched ``immutable`` (RFC 8246) and a repeat visit asks for nothing but the page. Relative ES-module
imports (``./api.js``) resolve under the same prefix. plotly.js is versioned by plotly's own version. The
unversioned paths stay for old links, with ``no-cache`` (the browser revalidates by ETag).
"""
from __future__ import annotations

import hashlib
from pathlib import Path

from starlette.staticfiles import StaticFiles

IMMUTABLE = "public, max-age=31536000, immutable"
REVALIDATE = "no-cache"


def content_version(directory: Path) -> str:
    """12 hex digits of SHA-256 over every file's path (relative, '/'-separated) and bytes, in path order."""
    digest = hashlib.sha256()
    for path in sorted(p for p in directory.rglob("*") if p.is_file()):
        digest.update(path.relative_to(directory).as_posix().encode() + b"\0")
        digest.update(path.read_bytes() + b"\0")
    return digest.hexdigest()[:12]


class CachedStaticFiles(StaticFiles):
    """StaticFiles whose answers carry one Cache-Control header."""

    def __init__(self, *, directory: Path, cache_control: str):
        super().__init__(directory=directory)
        self.cache_control = cache_control

    def file_response(self, *args, **kwargs):
        response = super().file_response(*args, **kwargs)
        response.headers["cache-control"] = self.cache_control
        return response


def mount_versioned(app, prefix: str, directory: Path, version: str, name: str) -> str:
    """Serve directory at prefix/version (immutable) and at prefix (revalidated); the versioned prefix."""
    versioned = f"{prefix}/{version}"
    app.mount(versioned, CachedStaticFiles(directory=directory, cache_control=IMMUTABLE), name=f"{name}-versioned")
    app.mount(prefix, CachedStaticFiles(directory=directory, cache_control=REVALIDATE), name=name)
    return versioned
