"""A cache of the computing endpoints' answers, for a classroom where many students ask the same questions.

Thirty students dragging the same slider of the same scene send the same bodies: the sliders' values are
quantised to their step, so the same few hundred positions come back again and again. This pure ASGI
middleware keeps the 200 answers of the computing POST endpoints (CACHED_ENDPOINTS) in memory and answers
a repeated question without computing. It sits inside the GZip middleware and keeps each answer once:
gzip-compressed (GZIP_LEVEL, from GZIP_MINIMUM_SIZE bytes, as the GZip middleware would), or as it is when too
small to gain: a client that accepts gzip (every browser) gets the compressed bytes, compressed once when the
answer was computed and never again on a hit; any other client gets the plain body, decompressed for it. The GZip middleware leaves an answer that
already names its Content-Encoding alone.

The cache looks a question up only once it has validated, and keys it on the validated request: the body is
parsed as FastAPI parses it (JSON only with a JSON Content-Type), validated with the endpoint's own model
(ENDPOINTS, the family's FamilyRequest), and the key is the SHA-256 of the path, the query (each parameter's last
value, the one the route reads) and the validated model as canonical JSON (keys sorted, every number exact).
A body that is not JSON or does not validate is passed on uncached (counted as bypassed): the route answers its
422 as it would without a cache, so the cache can never make a refused question answer 200. Numbers are not
rounded for the key: two values a hair apart may sit on either side of a bound that only the core checks (the rod
no longer than the crank), and an answer echoes the values asked. On a miss the route validates the body again
(tens of microseconds, against the milliseconds of computing it saves on a hit). The live work-precision studies
(their answer is a timing measurement), the assignments, pages and files are not cached.
Only complete 200 answers are stored; 422s and other errors are computed every time, and so is an answer
that says it is partial (header X-Partial: 1, serialise.PARTIAL_HEADER): a time or work bound cut its
computation short, and computing it again may get further. Whether an answer is stored depends on the
answer alone, never on how long it took.

Entries are evicted least recently used first once their total size passes ``max_bytes`` (default 64 MB,
environment variable MDL_CACHE_BYTES; 0 turns the cache off). The cache is per process: with several
workers each has its own; the slider families (SHARED_ENDPOINTS), the costly answers a class asks for alike,
are also kept in a layer the workers share (server/runtime/shared_cache.py): a worker that misses its own
cache looks there before computing (a hit, stored in its own cache too), and every family it computes goes
there as well. An answer that says ``Cache-Control: no-store`` (a family answered coarse because the server
was busy, routers/family.py) is passed on and never stored. Every cached path answers with the header ``X-Cache: hit`` or ``X-Cache: miss``;
GET /api/v1/cache reports hits, misses, entries and bytes of the worker that answers; as it stops, each
worker logs the same counters in one line (CACHE_AT_EXIT). An answer served from the cache is the stored
bytes of the first computation, its ``numerics.runtime_ms`` included.
"""
from __future__ import annotations

import asyncio
import hashlib
import gzip
import json
import os
import threading
from collections import OrderedDict
from dataclasses import dataclass
from urllib.parse import parse_qsl, urlencode

import orjson
import pydantic_core
from pydantic import BaseModel

from ..families import family
from . import shared_cache
from .shared_cache import SharedStore

PARTIAL_HEADER = "X-Partial"      # an answer a time or work bound cut short (the serialiser sets it)
DEFAULT_MAX_BYTES = 64 * 1024 * 1024
ENV_MAX_BYTES = "MDL_CACHE_BYTES"
PARTIAL = PARTIAL_HEADER.lower().encode()
GZIP_MINIMUM_SIZE = 1000           # smaller bodies gain nothing from compression (the app's GZip middleware too)
GZIP_LEVEL = 3                      # cheap CPU, ~5× smaller for curves (the app's GZip middleware too)
ENTRY_OVERHEAD_BYTES = 200          # key, bookkeeping and object headers of one entry, roughly
CACHE_AT_EXIT = "response cache at exit:"   # each worker logs its counters (JSON) after this as it stops


# What an answer depends on, where it is less than the whole request: a family not on its slider's current value.
KEY_FORMS = {"family": family.shared}
SHARED_ENDPOINTS = ("family",)      # kept in the layer the workers share as well (shared_cache.py)
NO_STORE = b"no-store"


WHOLE_LIMIT = 2.0 ** 53           # below it every whole float is exactly an int


def canonical_json(data) -> bytes:
    """`data` (a validated model's dump) as one JSON text: keys sorted, no spaces, every float in its shortest
    round-trip form and a whole one as an int (1.0 as 1, as a browser's JSON.stringify writes it: a field the
    models leave untyped, a family's ``request``, keeps the spelling it came with, and the page's 1 and a script's
    1.0 are one question). orjson writes a non-finite float as null, so data that holds one (pydantic_core spells
    them NaN and Infinity) is written by the standard library instead, which keeps NaN, None and ±inf apart."""
    data = _whole_floats_as_ints(data)
    probe = pydantic_core.to_json(data, inf_nan_mode="constants")
    if b"NaN" in probe or b"Infinity" in probe:
        return json.dumps(data, sort_keys=True, allow_nan=True, separators=(",", ":")).encode()
    return orjson.dumps(data, option=orjson.OPT_SORT_KEYS | orjson.OPT_NON_STR_KEYS)


