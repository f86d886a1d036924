"""What the LTI pages share: the tool's URLs, the pages and refusals (framed by the launching LMS only), and the
registered LMSs' origins that may frame the pages a launch opens (security.FRAMED_PATHS)."""
from __future__ import annotations

import logging
import time
from urllib.parse import urlsplit

from fastapi import Request
from fastapi.responses import HTMLResponse, Response

from . import security
from ..classroom.assignment_store import store
from .routers.pages import _context, templates
from .schemas_lti import ToolUrls
from .security import CONTENT_SECURITY_POLICY

ORIGINS_TTL_S = 30.0                # a platform registered on one server may frame the pages of all within this
log = logging.getLogger("mdl.lti")


def base_url(request: Request) -> str:
    return str(request.base_url).rstrip("/")


def tool_urls(request: Request) -> ToolUrls:
    base = base_url(request)
    return ToolUrls(login_url=f"{base}/lti/login", launch_url=f"{base}/lti/launch", jwks_url=f"{base}/lti/jwks",
                    deep_linking_url=f"{base}/lti/launch")


def origin(url: str) -> str:
    parts = urlsplit(url)
    return f"{parts.scheme}://{parts.netloc}" if parts.scheme and parts.netloc else ""


def framed_by(response: Response, origins: set[str], form_to: str = "") -> Response:
    """Let the platform frame this page (CSP frame-ancestors; X-Frame-Options then ignored) and, for the deep
    linking answer, post a form to it."""
    allowed = " ".join(sorted(o for o in origins if o))
    policy = CONTENT_SECURITY_POLICY.replace("frame-ancestors 'none'", f"frame-ancestors 'self' {allowed}".strip())
    if form_to:
        policy = policy.replace("form-action 'self'", f"form-action 'self' {form_to}")
    response.headers["content-security-policy"] = policy
    response.headers["x-frame-options"] = "SAMEORIGIN"
    response.headers["cache-control"] = "no-store"
    return response


def platform_origins(platform) -> set[str]:
    return {origin(platform.issuer), origin(platform.auth_login_url)} if platform is not None else set()


def page(request: Request, template: str, lang: str | None, status: int = 200, **values) -> HTMLResponse:
    return templates.TemplateResponse(request, template, _context(request, lang) | values, status_code=status)


def refused_page(request: Request, status: int, code: str, reason: str, lang: str | None = None,
                 origins: set[str] = frozenset()) -> HTMLResponse:
    """A refusal page: what to do in the reader's language (the launch's, else ?lang=), the reason, the code."""
    response = page(request, "lti_error.html", lang or request.query_params.get("lang"), status, code=code,
                    reason=reason)
    return framed_by(response, set(origins))


_framing = {"at": -ORIGINS_TTL_S, "origins": ()}


def framing_origins() -> tuple[str, ...]:
    """The registered LMSs' origins, which may frame the pages a launch opens (security.FRAMED_PATHS); read from
    the database at most every ORIGINS_TTL_S, so that every server learns of a new platform."""
    now = time.monotonic()
    if now - _framing["at"] > ORIGINS_TTL_S:
        try:
            found = {o for platform in store().lti_platforms() for o in platform_origins(platform) if o}
            _framing["origins"] = tuple(sorted(found))
        except Exception:                                    # noqa: BLE001 - keep the last known; pages still answer
            log.warning("the LMS origins could not be read; framing stays as it was")
        _framing["at"] = now
    return _framing["origins"]





def forget_origins() -> None:
    """Read the origins again at the next response (a platform was registered on this server)."""
    _framing["at"] = -ORIGINS_TTL_S


security.allow_framing_by(framing_origins)
