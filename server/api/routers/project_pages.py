"""The course project's page (/project): a student's mechanism (the editor's address m, d, or a preset) with its
design data and the project's settings, and the whole project as one report to print (Chaika–Vasylenko §3.4).
Every number of the report is from POST /api/v1/course-project; here the page gets only its texts, the presets
(with their masses, loads and machine where they have them) and its language."""
import json

from fastapi import APIRouter, Request
from fastapi.responses import HTMLResponse

from ...core.structure.presets import presets
from .pages import _context, templates

router = APIRouter(include_in_schema=False)


@router.get("/project", response_class=HTMLResponse)
def project_page(request: Request, lang: str | None = None):
    context = _context(request, lang)
    choices = [{"name": name, "title": p["title"][context["lang"]], "source": p["source"][context["lang"]],
                "linkage": p["linkage"], "dynamics": p.get("dynamics")} for name, p in presets().items()
               if p["linkage"].get("input", {}).get("kind", "crank") == "crank"]   # the project's input is a crank
    return templates.TemplateResponse(request, "course_project.html", context | {
        "presets_json": json.dumps(choices, ensure_ascii=False)})
