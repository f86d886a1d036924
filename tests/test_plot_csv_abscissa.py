"""A plot's CSV (web/static/js/common/view/export_csv.js, run in Node without a DOM): the abscissa column is
written to six significant digits, so φ in degrees derived from the server's 7-digit radians reads 1, 2, 359
and not 0,9999998556178845; the curves' values stay every digit the server sent."""
from __future__ import annotations

import json
import math
import shutil
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[1]
MODULE = REPO / "web" / "static" / "js" / "common" / "view" / "export_csv.js"
NODE = shutil.which("node") or shutil.which("nodejs")
pytestmark = pytest.mark.skipif(NODE is None, reason="Node is not installed")


def csv_of(graph: dict, decimal: str) -> str:
    script = (f"import {{ plotColumns, csvText }} from {json.dumps(MODULE.as_uri())};\n"
              f"const graph = {json.dumps(graph)};\n"
              f"process.stdout.write(csvText(plotColumns(graph), {json.dumps(decimal)}));\n")
    done = subprocess.run([NODE, "--input-type=module", "-e", script], capture_output=True, timeout=60)
    assert done.returncode == 0, done.stderr.decode()
    return done.stdout.decode("utf-8")


def test_the_angle_column_carries_no_float_noise_and_the_values_every_digit():
    radians = [float(f"{math.radians(degree):.7g}") for degree in range(0, 361, 45)]
    degrees = [r * 180 / math.pi for r in radians]                 # as a plot derives them: 0.99999986 …
    assert any(abs(d - round(d)) > 1e-9 for d in degrees)
    values = [0.1234567, -1.5e-7, 2.0, 3.25, None, 7.654321, 1e-3, 8.0, 9.5]
    graph = {"data": [{"x": degrees, "y": values, "hovertemplate": "u₃₁ = %{y} м<extra></extra>"}],
             "layout": {"xaxis": {"title": {"text": "Угол кривошипа φ, °"}}}}
    text = csv_of(graph, "comma")
    assert text.startswith("\ufeff") and text.endswith("\r\n")
    rows = [line.split(";") for line in text.lstrip("\ufeff").splitlines() if line]
    assert rows[0] == ["Угол кривошипа φ, °", "u₃₁, м"]
    assert [row[0] for row in rows[1:]] == [str(d) for d in range(0, 361, 45)]
    assert [row[1] for row in rows[1:]] == ["0,1234567", "-1,5e-7", "2", "3,25", "", "7,654321", "0,001", "8", "9,5"]
    rows = [line.split(",") for line in csv_of(graph, "point").lstrip("\ufeff").splitlines() if line]
    assert rows[2] == ["45", "-1.5e-7"]


def test_a_letter_superscript_keeps_its_caret_in_the_header():
    """The reduced moment's column reads "Mд^пр, Н·м" (not "Mдпр"); a digit superscript is a glyph (R^{1/3} → R¹/³
    as notation.js writes it), a subscript digit too ("Mс₀")."""
    graph = {"data": [{"x": [0, 1], "y": [1.5, 2.5], "hovertemplate": "M<sub>д</sub><sup>пр</sup> = %{y} Н·м<extra></extra>"},
                      {"x": [0, 1], "y": [3, 4], "hovertemplate": "M<sub>с0</sub><sup>2</sup> = %{y} Н·м<extra></extra>"}],
             "layout": {"xaxis": {"title": {"text": "φ, °"}}}}
    header = csv_of(graph, "comma").lstrip("\ufeff").splitlines()[0].split(";")
    assert header == ["φ, °", "Mд^пр, Н·м", "Mс₀², Н·м"]
