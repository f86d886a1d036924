"""The app as an LTI 1.3 tool: OIDC login, launches, the tool's JWKS, deep linking, the instructor's results
without a token, and "Open in a new window" tickets; registration is ``lti_registration``'s.

Every refusal is a page naming its reason and code (401 a forged, expired or replayed launch; 403 an unknown
issuer or deployment, or a learner where an instructor is needed; 422 a malformed request). The protocol checks
are pylti1p3's (``lti_adapters``), the classroom side is ``lti_classroom``, the pages' framing ``lti_pages``.
In a frame of the same site a launch opens its page in the frame; in a frame of another site (where the session
cookie is blocked) it answers a small page that opens it in a new window with a single-use ticket.
"""
from __future__ import annotations

import logging
import os
from datetime import datetime, timezone
from urllib.parse import parse_qs, urlencode

from fastapi import APIRouter, Request
from fastapi.responses import HTMLResponse, JSONResponse, RedirectResponse, Response
from pylti1p3.deep_link_resource import DeepLinkResource
from pylti1p3.exception import LtiException, OIDCException
from pylti1p3.lineitem import LineItem
from starlette.concurrency import run_in_threadpool

from ...classroom.lti import tool_key
from ...classroom.lti.members import ROLES_CLAIM, teaches
from ...classroom.lti.platforms import DatabaseToolConf
from ...classroom.spec import MAX_QUESTIONS, AssignmentSpec, QuestionPick
from ...classroom.variants import SpecError
from ...lessons.scenes import LANGUAGES, scenes
from ...classroom import assignments, lti_classroom
from .. import lti_adapters
from ...classroom.assignment_store import store
from ..lti_pages import base_url, framed_by, origin, page, platform_origins, refused_page, tool_urls
from ..student_secret import from_another_site, hand_over
from . import lti_registration
from .pages import _context, templates

MAX_FORM_BYTES = 64 * 1024          # a launch's id_token is a few kilobytes
RECENT_S = 14 * 86400               # the picker offers assignments made from the same address this recently
CUSTOM_CLAIM = "https://purl.imsglobal.org/spec/lti/claim/custom"
PRESENTATION_CLAIM = "https://purl.imsglobal.org/spec/lti/claim/launch_presentation"
DEEP_LINKING = "LtiDeepLinkingRequest"
MESSAGE_TYPE_CLAIM = "https://purl.imsglobal.org/spec/lti/claim/message_type"
log = logging.getLogger("mdl.lti")

router = APIRouter()                                    # the protocol and its pages: not in the OpenAPI


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


def needs_new_window(request: Request) -> bool:
    """Whether the browser says this launch loads into a frame of another site (the LMS's iframe, the LMS on
    another site): there the session cookie is a third-party cookie, which browsers block. In a frame of the same
    site (lms.example.edu framing lab.example.edu) it is kept, and the pages open in the frame."""
    return (request.headers.get("sec-fetch-dest") in ("iframe", "frame")
            and request.headers.get("sec-fetch-site") not in ("same-origin", "same-site"))


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
async def required_form(request: Request, what: str, fields: tuple[str, ...], how: str = ""):
    """The request's form (or query) fields, or the 422 page naming the one missing or the size."""
    params = await form_params(request)
    if params is None:
        return refused_page(request, 422, "too_large", f"{what} is too large")
    for field in fields:
        if not params.get(field):
            return refused_page(request, 422, f"no_{field}", f"{what} has no {field}{how}")
    return params


@router.api_route("/lti/login", methods=["GET", "POST"], include_in_schema=False)
async def login(request: Request):
    params = await required_form(request, "the login request", ("iss", "login_hint"))
    if not isinstance(params, dict):
        return params
    return await run_in_threadpool(_login, request, params)


def _login(request: Request, params: dict[str, str]):
    lti_classroom.sweep_expired()
    oidc = lti_adapters.login(request, params, store())
    try:
        return oidc.pass_params_to_launch({"target": params.get("target_link_uri") or ""}).redirect(
            f"{base_url(request)}/lti/launch")
    except (OIDCException, LtiException) as error:
        return refused_page(request, 403, "unknown_issuer", f"no platform with this issuer (and client id) is "
                                                            f"registered here ({error})")


@router.post("/lti/launch", include_in_schema=False)
async def launch(request: Request):
    params = await required_form(request, "the launch", ("id_token", "state"), " (post it as a form field)")
    if not isinstance(params, dict):
        return params
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
        student = lti_classroom.enter_learner(record, resolved, platform, claims)
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
                    jwt=deep.get_response_jwt([resource]))
    return framed_by(response, origins, form_to=origin(return_url))


router.include_router(lti_registration.router)     # /lti/register/<code> and /api/v1/lti
