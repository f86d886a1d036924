"""Where a course-project variant opens: the course-project page (/project) and the mechanism editor (/editor),
with the variant's linkage and design data in the address as those pages read it (web/static/js/course_project/
model/address.js): ``m`` = base64url of the linkage's JSON, ``d`` = base64url of {masses, inertias, flywheel:
{omega_mean, delta}} (the editor's form of the design data), ``p`` = base64url of the project's settings
{positions, start, output, chosen, drawn, title}."""
from __future__ import annotations

import base64
import json
from urllib.parse import urlencode

from .requests import project_body
from .scenes import Variant


def base64url(document) -> str:
    """A JSON document as it rides in a page address (RFC 4648 §5, no padding)."""
    text = json.dumps(document, ensure_ascii=False, separators=(",", ":"))
    return base64.urlsafe_b64encode(text.encode("utf-8")).decode("ascii").rstrip("=")


def read_base64url(text: str):
    """The JSON document of base64url text (the inverse of base64url)."""
    return json.loads(base64.urlsafe_b64decode(text + "=" * (-len(text) % 4)).decode("utf-8"))


def project_documents(variant: Variant, values: dict, title: dict | None = None) -> dict:
    """The address's documents {m, d, p} of a course-project variant at the slider values."""
    body = project_body(variant, values)
    dynamics = {"masses": body["masses"], "inertias": body.get("inertias", {}),
                "flywheel": {"omega_mean": body["omega_mean"], "delta": body["delta"]}}
    settings = {"positions": body.get("positions", 12), "start": body.get("start"), "output": body.get("output"),
                "chosen": body.get("chosen"), "drawn": None,
                "title": {"student": "", "group": "", "variant": ""} | (title or {})}
    return {"m": body["linkage"], "d": dynamics, "p": settings}


def project_links(variant: Variant, values: dict, lang: str, title: dict | None = None) -> dict[str, str]:
    """{"project": /project?…, "editor": /editor?…} opening the variant at the slider values."""
    documents = project_documents(variant, values, title)
    mechanism = {"lang": lang, "m": base64url(documents["m"]), "d": base64url(documents["d"])}
    return {"project": "/project?" + urlencode(mechanism | {"p": base64url(documents["p"])}),
            "editor": "/editor?" + urlencode(mechanism)}


def address_documents(m: str | None, d: str | None) -> dict | None:
    """The documents {m, d} of a page address (base64url JSON objects, as the editor writes them), or None where
    either is missing or unreadable."""
    try:
        documents = {"m": read_base64url(m), "d": read_base64url(d)} if m and d else None
    except ValueError:
        return None
    return documents if documents and all(isinstance(v, dict) for v in documents.values()) else None
