"""The README's two commands are the ones CI and the Dockerfile use."""
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def readme_command(heading: str) -> str:
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    section = text.split(f"## {heading}", 1)[1]
    return re.search(r"```bash\n(.+?)\n```", section, re.S).group(1).strip()


def test_ci_runs_the_readme_test_command():
    ci = (ROOT / ".ci" / "run").read_text(encoding="utf-8")
    assert readme_command("Run the tests") in ci.splitlines()


def test_dockerfile_installs_and_starts_like_the_readme():
    install, start = (part.strip() for part in readme_command("Start the app").split("&&"))
    dockerfile = (ROOT / "Dockerfile").read_text(encoding="utf-8")
    # the image installs the same package, not editable: its sources are removed once installed
    assert install.replace(" -e .", " .") != install
    assert any(line.startswith(f"RUN {install.replace(' -e .', ' .')}") for line in dockerfile.splitlines())
    cmd = re.search(r"^CMD (\[.+\])$", dockerfile, re.M).group(1)
    words = [w.strip(' "') for w in cmd.strip("[]").split(",")]
    assert " ".join(words).startswith(start + " ")
    assert "--host" in words and "0.0.0.0" in words   # reachable from outside the container


def test_setup_commands_need_nothing_installed_by_hand():
    runner = (ROOT / "tests" / "run.sh").read_text(encoding="utf-8")
    assert 'pip install' in runner and '".[test]"' in runner
    assert "apt-get install -y -qq chromium" in runner
