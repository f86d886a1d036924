"""bench/browser_keys.py (a slider's keys in Chromium, key → visible change per scene) runs: on one scene, with a
key held for two keydowns and one single press, it writes its table, and the page's requests are as the keys'
contract says (none while the key is held, one exact answer per rest). No timing is asserted; the timeout is a
guard against a hang. The script starts and stops its own server; none of its processes outlives it."""
from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[1]
GUARD_S = 900

pytestmark = pytest.mark.browser


@pytest.mark.skipif(not Path("/usr/bin/chromium").exists(), reason="Chromium is not installed at /usr/bin/chromium")
def test_the_keyboard_bench_writes_its_table_for_one_scene(tmp_path):
    output = tmp_path / "keyboard.md"
    run = subprocess.run([sys.executable, "bench/browser_keys.py", "--scenes", "transfer_functions", "--keys", "2",
                          "--presses", "1", "--out", str(output)], cwd=REPO, capture_output=True, text=True,
                         stdin=subprocess.DEVNULL, timeout=GUARD_S)
    assert run.returncode == 0, run.stderr[-3000:]
    text = output.read_text(encoding="utf-8")
    number = r"\d+\.\d"
    row = re.search(rf"^\| transfer-functions \(slider_crank\) \| lambda, Arrow(?:Left|Right) \| (\d+) \| yes "
                    rf"\| {number} / {number} \(2/2\) \| (\d+) \| \d+ \| {number} / {number} \(1/1\) \| (\d+) \|$",
                    text, re.MULTILINE)
    assert row, text
    observed, asked_while_held, asked_per_press = map(int, row.groups())
    assert observed >= 1                         # panels in view watched
    assert asked_while_held == 0 and asked_per_press == 1
    assert "load average" in text and "Processes outliving the server: 0." in text
    assert "Page errors" not in text, text
