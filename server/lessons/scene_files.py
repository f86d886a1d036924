"""A scene file as written and as the app reads it: shared slider definitions and variants that inherit.

Three kinds of reference keep content/scenes/*.json free of copies (adding a lesson still needs no Python):

- **A shared slider.** A slider (or a variant's ``overlay``) written ``{"use": "<name>", …}`` is the definition
  ``<name>`` of content/sliders.json with the reference's own keys replacing the definition's (a scene's range,
  default, or the path it sets: ``{"use": "crank_rod_ratio", "min": 1.05, "default": 4}``).
- **A variant that extends another** of the same scene, ``{"extends": "<variant id>", …}``: the named variant
  (itself resolved first) with the variant's own keys replacing its keys, except ``request``, which is merged
  key by key (a request's top-level key, e.g. ``"motor"``, is replaced whole). A variant that names sliders
  names all of them; one that does not keeps the other's.
- **A mechanism preset** of content/mechanisms/, ``"preset": {"name": "shaping_machine", "request": {"linkage":
  "linkage", "masses": "dynamics.masses"}}``: each named key of the variant's ``request`` is the value at that
  dotted path of the preset, with the variant's own ``request`` merged over it key by key at every depth (its
  ``"masses": {"friction": 0.1}`` adds to the preset's masses). The scene names the preset; the linkage and the
  masses stay written once, in the preset.

- **A mechanism from the page address**, ``"address": {"request": {"linkage": "m", "masses": "d.masses", …},
  "example": "shaping_machine"}``: the variant computes the reader's own mechanism, carried in the address by
  the editor (``m``: the linkage, ``d``: its masses, loads and motor, as a preset's "dynamics"). Each named key of
  the request is the value at that dotted path of the address's documents {"m": …, "d": …}, the variant's own
  ``request`` merged over it as for a preset (``addressed``); a slider with ``"relative": {"min", "max", "step",
  "default"}`` takes those as multiples of the request's value at its ``param`` (a motor's M₀ from 0.5 to 2 times
  the mechanism's own; only "default": the flywheel's [δ] from the address, its range the scene's). The page does the same with the documents in its address (dynamics_scene.js) and says in
  words how to get a mechanism where there is none; the server, which has no address, resolves the variant with
  the preset named ``example`` (assignments do not offer such a variant).

A reference to nothing, a loop of variants or a variant without an id is refused with the scene file, the
variant and the slider named (``ContentError``).
"""
from __future__ import annotations

import copy

from .content_errors import ContentError
from .dotted_paths import path_value
from .tables import with_reference_tables, with_table_pickers

MERGED_KEYS = ("request",)   # merged key by key under "extends"; every other key is replaced whole


def resolved_scene(raw: dict, where: str, shared: dict[str, dict], presets: dict[str, dict] | None = None,
                   tables: dict[str, dict] | None = None) -> dict:
    """The scene ``raw`` (read from the file ``where``) with every "extends", "use", "preset" and table picker
    resolved (``presets``: content/mechanisms/*.json by name; ``tables``: content/tables/*.json, tables.py)."""
    variants = raw.get("variants", [])
    by_id = {}
    for index, variant in enumerate(variants):
        if not isinstance(variant, dict) or not isinstance(variant.get("id"), str):
            raise ContentError(f"{where}: variant {index}: no id")
        if variant["id"] in by_id:
            raise ContentError(f"{where}: variant {variant['id']}: two variants with this id")
        by_id[variant["id"]] = variant
    resolved = [copy.deepcopy(with_table_pickers(_with_example(_with_preset(_with_shared_sliders(
        _inherited(v, by_id, where, ()), where, shared), where, presets or {}), where, presets or {}), where,
        tables or {})) for v in variants]                   # each its own objects: inherited parts are not shared
    panels = {"panels": with_reference_tables(raw["panels"], where, tables or {})} if "panels" in raw else {}
    return copy.deepcopy(raw | {"variants": []} | panels) | {"variants": resolved}


def _inherited(variant: dict, by_id: dict[str, dict], where: str, chain: tuple[str, ...]) -> dict:
    """The variant with what it inherits through "extends" (a chain of any length)."""
    base_id = variant.get("extends")
    if base_id is None:
        return variant
    name = variant["id"]
    if base_id == name or base_id in chain:
        loop = " → ".join((*chain, name, base_id))
        raise ContentError(f"{where}: variant {name}: extends {base_id} in a loop ({loop})")
    if base_id not in by_id:
        raise ContentError(f"{where}: variant {name}: extends {base_id!r}, which is no variant of this scene "
                           f"({', '.join(by_id)})")
    base = _inherited(by_id[base_id], by_id, where, (*chain, name))
    own = {key: value for key, value in variant.items() if key != "extends"}
    merged = base | own
    for key in MERGED_KEYS:
        if isinstance(base.get(key), dict) and isinstance(own.get(key), dict):
            merged[key] = base[key] | own[key]
    return merged