def _whole_floats_as_ints(data):
    if isinstance(data, float):
        return int(data) if data.is_integer() and abs(data) < WHOLE_LIMIT else data
    if isinstance(data, dict):
        return {key: _whole_floats_as_ints(value) for key, value in data.items()}
    if isinstance(data, (list, tuple)):
        return [_whole_floats_as_ints(value) for value in data]
    return data


def validated_body(raw: bytes, model: type[BaseModel], form=None) -> bytes | None:
    """The canonical JSON of the body validated by `model` (then mapped by `form`, KEY_FORMS), or None when it
    is not JSON or does not validate (whatever the reason: the route then answers exactly as without a cache)."""
    try:
        data = model.model_validate(json.loads(raw)).model_dump()
        return canonical_json(form(data) if form else data)
    except Exception:                  # noqa: BLE001 — ValueError, ValidationError, or a validator's own failure
        return None


def cache_key(path: str, query: str, canonical: bytes) -> bytes:
    """SHA-256 of the path, the query's parameters (the last value of each, as the route reads them, sorted by
    name) and the canonical validated body: 32 bytes per entry."""
    pairs = urlencode(sorted(dict(parse_qsl(query, keep_blank_values=True)).items()))
    return hashlib.sha256(f"{path}\n{pairs}\n".encode() + canonical).digest()


@dataclass(frozen=True)
class CachedAnswer:
    """A complete 200 answer: its raw ASGI headers and its body, kept once: gzip-compressed (``gzipped``) when it
    gains from it, else as it is (``plain``). Every browser takes gzip; the plain body of a compressed answer is
    made again for a client that does not (``body``). Kept once, a family (up to 2 MB of JSON, a tenth of that
    compressed) takes a tenth of the cache it took beside its plain copy."""

    headers: tuple[tuple[bytes, bytes], ...]
    plain: bytes | None
    gzipped: bytes | None = None

    @classmethod
    def of(cls, headers, body: bytes) -> "CachedAnswer":
        """The answer with its compressed body made once (mtime 0: the same bytes for the same body). An answer
        the route sent gzip-compressed already (a family, compressed in the heavy process: routers/family.py) is
        kept as it came, its headers those of the plain body. Its Server-Timing (the computation's,
        admission.with_timing) is not kept: a hit was not computed."""
        headers = [(n, v) for n, v in headers if n.lower() != b"server-timing"]
        if _header(headers, b"content-encoding") == b"gzip":
            plain_length = len(gzip.decompress(body))
            kept = [(n, v) for n, v in headers if n.lower() not in (b"content-encoding", b"content-length", b"vary")]
            return cls((*kept, (b"content-length", str(plain_length).encode())), None, body)
        packed = compressed(body)
        return cls(tuple(headers), body if packed is None else None, packed)

    @property
    def body(self) -> bytes:
        """The plain body."""
        return self.plain if self.plain is not None else gzip.decompress(self.gzipped)

    @property
    def size(self) -> int:
        return (len(self.plain or b"") + len(self.gzipped or b"") + sum(len(n) + len(v) for n, v in self.headers)
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

    def __init__(self, max_bytes: int = DEFAULT_MAX_BYTES, shared: SharedStore | None = None):
        if max_bytes < 0:
            raise ValueError("the cache size must be 0 (off) or a positive number of bytes")
        self.max_bytes = max_bytes
        self.shared = shared             # the layer the workers share (SHARED_ENDPOINTS), or None
        self._entries: OrderedDict[bytes, CachedAnswer] = OrderedDict()
        self._lock = threading.Lock()
        self.bytes = self.hits = self.misses = self.bypassed = self.evictions = 0

    @classmethod
    def from_env(cls) -> "ResponseCache":
        """The size from MDL_CACHE_BYTES (bytes; 0 turns the cache off), else 64 MB; the shared layer as
        shared_cache.from_env says (none with the cache off)."""
        text = os.environ.get(ENV_MAX_BYTES, "").strip()
        try:
            max_bytes = int(text) if text else DEFAULT_MAX_BYTES
        except ValueError:
            raise ValueError(f"{ENV_MAX_BYTES} must be a whole number of bytes (0 turns the cache off), "
                             f"not {text!r}") from None
        if max_bytes < 0:
            return cls(max_bytes)            # refused with its reason
        return cls(max_bytes, shared_cache.from_env(max_bytes))

    def get_shared(self, key: bytes) -> CachedAnswer | None:
        """The answer the shared layer holds under key (then kept in this cache too, and counted a hit), or None."""
        found = self.shared.get(key) if self.shared is not None else None
        if found is None:
            return None
        headers, body, gzipped = found
        answer = CachedAnswer(tuple(headers), None, body) if gzipped else CachedAnswer(tuple(headers), body, None)
        self.put(key, answer)
        with self._lock:
            self.hits, self.misses = self.hits + 1, self.misses - 1
        return answer

    def put_shared(self, key: bytes, answer: CachedAnswer) -> None:
        """Keep the answer in the shared layer (any thread; a failure is skipped there)."""
        if self.shared is not None:
            gzipped = answer.gzipped is not None
            self.shared.put(key, answer.headers, answer.gzipped if gzipped else answer.body, gzipped)

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
                    "evictions": self.evictions, "pid": os.getpid(),
                    "shared": self.shared.stats() if self.shared is not None else None}


