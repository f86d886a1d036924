"""A layer of the response cache that the workers of one server share: the slider families.

A class opens the same scene at the same defaults and grabs the same slider, so most of its families are the same
question (the response cache keys a family without its slider's own value: family.shared). With several workers
each has its own response cache, and a family that one worker has computed (0.05–1 CPU-s) would be computed
again by the other. This store keeps the complete family answers in one SQLite file beside the workers: a worker
that misses its own cache looks there before computing, and every family it computes goes there as well.

The file: ``MDL_SHARED_CACHE`` names it (the app servers of one host should name the same file: a family one
server computed is then not computed by another, bench/results/capacity_staggered.md; ``0`` turns the layer
off). Unset, the workers of a server started with ``--workers N`` (N ≥ 2) share a file of their own in the
temporary folder, named after the process that started them; a single worker (or an app in a test) has no
shared layer, since its own response cache is the whole of it. The server removes its file as it stops (and a
server starting removes the files of servers no longer running, killed ones included).

Entries are the answer's raw headers and its gzip-compressed body, keyed by the response cache's key (SHA-256 of
the path, the query and the validated body) after the version of the code that computed it (``code_version``:
a named file outlives its servers, and after an update, or beside a server not yet updated, an answer of other
code is never served); the oldest go first once their total passes the response cache's
size. A write or a read that fails (the disk full, the file locked for longer than the timeout) is skipped:
the layer only saves work, it never answers wrongly or fails a request.
"""
from __future__ import annotations

import functools
import json
import logging
import os
import sqlite3
import threading
from pathlib import Path

from ..paths import CONTENT, PACKAGE, files_digest
from . import server_files

ENV_PATH = "MDL_SHARED_CACHE"
PREFIX = "mdl-shared-cache-"
TIMEOUT_S = 0.5                 # how long a read or a write waits for the file's lock before giving up
SCHEMA = ("CREATE TABLE IF NOT EXISTS answers (key BLOB PRIMARY KEY, headers TEXT NOT NULL, body BLOB NOT NULL,"
          " size INTEGER NOT NULL)")
log = logging.getLogger("uvicorn.error")


def default_path() -> Path | None:
    """MDL_SHARED_CACHE, else a file of this server's workers when it has several (server_files), else None."""
    named = os.environ.get(ENV_PATH, "").strip()
    if named:
        return None if named == "0" else Path(named)
    return server_files.workers_file(PREFIX, ".sqlite")


def remove_own() -> None:
    """Remove the file of this supervisor's workers (called by it once they have all stopped)."""
    server_files.remove_own(PREFIX)


@functools.cache
def code_version() -> bytes:
    """16 bytes of SHA-256 over the app's code and lessons (every server/**/*.py and content/** file: its path and
    bytes, in path order): what an answer depends on besides its request."""
    return files_digest([*((f"server/{p.relative_to(PACKAGE).as_posix()}", p) for p in PACKAGE.rglob("*.py")),
                         *((f"content/{p.relative_to(CONTENT).as_posix()}", p) for p in CONTENT.rglob("*")
                           if p.is_file())])[:16]


class SharedStore:
    """Complete answers by key in one SQLite file, bounded by total bytes (oldest out first); each key is stored
    after `version` (default code_version()), and an entry of another version is not seen."""

    def __init__(self, path: Path, max_bytes: int, version: bytes | None = None):
        self.path, self.max_bytes = Path(path), max_bytes
        self.version = code_version() if version is None else version
        self._local = threading.local()
        self.hits = self.misses = self.writes = self.failures = 0
        self._connection().execute(SCHEMA)

    def _connection(self) -> sqlite3.Connection:
        connection = getattr(self._local, "connection", None)
        if connection is None:
            connection = sqlite3.connect(self.path, timeout=TIMEOUT_S, isolation_level=None)
            connection.execute("PRAGMA journal_mode=WAL")
            connection.execute("PRAGMA synchronous=OFF")      # a cache: a lost write after a crash costs nothing
            self._local.connection = connection
        return connection

    def get(self, key: bytes) -> tuple[list[tuple[bytes, bytes]], bytes, bool] | None:
        """(raw headers, body, whether the body is gzip-compressed) stored under key, or None."""
        try:
            row = self._connection().execute("SELECT headers, body FROM answers WHERE key = ?",
                                             (self.version + key,)).fetchone()
        except sqlite3.Error as error:
            self._failed("read", error)
            return None
        if row is None:
            self.misses += 1
            return None
        self.hits += 1
        stored = json.loads(row[0])
        return ([(name.encode("latin-1"), value.encode("latin-1")) for name, value in stored["headers"]], row[1],
                stored["gzip"])

    def put(self, key: bytes, headers, body: bytes, gzipped: bool) -> None:
        """Store (headers, body, whether gzip-compressed) under key; drop the oldest entries beyond max_bytes."""
        text = json.dumps({"headers": [(name.decode("latin-1"), value.decode("latin-1")) for name, value in headers],
                           "gzip": gzipped})
        key = self.version + key
        size = len(body) + len(text) + len(key)
        if size > self.max_bytes:
            return
        try:
            connection = self._connection()
            connection.execute("INSERT OR REPLACE INTO answers (key, headers, body, size) VALUES (?, ?, ?, ?)",
                               (key, text, body, size))
            total = connection.execute("SELECT COALESCE(SUM(size), 0) FROM answers").fetchone()[0]
            if total > self.max_bytes:
                connection.execute(
                    "DELETE FROM answers WHERE rowid IN (SELECT rowid FROM answers ORDER BY rowid LIMIT "
                    "(SELECT COUNT(*) FROM answers) / 4 + 1)")
            self.writes += 1
        except sqlite3.Error as error:
            self._failed("write", error)

    def _failed(self, what: str, error: Exception) -> None:
        self.failures += 1
        if self.failures <= 3:
            log.warning("shared response cache %s: %s skipped (%s)", self.path, what, error)

    def stats(self) -> dict:
        return {"path": str(self.path), "hits": self.hits, "misses": self.misses, "writes": self.writes,
                "failures": self.failures}


def from_env(max_bytes: int) -> SharedStore | None:
    """The shared store this process should use (default_path), or None; None as well when it cannot be opened."""
    path = default_path()
    if path is None or max_bytes <= 0:
        return None
    try:
        return SharedStore(path, max_bytes)
    except (sqlite3.Error, OSError) as error:
        log.warning("shared response cache %s not opened (%s): each worker keeps its own", path, error)
        return None
