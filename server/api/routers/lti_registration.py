"""Registering an LMS: by an administrator (``/api/v1/lti/platforms`` with MDL_ADMIN_TOKEN; unset, registration
is closed), or by the LMS itself with a single-use link the administrator made (LTI Dynamic Registration,
``/lti/register/<code>``); the tool's URLs to paste (``/api/v1/lti/tool``); the grades still to post."""
from __future__ import annotations

import hashlib
import os
import secrets
import time
from datetime import datetime, timezone

import requests
from fastapi import APIRouter, Depends, Request
from fastapi.responses import JSONResponse
from fastapi.security import HTTPAuthorizationCredentials, HTTPBearer

from ...classroom.lti import dynamic, tool_key
from ...classroom.lti.grades import TimeoutSession
from ...classroom.lti.platforms import PlatformRefused, new_platform
from ...classroom import lti_classroom
from ...classroom.assignment_store import store
from ..lti_pages import (base_url, forget_origins, framed_by, origin, page, platform_origins, refused_page,
                         tool_urls)
from ..schemas_lti import (PendingScoreInfo, PlatformInfo, PlatformRegistered, PlatformRegistration, Platforms,
                           RegistrationLink, ToolUrls)

REGISTRATION_LINK_S = 7 * 86400     # a dynamic-registration link works once within a week
ADMIN = HTTPBearer(auto_error=False, scheme_name="admin_token", description="MDL_ADMIN_TOKEN")

router = APIRouter()                                    # /lti/register/<code>: not in the OpenAPI
api = APIRouter(prefix="/api/v1/lti", tags=["lti"])


def admin_refusal(credentials: HTTPAuthorizationCredentials | None) -> JSONResponse | None:
    expected = os.environ.get("MDL_ADMIN_TOKEN", "")
    if not expected:
        return JSONResponse(status_code=403, content={"detail": [{
            "loc": ["header", "authorization"], "type": "registration_closed",
            "msg": "registration is closed: MDL_ADMIN_TOKEN is not set on the server"}]})
    if credentials is None or not secrets.compare_digest(credentials.credentials.encode(), expected.encode()):
        return JSONResponse(status_code=401, headers={"WWW-Authenticate": "Bearer"}, content={"detail": [{
            "loc": ["header", "authorization"], "type": "not_admin",
            "msg": "send Authorization: Bearer <MDL_ADMIN_TOKEN>"}]})
    return None


def iso(at: float) -> str:
    return datetime.fromtimestamp(at, timezone.utc).isoformat(timespec="seconds")


@api.post("/platforms", status_code=201, response_model=PlatformRegistered, summary="Register an LMS (platform)",
          responses={401: {"description": "no or a wrong admin token"}, 403: {"description": "registration closed"},
                     409: {"description": "this issuer and client id are registered already"},
                     422: {"description": "the field and the reason"}})
def register_platform(body: PlatformRegistration, request: Request,
                      credentials: HTTPAuthorizationCredentials | None = Depends(ADMIN)):
    refused = admin_refusal(credentials)
    if refused is not None:
        return refused
    try:
        platform = new_platform(body.issuer, body.client_id, body.deployment_ids, body.auth_login_url,
                                body.auth_token_url, body.key_set_url, body.name)
    except PlatformRefused as error:
        return JSONResponse(status_code=422, content={"detail": [{"loc": ["body", error.field], "msg": error.reason,
                                                                  "type": "platform_error"}]})
    if not store().lti_add_platform(platform):
        return JSONResponse(status_code=409, content={"detail": [{"loc": ["body", "client_id"], "type": "registered",
                                                                  "msg": "this issuer and client id are registered "
                                                                         "already"}]})
    tool_key.tool_key(store())                      # the key pair exists before the platform asks for it
    forget_origins()                                # this server lets it frame the pages at once
    return PlatformRegistered(id=platform.id, tool=tool_urls(request))


@api.get("/platforms", response_model=Platforms, summary="The registered LMSs, and scores still to post",
         responses={401: {"description": "no or a wrong admin token"}, 403: {"description": "registration closed"}})
