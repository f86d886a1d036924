"""The app as an LTI 1.3 tool: OIDC login, launches, the tool's JWKS, deep linking, the instructor's results
without a token, "Open in a new window" tickets, and the administrator's registration API.

Every refusal names its reason: a page (401 forged, expired or replayed launch; 403 unknown issuer or
deployment, or a learner where an instructor is needed; 422 a malformed request) or, on the API, JSON. The
protocol checks are pylti1p3's (``lti_adapters``), the classroom side is ``lti_classroom``. The app's pages
refuse to be framed; inside an LMS frame a launch answers a small page of its own (framed by that LMS only)
that opens the assignment in a new window with a single-use ticket.
"""
from __future__ import annotations

import base64
import hashlib
import logging
import os
import secrets
import time
from datetime import datetime, timezone
from urllib.parse import parse_qs, urlencode, urlsplit

import requests
from fastapi import APIRouter, Depends, Request
from fastapi.responses import HTMLResponse, JSONResponse, RedirectResponse, Response
from fastapi.security import HTTPAuthorizationCredentials, HTTPBearer
from pylti1p3.deep_link_resource import DeepLinkResource
from pylti1p3.exception import LtiException, OIDCException
from pylti1p3.lineitem import LineItem
from starlette.concurrency import run_in_threadpool

from ...classroom.lti import dynamic, tool_key
from ...classroom.lti.grades import TimeoutSession
from ...classroom.lti.members import ROLES_CLAIM, teaches
from ...classroom.lti.platforms import DatabaseToolConf, PlatformRefused, new_platform
from ...classroom.spec import MAX_QUESTIONS, AssignmentSpec, QuestionPick
from ...classroom.variants import SpecError
from ...lessons.scenes import LANGUAGES, scenes
from .. import assignments, lti_adapters, lti_classroom, security
from ..assignment_store import store
from ..schemas_lti import (PendingScoreInfo, PlatformInfo, PlatformRegistered, PlatformRegistration, Platforms,
                           RegistrationLink, ToolUrls)
from ..security import CONTENT_SECURITY_POLICY, policy_with_script_hashes
from ..student_secret import from_another_site, hand_over
from .pages import _context, templates

MAX_FORM_BYTES = 64 * 1024          # a launch's id_token is a few kilobytes
ORIGINS_TTL_S = 30.0                # a platform registered on one server may frame the pages of all within this
RECENT_S = 14 * 86400               # the picker offers assignments made from the same address this recently
CUSTOM_CLAIM = "https://purl.imsglobal.org/spec/lti/claim/custom"
PRESENTATION_CLAIM = "https://purl.imsglobal.org/spec/lti/claim/launch_presentation"
DEEP_LINKING = "LtiDeepLinkingRequest"
MESSAGE_TYPE_CLAIM = "https://purl.imsglobal.org/spec/lti/claim/message_type"
AUTO_SUBMIT = "document.getElementById('lti-return').submit();"
AUTO_SUBMIT_HASH = base64.b64encode(hashlib.sha256(AUTO_SUBMIT.encode()).digest()).decode()
CLOSE_REGISTRATION = "(window.opener || window.parent).postMessage({subject: 'org.imsglobal.lti.close'}, '*');"
CLOSE_REGISTRATION_HASH = base64.b64encode(hashlib.sha256(CLOSE_REGISTRATION.encode()).digest()).decode()
REGISTRATION_LINK_S = 7 * 86400     # a dynamic-registration link works once within a week
log = logging.getLogger("mdl.lti")

router = APIRouter()                                    # the protocol and its pages: not in the OpenAPI
api = APIRouter(prefix="/api/v1/lti", tags=["lti"])
ADMIN = HTTPBearer(auto_error=False, scheme_name="admin_token", description="MDL_ADMIN_TOKEN")


