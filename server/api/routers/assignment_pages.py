"""Assignment pages: the instructor's form (from any scene with questions), the student's page (who are you?
then the personal link, shown once, then the scene with their variant and the questions), the personal link
that lets a student in on any device, and the instructor's private results page."""
from __future__ import annotations

from urllib.parse import parse_qs

from fastapi import APIRouter, Depends, HTTPException, Request
from fastapi.responses import HTMLResponse, RedirectResponse
from starlette.concurrency import run_in_threadpool

from ...classroom.identity import personal_path
from ...classroom.names import NameRefused
from ...classroom import assignments
from ...classroom.answers import student_scene, unlocked_predictions
from ...classroom.assignment_store import store
from ..errors import NAME_STATUS
from ..student_secret import forget, from_another_site, hand_over, keep_private, sent_secret
from ...classroom.visibility import public_views
from ...lessons.scenes import scenes
from .pages import scene_context, templates, _context
from ..scene_urls import renamed
from ...classroom.spec import OwnMechanism
from ...lessons.project_links import address_documents, project_links
from ...lessons.requests import scene_variant

NAME_FIELD = "student"
MAX_FORM_BYTES = 4096

router = APIRouter(include_in_schema=False)


@router.get("/scenes/{scene_id}/assign", response_class=HTMLResponse)
def builder(request: Request, scene_id: str, lang: str | None = None, variant: str | None = None):
    """The instructor's form, opened with the scene's variant and slider values from the page address."""
    scene = scenes().get(scene_id)
    if scene is not None and (moved := renamed(request, scene_id, scene.id)):
        return moved
    if scene is None or not scene.questions:
        raise HTTPException(404, f"no scene '{scene_id}' with questions")
    chosen = next((v for v in scene.variants if v.id == variant), None)
    own = address_documents(request.query_params.get("m"), request.query_params.get("d")) \
        if scene.kind == "project" else None           # a course project of the editor's mechanism (address m, d)
    offered = [v for v in scene.variants if (v.address is None or own is not None)   # else an address is no assignment
               and any(not q.variants or v.id in q.variants for q in scene.questions)]
    chosen = chosen if chosen in offered else offered[0]
    if chosen.address is not None:
        try:
            chosen = scene_variant(scene.id, chosen.id, OwnMechanism.model_validate(own).documents())
        except (KeyError, ValueError):
            raise HTTPException(422, "the address's mechanism cannot make this variant: open it from the editor")
    values = {}
    for control in [*chosen.sliders, *chosen.toggles]:
        text = request.query_params.get(control.id)
        values[control.id] = control.default
        if text is not None:
            try:
                values[control.id] = float(text) if control in chosen.sliders else type(control.default)(text)
            except ValueError:
                pass
    questions = [q for q in scene.questions if not q.variants or chosen.id in q.variants]
    return templates.TemplateResponse(request, "assignment_builder.html", _context(request, lang) | {
        "scene": scene, "variant": chosen, "variants": offered, "values": values, "questions": questions,
        "shown": {q.id: public_views(scene, chosen, q) for q in questions},
        "own_mechanism": own if chosen.address is not None else None})


def start_page(request: Request, context: dict, about, status: int = 200, **state) -> HTMLResponse:
    """Who are you? (with the reason a try was refused, or the personal link once registered)."""
    return templates.TemplateResponse(request, "assignment_start.html", context | {"assignment": about} | state,
                                      status_code=status)


def refusal_text(t: dict, refused: NameRefused) -> str:
    """A refused name in the reader's language: content/i18n's assignment_error_<code> with its details."""
    about = dict(refused.about)
    if "script" in about:
        about["script"] = t.get(f"assignment_script_{about['script'].lower()}", about["script"])
    return t.get(f"assignment_error_{refused.code}", refused.reason).format(**about)