def _with_shared_sliders(variant: dict, where: str, shared: dict[str, dict]) -> dict:
    resolved = dict(variant)
    if isinstance(variant.get("sliders"), list):
        resolved["sliders"] = [_slider(entry, f"{where}: variant {variant['id']}, slider", index, shared)
                               for index, entry in enumerate(variant["sliders"])]
    if isinstance(variant.get("overlay"), dict):
        resolved["overlay"] = _slider(variant["overlay"], f"{where}: variant {variant['id']}, overlay", 0, shared)
    return resolved


def _with_preset(variant: dict, where: str, presets: dict[str, dict]) -> dict:
    """The variant with its request's keys taken from the mechanism preset it names, its own merged over them."""
    reference = variant.get("preset")
    if reference is None:
        return variant
    name = reference.get("name") if isinstance(reference, dict) else None
    if name not in presets:
        raise ContentError(f"{where}: variant {variant['id']}: preset {name!r} is no file of content/mechanisms "
                           f"({', '.join(sorted(presets))})")
    try:
        taken = _taken(presets[name], reference.get("request", {}))
    except KeyError as missing:
        path, key = missing.args
        raise ContentError(f"{where}: variant {variant['id']}: preset {name} has no {path!r} (for {key})") from None
    return variant | {"request": _merged(taken, variant.get("request", {}))}


def _taken(documents: dict, paths: dict) -> dict:
    """Each request key's value (a copy) at its dotted path of documents; KeyError(path, key) where one is
    missing."""
    taken = {}
    for key, path in paths.items():
        value = documents
        for step in str(path).split("."):
            if not isinstance(value, dict) or step not in value:
                raise KeyError(path, key)
            value = value[step]
        taken[key] = copy.deepcopy(value)
    return taken


def _with_example(variant: dict, where: str, presets: dict[str, dict]) -> dict:
    """A variant that takes its mechanism from the page address, resolved with its example preset's documents."""
    reference = variant.get("address")
    if reference is None:
        return variant
    name = reference.get("example") if isinstance(reference, dict) else None
    if name not in presets or "dynamics" not in presets[name]:
        raise ContentError(f"{where}: variant {variant['id']}: address example {name!r} is no preset of "
                           f"content/mechanisms with dynamics")
    try:
        return addressed(variant, example_documents(presets[name]))
    except KeyError as missing:
        raise ContentError(f"{where}: variant {variant['id']}: the address has no {missing.args[0]!r}") from None


def example_documents(preset: dict) -> dict:
    """The address's documents as the editor writes them for a preset: m the linkage, d its dynamics."""
    return {"m": preset["linkage"], "d": preset["dynamics"]}


def addressed(variant: dict, documents: dict) -> dict:
    """The variant with its request's keys taken from the address's documents (``address.request``: key → dotted
    path), its own ``address.own`` request (kept from the file) merged over them, and its relative sliders'
    ranges as multiples of the request's values. KeyError(path, key) names a path the documents lack."""
    reference = variant["address"]
    own = reference.get("own", variant.get("request", {}))
    request = _merged(_taken(documents, reference.get("request", {})), own)
    sliders = [_relative(slider, request) for slider in variant.get("sliders", [])]
    return variant | {"address": reference | {"own": own}, "request": request, "sliders": sliders}


def _relative(slider, request: dict):
    """A slider whose range is relative to the request's value at its path, as absolute numbers."""
    if not isinstance(slider, dict) or not isinstance(slider.get("relative"), dict):
        return slider
    value = path_value(request, slider["param"])
    return slider | {key: float(f"{factor * value:.6g}") for key, factor in slider["relative"].items()}


def _merged(base: dict, own: dict) -> dict:
    """base with own's keys replacing its keys, dictionaries merged key by key at every depth."""
    out = dict(base)
    for key, value in own.items():
        out[key] = _merged(base[key], value) if isinstance(base.get(key), dict) and isinstance(value, dict) else value
    return out


def _slider(entry, where: str, index: int, shared: dict[str, dict]):
    """The slider a scene writes: itself, or the shared definition it uses with its own keys replacing."""
    if not isinstance(entry, dict) or "use" not in entry:
        return entry
    name = entry["use"]
    if not isinstance(name, str) or name not in shared:
        raise ContentError(f"{where} {entry.get('id', index)}: uses {name!r}, which content/sliders.json "
                           f"does not define")
    return shared[name] | {key: value for key, value in entry.items() if key != "use"}