# what pylti1p3 says → (status, code, reason in words)
REFUSALS = (
    ("State not found", 401, "unknown_state", "this launch's state was not issued here or is already used "
                                              "(a replayed or forged launch): start again from the LMS"),
    ("Invalid Nonce", 401, "replayed_nonce", "the launch's nonce is not the one issued, or already used"),
    ('"nonce" is empty', 401, "replayed_nonce", "the launch carries no nonce"),
    ("Registration not found", 403, "unknown_issuer", "no platform with this issuer and client id is registered "
                                                      "here: an administrator registers it first"),
    ("Client id not registered", 403, "unknown_issuer", "this client id is not registered for the issuer"),
    ("Unable to find deployment", 403, "unknown_deployment", "this deployment id is not registered for the platform"),
    ("Signature has expired", 401, "expired", "the launch has expired: start again from the LMS"),
    ("The token is not yet valid", 401, "expired", "the launch is issued in the future (clocks differ?)"),
    ("Signature verification failed", 401, "bad_signature", "the launch's signature is not the platform's"),
    ("Unable to find public key", 401, "bad_signature", "the launch is signed with a key the platform does "
                                                         "not publish"),
    ("Can't decode id_token", 401, "bad_token", "the id_token cannot be verified"),
    ("Invalid id_token", 422, "bad_token", "the id_token is not a JWT"),
    ("Invalid JWT format", 422, "bad_token", "the id_token is not a JWT"),
)


def refusal(error: Exception) -> tuple[int, str, str]:
    text = str(error)
    for start, status, code, reason in REFUSALS:
        if start in text:
            return status, code, reason
    return 422, "invalid_launch", f"the launch is not valid LTI 1.3: {text[:200]}"


def base_url(request: Request) -> str:
    return str(request.base_url).rstrip("/")


def tool_urls(request: Request) -> ToolUrls:
    base = base_url(request)
    return ToolUrls(login_url=f"{base}/lti/login", launch_url=f"{base}/lti/launch", jwks_url=f"{base}/lti/jwks",
                    deep_linking_url=f"{base}/lti/launch")


def origin(url: str) -> str:
    parts = urlsplit(url)
    return f"{parts.scheme}://{parts.netloc}" if parts.scheme and parts.netloc else ""


def framed_by(response: Response, origins: set[str], form_to: str = "", script_hash: str = "") -> Response:
    """Let the platform frame this page (CSP frame-ancestors; X-Frame-Options then ignored) and, for the deep
    linking answer, post a form to it with the one inline script of that hash."""
    allowed = " ".join(sorted(o for o in origins if o))
    policy = policy_with_script_hashes([script_hash]) if script_hash else CONTENT_SECURITY_POLICY
    policy = policy.replace("frame-ancestors 'none'", f"frame-ancestors 'self' {allowed}".strip())
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
    response = page(request, "lti_error.html", lang, status, code=code, reason=reason)
    return framed_by(response, set(origins))


async def form_params(request: Request) -> dict[str, str] | None:
    """The query and the urlencoded form of a request, one value each; None past MAX_FORM_BYTES."""
    body = await request.body() if request.method == "POST" else b""
    if len(body) > MAX_FORM_BYTES:
        return None
    params = {k: v for k, v in request.query_params.items()}
    params.update({k: v[0] for k, v in parse_qs(body.decode("utf-8", "replace")).items()})
    return params


def launch_language(claims: dict, fallback: str | None) -> str | None:
    locale = str((claims.get(PRESENTATION_CLAIM) or {}).get("locale") or "")[:2].lower()
    return locale if locale in LANGUAGES else fallback


def needs_new_window(request: Request) -> bool:
    """Whether the browser says this launch loads into a frame of another site (the LMS's iframe, the LMS on
    another site): there the session cookie is a third-party cookie, which browsers block. In a frame of the same
    site (lms.example.edu framing lab.example.edu) it is kept, and the pages open in the frame."""
    return (request.headers.get("sec-fetch-dest") in ("iframe", "frame")
            and request.headers.get("sec-fetch-site") not in ("same-origin", "same-site"))


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


security.allow_framing_by(framing_origins)