@router.get("/assignments/{assignment_id}", response_class=HTMLResponse)
def student_page(request: Request, assignment_id: str, lang: str | None = None,
                 secret: str | None = Depends(sent_secret)):
    """The student's variant when the request carries their secret (the cookie); else who are you?"""
    record, resolved = assignments.load(assignment_id)
    context = _context(request, lang)
    about = assignments.info(record, resolved, context["lang"])
    student = assignments.identify(record, secret)
    if student is None:
        response = start_page(request, context, about, error=context["t"]["assignment_link_invalid"] if secret else None)
        if secret:
            forget(response, request, record.id)
        return response
    shown = student_scene(resolved, student.parameters,
                          unlocked_predictions(resolved, store().submissions(record.id, student.key)))
    page = {"id": record.id, "student": student.name, "variant": student.variant + 1,
            "variants": resolved.count, "values": student.parameters, "info": about.model_dump()}
    if resolved.scene.kind == "project":             # the variant opens on /project and in the editor
        page["links"] = project_links(resolved.variant, student.parameters, context["lang"],
                                      {"student": student.name, "variant": str(student.variant + 1)})
    return templates.TemplateResponse(request, "scene.html", scene_context(request, context, shown) | {
        "assignment": page})


@router.post("/assignments/{assignment_id}", response_class=HTMLResponse)
async def register(request: Request, assignment_id: str, lang: str | None = None,
                   sent: str | None = Depends(sent_secret)):
    """The name form: register, set the cookie, and show the personal link once."""
    body = await request.body()
    form = parse_qs(body[:MAX_FORM_BYTES].decode("utf-8", "replace"))
    name = (form.get(NAME_FIELD) or [""])[0]
    return await run_in_threadpool(registered_page, request, assignment_id, lang, name, sent)


def registered_page(request: Request, assignment_id: str, lang: str | None, name: str,
                    sent: str | None) -> HTMLResponse:
    record, resolved = assignments.load(assignment_id)
    context = _context(request, lang)
    t = context["t"]
    about = assignments.info(record, resolved, context["lang"])
    if from_another_site(request, form=True):
        return start_page(request, context, about, 403, error=t["assignment_error_cross_site"], name=name)
    client = request.client.host if request.client else "unknown"
    try:
        student, secret = assignments.register(record, resolved, name, assignments.identify(record, sent), client)
    except NameRefused as refused:
        page = start_page(request, context, about, NAME_STATUS[refused.code],
                          error=refusal_text(t, refused), name=name)
        if refused.code == "too_many_registrations":
            page.headers["Retry-After"] = str(assignments.REGISTRATION_WINDOW_S)
        return page
    if secret is None:                                   # already this student on this browser
        return RedirectResponse(f"/assignments/{record.id}?lang={context['lang']}", status_code=303)
    link = str(request.base_url).rstrip("/") + personal_path(record.id, secret) + f"?lang={context['lang']}"
    response = keep_private(start_page(request, context, about, 201, registered=student.name,
                                       personal_link=link))      # the secret: kept by no cache
    hand_over(response, request, record.id, secret)
    return response


@router.get("/assignments/{assignment_id}/me/{secret}", response_class=HTMLResponse)
def personal_link(request: Request, assignment_id: str, secret: str, lang: str | None = None):
    """The personal link: on any device, set the cookie and go to the student's variant."""
    record, resolved = assignments.load(assignment_id)
    context = _context(request, lang)
    if assignments.identify(record, secret) is None:
        about = assignments.info(record, resolved, context["lang"])
        return keep_private(start_page(request, context, about, 404, error=context["t"]["assignment_link_invalid"]))
    response = keep_private(RedirectResponse(f"/assignments/{record.id}?lang={context['lang']}", status_code=303))
    hand_over(response, request, record.id, secret)
    return response


@router.post("/assignments/{assignment_id}/leave")
def leave(request: Request, assignment_id: str, lang: str | None = None):
    """Not me: forget the secret on this browser (the personal link keeps working)."""
    record, _ = assignments.load(assignment_id)
    response = RedirectResponse(f"/assignments/{record.id}?lang={_context(request, lang)['lang']}", status_code=303)
    forget(response, request, record.id)
    return response


@router.get("/assignments/{assignment_id}/results/{token}", response_class=HTMLResponse)
def results_page(request: Request, assignment_id: str, token: str, lang: str | None = None):
    record, resolved = assignments.load(assignment_id)
    assignments.check_token(record, token)
    context = _context(request, lang)
    return keep_private(templates.TemplateResponse(request, "assignment_results.html", context | {
        "assignment": assignments.info(record, resolved, context["lang"]), "token": token,
        "sliders": resolved.variant.sliders, "toggles": resolved.variant.toggles,
        "rows": assignments.result_rows(record, resolved), "roster_locked": record.roster_locked}))
