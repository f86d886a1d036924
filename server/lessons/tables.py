"""Tables of the sources as data (content/tables/*.json) and the pickers they give a scene.

A toggle written ``{"table": "<name>", "picker": "<key>"}`` in a variant is the picker ``<key>`` of
content/tables/<name>.json: a drop-down list (``display: "select"``) of the table's rows it names, each setting
the request path ``param`` to the row's ``value``, labelled with the row's label, its default the row named
``default``; the reference's own keys (an ``id``) replace the picker's.  A table, picker or row that does not
exist, or two rows of one picker with the same value (the list could not tell them apart), is refused with
the scene file and the variant named.

A panel ``{"kind": "reference_table", "table": "<name>"}`` shows the table's ``reference`` (its title, note,
columns and rows, read on the page without an answer): its parts are copied into the panel, the panel's own keys
kept.
"""
from __future__ import annotations

from .content_errors import ContentError


def with_table_pickers(variant: dict, where: str, tables: dict[str, dict]) -> dict:
    """The variant with each toggle that names a table's picker written out in full."""
    if not isinstance(variant.get("toggles"), list):
        return variant
    return variant | {"toggles": [_picker(entry, f"{where}: variant {variant.get('id')}", tables)
                                  for entry in variant["toggles"]]}


def _picker(entry, where: str, tables: dict[str, dict]):
    if not isinstance(entry, dict) or "table" not in entry:
        return entry
    table = tables.get(entry["table"])
    picker = (table or {}).get("pickers", {}).get(entry.get("picker"))
    if picker is None:
        raise ContentError(f"{where}: toggle {entry.get('id', entry.get('picker'))}: content/tables has no picker "
                           f"{entry.get('picker')!r} in {entry['table']!r}")
    missing = [key for key in (*picker["rows"], picker["default"]) if key not in table["rows"]]
    if missing:
        raise ContentError(f"{where}: picker {entry['picker']} of {entry['table']}: no rows {', '.join(missing)}")
    rows = [table["rows"][key] for key in picker["rows"]]
    values = [row["value"] for row in rows]
    if len(set(values)) < len(values):
        raise ContentError(f"{where}: picker {entry['picker']} of {entry['table']}: two rows with one value")
    toggle = {"id": entry["picker"], "param": picker["param"], "label": picker["label"], "options": values,
              "option_labels": [row["label"] for row in rows], "default": table["rows"][picker["default"]]["value"],
              "display": "select"}
    return toggle | {key: value for key, value in entry.items() if key not in ("table", "picker")}


def with_reference_tables(panels, where: str, tables: dict[str, dict]):
    """The scene's panels with each reference_table panel's table written in (module docstring)."""
    if not isinstance(panels, dict):
        return panels
    written = {}
    for name, panel in panels.items():
        if isinstance(panel, dict) and panel.get("kind") == "reference_table":
            reference = (tables.get(panel.get("table")) or {}).get("reference")
            if reference is None:
                raise ContentError(f"{where}: panel {name}: content/tables has no reference table "
                                   f"{panel.get('table')!r}")
            panel = reference | panel
        written[name] = panel
    return written
