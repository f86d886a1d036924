"""A cache of the computing endpoints' answers, for a classroom where many students ask the same questions.

Thirty students dragging the same slider of the same scene send the same bodies: the sliders' values are
quantised to their step, so the same few hundred positions come back again and again. This pure ASGI
middleware keeps the 200 answers of the computing POST endpoints (CACHED_ENDPOINTS) in memory and answers
a repeated question without computing. It sits inside the GZip middleware and keeps each answer both as it
is and gzip-compressed (GZIP_LEVEL, from GZIP_MINIMUM_SIZE bytes, as the GZip middleware would): a client
that accepts gzip (every browser) gets the compressed bytes, compressed once when the answer was computed
and never again on a hit; any other client gets the plain body. The GZip middleware leaves an answer that
already names its Content-Encoding alone.

The key is the path, the query (``lang``, ``precision``) and the JSON body canonicalised: parsed, every float rounded to
10 significant digits (0.1·3 and 0.3 are one question; the answers of two bodies that differ only past the
10th digit differ by about 1e-10 relatively), keys sorted, hashed with SHA-256. A body that is not JSON
(by its content type or by parsing) bypasses the cache, and so does every other path: the live
work-precision studies (their answer is a timing measurement), the assignments, pages and files.
Only complete 200 answers are stored; 422s and other errors are computed every time, and so is an answer
that says it is partial (header X-Partial: 1, serialise.PARTIAL_HEADER): a time or work bound cut its
computation short, and computing it again may get further. Whether an answer is stored depends on the
answer alone, never on how long it took.

Entries are evicted least recently used first once their total size passes ``max_bytes`` (default 64 MB,
environment variable MDL_CACHE_BYTES; 0 turns the cache off). The cache is per process: with several
workers each has its own. Every cached path answers with the header ``X-Cache: hit`` or ``X-Cache: miss``;
GET /api/v1/cache reports hits, misses, entries and bytes of the worker that answers; as it stops, each
worker logs the same counters in one line (CACHE_AT_EXIT). An answer served from the cache is the stored
bytes of the first computation, its ``numerics.runtime_ms`` included.
"""
from __future__ import annotations

import hashlib
import gzip
import math
import os
import threading
from collections import OrderedDict
from dataclasses import dataclass
from urllib.parse import parse_qsl, urlencode

import orjson

from . import family
from .endpoints import ENDPOINTS
from .serialise import PARTIAL_HEADER

DEFAULT_MAX_BYTES = 64 * 1024 * 1024
ENV_MAX_BYTES = "MDL_CACHE_BYTES"
SIGNIFICANT_DIGITS = 10
PARTIAL = PARTIAL_HEADER.lower().encode()
GZIP_MINIMUM_SIZE = 1000           # smaller bodies gain nothing from compression (the app's GZip middleware too)
GZIP_LEVEL = 3                      # cheap CPU, ~5× smaller for curves (the app's GZip middleware too)
ENTRY_OVERHEAD_BYTES = 200          # key, bookkeeping and object headers of one entry, roughly
CACHE_AT_EXIT = "response cache at exit:"   # each worker logs its counters (JSON) after this as it stops

# The computing endpoints and the slider families, whose answer is a function of (path, query, body) alone.
CACHED_ENDPOINTS = (*ENDPOINTS, "family")
# What an answer depends on, where it is less than the whole body: a family not on its slider's current value.
KEY_FORMS = {"family": family.shared}


def canonical_body(raw: bytes, form=None) -> bytes | None:
    """The body as one canonical JSON text (floats to 10 significant digits, keys sorted, no spaces), None if
    it is not JSON (orjson: strict, so NaN and Infinity are not JSON either); `form` first maps the parsed body
    to what the answer depends on (KEY_FORMS)."""
    try:
        parsed = orjson.loads(raw)
        return orjson.dumps(_rounded(form(parsed) if form else parsed), option=orjson.OPT_SORT_KEYS)
    except (orjson.JSONDecodeError, RecursionError):
        return None