# the tool's public face
@router.get("/lti/jwks", include_in_schema=False)
def jwks() -> JSONResponse:
    return JSONResponse(tool_key.jwks(store()), headers={"Cache-Control": "public, max-age=300"})


@router.get("/lti", response_class=HTMLResponse, include_in_schema=False)
def tool_page(request: Request, lang: str | None = None):
    """The tool's URLs for an LMS administrator to paste, and how to register the platform here."""
    return page(request, "lti_tool.html", lang, urls=tool_urls(request),
                registration_open=bool(os.environ.get("MDL_ADMIN_TOKEN")))


# OIDC login and launch
@router.api_route("/lti/login", methods=["GET", "POST"], include_in_schema=False)
async def login(request: Request):
    params = await form_params(request)
    if params is None:
        return refused_page(request, 422, "too_large", "the login request is too large")
    for field in ("iss", "login_hint"):
        if not params.get(field):
            return refused_page(request, 422, f"no_{field}", f"the login request has no {field}")
    return await run_in_threadpool(_login, request, params)


def _login(request: Request, params: dict[str, str]):
    oidc = lti_adapters.login(request, params, store())
    try:
        return oidc.pass_params_to_launch({"target": params.get("target_link_uri") or ""}).redirect(
            f"{base_url(request)}/lti/launch")
    except (OIDCException, LtiException) as error:
        return refused_page(request, 403, "unknown_issuer", f"no platform with this issuer (and client id) is "
                                                            f"registered here ({error})")


@router.post("/lti/launch", include_in_schema=False)
async def launch(request: Request):
    params = await form_params(request)
    if params is None:
        return refused_page(request, 422, "too_large", "the launch is too large")
    for field in ("id_token", "state"):
        if not params.get(field):
            return refused_page(request, 422, f"no_{field}", f"the launch has no {field} (post it as a form field)")
    return await run_in_threadpool(_launch, request, params)


def _launch(request: Request, params: dict[str, str]):
    found = lti_adapters.launch(request, params, store())
    found.set_jwt_verify_options({"verify_aud": False, "require": ["exp", "iat"]})
    try:
        claims = found.get_launch_data()
    except (LtiException, KeyError, ValueError, TypeError) as error:
        status, code, reason = refusal(error)
        log.info("LTI launch refused: %s (%s)", code, str(error)[:200])
        return refused_page(request, status, code, reason)
    aud = claims.get("aud")
    client_id = aud[0] if isinstance(aud, list) else aud
    platform = DatabaseToolConf(store()).platform(claims["iss"], client_id)
    origins = platform_origins(platform)
    roles = claims.get(ROLES_CLAIM) or []
    if claims.get(MESSAGE_TYPE_CLAIM) == DEEP_LINKING:
        if not teaches(roles):
            return refused_page(request, 403, "not_instructor", "only an instructor chooses content", origins=origins)
        return framed_by(picker(request, found.get_launch_id(), platform, claims), origins)
    custom = claims.get(CUSTOM_CLAIM) or {}
    lang = launch_language(claims, None)
    if custom.get("assignment"):
        return open_assignment(request, found, platform, claims, str(custom["assignment"]), lang, origins)
    scene = scenes().get(str(custom.get("scene") or ""))
    if scene is None:
        return refused_page(request, 422, "no_resource", "the link names no scene or assignment of this tool "
                                                         "(custom parameter scene=… or assignment=…)", lang, origins)
    target = f"/scenes/{scene.id}?" + urlencode({"lang": lang or "ru", **(
        {"variant": str(custom["variant"])} if custom.get("variant") else {})})
    if needs_new_window(request):
        return framed_by(page(request, "lti_new_window.html", lang, link=target, title=scene.title[lang or "ru"]),
                         origins)
    return RedirectResponse(target, status_code=303)


