"""A family's members as requests: the request with the varied dotted paths set, and the fields (dotted paths)
a preview draws, as a trie that prunes an answer to them."""
from __future__ import annotations

from dataclasses import dataclass


from ..lessons.dotted_paths import path_key

@dataclass(frozen=True)
class Vary:
    """One dotted path of the request set to value × factor (factor converts the slider's units to SI)."""

    path: str
    factor: float


def member_body(request: dict, vary: list[Vary], value: float) -> dict:
    """The request with each varied path set to value × factor: new objects along the varied paths, the rest
    shared with the request (read, never written: the endpoints validate a body into models of their own)."""
    body = dict(request)
    for item in vary:
        *keys, last = item.path.split(".")
        holder = body
        for key in keys:
            step = path_key(holder, key)
            holder[step] = holder = (list if isinstance(holder[step], list) else dict)(holder[step])
        holder[path_key(holder, last)] = value * item.factor
    return body


def shared(body):
    """The family body as the response cache keys it: the varied paths' current values left out (every member
    sets them), so that students whose other values agree share one family wherever their slider stands.
    A body that is not a well-formed family request is returned as it is (validation refuses it later)."""
    try:
        varied = member_body(body["request"], [Vary(item["path"], 0.0) for item in body["vary"]], 0.0)
    except (KeyError, TypeError, AttributeError, IndexError):
        return body
    return body | {"request": varied, "stage": body.get("stage", "full")}


def path_exists(request: dict, path: str) -> bool:
    """Whether the dotted path names a number (not a boolean) in the request."""
    holder = request
    for key in path.split("."):
        if isinstance(holder, list) and key.isdigit() and int(key) < len(holder):
            holder = holder[int(key)]
        elif isinstance(holder, dict) and key in holder:
            holder = holder[key]
        else:
            return False
    return isinstance(holder, (int, float)) and not isinstance(holder, bool)


# ---- fields: the leaves a preview draws ------------------------------------------------------------------

Fields = dict      # a trie of dotted paths: key → True (the whole subtree) or a trie of its keys


def field_trie(fields: list[str]) -> Fields:
    """The dotted paths as a trie; a path under another one named whole adds nothing ("modal", "modal.phi")."""
    trie: Fields = {}
    for path in fields:
        *keys, last = path.split(".")
        node = trie
        for key in keys:
            node = node.setdefault(key, {})
            if node is True:
                break
        else:
            node[last] = True
    return trie


def pruned(answer: dict, trie: Fields) -> dict:
    """The answer's subtrees the trie names (each kept whole, not copied); what it does not hold is left out,
    and so is an object of which nothing named is held."""
    kept = {}
    for key, below in trie.items():
        if key not in answer:
            continue
        if below is True:
            kept[key] = answer[key]
        elif isinstance(answer[key], dict):
            inner = pruned(answer[key], below)
            if inner:
                kept[key] = inner
    return kept