def _rounded(value):
    if isinstance(value, float):
        return float(f"{value:.{SIGNIFICANT_DIGITS}g}") if math.isfinite(value) else value
    if isinstance(value, dict):
        return {key: _rounded(item) for key, item in value.items()}
    if isinstance(value, list):
        return [_rounded(item) for item in value]
    return value


def cache_key(path: str, query: str, canonical: bytes) -> bytes:
    """SHA-256 of the path, the query's pairs sorted and the canonical body: 32 bytes per entry."""
    pairs = urlencode(sorted(parse_qsl(query, keep_blank_values=True)))
    return hashlib.sha256(f"{path}\n{pairs}\n".encode() + canonical).digest()


@dataclass(frozen=True)
class CachedAnswer:
    """A complete 200 answer: its raw ASGI headers and body, and the body gzip-compressed (None when too small
    to gain from it)."""

    headers: tuple[tuple[bytes, bytes], ...]
    body: bytes
    gzipped: bytes | None = None

    @classmethod
    def of(cls, headers, body: bytes) -> "CachedAnswer":
        """The answer with its compressed body made once (mtime 0: the same bytes for the same body)."""
        small = len(body) < GZIP_MINIMUM_SIZE
        return cls(tuple(headers), body, None if small else gzip.compress(body, GZIP_LEVEL, mtime=0))

    @property
    def size(self) -> int:
        return (len(self.body) + len(self.gzipped or b"") + sum(len(n) + len(v) for n, v in self.headers)
                + ENTRY_OVERHEAD_BYTES)

    def message_start(self, gzip_accepted: bool, cache: bytes) -> dict:
        """The http.response.start of this answer in the encoding the client accepts, X-Cache: cache."""
        if not (gzip_accepted and self.gzipped is not None):
            return {"type": "http.response.start", "status": 200, "headers": [*self.headers, (b"x-cache", cache)]}
        headers = [(name, value) for name, value in self.headers if name.lower() != b"content-length"]
        return {"type": "http.response.start", "status": 200,
                "headers": [*headers, (b"content-encoding", b"gzip"), (b"content-length", str(len(self.gzipped)).encode()),
                            (b"vary", b"Accept-Encoding"), (b"x-cache", cache)]}

    def body_for(self, gzip_accepted: bool) -> bytes:
        return self.gzipped if gzip_accepted and self.gzipped is not None else self.body


class ResponseCache:
    """A least-recently-used store bounded by total bytes, safe to share between threads."""

    def __init__(self, max_bytes: int = DEFAULT_MAX_BYTES):
        if max_bytes < 0:
            raise ValueError("the cache size must be 0 (off) or a positive number of bytes")
        self.max_bytes = max_bytes
        self._entries: OrderedDict[bytes, CachedAnswer] = OrderedDict()
        self._lock = threading.Lock()
        self.bytes = self.hits = self.misses = self.bypassed = self.evictions = 0

    @classmethod
    def from_env(cls) -> "ResponseCache":
        """The size from MDL_CACHE_BYTES (bytes; 0 turns the cache off), else 64 MB."""
        text = os.environ.get(ENV_MAX_BYTES, "").strip()
        if not text:
            return cls()
        try:
            return cls(int(text))
        except ValueError:
            raise ValueError(f"{ENV_MAX_BYTES} must be a whole number of bytes (0 turns the cache off), "
                             f"not {text!r}") from None

    @property
    def enabled(self) -> bool:
        return self.max_bytes > 0

    def get(self, key: bytes) -> CachedAnswer | None:
        with self._lock:
            answer = self._entries.get(key)
            if answer is None:
                self.misses += 1
                return None
            self._entries.move_to_end(key)
            self.hits += 1
            return answer

    def put(self, key: bytes, answer: CachedAnswer) -> None:
        size = answer.size
        if size > self.max_bytes:
            return
        with self._lock:
            previous = self._entries.pop(key, None)
            if previous is not None:
                self.bytes -= previous.size
            self._entries[key] = answer
            self.bytes += size
            while self.bytes > self.max_bytes:
                _, evicted = self._entries.popitem(last=False)
                self.bytes -= evicted.size
                self.evictions += 1

    def count_bypass(self) -> None:
        with self._lock:
            self.bypassed += 1

    def stats(self) -> dict:
        with self._lock:
            looked_up = self.hits + self.misses
            return {"enabled": self.enabled, "max_bytes": self.max_bytes, "bytes": self.bytes,
                    "entries": len(self._entries), "hits": self.hits, "misses": self.misses,
                    "hit_rate": self.hits / looked_up if looked_up else None, "bypassed": self.bypassed,
                    "evictions": self.evictions, "pid": os.getpid()}