def open_assignment(request: Request, found, platform, claims: dict, assignment_id: str, lang: str | None,
                    origins: set[str]):
    record = store().assignment(assignment_id) if len(assignment_id) <= 40 else None
    if record is None:
        return refused_page(request, 422, "unknown_assignment", "the link names an assignment this tool does not "
                                                                "have", lang, origins)
    _, resolved = assignments.load(record.id)
    lang = lang or resolved.spec.lang
    context = lti_classroom.context_id(claims)
    if teaches(claims.get(ROLES_CLAIM)):
        if store().lti_placements_of(record.id) and not placeable(request, record, platform, context):
            return refused_page(request, 403, "another_course", "this assignment belongs to another course: its "
                                                                "results open from that course only", lang, origins)
        store().lti_place(platform.id, context, record.id, resolved.spec.title or resolved.scene.title[lang],
                          datetime.now(timezone.utc).timestamp())
        if found.has_nrps():
            try:
                outcome = lti_classroom.fill_roster(record, resolved, platform, context,
                                                    found.get_nrps().get_members())
                log.info("LTI roster of assignment %s from the course: %s", record.id, outcome)
            except Exception as error:                     # noqa: BLE001 - the results open all the same
                log.warning("LTI roster of assignment %s not read: %s", record.id, str(error)[:300])
        lti_classroom.post_scores_later()                  # a chance for scores that wait
        about = {"kind": "teacher", "assignment": record.id, "platform": platform.id, "context": context,
                 "lang": lang}
    else:
        student, _ = lti_classroom.enter_learner(record, resolved, platform, claims)
        about = {"kind": "student", "assignment": record.id, "student": student.key, "lang": lang}
    if needs_new_window(request):
        ticket = lti_classroom.new_ticket(about)
        return framed_by(page(request, "lti_new_window.html", lang, link=f"/lti/continue/{ticket}",
                              title=resolved.spec.title or resolved.scene.title[lang]), origins)
    return enter(request, about)


def enter(request: Request, about: dict) -> Response:
    """The session of a launch (a student's secret cookie, or an instructor's session) and on to the page."""
    assignment_id, lang = about["assignment"], about.get("lang") or "ru"
    if about["kind"] == "teacher":
        response = RedirectResponse(f"/lti/results/{assignment_id}?lang={lang}", status_code=303)
        token = lti_classroom.new_teacher_session(assignment_id, about["platform"], about["context"])
        response.set_cookie(lti_classroom.TEACHER_COOKIE, token, max_age=lti_classroom.TEACHER_SECONDS,
                            path=f"/lti/results/{assignment_id}", httponly=True, samesite="lax",
                            secure=request.url.scheme == "https")
    else:
        secret = lti_classroom.new_secret_for(assignment_id, about["student"])
        if secret is None:
            return refused_page(request, 403, "no_such_student", "this student is no longer in the assignment: "
                                                                 "open it again from the LMS", lang)
        response = RedirectResponse(f"/assignments/{assignment_id}?lang={lang}", status_code=303)
        hand_over(response, request, assignment_id, secret)
    response.headers["cache-control"] = "no-store"
    return response


@router.get("/lti/continue/{ticket}", include_in_schema=False)
def continue_launch(request: Request, ticket: str):
    """The launch continued in a new window (first-party: its cookies are kept); the ticket works once."""
    about = lti_classroom.take_ticket(ticket)
    if about is None:
        return refused_page(request, 403, "ticket_used", "this link has been used or has expired: open the "
                                                         "activity again from the LMS")
    return enter(request, about)


# the instructor's results, by session
def teacher_of(request: Request, assignment_id: str) -> dict | None:
    return lti_classroom.teacher_session(request.cookies.get(lti_classroom.TEACHER_COOKIE), assignment_id)


