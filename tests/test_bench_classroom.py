"""Smoke test of the classroom load test (bench/classroom.py): a class of 3 students for 3 seconds against the
servers it starts (1 and 2 workers) writes its tables, with requests answered and no errors."""
from __future__ import annotations

import importlib.util
import random
import re
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
SPEC = importlib.util.spec_from_file_location("classroom", REPO / "bench" / "classroom.py")
classroom = importlib.util.module_from_spec(SPEC)
SPEC.loader.exec_module(classroom)


def test_the_class_is_spread_over_the_scenes_by_the_stated_shares():
    scenes = classroom.apportion(60, classroom.SCENE_MIX)
    assert len(scenes) == 60
    assert {s: scenes.count(s) for s in ("transfer-functions", "equation-of-motion", "flywheel", "angular-acceleration")} \
        == {"transfer-functions": 18, "equation-of-motion": 9, "flywheel": 9, "angular-acceleration": 3}
    assert len(classroom.apportion(3, classroom.SCENE_MIX)) == 3


def test_a_student_walks_over_the_values_the_slider_can_express():
    from server.lessons.scenes import scenes
    student = classroom.Student(scenes()["transfer-functions"], random.Random(1))
    for _ in range(500):
        student.move()
        value = student.values[student.variant.id][student.slider.id]
        assert value in student.positions
    assert student.body().startswith(b"{")


def test_three_students_for_three_seconds_write_the_tables_without_errors(tmp_path):
    output = tmp_path / "classroom.md"
    run = subprocess.run([sys.executable, "bench/classroom.py", "--students", "3", "--seconds", "3",
                          "--compare-clients", "0", "--output", str(output)],
                         cwd=REPO, capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr[-3000:]
    text = output.read_text(encoding="utf-8")
    assert "## 1 worker" in text and "## 2 workers" in text
    totals = re.findall(r"^\| \*\*all\*\* \| (\d+) \|.*\| (\d+) \((\d+) / (\d+) / (\d+)\) \|", text, re.MULTILINE)
    assert len(totals) == 2, text
    for requests, errors, *_ in totals:
        assert int(requests) > 0 and int(errors) == 0, text
    for workers in (1, 2):    # every worker logged its cache counters as it stopped; they count what the clients saw
        counted = re.search(rf"logs as it stops \({workers} of {workers}\): (\d+) hits, .* the clients saw (\d+) "
                            r"answers with X-Cache: hit", text)
        assert counted and counted[1] == counted[2], text
    assert text.count("s after it stopped (SIGTERM, 15 s): 0.") == 2, text       # no process outlives it
