"""Files that the workers of one server share, in the temporary folder, named after the process that started them.

A server started with ``--workers N`` (N ≥ 2) is a supervisor and N workers it spawned; a worker finds the
supervisor as its parent process. A file of theirs is ``<prefix><supervisor pid><suffix>``: the supervisor removes
its own as it stops (``remove_own``), and a worker opening one removes those of supervisors no longer running
(killed ones included).
"""
from __future__ import annotations

import multiprocessing
import os
import tempfile
from pathlib import Path


def workers_file(prefix: str, suffix: str) -> Path | None:
    """The file of this server's workers, or None when this process is no worker of a supervisor (one worker, or
    an app in a test: nothing to share)."""
    parent = multiprocessing.parent_process()
    if parent is None or parent.pid is None:
        return None
    folder = Path(tempfile.gettempdir())
    _remove_orphans(folder, prefix)
    return folder / f"{prefix}{parent.pid}{suffix}"


def remove_own(prefix: str) -> None:
    """Remove this supervisor's workers' files of `prefix` (called by it once they have all stopped)."""
    for path in Path(tempfile.gettempdir()).glob(f"{prefix}{os.getpid()}.*"):
        try:
            path.unlink()
        except OSError:
            pass


def alive(pid: int) -> bool:
    """Whether a process of this pid runs."""
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def _remove_orphans(folder: Path, prefix: str) -> None:
    """Remove the files of `prefix` of supervisors that no longer run."""
    for path in folder.glob(f"{prefix}*"):
        pid = path.name[len(prefix):].split(".")[0]
        if pid.isdigit() and not alive(int(pid)):
            try:
                path.unlink()
            except OSError:
                pass
