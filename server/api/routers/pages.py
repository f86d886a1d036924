"""HTML pages: the start page listing the scenes, one page per scene, and the measurements page (the
work–precision tables of bench/results)."""
import unicodedata

from fastapi import APIRouter, HTTPException, Request
from fastapi.responses import FileResponse, HTMLResponse
from fastapi.templating import Jinja2Templates
from markupsafe import Markup, escape

from ...lessons.scenes import LANGUAGES, interface_texts, language, scenes
from ...paths import BENCH_RESULTS, WEB
from ..bench_pages import measurements_html
from ..scene_urls import renamed
from ..messages import signed

templates = Jinja2Templates(directory=WEB / "templates")
MEASUREMENTS = BENCH_RESULTS / "work_precision.md"


def _lowers(char: str) -> bool:
    """A character of a run after "_" or "^": a letter, a decimal digit or a combining mark (\\p{L}, \\p{Nd},
    \\p{M} in web/static/js/common/view/notation.js)."""
    category = unicodedata.category(char)
    return category[0] in "LM" or category == "Nd"


def notation_parts(text: str) -> list[tuple[str, str]]:
    """text split into (run, shift) with shift "", "sub" or "sup": the markup of web/static/js/common/view/notation.js
    ("M_c0", "A_{P,k}", "R^{1/3}", "\\_" a plain underscore), read the same way."""
    parts, plain, i = [], "", 0
    while i < len(text):
        char = text[i]
        if char == "\\" and text[i + 1:i + 2] in ("_", "^"):
            plain, i = plain + text[i + 1], i + 2
            continue
        if char in "_^" and i > 0:
            if text[i + 1:i + 2] == "{" and "}" in text[i + 2:] and "{" not in text[i + 2:text.index("}", i + 2)]:
                end = text.index("}", i + 2)
                run, after = text[i + 2:end], end + 1
            else:
                end = i + 1
                while end < len(text) and _lowers(text[end]):
                    end += 1
                run, after = text[i + 1:end], end
            if run or after > i + 1:
                parts += [(plain, "")] if plain else []
                parts.append((run, "sub" if char == "_" else "sup"))
                plain, i = "", after
                continue
        plain, i = plain + char, i + 1
    return parts + ([(plain, "")] if plain else [])


def notation(text) -> Markup:
    """Jinja filter: an interface text with its subscripts and superscripts as <sub>/<sup>, everything else
    escaped (autoescape stays on)."""
    return Markup("").join(escape(run) if not shift else Markup(f"<{shift}>{escape(run)}</{shift}>")
                           for run, shift in notation_parts(str(text)))


def plain(text) -> str:
    """Jinja filter: an interface text where only plain text can stand (a title attribute), as the page's
    aria-labels write it (csv_export.plain_label: "I_м" → "Iм", "u_31" → "u₃₁")."""
    from ..csv_export import plain_label                       # imported here: csv_export imports this module
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
