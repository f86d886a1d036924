"""`python3 -m server.core.warm_up` (tests/run.sh, the Dockerfile, the deployment guide) compiles every part that
warm_up() loads at a server's start (warm_up.PARTS), side by side in a process per CPU, and says how long each
took."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from server.core import warm_up

ROOT = Path(__file__).resolve().parents[1]


def test_the_command_compiles_every_part_and_names_it():
    done = subprocess.run([sys.executable, "-m", "server.core.warm_up"], cwd=ROOT, capture_output=True, text=True,
                          timeout=900)
    assert done.returncode == 0, done.stderr[-2000:]
    said = dict(part.rsplit(": ", 1) for part in done.stdout.strip().split(", "))
    assert set(said) == set(warm_up.PARTS), done.stdout
    assert all(seconds.endswith(" s") and float(seconds[:-2]) >= 0 for seconds in said.values()), done.stdout