@router.get("/lti/results/{assignment_id}", response_class=HTMLResponse, include_in_schema=False)
def results(request: Request, assignment_id: str, lang: str | None = None):
    if teacher_of(request, assignment_id) is None:
        return refused_page(request, 401, "no_session", "no instructor session for this assignment: open it "
                                                        "from the LMS as its instructor", lang)
    record, resolved = assignments.load(assignment_id)
    context = _context(request, lang)
    linked = {learner.student_key for learner in store().lti_learners_of(record.id)}
    response = templates.TemplateResponse(request, "lti_results.html", context | {
        "assignment": assignments.info(record, resolved, context["lang"]), "sliders": resolved.variant.sliders,
        "rows": assignments.result_rows(record, resolved),
        "from_lms": {assignments.student_id(record.id, key) for key in linked},
        "pending": [p for p in store().lti_pending_scores() if p.assignment_id == record.id]})
    response.headers["cache-control"] = "no-store"
    return response


@router.post("/lti/results/{assignment_id}/students/{student_id}/reset", include_in_schema=False)
def reset_student(request: Request, assignment_id: str, student_id: str, lang: str | None = None):
    """Remove a student's submissions (the student starts again); their LMS grade is posted again (0)."""
    if teacher_of(request, assignment_id) is None or from_another_site(request):
        return refused_page(request, 401, "no_session", "no instructor session for this assignment", lang)
    record, _ = assignments.load(assignment_id)
    student = assignments.find_student(record, student_id)
    store().delete_student(record.id, student.key)
    lti_classroom.score_changed(record.id, student.key)
    return RedirectResponse(f"/lti/results/{record.id}?lang={_context(request, lang)['lang']}", status_code=303)


# deep linking
def client_of(request: Request) -> str:
    return request.client.host if request.client else "unknown"


def placeable(request: Request, record, platform, context: str) -> bool:
    """Whether this course may place the assignment: it is placed here already, or nowhere yet and made from
    this browser's address (an assignment is tied to the first course that places it: an instructor elsewhere
    who learns its id from a student's link sees no results)."""
    placements = store().lti_placements_of(record.id)
    if placements:
        return (platform.id, context) in placements
    return record.client == client_of(request)


def picker(request: Request, launch_id: str, platform, claims: dict) -> HTMLResponse:
    """The assignments of this course, those made lately from this address and placed nowhere, the scenes."""
    lang = launch_language(claims, None)
    offered = [scene for scene in scenes().values() if scene.questions]
    placed = store().lti_placed(platform.id, lti_classroom.context_id(claims))
    recent = store().lti_unplaced_by_client(client_of(request), datetime.now(timezone.utc).timestamp() - RECENT_S)
    titles = {scene_id: scene.title for scene_id, scene in scenes().items()}
    placed += [(assignment_id, spec.get("title") or titles.get(spec.get("scene"), {}).get(lang or "ru", assignment_id))
               for assignment_id, spec in recent]
    return page(request, "lti_picker.html", lang, launch_id=launch_id, scenes=offered, placed=placed,
                all_scenes=list(scenes().values()))


def default_spec(scene, lang: str) -> AssignmentSpec:
    """An assignment made from the picker: the scene's first variant that has questions, its questions."""
    variant = next(v for v in scene.variants if v.address is None
                   and any(not q.variants or v.id in q.variants for q in scene.questions))
    questions = [q for q in scene.questions if not q.variants or variant.id in q.variants][:MAX_QUESTIONS]
    return AssignmentSpec(scene=scene.id, variant=variant.id, title=scene.title[lang], lang=lang,
                          questions=[QuestionPick(id=q.id) for q in questions])


@router.post("/lti/deep-link", include_in_schema=False)
async def deep_link(request: Request):
    params = await form_params(request)
    if params is None or not params.get("launch") or not params.get("choice"):
        return refused_page(request, 422, "no_choice", "the form needs launch and choice")
    return await run_in_threadpool(_deep_link, request, params)


