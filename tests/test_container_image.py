"""The Docker image's layout, read from the Dockerfile and .dockerignore (no Docker daemon runs here): what of a
working copy enters the image, who runs the app, where its data lives.

The working copy is made to hold what a real one holds (a classroom database with students' names under data/,
the tests' artifacts, numba's caches, the history); the files that enter the image are those under the sources of
the Dockerfile's COPY lines that .dockerignore does not exclude (Docker's rules: Go's filepath.Match per path
segment, ``**`` any number of segments, a pattern excluding a folder excludes what is in it).
"""
from __future__ import annotations

import fnmatch
import re
import shutil
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
DOCKERFILE = (ROOT / "Dockerfile").read_text(encoding="utf-8")
IGNORED = [line.strip() for line in (ROOT / ".dockerignore").read_text(encoding="utf-8").splitlines()
           if line.strip() and not line.lstrip().startswith("#")]


def _segments_match(pattern: list[str], path: list[str]) -> bool:
    if not pattern:
        return not path
    if pattern[0] == "**":
        return any(_segments_match(pattern[1:], path[i:]) for i in range(len(path) + 1))
    return bool(path) and fnmatch.fnmatchcase(path[0], pattern[0]) and _segments_match(pattern[1:], path[1:])


def ignored(relative: str) -> bool:
    """True when .dockerignore leaves the file out (the file, or a folder it is in, matches a pattern)."""
    parts = relative.split("/")
    excluded = False
    for rule in IGNORED:
        negate = rule.startswith("!")
        pattern = rule.lstrip("!").strip("/").split("/")
        if any(_segments_match(pattern, parts[:k]) for k in range(1, len(parts) + 1)):
            excluded = not negate
    return excluded


def copied_sources() -> list[str]:
    sources = []
    for line in DOCKERFILE.splitlines():
        if line.startswith("COPY "):
            words = [w for w in line.split()[1:] if not w.startswith("--")]
            sources += words[:-1]
    return sources


def entering(workdir: Path) -> set[str]:
    files = set()
    for source in copied_sources():
        path = workdir / source
        candidates = [path] if path.is_file() else [p for p in path.rglob("*") if p.is_file()]
        files |= {p.relative_to(workdir).as_posix() for p in candidates}
    return {f for f in files if not ignored(f)}


def test_only_the_app_enters_the_image(tmp_path):
    work = tmp_path / "copy"
    subprocess.run(["git", "clone", "-q", "--depth", "1", f"file://{ROOT}", str(work)], check=True, timeout=300)
    (work / "data").mkdir()
    (work / "data" / "classroom.sqlite3").write_bytes(b"students' names")
    (work / "test-artifacts").mkdir()
    (work / "test-artifacts" / "page.png").write_bytes(b"png")
    cache = work / "server" / "core" / "dynamics" / "__pycache__"
    cache.mkdir(parents=True, exist_ok=True)
    (cache / "compiled.rk4-71.py311.nbi").write_bytes(b"numba")
    (work / "bench" / "results" / "__pycache__").mkdir(exist_ok=True)
    files = entering(work)
    assert "server/api/app.py" in files and "web/templates/base.html" in files
    assert "content/scenes/flywheel.json" in files and "pyproject.toml" in files
    assert "bench/results/work_precision.md" in files
    leaked = sorted(f for f in files if f.startswith(("data/", "test-artifacts/", ".git", "tests/"))
                    or "__pycache__" in f or f.endswith((".sqlite3", ".nbi", ".nbc")))
    assert leaked == []
    shutil.rmtree(work)


def test_no_copy_of_the_whole_context():
    assert "." not in copied_sources() and "./" not in copied_sources()
    for ignored_path in ("data/classroom.sqlite3", "test-artifacts/x.png", ".git/HEAD", "tests/test_api.py"):
        assert ignored(ignored_path), ignored_path


def test_the_app_runs_unprivileged_with_its_data_in_a_volume():
    lines = [line.strip() for line in DOCKERFILE.splitlines() if line.strip() and not line.startswith("#")]
    users = [line.split()[1] for line in lines if line.startswith("USER ")]
    assert users and users[-1] not in ("root", "0"), "the last USER before CMD runs the app"
    cmd_at = max(i for i, line in enumerate(lines) if line.startswith("CMD "))
    user_at = max(i for i, line in enumerate(lines) if line.startswith("USER "))
    assert user_at < cmd_at
    data_dir = re.search(r"MDL_DATA_DIR=(\S+)", DOCKERFILE).group(1)
    volume = re.search(r'VOLUME \["([^"]+)"\]', DOCKERFILE).group(1)
    assert volume == data_dir
    assert re.search(rf"chown [^\n]*{users[-1]}:{users[-1]} [^\n]*{re.escape(data_dir)}", DOCKERFILE), \
        "the data folder belongs to the user who runs the app"
    assert "pip install ." in DOCKERFILE and "pip install -e" not in DOCKERFILE
