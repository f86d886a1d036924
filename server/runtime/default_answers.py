"""Every scene's default answers, and the families of its sliders at the defaults, computed once after the server
starts, so that a class's first page loads and first grabs are cache hits.

In a lesson the students open the same scene at the same defaults: each page's first request is the scene's
default request (server.lessons.requests.scene_request: the variant at its sliders' defaults, in the page's
language), and its first grab of a slider asks for that slider's family at the others' defaults
(server.lessons.family_requests: the coarse stage, then the full one; the cache keys a family without the
slider's own value, so the warmed family answers a grab wherever the slider stands). Unless
``MDL_WARM_DEFAULTS`` is 0, each worker, once it has started, sends every variant's default request (the first
variant of every scene before the others) in each language named and, in the first language named, each
variant's families after its answer, through its own app as a page would (``POST /api/v1/<endpoint>?lang=…``:
the same validation, cache key and stored bytes), so that the response cache holds the answers before the
students ask. Only the cached endpoints (ResponseCacheMiddleware's paths) are asked; with the cache off nothing is.

It never delays the server: the task starts after the start-up and the server answers meanwhile. It takes only
spare CPU: before each request it waits until the worker has been quiet (this process used less than
IDLE_SHARE of a CPU over QUIET_S) and no heavy lane is busy (heavy.busy), one request at a time, and it asks as
one client of its own (CLIENT: admission serves it in turn with the students). It stops with the worker: ``stop``
cancels the task and waits for it, so no thread or task of it outlives the app.

    MDL_WARM_DEFAULTS=ru,uk,en   # the languages, in this order; unset, "1" or "on": ru, uk, en; "" or "0": off
"""
from __future__ import annotations

import asyncio
import logging
import os
import time
from dataclasses import dataclass, field
from urllib.parse import urlencode

import orjson

from . import heavy

ENV = "MDL_WARM_DEFAULTS"
LANGUAGES = ("ru", "uk", "en")
QUIET_S = 0.25                 # the window in which the worker must have been quiet before the next request
IDLE_SHARE = 0.2               # quiet: this process used less than this share of one CPU over the window
CLIENT = ("default-answers", 0)   # the address admission sees for these requests
FAMILY = "family"                  # the families' endpoint
API_PREFIX = "/api/v1"
log = logging.getLogger("uvicorn.error")


def languages_from_env(text: str | None = None) -> tuple[str, ...]:
    """The languages MDL_WARM_DEFAULTS names, in its order (none: warming off; unset: every language);
    ValueError names an unknown one."""
    text = os.environ.get(ENV) if text is None else text
    if text is None:
        return LANGUAGES
    text = text.strip().lower()
    if text in ("", "0", "off", "no", "false"):
        return ()
    if text in ("1", "on", "yes", "true"):
        return LANGUAGES
    named = tuple(dict.fromkeys(part.strip() for part in text.split(",") if part.strip()))
    unknown = [lang for lang in named if lang not in LANGUAGES]
    if unknown:
        raise ValueError(f"{ENV} names {', '.join(unknown)}: it takes 1 (every language), 0 (off) or a "
                         f"comma-separated list of {', '.join(LANGUAGES)}")
    return named


def default_requests(cached: set[str], languages: tuple[str, ...]) -> list[tuple[str, str, bytes]]:
    """(path, query, body) of every scene's default request of a cached endpoint: each language in turn, and in
    each the first variant of every scene, then the second, and so on. In the first language, when the families
    are cached, each round of variants is followed by their families (_families). A variant whose request cannot
    be made here (one that needs an address's documents) is left out, its families too."""
    from ..lessons.requests import scene_request
    from ..lessons.scenes import scenes

    catalogue = scenes()
    rounds = max(len(scene.variants) for scene in catalogue.values())
    found = []
    for lang in languages:
        query = urlencode({"lang": lang})
        for k in range(rounds):
            made = []
            for scene in catalogue.values():
                if k >= len(scene.variants) or scene.endpoint not in cached:
                    continue
                try:
                    body = orjson.dumps(scene_request(scene, scene.variants[k]))
                except Exception:          # noqa: BLE001 — a variant that needs documents: not a default page load
                    continue
                found.append((f"{API_PREFIX}/{scene.endpoint}", query, body))
                made.append((scene, scene.variants[k]))
            if FAMILY in cached and lang == languages[0]:
                found += [(f"{API_PREFIX}/{FAMILY}", query, body) for body in _families(made)]
    return found


