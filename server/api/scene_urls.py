"""One URL per scene: its id (lowercase words joined by hyphens). An address with a former id
(``Scene.former_ids``: /scenes/flywheel_analysis) is redirected permanently to the same path with the current
id, the query kept, so old links and bookmarks keep working."""
from __future__ import annotations

from fastapi import Request
from fastapi.responses import RedirectResponse


def renamed(request: Request, requested: str, current: str) -> RedirectResponse | None:
    """301 to the same path and query with the current id, when the request named a former one."""
    if requested == current:
        return None
    path = request.url.path.replace(f"/{requested}", f"/{current}", 1)
    query = f"?{request.url.query}" if request.url.query else ""
    return RedirectResponse(path + query, status_code=301)
