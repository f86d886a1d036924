"""Assignment pages: the instructor's form (from any scene with questions), the student's page (the
scene with their variant and the questions), and the instructor's private results page."""
from __future__ import annotations

from fastapi import APIRouter, HTTPException, Request
from fastapi.responses import HTMLResponse

from ...classroom.variants import SpecError
from .. import assignments
from ..answers import student_scene, unlocked_predictions
from ..assignment_store import store
from ...classroom.visibility import public_views
from ...lessons.scenes import scenes
from .pages import scene_context, templates, _context

router = APIRouter(include_in_schema=False)


@router.get("/scenes/{scene_id}/assign", response_class=HTMLResponse)
def builder(request: Request, scene_id: str, lang: str | None = None, variant: str | None = None):
    """The instructor's form, opened with the scene's variant and slider values from the page address."""
    scene = scenes().get(scene_id)
    if scene is None or not scene.questions:
        raise HTTPException(404, f"no scene '{scene_id}' with questions")
    chosen = next((v for v in scene.variants if v.id == variant), None)
    offered = [v for v in scene.variants if any(not q.variants or v.id in q.variants for q in scene.questions)]
    chosen = chosen if chosen in offered else offered[0]
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
        "shown": {q.id: public_views(scene, chosen, q) for q in questions}})


@router.get("/assignments/{assignment_id}", response_class=HTMLResponse)
def student_page(request: Request, assignment_id: str, lang: str | None = None, student: str | None = None):
    """Without a name: who are you? With one: the scene at the student's variant, and the questions."""
    record, resolved = assignments.load(assignment_id)
    context = _context(request, lang)
    about = assignments.info(record, resolved, context["lang"])
    name = " ".join((student or "").split())
    if not name:
        return templates.TemplateResponse(request, "assignment_start.html", context | {"assignment": about})
    try:
        enrolled = assignments.enrol(record, resolved, name)
    except SpecError:
        return templates.TemplateResponse(request, "assignment_start.html", context | {"assignment": about})
    shown = student_scene(resolved, enrolled.parameters,
                          unlocked_predictions(resolved, store().submissions(record.id, enrolled.key)))
    page = {"id": record.id, "student": enrolled.name, "variant": enrolled.variant + 1,
            "variants": resolved.count, "values": enrolled.parameters, "info": about.model_dump()}
    return templates.TemplateResponse(request, "scene.html", scene_context(request, context, shown) | {
        "assignment": page})


@router.get("/assignments/{assignment_id}/results/{token}", response_class=HTMLResponse)
def results_page(request: Request, assignment_id: str, token: str, lang: str | None = None):
    record, resolved = assignments.load(assignment_id)
    assignments.check_token(record, token)
    context = _context(request, lang)
    return templates.TemplateResponse(request, "assignment_results.html", context | {
        "assignment": assignments.info(record, resolved, context["lang"]), "token": token,
        "sliders": resolved.variant.sliders, "toggles": resolved.variant.toggles,
        "rows": assignments.result_rows(record, resolved)})