def _families(variants) -> list[bytes]:
    """The bodies of the families a class grabs first on these (scene, variant)s: every slider at its variant's
    defaults, the coarse stage (the page's first question) then the full one; in the first language only (the
    families are the cache's largest answers: three languages' would not fit its default size). The cache keys a
    family without its slider's own value (families.bodies.shared): each answers a grab wherever that slider
    stands."""
    from ..lessons.family_requests import family_request

    bodies = []
    for scene, variant in variants:
        if scene.kind == "project" or variant.address:    # a course project's page drags no slider; a variant
            continue                                     # of the reader's own mechanism has none at its defaults
        for slider in variant.sliders:
            body = family_request(scene, variant, slider)
            if body["request"].get("outputs") == []:        # the page asks no family for a page of tables
                continue
            bodies += [orjson.dumps(body | {"stage": "coarse"}), orjson.dumps(body)]
    return bodies


@dataclass
class Warming:
    """The warming task of one worker and what it has done (read by the tests and the log)."""

    requests: list[tuple[str, str, bytes]]
    answered: int = 0            # 200s (stored by the cache unless partial)
    refused: int = 0             # anything else
    done: asyncio.Event = field(default_factory=asyncio.Event)
    task: asyncio.Task | None = None
    cpu_s: float = 0.0           # this process's CPU time while the requests were answered (all threads)


def start(app, cached: set[str], languages: tuple[str, ...] | None = None) -> Warming | None:
    """Start warming the app's response cache (None when MDL_WARM_DEFAULTS is off or the cache is off).
    ``cached``: the endpoints the cache keeps (the app's cache middleware's; "family" for the families)."""
    languages = languages_from_env() if languages is None else languages
    cache = getattr(app.state, "response_cache", None)
    if not languages or cache is None or not cache.enabled:
        return None
    warming = Warming(default_requests(cached, languages))
    warming.task = asyncio.get_running_loop().create_task(_warm(app, warming), name="default answers")
    return warming


async def stop(warming: Warming | None) -> None:
    """Cancel the warming task and wait until it has ended (the request it was sending ends with it)."""
    if warming is None or warming.task is None:
        return
    warming.task.cancel()
    try:
        await warming.task
    except asyncio.CancelledError:
        pass


async def _warm(app, warming: Warming) -> None:
    started = time.perf_counter()
    for path, query, body in warming.requests:
        await _quiet()
        cpu = time.process_time()
        status = await _post(app, path, query, body)
        warming.cpu_s += time.process_time() - cpu
        if status == 200:
            warming.answered += 1
        else:
            warming.refused += 1
    warming.done.set()
    log.info("default answers in the cache: %d of %d requests (%.1f s, %.1f CPU-s)", warming.answered,
             len(warming.requests), time.perf_counter() - started, warming.cpu_s)


async def _quiet() -> None:
    """Return once this worker has been quiet for QUIET_S and no heavy lane is busy."""
    while True:
        cpu = time.process_time()
        await asyncio.sleep(QUIET_S)
        if time.process_time() - cpu < IDLE_SHARE * QUIET_S and not heavy.busy():
            return


async def _post(app, path: str, query: str, body: bytes) -> int:
    """POST body to path?query through the whole app, as a browser's page would; the answer's status."""
    scope = {"type": "http", "asgi": {"version": "3.0", "spec_version": "2.3"}, "http_version": "1.1",
             "method": "POST", "scheme": "http", "path": path, "raw_path": path.encode(),
             "query_string": query.encode(), "root_path": "", "client": CLIENT, "server": ("127.0.0.1", 80),
             "headers": [(b"host", b"localhost"), (b"content-type", b"application/json"),
                         (b"accept-encoding", b"gzip"), (b"content-length", str(len(body)).encode())],
             "state": {}}
    sent = False
    status = 0

    async def receive():
        nonlocal sent
        if not sent:
            sent = True
            return {"type": "http.request", "body": body, "more_body": False}
        await asyncio.Event().wait()          # no disconnect: the answer is wanted until the task is cancelled
        return {"type": "http.disconnect"}

    async def send(message):
        nonlocal status
        if message["type"] == "http.response.start":
            status = message["status"]

    await app(scope, receive, send)
    return status
