"""Dotted paths into request bodies ("masses.forces.0.working"): a number in the path indexes a list.
The page's twin is web/static/js/common/model/dotted_paths.js."""
from __future__ import annotations


def path_key(holder, key: str):
    """The key of a dotted path as its holder takes it: a list's item by its index ("forces.0"), else the name."""
    return int(key) if isinstance(holder, list) and key.isdigit() else key


def path_value(body: dict, path: str):
    """The value at a dotted path."""
    for key in path.split("."):
        body = body[path_key(body, key)]
    return body


def set_path(body: dict, path: str, value) -> None:
    """Put value at a dotted path, making the objects on the way (a list on the way must hold the index)."""
    *keys, last = path.split(".")
    for key in keys:
        body = body[path_key(body, key)] if isinstance(body, list) else body.setdefault(key, {})
    body[path_key(body, last)] = value