def list_platforms(credentials: HTTPAuthorizationCredentials | None = Depends(ADMIN)):
    refused = admin_refusal(credentials)
    if refused is not None:
        return refused
    return Platforms(platforms=[PlatformInfo(id=p.id, issuer=p.issuer, client_id=p.client_id, name=p.name,
                                             deployment_ids=list(p.deployment_ids), auth_login_url=p.auth_login_url,
                                             auth_token_url=p.auth_token_url, key_set_url=p.key_set_url,
                                             created_at=iso(p.created_at)) for p in store().lti_platforms()],
                     pending_scores=[PendingScoreInfo(assignment_id=p.assignment_id, tries=p.tries,
                                                      last_error=p.last_error, retry_at=iso(p.retry_at))
                                     for p in store().lti_pending_scores()])


@api.post("/scores/retry", response_model=dict[str, int], summary="Post the scores that wait now (they are also retried on later submissions)",
          responses={401: {"description": "no or a wrong admin token"}, 403: {"description": "registration closed"}})
def retry_scores(credentials: HTTPAuthorizationCredentials | None = Depends(ADMIN)):
    refused = admin_refusal(credentials)
    if refused is not None:
        return refused
    return lti_classroom.post_due_now()


@api.post("/registration-links", status_code=201, response_model=RegistrationLink,
          summary="A single-use URL for an LMS's dynamic registration (LTI Dynamic Registration 1.0)",
          responses={401: {"description": "no or a wrong admin token"}, 403: {"description": "registration closed"}})
def registration_link(request: Request, credentials: HTTPAuthorizationCredentials | None = Depends(ADMIN)):
    refused = admin_refusal(credentials)
    if refused is not None:
        return refused
    code = secrets.token_urlsafe(24)
    store().lti_put(f"register:{hashlib.sha256(code.encode()).hexdigest()}", {"made": time.time()},
                    time.time() + REGISTRATION_LINK_S)
    return RegistrationLink(url=f"{base_url(request)}/lti/register/{code}", expires_in=REGISTRATION_LINK_S)


@router.get("/lti/register/{code}", include_in_schema=False)
def dynamic_registration(request: Request, code: str, openid_configuration: str = "", registration_token: str = "",
                         lang: str | None = None):
    """The LMS's dynamic registration, opened by its administrator with the URL made above."""
    if not openid_configuration or len(openid_configuration) > 2000 or len(registration_token) > 8000:
        return refused_page(request, 422, "no_configuration", "the LMS sent no (or too long an) openid_configuration "
                                                              "or registration_token", lang)
    lms = {origin(openid_configuration)}            # the LMS shows this page in its frame: its errors too
    if len(code) > 64 or store().lti_take(f"register:{hashlib.sha256(code.encode()).hexdigest()}",
                                          time.time()) is None:
        return refused_page(request, 403, "registration_code", "this registration link is unknown, used or expired: "
                                                               "make a new one (POST /api/v1/lti/registration-links)",
                            lang, lms)
    try:
        platform = dynamic.register(openid_configuration, registration_token, base_url(request),
                                    "Mechanism Dynamics Lab", TimeoutSession())
    except PlatformRefused as error:
        return refused_page(request, 422, "registration_refused", f"{error.field}: {error.reason}", lang, lms)
    except (requests.RequestException, ValueError) as error:
        return refused_page(request, 422, "registration_failed", f"the LMS could not be read: "
                                                                 f"{type(error).__name__}", lang, lms)
    if not store().lti_add_platform(platform):
        return refused_page(request, 409, "registered", "this issuer and client id are registered already", lang,
                            lms)
    tool_key.tool_key(store())
    forget_origins()
    response = page(request, "lti_registered.html", lang, platform=platform)
    return framed_by(response, platform_origins(platform))


@api.get("/tool", response_model=ToolUrls, summary="The tool's URLs to paste into the LMS")
def tool(request: Request) -> ToolUrls:
    return tool_urls(request)


router.include_router(api)