def _deep_link(request: Request, params: dict[str, str]):
    try:
        found = lti_adapters.cached_launch(request, params["launch"][:100], store())
        claims = found.get_launch_data()
    except LtiException:
        return refused_page(request, 401, "picker_expired", "this choice has expired: open the picker again "
                                                            "from the LMS")
    aud = claims.get("aud")
    platform = DatabaseToolConf(store()).platform(claims["iss"], aud[0] if isinstance(aud, list) else aud)
    origins = platform_origins(platform)
    if claims.get(MESSAGE_TYPE_CLAIM) != DEEP_LINKING or not teaches(claims.get(ROLES_CLAIM)):
        return refused_page(request, 403, "not_instructor", "only an instructor's deep-linking launch chooses "
                                                            "content", origins=origins)
    lang = launch_language(claims, "ru")
    kind, _, what = params["choice"].partition(":")
    resource = DeepLinkResource().set_url(f"{base_url(request)}/lti/launch")
    if kind == "scene" and what in scenes():
        resource.set_title(scenes()[what].title[lang]).set_custom_params({"scene": what})
    elif kind in ("new", "assignment"):
        if kind == "new":
            if what not in scenes() or not scenes()[what].questions:
                return refused_page(request, 422, "unknown_scene", "no scene with questions of that id", lang, origins)
            try:
                record, resolved, _ = assignments.create(default_spec(scenes()[what], lang),
                                                         request.client.host if request.client else "lti")
            except SpecError as error:
                return refused_page(request, 422, "assignment_error", f"{error.field}: {error.reason}", lang, origins)
        else:
            record = store().assignment(what[:40])
            if record is None or not placeable(request, record, platform, lti_classroom.context_id(claims)):
                return refused_page(request, 403, "another_course", "no such assignment of this course", lang,
                                    origins)
            record, resolved = assignments.load(what)
        title = resolved.spec.title or resolved.scene.title[lang]
        store().lti_place(platform.id, lti_classroom.context_id(claims), record.id, title,
                          datetime.now(timezone.utc).timestamp())
        resource.set_title(title).set_custom_params({"assignment": record.id}).set_lineitem(
            LineItem().set_score_maximum(len(resolved.spec.questions)).set_label(title).set_resource_id(record.id))
    else:
        return refused_page(request, 422, "unknown_choice", "choose a scene or an assignment", lang, origins)
    deep = found.get_deep_link()
    return_url = claims["https://purl.imsglobal.org/spec/lti-dl/claim/deep_linking_settings"]["deep_link_return_url"]
    response = page(request, "lti_deep_link_return.html", lang, return_url=return_url,
                    jwt=deep.get_response_jwt([resource]), script=AUTO_SUBMIT)
    return framed_by(response, origins, form_to=origin(return_url), script_hash=AUTO_SUBMIT_HASH)


# registration by an administrator
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
    _framing["at"] = -ORIGINS_TTL_S                 # this server lets it frame the pages at once
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
    if len(code) > 64 or store().lti_take(f"register:{hashlib.sha256(code.encode()).hexdigest()}",
                                          time.time()) is None:
        return refused_page(request, 403, "registration_code", "this registration link is unknown, used or expired: "
                                                               "make a new one (POST /api/v1/lti/registration-links)",
                            lang)
    try:
        platform = dynamic.register(openid_configuration, registration_token, base_url(request),
                                    "Mechanism Dynamics Lab", TimeoutSession())
    except PlatformRefused as error:
        return refused_page(request, 422, "registration_refused", f"{error.field}: {error.reason}", lang)
    except (requests.RequestException, ValueError) as error:
        return refused_page(request, 422, "registration_failed", f"the LMS could not be read: "
                                                                 f"{type(error).__name__}", lang)
    if not store().lti_add_platform(platform):
        return refused_page(request, 409, "registered", "this issuer and client id are registered already", lang)
    tool_key.tool_key(store())
    _framing["at"] = -ORIGINS_TTL_S
    response = page(request, "lti_registered.html", lang, platform=platform, script=CLOSE_REGISTRATION)
    return framed_by(response, platform_origins(platform), script_hash=CLOSE_REGISTRATION_HASH)


@api.get("/tool", response_model=ToolUrls, summary="The tool's URLs to paste into the LMS")
def tool(request: Request) -> ToolUrls:
    return tool_urls(request)


router.include_router(api)
