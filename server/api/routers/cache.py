"""GET /api/v1/cache: how the response cache of this server process is doing; and what it caches: the computing
endpoints and the slider families, whose answer is a function of (path, query, validated body)."""
import os

from fastapi import APIRouter, Request
from pydantic import BaseModel, Field

from ..endpoints import ENDPOINTS
from .family import FamilyRequest

# The computing endpoints and the slider families, whose answer is a function of (path, query, validated body).
CACHED_ENDPOINTS = (*ENDPOINTS, "family")

router = APIRouter(tags=["cache"])


def request_models() -> dict[str, type[BaseModel]]:
    """The request model of each cached endpoint (the family's lives with its route): given to the cache."""
    return {**{name: model for name, (model, _) in ENDPOINTS.items()}, "family": FamilyRequest}


class CacheStats(BaseModel):
    """Counters of one server process's response cache since it started (each worker has its own)."""

    enabled: bool = Field(description="false when MDL_CACHE_BYTES is 0")
    max_bytes: int = Field(description="bound of the stored answers' total size, bytes (MDL_CACHE_BYTES)")
    bytes: int = Field(description="total size of the stored answers now, bytes")
    entries: int = Field(description="answers stored now")
    hits: int = Field(description="requests answered from the cache")
    misses: int = Field(description="cacheable requests that were computed")
    hit_rate: float | None = Field(description="hits / (hits + misses); null before the first cacheable request")
    bypassed: int = Field(description="requests to a cached endpoint whose body is not JSON or does not validate, passed on uncached (the route answers its 422)")
    evictions: int = Field(description="answers dropped, least recently used first, to stay within max_bytes")
    pid: int = Field(description="the server process answering: each worker keeps its own cache")
    endpoints: list[str] = Field(description="the endpoints whose 200 answers are cached (POST /api/v1/<name>)")


@router.get("/cache", response_model=CacheStats,
            summary="Response cache of this server process: hits, misses, entries, bytes")
def cache_stats(request: Request) -> CacheStats:
    cache = getattr(request.app.state, "response_cache", None)
    stats = cache.stats() if cache is not None else {
        "enabled": False, "max_bytes": 0, "bytes": 0, "entries": 0, "hits": 0, "misses": 0, "hit_rate": None,
        "bypassed": 0, "evictions": 0, "pid": os.getpid()}
    return CacheStats(**stats, endpoints=list(CACHED_ENDPOINTS))
