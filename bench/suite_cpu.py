"""The CPU a command's processes use, by kind: Chromium's (by --type), the app's servers and heavy processes, the
test processes. For the test suite, whose wall time on a 2-CPU machine is its CPU over two: which part to make
cheaper, and whether a change did (run it twice, before and after, on the same machine, one after the other).

    python bench/suite_cpu.py -- python3 -m pytest -q -n 4 --dist loadgroup tests/browser
    python bench/suite_cpu.py --output bench/results/suite_cpu.md --label "keeper page" -- python3 -m pytest ...

Every process descending from the command is read from /proc every SAMPLE_S seconds (utime + stime, by pid and
start time); one that lives less than that may be missed, so the figures are a lower bound, the same for both runs.
"""
from __future__ import annotations

import argparse
import collections
import datetime
import os
import re
import subprocess
import sys
import time
from pathlib import Path

SAMPLE_S = 0.5
HZ = os.sysconf("SC_CLK_TCK")


def kind(command: str) -> str:
    """The process's kind from its command line."""
    if "chromium" in command:
        found = re.search(r"--type=(\S+)", command)
        return f"chromium {found.group(1) if found else 'browser'}"
    if "multiprocessing.forkserver" in command:
        return "app heavy processes (forkserver)"
    if "uvicorn" in command or "-m server" in command:
        return "app servers"
    if "spawn_main" in command or "multiprocessing" in command:
        return "other multiprocessing children"
    if "pytest" in command or "execnet" in command or "sys.stdin.readline" in command:
        return "test processes"
    if "node" in command:
        return "node (Playwright's driver)"
    return "other"


def processes() -> dict[int, tuple[int, str, str, float]]:
    """pid → (parent pid, start time, command line, CPU seconds) of every readable process."""
    found = {}
    for name in os.listdir("/proc"):
        if not name.isdigit():
            continue
        try:
            command = Path(f"/proc/{name}/cmdline").read_bytes().replace(b"\0", b" ").decode(errors="replace")
            fields = Path(f"/proc/{name}/stat").read_text().rsplit(")", 1)[1].split()
        except OSError:
            continue
        found[int(name)] = (int(fields[1]), fields[19], command, (int(fields[11]) + int(fields[12])) / HZ)
    return found


def descendants(root: int, table: dict) -> set[int]:
    children = collections.defaultdict(list)
    for pid, (parent, *_rest) in table.items():
        children[parent].append(pid)
    seen, todo = set(), [root]
    while todo:
        pid = todo.pop()
        seen.add(pid)
        todo.extend(children[pid])
    return seen


def measure(command: list[str]) -> tuple[dict[str, float], float, int]:
    """CPU seconds by kind, the wall time and the command's exit status."""
    start = time.monotonic()
    process = subprocess.Popen(command)
    last: dict[tuple[int, str], tuple[str, float]] = {}
    while True:
        table = processes()
        for pid in descendants(process.pid, table):
            if pid in table:
                _, started, line, cpu = table[pid]
                last[pid, started] = (kind(line), cpu)
        if process.poll() is not None:
            break
        time.sleep(SAMPLE_S)
    by_kind: dict[str, float] = collections.Counter()
    for what, cpu in last.values():
        by_kind[what] += cpu
    return dict(by_kind), time.monotonic() - start, process.returncode


def table(label: str, by_kind: dict[str, float], wall: float) -> str:
    rows = [f"| {what} | {cpu:,.0f} |" for what, cpu in sorted(by_kind.items(), key=lambda item: -item[1])]
    return "\n".join([f"### {label}", "", f"Wall time {wall:,.0f} s; CPU {sum(by_kind.values()):,.0f} s in all.", "",
                      "| processes | CPU (s) |", "|---|---:|", *rows, ""])


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("command", nargs=argparse.REMAINDER, help="the command to run, after --")
    parser.add_argument("--label", default="run", help="the table's title")
    parser.add_argument("--output", type=Path, help="append the table to this Markdown file")
    parser.add_argument("--no-write", action="store_true", help="print only")
    arguments = parser.parse_args()
    command = arguments.command[1:] if arguments.command[:1] == ["--"] else arguments.command
    if not command:
        parser.error("no command given (after --)")
    by_kind, wall, status = measure(command)
    text = table(f"{arguments.label} ({datetime.date.today()}, {os.cpu_count()} CPUs): {' '.join(command)}",
                 by_kind, wall)
    print(text)
    if arguments.output and not arguments.no_write:
        with arguments.output.open("a", encoding="utf-8") as out:
            out.write("\n" + text)
    return status


if __name__ == "__main__":
    sys.exit(main())
