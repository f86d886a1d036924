"""What the side-by-side benchmarks share: the two source trees (old = the commit before a change, new = this
repository), the lesson model of whichever tree is imported, free loopback ports and the app started as the
README says (``python3 -m server --port P``) from a given tree, in a session of its own.

A tree is a directory holding a ``server`` package: a throwaway ``git worktree add /tmp/mdl-old 276f0e6`` for
the old one. ``python3 -m server`` started with the tree as its working directory imports that tree's package
(the working directory comes first on ``sys.path``), whatever is installed.
"""
from __future__ import annotations

import argparse
import http.client
import importlib
import json
import os
import signal
import socket
import subprocess
import sys
import tempfile
import time
from contextlib import contextmanager
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
DEFAULT_OLD = Path("/tmp/mdl-old")
BASE_COMMIT = "276f0e6"
OUTLIVE_GRACE_S = 3.0           # multiprocessing's resource tracker may still be cleaning up as the server exits

# Where the lesson model lives: server/lessons/ with slider families, server/api/ before.
LESSON_MODULES = ("server.lessons.scene_requests", "server.lessons.requests", "server.api.scene_requests")
CONTENT_MODULES = ("server.lessons.content", "server.lessons.scenes", "server.lessons", "server.api.content")


def first_module_with(candidates: tuple[str, ...], name: str):
    """The first importable module among candidates that defines `name`."""
    for candidate in candidates:
        try:
            module = importlib.import_module(candidate)
        except ImportError:
            continue
        if hasattr(module, name):
            return module
    raise ImportError(f"none of {candidates} defines {name}")


def lessons():
    """(scenes, scene_request, slider_values, defaults, path_value) of the imported tree's lesson model."""
    requests = first_module_with(LESSON_MODULES, "scene_request")
    content = first_module_with(CONTENT_MODULES, "scenes")
    return content.scenes, requests.scene_request, requests.slider_values, requests.defaults, requests.path_value


def add_tree_arguments(parser) -> None:
    parser.add_argument("--old", type=Path, default=DEFAULT_OLD,
                        help=f"the baseline tree (default {DEFAULT_OLD}: git worktree add {DEFAULT_OLD} {BASE_COMMIT})")
    parser.add_argument("--new", type=Path, default=ROOT, help="the tree under test (default: this repository)")


def check_tree(tree: Path) -> Path:
    tree = tree.resolve()
    if not (tree / "server" / "__init__.py").is_file():
        raise SystemExit(f"{tree} holds no server package (for the old tree: git worktree add {tree} {BASE_COMMIT})")
    return tree


