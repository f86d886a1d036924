"""The capacity benchmark (bench/capacity.py): its search for the largest class that holds, its verdict on a run
against the class targets, and a tiny run (``--quick``: 2 students for 3 s on one server pinned to CPU 0 and on
two servers behind the shipped nginx site) that writes its tables and leaves no process behind. No timing is
asserted: whether the tiny class holds depends on the machine."""
from __future__ import annotations

import importlib.util
import math
import os
import tempfile
import shutil
import re
import subprocess
import sys
import time
import uuid
from pathlib import Path

import numpy as np
import pytest

REPO = Path(__file__).resolve().parents[1]
SPEC = importlib.util.spec_from_file_location("capacity", REPO / "bench" / "capacity.py")
capacity = importlib.util.module_from_spec(SPEC)
sys.modules["capacity"] = capacity           # its dataclasses look their module up
SPEC.loader.exec_module(capacity)
sys.path.insert(0, str(Path(__file__).resolve().parent))
from leftover_processes import processes  # noqa: E402

RUN_GUARD_S = 900          # a guard against a hang on a loaded machine, not a measure of speed
EXIT_GRACE_S = 10.0


def searched(capacity_of: int, sizes=(10, 20, 30, 45, 60), resolution=0.1, bisect=True):
    tried = []

    def holds(students: int) -> bool:
        tried.append(students)
        return students <= capacity_of

    return capacity.search(holds, list(sizes), resolution, bisect), tried


def test_the_search_stops_at_the_first_class_that_fails_and_bisects_below_it():
    found, tried = searched(37)
    assert tried[:4] == [10, 20, 30, 45]             # 60 is never run
    assert found["bounded"] and found["held"] <= 37 < found["failed"]
    assert found["failed"] - found["held"] <= max(1, math.ceil(0.1 * found["held"]))
    assert all(tried.count(size) == 1 for size in tried)


def test_a_deployment_that_holds_every_class_is_a_lower_bound_and_none_held_is_zero():
    found, tried = searched(1000)
    assert found == {"held": 60, "failed": None, "bounded": False} and tried == [10, 20, 30, 45, 60]
    found, tried = searched(3)
    assert found["held"] == 3 and found["failed"] == 4 and tried[0] == 10
    found, tried = searched(3, bisect=False)
    assert found == {"held": 0, "failed": 10, "bounded": True} and tried == [10]


def row(kind, light, seconds, status=200, partial=False):
    return ("kinematics" if light == "light" else "elastic", seconds, status, "", partial, kind, light)


def test_the_verdict_counts_a_preview_given_up_as_late_and_every_error_and_cut_short_answer():
    quick = [row("exact", "light", 0.01)] * 40 + [row("coarse", "light", 0.1)] * 19
    assert capacity.verdict({"rows": quick, "given_up": []})["held"]
    late = capacity.verdict({"rows": quick, "given_up": [("coarse", "light")] * 2})
    assert not late["held"] and late["cells"]["coarse", "light"] == (math.inf, 19, 2), late
    assert capacity.verdict({"rows": quick, "given_up": [("family", "light")] * 5})["held"]  # the full one: no target
    failed = capacity.verdict({"rows": quick + [row("family", "light", 0.2, status=503)], "given_up": []})
    assert not failed["held"] and failed["errors"] == 1
    cut = capacity.verdict({"rows": quick + [row("exact", "elastic", 0.2, partial=True)], "given_up": []})
    assert not cut["held"] and cut["partial"] == 1
    slow = capacity.verdict({"rows": quick + [row("exact", "elastic", 0.6)] * 3, "given_up": []})
    assert not slow["held"] and slow["reasons"] == ["exact, elastic p95 600 > 500 ms"]


def test_the_verdicts_p95_is_the_classroom_tables_one_linear_between_the_ranks():
    """One slow elastic answer of fifteen is not their p95: the verdict interpolates between the ranks as numpy
    (and bench/classroom.py's tables, by which point 1's targets are read) does."""
    seconds = [0.02 + 0.001 * k for k in range(14)] + [0.742]
    verdict = capacity.verdict({"rows": [row("exact", "elastic", s) for s in seconds], "given_up": []})
    p95, answered, late = verdict["cells"]["exact", "elastic"]
    assert (answered, late) == (15, 0) and p95 == pytest.approx(float(np.percentile([1000 * s for s in seconds], 95)))
    assert verdict["held"] and p95 < 500


def started_by_the_run(tag: str, folder: Path) -> dict[int, str]:
    """The app servers, nginx and their helpers still running that the run started: those whose environment
    holds its tag, or whose working directory is in its temporary folder (nginx's master and workers: nginx
    writes its title over its environment)."""
    found = {}
    for pid, command in processes().items():
        try:
            environment = Path(f"/proc/{pid}/environ").read_bytes()
            directory = os.readlink(f"/proc/{pid}/cwd")
        except OSError:
            continue
        if tag.encode() in environment or directory.startswith(str(folder)):
            found[pid] = command
    return found


def test_a_quick_run_writes_its_tables_and_stops_every_server_and_nginx(tmp_path, request):
    output = tmp_path / "capacity.md"
    # the run's temporary folder, short: the heavy processes' forkserver binds a Unix socket in it (108 bytes at
    # most), and pytest's tmp_path under xdist is too deep for that
    folder = Path(tempfile.mkdtemp(prefix="mdl-cap-", dir="/tmp"))
    request.addfinalizer(lambda: shutil.rmtree(folder, ignore_errors=True))
    tag = uuid.uuid4().hex
    run = subprocess.run([sys.executable, "bench/capacity.py", "--quick", "--output", str(output)], cwd=REPO,
                         env={**os.environ, "MDL_CAPACITY_TEST": tag, "TMPDIR": str(folder)}, capture_output=True,
                         text=True, timeout=RUN_GUARD_S)
    deadline = time.monotonic() + EXIT_GRACE_S
    while (left := started_by_the_run(tag, folder)) and time.monotonic() < deadline:
        time.sleep(0.5)
    assert not left, f"left behind: {left}"
    assert run.returncode == 0, run.stderr[-3000:]
    text = output.read_text(encoding="utf-8")
    for name in ("one-cpu", "two-servers"):
        # students held: a number, or "≥ n (every class tried held)" on a machine fast enough for every class
        assert re.search(rf"^\| {name}: .+ \| \d \| (≥ )?\d+[^|]* \| (≥ )?[\d.]+ \| .+ \| 1 \| \d+ \|$", text, re.M), text
        assert f"## {name}: " in text and f"## {name}, 2 students" in text, text
    assert "taskset -c 0 python3 -m server --port P1" in text and "taskset -c 1 python3 -m server --port P2" in text
    runs = re.findall(r"^\| 2 \| [\d.]+ / [\d.]+ / [\d.]+ \| .*\| (yes.*|\*\*no\*\*.*) \|$", text, re.M)   # held or not
    assert len(runs) == 2, text
    balanced = re.search(r"requests per app server: (\d+), (\d+) \|$", text, re.M)    # nginx used both servers
    assert balanced and int(balanced[1]) > 0 and int(balanced[2]) > 0, text
    assert "× one CPU" in text and "two-workers" not in text
