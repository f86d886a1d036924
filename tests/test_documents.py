"""The user documentation: README.md, docs/*.md and bench/README.md, and the measured results in bench/results/*.md.

- The README is short (at most 250 lines) and its lessons table lists every scene of content/scenes by id, with
  the scene's English title.
- Every relative link and image resolves to a file of the repository, and so does every repository path a
  document names in backticks (`server/core/…`, `deploy/nginx/mdl.conf`, `bench/results/…`).
- Every environment variable the server reads (MDL_…) is in docs/deployment.md's settings.
- No document carries the development's history: issue numbers, work sessions, stops, commit hashes, "today",
  "new:". Exact text checks: nothing to tolerate. The results in bench/results/*.md are documents too (a
  comparison names its trees by what they are, "the tree before the compiled family engine", "old tree" / "new
  tree", never by a commit); the other checks cover the documentation only.
"""
from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[1]
README = REPO / "README.md"
DOCUMENTS = [README, *sorted((REPO / "docs").glob("*.md")), REPO / "bench" / "README.md"]
RESULTS = sorted((REPO / "bench" / "results").glob("*.md"))
TOP_LEVEL = ("server", "web", "content", "tests", "bench", "deploy", "docs", ".ci")
ROOT_FILES = ("Dockerfile", "pyproject.toml", "LICENSE", ".dockerignore", "README.md")

LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")
CODE_SPAN = re.compile(r"`([^`\n]+)`")
FENCE = re.compile(r"^```.*?^```", re.MULTILINE | re.DOTALL)
PATH = re.compile(r"^(?:" + "|".join(re.escape(name) for name in TOP_LEVEL) + r")/[\w./@-]*$")
PLACEHOLDER = set("<>{}*…$")

# Words a development log uses and a user's document does not.
HISTORY = {
    "an issue number": re.compile(r"\bissues? ?#?\d+", re.IGNORECASE),
    "a stop of the work": re.compile(r"\bstops? \d+\b|\b(?:this|that|the previous|the last|the next) stop\b",
                                     re.IGNORECASE),
    # 7 to 40 hex digits, at least one a digit and one a letter, not part of a number (1.632862e-17) or a word
    "a commit hash": re.compile(r"(?<![\w.+-])(?=[0-9a-f]*\d)(?=[0-9a-f]*[a-f])[0-9a-f]{7,40}(?![\w+-]|\.\d)"),
    "a date relative to the work": re.compile(r"\btoday\b|\byesterday\b|(?<![\w/])new:", re.IGNORECASE),
}
# a stretch of the work ("the second session", "this session", "session 3"), not a thing of the software (a
# browser's session, an LTI launch's session, the session cookie)
SESSION = re.compile(r"\b(?:this|that|previous|earlier|next|last|first|second|third|fourth|fifth|later|current|same|"
                     r"another|work|working|development) sessions?\b|\bsessions? \d+\b|\bthe session['’]s (?:start|end)\b",
                     re.IGNORECASE)


def relative(path: Path) -> str:
    return str(path.relative_to(REPO))


def prose(path: Path) -> str:
    return path.read_text(encoding="utf-8")


def links(text: str) -> list[str]:
    return [target for target in LINK.findall(text)
            if not re.match(r"^(?:[a-z][a-z0-9+.-]*:|#|/)", target)]


def named_paths(text: str) -> list[str]:
    """Repository paths named in backticks (inside fenced blocks too: commands name files), each word alone."""
    found = []
    for span in CODE_SPAN.findall(FENCE.sub(lambda block: block.group(0).replace("\n", "`\n`"), text)):
        for word in span.split():
            word = word.strip("'\"(),;:")
            if any(ch in PLACEHOLDER for ch in word) or "//" in word:
                continue
            if PATH.match(word) or word in ROOT_FILES:
                found.append(word)
    return found


def scenes() -> list[dict]:
    files = sorted((REPO / "content" / "scenes").glob("*.json"))
    return [json.loads(path.read_text(encoding="utf-8")) for path in files]


def test_the_readme_is_at_most_250_lines():
    assert len(prose(README).splitlines()) <= 250


@pytest.mark.parametrize("document", DOCUMENTS, ids=relative)
def test_every_relative_link_and_image_exists(document):
    missing = [target for target in links(prose(document))
               if not (document.parent / target.split("#", 1)[0]).exists()]
    assert missing == [], f"{relative(document)} links to files that do not exist"


@pytest.mark.parametrize("document", DOCUMENTS, ids=relative)
def test_every_repository_path_named_exists(document):
    missing = sorted({path for path in named_paths(prose(document)) if not (REPO / path.rstrip(".")).exists()})
    assert missing == [], f"{relative(document)} names paths that do not exist"


def test_the_readmes_images_exist():
    images = re.findall(r"!\[[^\]]*\]\(([^)\s]+)\)", prose(README))
    assert images and all((REPO / image).is_file() for image in images)


@pytest.mark.parametrize("document", DOCUMENTS + RESULTS, ids=relative)
def test_no_document_carries_the_development_history(document):
    text = prose(document)
    found = [f"{what}: {match.group(0)!r}" for what, pattern in HISTORY.items() for match in pattern.finditer(text)]
    found += [f"a work session: {match.group(0)!r}" for match in SESSION.finditer(text)]
    if document == README:
        found += [f"the time of writing: {match.group(0)!r}" for match in re.finditer(r"\bnow\b", text, re.I)]
    assert found == [], f"{relative(document)} reads like a development log"


def test_the_readmes_lessons_table_lists_every_scene_with_its_title_and_sources():
    """A row per scene: its id, its English title, and the keys of the sources its English source text names
    (content/sources.json), in that file's order."""
    sources = json.loads((REPO / "content" / "sources.json").read_text(encoding="utf-8"))
    rows = {row[0]: (row[1], row[2]) for row in re.findall(r"^\| `([a-z0-9-]+)` \| ([^|]+?) \| [^|]+ \| ([^|]+?) \|$",
                                                            prose(README), re.MULTILINE)}
    for scene in scenes():
        assert scene["id"] in rows, f"the README's lessons table has no row for {scene['id']}"
        title, keys = rows[scene["id"]]
        assert title == scene["title"]["en"], scene["id"]
        named = [key for key, record in sources.items()
                 if any(name in scene["source"]["en"] for name in record["names"]["en"])]
        assert keys == ", ".join(named), scene["id"]


def test_the_deployment_guide_lists_every_setting_the_server_reads():
    code = "\n".join(path.read_text(encoding="utf-8") for path in (REPO / "server").rglob("*.py"))
    example = (REPO / "deploy" / "mdl.env.example").read_text(encoding="utf-8")
    names = set(re.findall(r"\bMDL_[A-Z0-9_]+\b", code)) | set(re.findall(r"^(MDL_[A-Z0-9_]+)=", example, re.M))
    guide = prose(REPO / "docs" / "deployment.md")
    listed = set(re.findall(r"^\| `(MDL_[A-Z0-9_]+)` \|", guide, re.MULTILINE))
    assert names - listed == set(), "settings the server reads that docs/deployment.md does not list"


def test_the_benchmarks_index_lists_every_result():
    index = prose(REPO / "bench" / "README.md")
    listed = {target.removeprefix("results/") for target in links(index) if target.startswith("results/")}
    present = {path.name for path in (REPO / "bench" / "results").iterdir() if path.is_file()}
    assert present - listed == set(), "files in bench/results/ that bench/README.md does not list"
