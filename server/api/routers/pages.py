"""HTML pages: the start page listing the scenes, and one page per scene."""
from pathlib import Path

from fastapi import APIRouter, HTTPException, Request
from fastapi.responses import FileResponse, HTMLResponse
from fastapi.templating import Jinja2Templates

from ...lessons.scenes import LANGUAGES, REPO_ROOT, interface_texts, language, scenes

templates = Jinja2Templates(directory=Path(REPO_ROOT, "web", "templates"))


def decimal(value, lang: str, digits: int = 6) -> str:
    """A number for a table in the reader's language: 6 significant digits, a decimal comma in ru/uk."""
    if not isinstance(value, (int, float)) or isinstance(value, bool):
        return str(value)
    text = f"{value:.{digits}g}"
    return text if lang == "en" else text.replace(".", ",")


templates.env.filters["decimal"] = decimal
router = APIRouter(include_in_schema=False)


def _context(request: Request, lang: str | None) -> dict:
    lang = language(lang)
    return {"request": request, "lang": lang, "languages": LANGUAGES, "t": interface_texts(lang)}


@router.get("/", response_class=HTMLResponse)
def index(request: Request, lang: str | None = None):
    return templates.TemplateResponse(request, "index.html", _context(request, lang) | {"scenes": scenes().values()})


@router.get("/favicon.ico")
def favicon():
    """The icon a browser asks for on pages without a <link rel="icon"> (the stored figures at /bench-results)."""
    return FileResponse(Path(REPO_ROOT, "web", "static", "img", "favicon.svg"), media_type="image/svg+xml",
                        headers={"Cache-Control": "public, max-age=86400"})


@router.get("/scenes/{scene_id}", response_class=HTMLResponse)
def scene_page(request: Request, scene_id: str, lang: str | None = None):
    scene = scenes().get(scene_id)
    if scene is None:
        raise HTTPException(404, f"no scene '{scene_id}'")
    return templates.TemplateResponse(request, "scene.html", scene_context(request, _context(request, lang), scene))


def scene_context(request: Request, context: dict, scene) -> dict:
    """What scene.html needs to show scene (plotly only when a panel plots)."""
    needs_plotly = any(panel.get("kind") == "plot" for panel in scene.panels.values())
    return context | {"scene": scene, "scene_json": scene.model_dump_json(), "needs_plotly": needs_plotly,
                      "assignment": None}