def _header(headers, name: bytes) -> bytes:
    for key, value in headers:
        if key.lower() == name:
            return value
    return b""


def _is_json(content_type: bytes) -> bool:
    """FastAPI reads a body as JSON when it names no type or a JSON type; anything else gets a 422."""
    media = content_type.split(b";")[0].strip().lower()
    return not media or media == b"application/json" or (media.startswith(b"application/") and media.endswith(b"+json"))


class ResponseCacheMiddleware:
    """Answers repeated POSTs to the computing endpoints from a ResponseCache (see the module's docstring)."""

    def __init__(self, app, cache: ResponseCache, prefix: str = "/api/v1",
                 endpoints: tuple[str, ...] = CACHED_ENDPOINTS):
        self.app = app
        self.cache = cache
        self.paths = frozenset(f"{prefix}/{name}" for name in endpoints)
        self.forms = {f"{prefix}/{name}": form for name, form in KEY_FORMS.items()}

    async def __call__(self, scope, receive, send):
        if (scope["type"] != "http" or scope["method"] != "POST" or scope["path"] not in self.paths
                or not self.cache.enabled):
            await self.app(scope, receive, send)
            return
        chunks = []
        while True:
            message = await receive()
            if message["type"] == "http.disconnect":
                return                          # the client left before its question was complete
            chunks.append(message.get("body", b""))
            if not message.get("more_body", False):
                break
        raw = b"".join(chunks)
        replayed = False

        async def replay():
            nonlocal replayed
            if not replayed:
                replayed = True
                return {"type": "http.request", "body": raw, "more_body": False}
            return await receive()

        canonical = canonical_body(raw, self.forms.get(scope["path"])) if _is_json(_header(scope["headers"], b"content-type")) else None
        if canonical is None:
            self.cache.count_bypass()
            await self.app(scope, replay, send)
            return
        key = cache_key(scope["path"], scope.get("query_string", b"").decode("latin-1"), canonical)
        gzip_accepted = b"gzip" in _header(scope["headers"], b"accept-encoding")
        cached = self.cache.get(key)
        if cached is not None:
            await send(cached.message_start(gzip_accepted, b"hit"))
            await send({"type": "http.response.body", "body": cached.body_for(gzip_accepted)})
            return
        await self._compute_and_store(scope, replay, send, key, gzip_accepted)

    async def _compute_and_store(self, scope, receive, send, key: bytes, gzip_accepted: bool) -> None:
        """Compute; a complete 200 answer in one body message (every computing endpoint's) is stored and sent
        in the client's encoding from the stored entry; anything else passes as it comes, marked a miss."""
        start: dict | None = None

        async def send_and_keep(message):
            nonlocal start
            if message["type"] == "http.response.start":
                headers = list(message.get("headers", []))
                if (message["status"] == 200 and not _header(headers, b"set-cookie")
                        and not _header(headers, PARTIAL)):
                    start = {**message, "headers": headers}      # held until the body shows it complete
                    return
                message = {**message, "headers": [*headers, (b"x-cache", b"miss")]}
            elif message["type"] == "http.response.body" and start is not None:
                held, start = start, None
                body = message.get("body", b"")
                if not message.get("more_body", False) and len(body) <= self.cache.max_bytes:
                    answer = CachedAnswer.of(held["headers"], body)
                    self.cache.put(key, answer)
                    await send(answer.message_start(gzip_accepted, b"miss"))
                    await send({"type": "http.response.body", "body": answer.body_for(gzip_accepted)})
                    return
                await send({**held, "headers": [*held["headers"], (b"x-cache", b"miss")]})
            await send(message)

        await self.app(scope, receive, send_and_keep)
