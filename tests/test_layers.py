"""The server's folders are its layers (docs/architecture.md): every module under server/ read with `ast`, its
imports of server's modules (absolute and relative, at module level and inside functions alike) form a graph
that has no cycle, and whose arrows point down the layers only:

    core        imports nothing of server outside core (but server/paths.py)
    lessons     core
    families    core, lessons
    runtime     core, lessons, families
    classroom   core, lessons, families, runtime
    api         anything; nothing but api (and server/__main__.py, the entry point above them all) imports api

and no module below api imports the web framework (FastAPI, Starlette): the classroom refuses in its own
exceptions, which server/api answers over HTTP, and the runtime speaks the ASGI interface as plain scope, receive
and send.
"""
from __future__ import annotations

import ast
import functools
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SERVER = ROOT / "server"
BELOW = {                            # each layer and the layers it may import (besides itself)
    "core": set(),
    "lessons": {"core"},
    "families": {"core", "lessons"},
    "runtime": {"core", "lessons", "families"},
    "classroom": {"core", "lessons", "families", "runtime"},
    "api": {"core", "lessons", "families", "runtime", "classroom"},
}
ANYWHERE = {"server", "server.paths"}     # the package itself and the paths of the checkout: every layer's
WEB_FRAMEWORK = {"fastapi", "starlette"}  # imported by server/api alone


def module_name(path: Path) -> str:
    parts = list(path.relative_to(ROOT).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


MODULES = {module_name(path): path for path in SERVER.rglob("*.py")}


def _module_of(name: str) -> str | None:
    """The module `name` is, or the innermost module holding it (server.core.mechanisms.GeometryError → …)."""
    while name and name not in MODULES:
        name = name.rpartition(".")[0]
    return name or None


def imported_packages(name: str) -> set[str]:
    """The top-level packages outside server that module `name` imports, anywhere in it."""
    found = set()
    for node in ast.walk(ast.parse(MODULES[name].read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            found |= {alias.name.split(".")[0] for alias in node.names}
        elif isinstance(node, ast.ImportFrom) and not node.level and node.module:
            found.add(node.module.split(".")[0])
    return found - {"server"}


def imports(name: str) -> set[str]:
    """The modules of server that module `name` imports, anywhere in it."""
    path = MODULES[name]
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            found |= {_module_of(alias.name) for alias in node.names if alias.name.split(".")[0] == "server"}
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")[:len(package.split(".")) - node.level + 1]
                source = ".".join(base + ([node.module] if node.module else []))
            else:
                source = node.module or ""
            if source.split(".")[0] != "server":
                continue
            for alias in node.names:                           # `from . import heavy` imports the module heavy
                whole = f"{source}.{alias.name}"
                found.add(whole if whole in MODULES else _module_of(source))
    return found - {None, name}


@functools.cache
def graph() -> dict[str, set[str]]:
    """Each module of server and the modules of server it imports (parsed when a test first asks, not at
    collection, which every test process does)."""
    return {name: imports(name) for name in MODULES}


def layer(name: str) -> str | None:
    parts = name.split(".")
    return parts[1] if len(parts) > 2 or (len(parts) == 2 and parts[1] in BELOW) else None


def cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected components of more than one module (Tarjan), each as a cycle through them."""
    index, low, stack, on_stack, found = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in sorted(graph.get(v, ())):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                found.append(_a_cycle(graph, set(component)))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return found


def _a_cycle(graph, component: set[str]) -> list[str]:
    """A path around the component, from its first module back to it (breadth first: a shortest one)."""
    start = min(component)
    paths = {start: [start]}
    queue = [start]
    while queue:
        v = queue.pop(0)
        for w in sorted(graph[v] & component):
            if w == start:
                return paths[v] + [start]
            if w not in paths:
                paths[w] = paths[v] + [w]
                queue.append(w)
    return sorted(component)


def test_the_reader_sees_every_kind_of_import():
    """The graph is read right: relative, absolute, `from . import module`, and imports inside functions."""
    assert "server.core.warm_up" in graph()["server.runtime.heavy"]
    assert "server.runtime.heavy" in graph()["server.api.routers.family"]          # from ...runtime import heavy
    assert "server.families.family" in graph()["server.api.family_batch"]           # from ..families import family
    assert "server.classroom.store.postgres" in graph()["server.classroom.assignment_store"]   # inside a function
    assert cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c", "a"]]


def test_no_import_cycle():
    found = cycles(graph())
    assert not found, "import cycles:\n" + "\n".join(" → ".join(cycle) for cycle in found)


def test_imports_point_down_the_layers():
    wrong = []
    for name, imported in sorted(graph().items()):
        mine = layer(name)
        for other in sorted(imported - ANYWHERE):
            theirs = layer(other)
            if mine == theirs:
                continue
            if name == "server.__main__":              # the entry point stands above every layer
                continue
            if mine is None or theirs is None or theirs not in BELOW[mine]:
                wrong.append(f"{name} ({mine}) → {other} ({theirs})")
    assert not wrong, "imports against the layers:\n" + "\n".join(wrong)


def test_every_module_is_in_a_layer():
    """Only the package, its entry point and the checkout's paths stand outside the layers."""
    assert {name for name in MODULES if layer(name) is None} == {"server", "server.__main__", "server.paths"}


def test_the_reader_sees_the_packages_a_module_imports():
    assert {"fastapi", "starlette"} <= imported_packages("server.api.routers.assignment_pages")
    assert "orjson" in imported_packages("server.api.serialise")
    assert imported_packages("server.paths") & WEB_FRAMEWORK == set()


def test_no_layer_below_api_imports_the_web_framework():
    """HTTP is server/api's: the classroom's refusals (classroom/refusals.py) are answered by api/errors.py, its
    models are pydantic's, and the runtime's middleware is plain ASGI."""
    wrong = [f"{name} imports {', '.join(sorted(imported_packages(name) & WEB_FRAMEWORK))}"
             for name in sorted(MODULES) if layer(name) not in (None, "api") and imported_packages(name) & WEB_FRAMEWORK]
    assert not wrong, "the web framework below server/api:\n" + "\n".join(wrong)
