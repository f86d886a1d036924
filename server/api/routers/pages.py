"""HTML pages: the start page listing the scenes, one page per scene, and the measurements page (the
work–precision tables of bench/results)."""
from fastapi import APIRouter, HTTPException, Request
from fastapi.responses import FileResponse, HTMLResponse
from fastapi.templating import Jinja2Templates
from markupsafe import Markup, escape

from ...lessons.markup import notation_parts, plain_label
from ...lessons.scenes import LANGUAGES, interface_texts, language, scenes
from ...paths import BENCH_RESULTS, WEB
from ..bench_pages import measurements_html
from ..scene_urls import renamed
from ..messages import signed

templates = Jinja2Templates(directory=WEB / "templates")
MEASUREMENTS = BENCH_RESULTS / "work_precision.md"


def notation(text) -> Markup:
    """Jinja filter: an interface text with its subscripts and superscripts as <sub>/<sup>, everything else
    escaped (autoescape stays on)."""
    return Markup("").join(escape(run) if not shift else Markup(f"<{shift}>{escape(run)}</{shift}>")
                           for run, shift in notation_parts(str(text)))


def plain(text) -> str:
    """Jinja filter: an interface text where only plain text can stand (a title attribute), as the page's
    aria-labels write it (lessons.markup.plain_label: "I_м" → "Iм", "u_31" → "u₃₁")."""
    return plain_label(str(text))


def decimal(value, lang: str, digits: int = 6) -> str:
    """A number for a table in the reader's language: 6 significant digits, a decimal comma in ru/uk, a true
    minus sign and a power of ten written out ("−1,5·10⁻⁷", messages.signed)."""
    if not isinstance(value, (int, float)) or isinstance(value, bool):
        return str(value)
    text = f"{value:.{digits}g}"
    return signed(text if lang == "en" else text.replace(".", ","))


templates.env.filters["decimal"] = decimal
templates.env.filters["notation"] = notation
templates.env.filters["plain"] = plain
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
    return FileResponse(WEB / "static" / "img" / "favicon.svg", media_type="image/svg+xml",
                        headers={"Cache-Control": "public, max-age=86400"})


@router.get("/scenes/{scene_id}", response_class=HTMLResponse)
def scene_page(request: Request, scene_id: str, lang: str | None = None):
    scene = scenes().get(scene_id)
    if scene is None:
        raise HTTPException(404, f"no scene '{scene_id}'")
    if moved := renamed(request, scene_id, scene.id):
        return moved
    return templates.TemplateResponse(request, "scene.html", scene_context(request, _context(request, lang), scene))


def scene_context(request: Request, context: dict, scene) -> dict:
    """What scene.html needs to show scene (plotly only when a panel plots)."""
    needs_plotly = any(panel.get("kind") == "plot" for panel in scene.panels.values())
    return context | {"scene": scene, "scene_json": scene.model_dump_json(), "needs_plotly": needs_plotly,
                      "assignment": None}


@router.get("/measurements", response_class=HTMLResponse)
def measurements(request: Request, lang: str | None = None):
    """The full work–precision tables that the scenes' small live studies point to, in the reader's words."""
    context = _context(request, lang)
    tables = measurements_html(MEASUREMENTS.read_text(encoding="utf-8"), context["t"], context["lang"], notation,
                                notation_parts)
    return templates.TemplateResponse(request, "measurements.html", context | {"tables": tables})
