"""Our static files and plotly.js on versioned URLs, cached by browsers for a year; the old URLs revalidated.

``/static/<version>/js/common/model/api.js`` where the version is a hash of every file name and content under
web/static (its folders included), taken at start-up: a changed file gives a new version, hence new URLs, so a
browser may keep what it has fetched ``immutable`` (RFC 8246) and a repeat visit asks for nothing but the page.
Relative ES-module imports (``../common/model/api.js``) resolve under the same prefix. plotly.js (vendored in
web/vendor/plotly, so its version does not depend on the day of an install) is versioned by the version its header
names. The
unversioned paths stay for old links, with ``no-cache`` (the browser revalidates by ETag).

Text files are sent gzip-compressed from a copy compressed once per worker (in a thread, on first request),
not by the gzip middleware on every request: compressing plotly.js (1.3 MB, a partial bundle) takes the
worker's event loop about 0.1 s each time, which a class opening a scene together would queue every light
request behind.
"""
from __future__ import annotations

import asyncio
import gzip
import re
from pathlib import Path

import anyio.to_thread
from starlette.responses import FileResponse, Response
from starlette.staticfiles import StaticFiles

from ..paths import files_digest

IMMUTABLE = "public, max-age=31536000, immutable"
REVALIDATE = "no-cache"


def content_version(directory: Path) -> str:
    """12 hex digits of SHA-256 over every file's path (relative, '/'-separated) and bytes, in path order."""
    files = ((p.relative_to(directory).as_posix(), p) for p in directory.rglob("*") if p.is_file())
    return files_digest(files).hex()[:12]


def script_version(path: Path) -> str:
    """The version a vendored script names in its first lines ("* plotly.js v4.1.1" → "4.1.1")."""
    head = path.read_bytes()[:300].decode("utf-8", "replace")
    match = re.search(r"\bv(\d+(?:\.\d+)+)\b", head)
    if match is None:
        raise ValueError(f"{path} names no version in its first lines")
    return match.group(1)


COMPRESSIBLE = ("text/", "application/javascript", "application/json", "image/svg+xml")
MIN_COMPRESSED_BYTES = 1000


class CachedStaticFiles(StaticFiles):
    """StaticFiles whose answers carry one Cache-Control header, text files sent from a gzip copy."""

    def __init__(self, *, directory: Path, cache_control: str):
        super().__init__(directory=directory)
        self.cache_control = cache_control
        self._gzipped: dict[str, tuple[tuple, asyncio.Future]] = {}   # path → (size, mtime), its gzip bytes

    def file_response(self, *args, **kwargs):
        response = super().file_response(*args, **kwargs)
        response.headers["cache-control"] = self.cache_control
        return response

    async def get_response(self, path: str, scope) -> Response:
        response = await super().get_response(path, scope)
        if not (isinstance(response, FileResponse) and response.status_code == 200 and _accepts_gzip(scope)
                and response.headers.get("content-type", "").startswith(COMPRESSIBLE)
                and response.stat_result.st_size >= MIN_COMPRESSED_BYTES):
            return response
        body = await self._gzip(str(response.path), (response.stat_result.st_size, response.stat_result.st_mtime_ns))
        headers = {name: value for name, value in response.headers.items()
                   if name not in ("content-length", "accept-ranges")}
        return Response(body, headers=headers | {"content-encoding": "gzip", "vary": "Accept-Encoding"})

    async def _gzip(self, path: str, stamp: tuple) -> bytes:
        """The file compressed (level 9), once per version of the file: concurrent first requests share it."""
        known = self._gzipped.get(path)
        if known is None or known[0] != stamp:
            task = asyncio.ensure_future(anyio.to_thread.run_sync(_compress, path))
            known = self._gzipped[path] = (stamp, task)
        return await asyncio.shield(known[1])


def _compress(path: str) -> bytes:
    return gzip.compress(Path(path).read_bytes(), compresslevel=9, mtime=0)


def _accepts_gzip(scope) -> bool:
    return any(name == b"accept-encoding" and b"gzip" in value for name, value in scope.get("headers", [])) \
        and not any(name == b"range" for name, _ in scope.get("headers", []))


def mount_versioned(app, prefix: str, directory: Path, version: str, name: str) -> str:
    """Serve directory at prefix/version (immutable) and at prefix (revalidated); the versioned prefix."""
    versioned = f"{prefix}/{version}"
    app.mount(versioned, CachedStaticFiles(directory=directory, cache_control=IMMUTABLE), name=f"{name}-versioned")
    app.mount(prefix, CachedStaticFiles(directory=directory, cache_control=REVALIDATE), name=name)
    return versioned
