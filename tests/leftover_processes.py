"""Processes the suite left behind: a browser, a database, a proxy or an app server that a test started and did
not stop. ``--snapshot`` prints the process ids alive before the suite; ``--since IDS`` lists the processes of those
kinds started since (not among IDS), waits a little for the ones still exiting, and fails naming them.
"""
from __future__ import annotations

import argparse
import os
import re
import sys
import time
from pathlib import Path

KINDS = re.compile(r"chrom(e|ium)|headless_shell|postgres|nginx|uvicorn|-m server\b|multiprocessing\.(forkserver|"
                   r"spawn|resource_tracker)|lti_platform|playwright")
GRACE_S = 10.0


def processes() -> dict[int, str]:
    found = {}
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit() or int(entry.name) == os.getpid():
            continue
        try:
            command = (entry / "cmdline").read_bytes().replace(b"\0", b" ").decode(errors="replace").strip()
        except OSError:
            continue
        if command and KINDS.search(command):
            found[int(entry.name)] = command
    return found


def alive(pids: set[int]) -> set[int]:
    """Those of `pids` still running (a zombie, dead but not yet reaped, is not running)."""
    running = set()
    for pid in pids:
        try:
            state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
        except OSError:
            continue
        if state != "Z":
            running.add(pid)
    return running


def wait_gone(pids: set[int], what: str, guard_s: float = 300.0) -> None:
    """Wait until none of `pids` runs; fail naming `what` after `guard_s` (a guard against a hang, not a limit)."""
    deadline = time.monotonic() + guard_s
    while alive(pids):
        assert time.monotonic() < deadline, f"{what}: processes {sorted(alive(pids))} still running"
        time.sleep(0.1)


def main() -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument("--snapshot", action="store_true")
    parser.add_argument("--since", default=None)
    args = parser.parse_args()
    if args.snapshot:
        print(" ".join(str(pid) for pid in sorted(processes())))
        return 0
    alive_before = {int(pid) for pid in (args.since or "").split()}
    deadline = time.monotonic() + GRACE_S
    while True:
        left = {pid: command for pid, command in processes().items() if pid not in alive_before}
        if not left or time.monotonic() > deadline:
            break
        time.sleep(0.5)
    for pid, command in sorted(left.items()):
        print(f"left behind by the suite: {pid} {command[:200]}", file=sys.stderr)
    return 1 if left else 0


if __name__ == "__main__":
    sys.exit(main())