def tree_label(tree: Path) -> str:
    """How a result names a tree: "this checkout" for the repository these scripts belong to, "the checkout at
    `PATH`" for another, with " (uncommitted changes)" when its tracked files differ from its commit. No commit
    hash: a result is read beside the code it describes, not against the repository's history."""
    tree = Path(tree).resolve()
    label = "this checkout" if tree == ROOT else f"the checkout at `{tree}`"
    try:
        dirty = subprocess.run(["git", "-C", str(tree), "status", "--porcelain", "--untracked-files=no"],
                               capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        dirty = ""                      # not a git checkout (a copy): nothing to compare it with
    return label + (" (uncommitted changes)" if dirty else "")


def free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return sock.getsockname()[1]


def get_json(port: int, path: str) -> dict:
    """GET on a fresh connection."""
    connection = http.client.HTTPConnection("127.0.0.1", port, timeout=5)
    try:
        connection.request("GET", path, headers={"Connection": "close"})
        answer = connection.getresponse()
        if answer.status != 200:
            raise RuntimeError(f"GET {path}: HTTP {answer.status}")
        return json.loads(answer.read())
    finally:
        connection.close()


def started_workers(log: str) -> int:
    """Worker processes that have said 'Application startup complete.' in the server's log."""
    return log.count("Application startup complete.")


def server_command(port: int, workers: int) -> list[str]:
    """The README's command: python3 -m server, plus --port (and --workers when more than one)."""
    return [sys.executable, "-m", "server", "--port", str(port), *(["--workers", str(workers)] if workers > 1 else [])]


def session_processes(session: int, zombies: bool = True) -> dict[int, float]:
    """The processes of a session (the server started with start_new_session: its workers, and the processes
    they start for long computations, which a forkserver may reparent to init) and their user + system CPU
    seconds so far, from /proc. ``zombies=False`` leaves out those that have ended but are not yet reaped
    (an orphan's parent is init, which on some machines reaps late or never)."""
    ticks = os.sysconf("SC_CLK_TCK")
    found = {}
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            fields = (entry / "stat").read_text().rsplit(")", 1)[1].split()
        except OSError:
            continue
        if int(fields[3]) == session and (zombies or fields[0] != "Z"):   # state, ppid, pgrp, session, …
            found[int(entry.name)] = (int(fields[11]) + int(fields[12])) / ticks   # utime, stime
    return found


def server_cpu_s(process: subprocess.Popen) -> float:
    return sum(session_processes(process.pid).values())


def live_after(session: int, seconds: float) -> dict[int, float]:
    """The session's live processes once they have all ended or `seconds` have passed."""
    deadline = time.monotonic() + seconds
    while (live := session_processes(session, zombies=False)) and time.monotonic() < deadline:
        time.sleep(0.1)
    return live


def end_session(session: int) -> int:
    """End what is left of the server's session once the server has stopped (its own process group, by id)
    and OUTLIVE_GRACE_S has passed; returns how many processes had outlived it."""
    left = live_after(session, OUTLIVE_GRACE_S)
    if left:
        for sig in (signal.SIGTERM, signal.SIGKILL):
            try:
                os.killpg(session, sig)
            except ProcessLookupError:
                break
            if not live_after(session, 3.0):
                break
    return len(left)


@contextmanager
def running_server(workers: int = 1, tree: Path = ROOT, env: dict | None = None, command: list[str] | None = None,
                   ready_path: str = "/api/v1/cache", startup_s: float = 120):
    """The app of `tree` on a free loopback port with MDL_DATA_DIR in a temporary folder and, unless the
    environment or ``env`` says otherwise, no warming of its cache (MDL_WARM_DEFAULTS=0: an older tree does not
    warm, and a benchmark times what it asks for); yields (port, process).
    Ready once every worker has started and one of them answers GET ready_path; once stopped,
    ``process.log_path`` names its log while it runs, ``process.log_text`` holds it and ``process.outlived`` the processes that outlived it. `command`
    (with ``{port}``) replaces the README's command, e.g. for the bare floor app."""
    with tempfile.TemporaryDirectory(prefix="mdl-bench-") as data_dir:
        port = free_port()
        log_path = Path(data_dir) / "server.log"
        log = open(log_path, "wb")
        argv = [part.format(port=port) for part in command] if command else server_command(port, workers)
        process = subprocess.Popen(argv, cwd=tree, stdout=log, stderr=subprocess.STDOUT,
                                   env={"MDL_WARM_DEFAULTS": "0", **os.environ, "MDL_DATA_DIR": data_dir,
                                        **(env or {})},
                                   start_new_session=True)
        process.log_path = log_path
        try:
            deadline = time.monotonic() + startup_s
            while True:
                if process.poll() is not None:
                    raise RuntimeError(f"the server exited with code {process.returncode}: "
                                       + log_path.read_text(errors="replace")[-2000:])
                try:
                    if started_workers(log_path.read_text(errors="replace")) >= workers:
                        get_json(port, ready_path)
                        break
                except (OSError, RuntimeError, ValueError, http.client.HTTPException):
                    pass
                if time.monotonic() > deadline:
                    raise RuntimeError(f"the server's {workers} worker(s) did not all start and answer "
                                       f"within {startup_s:g} s")
                time.sleep(0.2)
            process.startup_s = startup_s - (deadline - time.monotonic())
            yield port, process
        finally:
            process.terminate()
            try:
                process.wait(timeout=15)
            except subprocess.TimeoutExpired:
                process.kill()
                process.wait()
            process.outlived = end_session(process.pid)
            log.close()
            process.log_text = log_path.read_text(errors="replace")


def percentiles(values, qs=(50, 95)) -> list[float]:
    """Percentiles (numpy's linear rule) of a non-empty sequence; NaN for an empty one."""
    import numpy as np
    return [float("nan")] * len(qs) if len(values) == 0 else [float(v) for v in np.percentile(values, qs)]


def write_result(text: str, path: Path) -> None:
    """Write a bench's Markdown result to path (its folder made if needed) and say where."""
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8")
    print(f"written to {path}")


def machine_line() -> str:
    import platform
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    return (f"{time.strftime('%Y-%m-%d %H:%M %Z')}, Python {platform.python_version()}, {platform.machine()}, "
            f"{os.cpu_count()} CPUs, load average {load:.1f} at the start")


if __name__ == "__main__":
    epilog = ("A module: the bench scripts' shared code (trees, ports, the app started from a tree)"
              "; nothing to run by itself.")
    argparse.ArgumentParser(description=__doc__.split("\n\n")[0], epilog=epilog).parse_args()
