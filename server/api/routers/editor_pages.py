"""The mechanism editor's page (/editor): build a mechanism from class-II structural groups in the browser,
see its structural analysis, animate it and draw its velocity and acceleration plans.  The page computes
through POST /api/v1/kinematics (mechanism "general"); here it only gets its texts and the presets (with their masses, loads and motor where they have them)."""
import json

from fastapi import APIRouter, Request
from fastapi.responses import HTMLResponse

from ...core.structure.presets import presets
from .pages import _context, templates

router = APIRouter(include_in_schema=False)


@router.get("/editor", response_class=HTMLResponse)
def editor_page(request: Request, lang: str | None = None):
    context = _context(request, lang)
    choices = [{"name": name, "title": p["title"][context["lang"]], "source": p["source"][context["lang"]],
                "linkage": p["linkage"], "dynamics": p.get("dynamics")} for name, p in presets().items()]
    return templates.TemplateResponse(request, "editor.html", context | {"presets_json": json.dumps(
        choices, ensure_ascii=False)})
