"""``pip install .`` (not editable) gives a working app: the wheel holds every package of server/ and the top-level
web/, content/ and bench/results/ (pyproject.toml maps them into the package; server/paths.py finds them).

The wheel is built from the checkout and installed into a fresh virtual environment in a temporary directory,
with the machine's packages visible (``--system-site-packages``: the dependencies are those the suite runs on)
but not the checkout: the app is imported and served from another directory, and ``server.__file__`` must be the
environment's copy. The checkout's own editable install, if any, comes after the environment's site-packages on
the import path (setuptools appends its finder to ``sys.meta_path``), so it cannot stand in for the wheel. The
kernels run as plain Python there (``NUMBA_DISABLE_JIT``): compiling them anew for the copy would take minutes,
and the compiled path is tested against the plain one elsewhere.
"""
from __future__ import annotations

import subprocess
import sys
import tomllib
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PYPROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))

SERVE_FROM_ELSEWHERE = r"""
import pathlib, re, sys
from fastapi.testclient import TestClient
import server
from server.api.app import app
print("server at", server.__file__)
assert pathlib.Path(server.__file__).is_relative_to(pathlib.Path(sys.prefix)), server.__file__
with TestClient(app) as client:
    for path in ("/", "/scenes/transfer-functions?lang=en", "/editor", "/project", "/measurements",
                 "/api/v1/scenes"):
        response = client.get(path)
        assert response.status_code == 200, (path, response.status_code, response.text[:300])
    assets = re.findall(r"/static/[^\x22\x27 ]+[.](?:js|css)", client.get("/").text)
    assert assets and all(client.get(asset).status_code == 200 for asset in assets), assets
    answer = client.post("/api/v1/kinematics", json={"mechanism": "slider_crank", "phi": [0.5],
                                                     "outputs": ["u31"]})
    assert answer.status_code == 200, answer.text[:300]
print("served")
"""


def test_every_package_of_server_is_in_the_wheel_list():
    """A package added under server/ and not listed would be missing from a normal install."""
    listed = set(PYPROJECT["tool"]["setuptools"]["packages"])
    found = {".".join(path.parent.relative_to(ROOT).parts) for path in (ROOT / "server").rglob("__init__.py")}
    assert found - listed == set(), f"add to [tool.setuptools] packages in pyproject.toml: {sorted(found - listed)}"
    mapped = set(PYPROJECT["tool"]["setuptools"]["package-dir"])
    assert listed - found == mapped, "every listed package is a folder of server/ or a mapped top-level folder"


@pytest.fixture(scope="module")
def wheel(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("wheel")
    build = subprocess.run([sys.executable, "-m", "pip", "wheel", "--quiet", "--no-deps", "--disable-pip-version-check",
                            "-w", str(out), str(ROOT)], capture_output=True, text=True, timeout=900)
    assert build.returncode == 0, build.stderr[-3000:]
    (found,) = out.glob("mechanism_dynamics_lab-*.whl")
    return found


def test_the_wheel_carries_the_pages_the_lessons_and_the_measurements(wheel):
    names = set(zipfile.ZipFile(wheel).namelist())
    for expected in ("server/api/app.py", "server/web/templates/base.html", "server/web/static/js/common/model/dotted_paths.js",
                     "server/content/scenes/flywheel.json", "server/content/i18n/uk.json",
                     "server/content/mechanisms/shaping_machine.json", "server/bench_results/work_precision.md"):
        assert expected in names, expected
    assert not any(name.startswith(("tests/", "data/", "test-artifacts/")) or "__pycache__" in name
                   for name in names)


def test_a_normal_install_serves_the_app_from_another_directory(wheel, tmp_path):
    env_dir = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", str(env_dir)], check=True, timeout=300)
    python = env_dir / "bin" / "python"
    install = subprocess.run([str(python), "-m", "pip", "install", "--quiet", "--no-deps",
                              "--disable-pip-version-check", str(wheel)], capture_output=True, text=True, timeout=600)
    assert install.returncode == 0, install.stderr[-3000:]
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    run = subprocess.run([str(python), "-c", SERVE_FROM_ELSEWHERE], cwd=elsewhere, capture_output=True, text=True,
                         timeout=600, env={"PATH": "/usr/bin:/bin", "HOME": str(tmp_path),
                                           "MDL_DATA_DIR": str(tmp_path / "data"), "NUMBA_DISABLE_JIT": "1",
                                           "MDL_WARM_DEFAULTS": "0"})
    assert run.returncode == 0, run.stdout[-2000:] + run.stderr[-4000:]
    assert "served" in run.stdout and str(env_dir) in run.stdout


def test_postgresql_is_an_extra_and_its_absence_is_said_at_start():
    """psycopg is installed only with ``[postgres]``; MDL_DATABASE_URL set without it stops the start with the
    reason and the command, not an ImportError's trace."""
    dependencies = " ".join(PYPROJECT["project"]["dependencies"])
    assert "psycopg" not in dependencies and "plotly" not in dependencies
    assert len({d.split(">")[0].split("=")[0] for d in PYPROJECT["project"]["dependencies"]}) == \
        len(PYPROJECT["project"]["dependencies"]), "a package listed twice"
    assert any("psycopg" in d for d in PYPROJECT["project"]["optional-dependencies"]["postgres"])
    without_psycopg = ("import sys; sys.modules['psycopg'] = None; sys.modules['psycopg_pool'] = None\n"
                       "from server.classroom.assignment_store import check\n"
                       "try:\n    check()\nexcept Exception as error:\n    print(type(error).__name__, error)\n")
    run = subprocess.run([sys.executable, "-c", without_psycopg], capture_output=True, text=True, timeout=300,
                         env={"PATH": "/usr/bin:/bin", "MDL_DATABASE_URL": "postgresql://mdl@127.0.0.1:1/mdl"})
    assert run.stdout.startswith("StoreUnavailable"), run.stdout + run.stderr[-2000:]
    assert "[postgres]" in run.stdout and "psycopg" in run.stdout
