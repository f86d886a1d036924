"""The mechanism editor's page (/editor): build a mechanism from class-II structural groups in the browser,
see its structural analysis, animate it and draw its velocity and acceleration plans.  The page computes
through POST /api/v1/kinematics (mechanism "general"); here it only gets its texts, the presets (with their masses, loads and motor where they have them) and the
scenes with a variant that takes the mechanism from the address (content: "address"), which it opens."""
import json

from fastapi import APIRouter, Request
from fastapi.responses import HTMLResponse

from ...core.structure.presets import presets
from ...lessons.scenes import scenes
from .pages import _context, templates

router = APIRouter(include_in_schema=False)


@router.get("/editor", response_class=HTMLResponse)
def editor_page(request: Request, lang: str | None = None):
    context = _context(request, lang)
    choices = [{"name": name, "title": p["title"][context["lang"]], "source": p["source"][context["lang"]],
                "linkage": p["linkage"], "dynamics": p.get("dynamics")} for name, p in presets().items()]
    own = [{"scene": scene.id, "variant": variant.id, "title": scene.title[context["lang"]]}
           for scene in sorted(scenes().values(), key=lambda scene: scene.order)
           for variant in scene.variants if variant.address is not None]     # the scenes that take one's own mechanism
    return templates.TemplateResponse(request, "editor.html", context | {
        "presets_json": json.dumps(choices, ensure_ascii=False), "own_scenes_json": json.dumps(own, ensure_ascii=False)})