def compressed(body: bytes) -> bytes | None:
    """body gzip-compressed as the cache keeps it (GZIP_LEVEL, mtime 0), or None when too small to gain."""
    return None if len(body) < GZIP_MINIMUM_SIZE else gzip.compress(body, GZIP_LEVEL, mtime=0)


def _header(headers, name: bytes) -> bytes:
    for key, value in headers:
        if key.lower() == name:
            return value
    return b""


def _is_json(content_type: bytes) -> bool:
    """FastAPI (strict content type) reads a body as JSON when it names a JSON type; a body without a type is text
    to it (a 422 for these routes)."""
    media = content_type.split(b";")[0].strip().lower()
    return media == b"application/json" or (media.startswith(b"application/") and media.endswith(b"+json"))


class ResponseCacheMiddleware:
    """Answers repeated POSTs to the computing endpoints from a ResponseCache (see the module's docstring)."""

    def __init__(self, app, cache: ResponseCache, models: dict[str, type[BaseModel]], prefix: str = "/api/v1"):
        self.app = app
        self.cache = cache
        self.models = {f"{prefix}/{name}": model for name, model in models.items()}
        self.forms = {f"{prefix}/{name}": form for name, form in KEY_FORMS.items()}
        self.shared_paths = {f"{prefix}/{name}" for name in SHARED_ENDPOINTS}

    async def __call__(self, scope, receive, send):
        if (scope["type"] != "http" or scope["method"] != "POST" or scope["path"] not in self.models
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

        path = scope["path"]
        canonical = (validated_body(raw, self.models[path], self.forms.get(path))
                     if _is_json(_header(scope["headers"], b"content-type")) else None)
        if canonical is None:
            self.cache.count_bypass()
            await self.app(scope, replay, send)
            return
        key = cache_key(path, scope.get("query_string", b"").decode("latin-1"), canonical)
        gzip_accepted = b"gzip" in _header(scope["headers"], b"accept-encoding")
        shared = path in self.shared_paths
        cached = self.cache.get(key)
        if cached is None and shared:
            cached = self.cache.get_shared(key)
        if cached is not None:
            await send(cached.message_start(gzip_accepted, b"hit"))
            await send({"type": "http.response.body", "body": cached.body_for(gzip_accepted)})
            return
        await self._compute_and_store(scope, replay, send, key, gzip_accepted, shared)

    async def _compute_and_store(self, scope, receive, send, key: bytes, gzip_accepted: bool,
                                 shared: bool = False) -> None:
        """Compute; a complete 200 answer in one body message (every computing endpoint's) is stored and sent
        in the client's encoding from the stored entry; anything else passes as it comes, marked a miss."""
        start: dict | None = None

        async def send_and_keep(message):
            nonlocal start
            if message["type"] == "http.response.start":
                headers = list(message.get("headers", []))
                if (message["status"] == 200 and not _header(headers, b"set-cookie")
                        and not _header(headers, PARTIAL) and NO_STORE not in _header(headers, b"cache-control")):
                    start = {**message, "headers": headers}      # held until the body shows it complete
                    return
                message = {**message, "headers": [*headers, (b"x-cache", b"miss")]}
            elif message["type"] == "http.response.body" and start is not None:
                held, start = start, None
                body = message.get("body", b"")
                if not message.get("more_body", False):          # put() keeps it if its size fits
                    answer = CachedAnswer.of(held["headers"], body)
                    self.cache.put(key, answer)
                    if shared and self.cache.shared is not None:       # written beside, not waited for
                        asyncio.get_running_loop().run_in_executor(None, self.cache.put_shared, key, answer)
                    start_message = answer.message_start(gzip_accepted, b"miss")
                    if timing := _header(held["headers"], b"server-timing"):    # this computation's, not kept
                        start_message["headers"].append((b"server-timing", timing))
                    await send(start_message)
                    await send({"type": "http.response.body", "body": answer.body_for(gzip_accepted)})
                    return
                await send({**held, "headers": [*held["headers"], (b"x-cache", b"miss")]})
            await send(message)

        await self.app(scope, receive, send_and_keep)
