"""Time one tree's in-process server compute, for bench/scene_sweep.py: run as
``python3 bench/tree_runner.py TREE`` with TREE's ``server`` package first on sys.path, commands as JSON lines on
stdin, one JSON answer line each on the original stdout (the tree's own prints go to stderr).

The compute timed is what the server does for a request up to the answer's bytes, without HTTP:
* a tree with ``server.api.endpoints.compute_answer`` and ``server.api.serialise.serialise`` (with slider families): the
  answer and its serialisation at the default (plot) precision, the bytes the page gets; failing those,
  ``server.api.endpoints.compute`` and the serialisation of its answer when it is not bytes;
* the base tree: validation and the route function of ``server.api.compute.ENDPOINTS`` — the JSONResponse it
  returns has rendered the bytes — leaving out the ``json.loads`` that ``compute()`` adds for its callers.
Long computations run in this process (MDL_HEAVY_PROCESSES=0), as the in-process ``compute`` does.

Commands: {"op": "info"}; {"op": "warm"} (every scene's default request once, untimed by the sweep);
{"op": "time", "scene": id, "variant": id, "values": {slider: value}, "answer": bool} → {"ms", "outcome",
"detail", "bytes"[, "answer": the JSON answer, parsed after the timing]}.
"""
from __future__ import annotations

import argparse
import json
import os
import sys
import time


def tree_argument() -> str:
    """The tree from the command line (``--help`` prints the usage and exits before anything is imported)."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     epilog="Commands on stdin, answers on stdout: see the module's docstring.")
    parser.add_argument("tree", help="a directory holding a server package")
    return os.path.abspath(parser.parse_args().tree)


TREE = tree_argument()
sys.path.insert(0, TREE)
os.chdir(TREE)
os.environ["MDL_HEAVY_PROCESSES"] = "0"
PROTOCOL = os.fdopen(os.dup(1), "w", buffering=1)
os.dup2(2, 1)                                   # the tree's prints and warnings: stderr
sys.stdout = sys.stderr

REFUSED = ("ValidationError", "GeometryError", "RequestValidationError", "SpecError", "HTTPException")
SERIALISERS = ("dumps", "serialise", "serialize", "to_json", "encode", "json_bytes", "render")


def serialiser():
    """The new tree's serialisation of an answer object to bytes, found by name in server.api.serialise."""
    try:
        import server.api.serialise as module
    except ImportError:
        return None, ""
    for name in SERIALISERS:
        function = getattr(module, name, None)
        if callable(function):
            try:
                if isinstance(function({"x": [1.5]}), (bytes, bytearray)):
                    return function, f"server.api.serialise.{name}"
            except Exception:      # noqa: BLE001 — a candidate with another signature
                continue
    return None, ""


def compute_function():
    """(function(endpoint, body, lang) → answer bytes or object, description)."""
    try:
        from server.api.endpoints import compute_answer
        from server.api.serialise import serialise

        def compute_plot(endpoint: str, body: dict, lang: str) -> bytes:
            return serialise(compute_answer(endpoint, body, lang).payload)
        return compute_plot, ("server.api.endpoints.compute_answer + server.api.serialise.serialise (the bytes "
                              "the page gets, plot precision)")
    except ImportError:
        pass
    try:
        from server.api.endpoints import compute
    except ImportError:
        from server.api.compute import ENDPOINTS

        def compute_old(endpoint: str, body: dict, lang: str):
            model, handler = ENDPOINTS[endpoint]
            answer = handler(model.model_validate(body), lang=lang)
            return getattr(answer, "body", answer)        # JSONResponse: the rendered bytes
        return compute_old, "server.api.compute.ENDPOINTS (validation + route + JSONResponse rendering)"
    dumps, name = serialiser()

    def compute_new(endpoint: str, body: dict, lang: str):
        answer = compute(endpoint, body, lang)
        if dumps is not None and not isinstance(answer, (bytes, bytearray)):
            answer = dumps(answer)
        return getattr(answer, "body", answer)
    return compute_new, "server.api.endpoints.compute" + (f" + {name}" if name else "")


sys.path.append(os.path.dirname(os.path.abspath(__file__)))
from trees import lessons  # noqa: E402  (this tree's lesson model, before or after its move)

scenes, scene_request, _, _, _ = lessons()
COMPUTE, DESCRIPTION = compute_function()
LANG = "ru"


def variant_of(scene_id: str, variant_id: str):
    scene = scenes()[scene_id]
    return scene, next(v for v in scene.variants if v.id == variant_id)


def timed(scene_id: str, variant_id: str, values: dict, with_answer: bool = False) -> dict:
    """The compute's time (ms), outcome, size; with the answer itself (parsed, after the timing) if asked."""
    scene, variant = variant_of(scene_id, variant_id)
    body = scene_request(scene, variant, values)
    start = time.perf_counter()
    try:
        answer = COMPUTE(scene.endpoint, body, LANG)
        outcome, detail = "ok", ""
    except Exception as error:   # noqa: BLE001 — reported, not hidden
        answer = b""
        kind = type(error).__name__
        outcome, detail = ("refused" if kind in REFUSED else "error"), f"{kind}: {str(error)[:200]}"
    ms = 1000 * (time.perf_counter() - start)
    if not isinstance(answer, (bytes, bytearray)):
        answer = json.dumps(answer, default=str).encode()
    found = {"ms": ms, "outcome": outcome, "detail": detail, "bytes": len(answer)}
    if with_answer and outcome == "ok":
        found["answer"] = json.loads(answer)
    return found


def info() -> dict:
    import server
    return {"tree": TREE, "server": os.path.dirname(server.__file__), "compute": DESCRIPTION,
            "scenes": {s.id: {v.id: [sl.id for sl in v.sliders] for v in s.variants} for s in scenes().values()}}


def warm(only: list[str] | None) -> dict:
    """Every scene's (or only those named) variants at their defaults once: imports, compilation, disk caches."""
    start = time.perf_counter()
    for scene in scenes().values():
        if only and scene.id not in only:
            continue
        for variant in scene.variants:
            timed(scene.id, variant.id, {})
    return {"ms": 1000 * (time.perf_counter() - start)}


def main() -> None:
    for line in sys.stdin:
        command = json.loads(line)
        op = command["op"]
        if op == "info":
            answer = info()
        elif op == "warm":
            answer = warm(command.get("scenes"))
        else:
            answer = timed(command["scene"], command["variant"], command["values"], command.get("answer", False))
        PROTOCOL.write(json.dumps(answer) + "\n")


if __name__ == "__main__":
    main()
