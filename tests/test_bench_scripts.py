"""Every benchmark script (bench/*.py) parses its command line with argparse: ``--help`` prints the usage and
exits 0 without measuring anything or writing any file under bench/results/ (each file's bytes and mtime the
same before and after). A script that took no arguments ran its whole benchmark on ``--help`` and overwrote its
committed results.

The timeout is a guard against a script that starts measuring instead of answering, not a measure of speed.
"""
from __future__ import annotations

import hashlib
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
BENCH = ROOT / "bench"
RESULTS = BENCH / "results"
SCRIPTS = sorted(path.name for path in BENCH.glob("*.py"))
GUARD_S = 120


def results_state() -> dict[str, tuple[str, int]]:
    """Each file under bench/results/: its SHA-256 and its mtime in ns."""
    return {str(path.relative_to(RESULTS)): (hashlib.sha256(path.read_bytes()).hexdigest(), path.stat().st_mtime_ns)
            for path in sorted(RESULTS.rglob("*")) if path.is_file()}


def test_every_bench_script_is_listed():
    assert len(SCRIPTS) > 10 and "elastic.py" in SCRIPTS and "steady_cycle.py" in SCRIPTS


@pytest.mark.parametrize("script", SCRIPTS)
def test_help_prints_the_usage_and_writes_nothing(script):
    before = results_state()
    done = subprocess.run([sys.executable, str(BENCH / script), "--help"], cwd=ROOT, capture_output=True, text=True,
                          stdin=subprocess.DEVNULL, timeout=GUARD_S)
    assert done.returncode == 0, done.stderr[-2000:]
    assert done.stdout.startswith("usage: "), done.stdout[:500]
    assert results_state() == before
