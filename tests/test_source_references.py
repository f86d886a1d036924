"""Sources are named once (README, "Sources"; content/sources.json) and cited by key and equation everywhere else.

Every file the project writes in server/, web/, content/ and tests/ is read as text: no source is cited by a
file number ("seed 000", "000.md", the notes' folder) and nothing by an issue number; every author-like name
followed by an equation, section, figure or table number is one of the five keys (or its ru/uk form), the
lecture is Lecture 10 and its formulas are numbered within the (L1)–(L30) that docs/sources.md lists; every scene
and every preset names its source in each of its three languages.  Exact text checks: nothing to tolerate.
"""
from __future__ import annotations

import json
import re
import subprocess
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
SOURCES = json.loads((REPO / "content" / "sources.json").read_text(encoding="utf-8"))
KEYS = ("Eremyants", "Chaika–Vasylenko", "Kuleshova–Tokhtar", "Drakunov–Tuleshova", "Lecture 10")
TEXT = {".py", ".js", ".json", ".html", ".css", ".md", ".sh", ".toml", ".sql", ".txt"}

FORBIDDEN = {
    "a seed's file number": re.compile(r"\bseeds?[ _-]?00[0-4](?![0-9])", re.IGNORECASE),
    "a notes file": re.compile(r"\b00[0-4]\.md\b|seeds/(?:notes|original)", re.IGNORECASE),
    "an issue number": re.compile(r"\bissues?[ _-]?#?\d+", re.IGNORECASE),
    "a section of Lecture 10 written as an equation (it numbers none; §10.9)":
        re.compile(r"\b(?:[Ll]ecture|[Лл]екци[яи]|[Лл]екці[яї]) 10 \(10\."),
    "a two-author key spelled otherwise than 'Chaika–Vasylenko' (an en dash)":
        re.compile(r"\b(?:Chaika|Drakunov|Kuleshova|Чайка|Дракунов|Кулешова)(?: ?&| and| и| і|,|-) ?(?=[A-ZА-ЯЄІ][a-zа-яєі])"),
}
WORD = r"[A-ZА-ЯЁЄІЇ][a-zа-яёєіїь]+(?:'(?!s\b)[a-zа-яёєіїь]+)?"      # Єрем'янц; an English possessive 's is not part of it
REFERENCE = r"(?:'s|')? (?:\(\d+(?:\.\d+)?\*?\)|§ ?\d|(?:Figs?\.|рис\.|Table|табл\.) ?\d)"
# A name in the middle of a sentence followed by an equation, section, figure or table: a citation.  At the
# start of a sentence a capital word is ordinary prose ("Check (3.2)"), so only joined names count there.
CITED = re.compile(r"(?<=[a-zа-яёєіїь0-9,;:(] )(" + WORD + r"(?:[–-]" + WORD + r")?)" + REFERENCE)
JOINED = re.compile(r"(" + WORD + r"[–-]" + WORD + r")" + REFERENCE)
LECTURE = re.compile(r"\b(?:[Ll]ecture|[Лл]екци[яиюе]|[Лл]екці[яїю]) (\d+)")
LECTURE_NUMBER = re.compile(r"\(L(\d+)\)")


def project_files() -> list[Path]:
    listed = subprocess.run(["git", "ls-files", "server", "web", "content", "tests"], cwd=REPO,
                            capture_output=True, text=True, check=True).stdout.split()
    return [REPO / name for name in listed
            if Path(name).suffix in TEXT and "vendor" not in Path(name).parts
            and Path(name).name != Path(__file__).name and (REPO / name).is_file()]


def lines_matching(pattern: re.Pattern) -> list[tuple[str, re.Match]]:
    """(file:line, match) for every match of the pattern in the project's files."""
    found = []
    for path in project_files():
        for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            found += [(f"{path.relative_to(REPO)}:{number}", match) for match in pattern.finditer(line)]
    return found


def names() -> set[str]:
    """The keys and each source's names in en, ru and uk (content/sources.json)."""
    return set(KEYS) | {name for record in SOURCES.values() for each in record["names"].values() for name in each}


def test_sources_json_holds_the_five_keys_with_their_bibliographic_data():
    assert tuple(SOURCES) == KEYS
    for key, record in SOURCES.items():
        assert record["title"] and record["title_original"] and record["cited_by"], key
        assert set(record["names"]) == {"en", "ru", "uk"}, key


def test_the_readme_names_each_source_once_in_its_sources_section():
    readme = (REPO / "README.md").read_text(encoding="utf-8")
    section = readme.split("\n## Sources\n", 1)[1].split("\n## ", 1)[0]
    rows = re.findall(r"^\| \*\*(.+?)\*\* \|(.*)\|$", section, re.MULTILINE)
    assert [key for key, _ in rows] == list(KEYS)
    for key, text in rows:
        record = SOURCES[key]
        assert record["title_original"] in text, key
        assert record["year"] is None or str(record["year"]) in text, key


def test_nothing_is_cited_by_a_file_number_or_an_issue_number():
    for what, pattern in FORBIDDEN.items():
        hits = [f"{where}: {match.group(0)}" for where, match in lines_matching(pattern)]
        assert hits == [], f"cited by {what}; cite the source's key and equation (README, Sources)"


def test_every_cited_name_is_one_of_the_five_sources():
    known = names()
    unknown = sorted({f"{where}: {match.group(0)}" for where, match in lines_matching(CITED) + lines_matching(JOINED)
                      if match.group(1) not in known})
    assert unknown == [], f"cited by a name that is not a key of content/sources.json: {unknown}"


def test_the_lecture_is_lecture_10_and_its_formula_numbers_are_the_ones_docs_sources_lists():
    assert [f"{where}: {match.group(0)}" for where, match in lines_matching(LECTURE) if match.group(1) != "10"] == []
    listing = (REPO / "docs" / "sources.md").read_text(encoding="utf-8")
    listed = set()
    for first, last in re.findall(r"^\| \(L(\d+)\)(?:–\(L(\d+)\))? \| §10\.\d+ \|", listing, re.MULTILINE):
        listed |= set(range(int(first), int(last or first) + 1))
    assert listed == set(range(1, 31))
    cited = {int(match.group(1)) for _, match in lines_matching(LECTURE_NUMBER)}
    assert cited and cited <= listed


def test_every_scene_and_preset_names_its_source_in_each_language():
    missing = []
    for path in sorted((REPO / "content" / "scenes").glob("*.json")) + sorted(
            (REPO / "content" / "mechanisms").glob("*.json")):
        source = json.loads(path.read_text(encoding="utf-8"))["source"]
        for lang in ("en", "ru", "uk"):
            local = {name for record in SOURCES.values() for name in record["names"][lang]}
            if not any(name in source[lang] for name in local):
                missing.append(f"{path.name} [{lang}]")
    assert missing == []


def served_texts():
    """(address, text) of everything the app serves in words: every page in ru, uk and en (the start page, each
    scene and its assignment builder where it has questions, the editor, the course project, the measurements), the scenes and
    mechanisms as JSON, and every stored Markdown or HTML file under /bench-results."""
    from fastapi.testclient import TestClient

    from server.api.app import app
    from server.lessons.scenes import scenes

    client = TestClient(app)
    pages = ["/", "/measurements", "/editor", "/project"]
    for scene_id, scene in scenes().items():
        pages += [f"/scenes/{scene_id}"] + [f"/scenes/{scene_id}/assign"] * bool(scene.questions)
    addresses = [f"{page}?lang={lang}" for page in pages for lang in ("ru", "uk", "en")]
    addresses += ["/api/v1/scenes", "/api/v1/mechanisms", "/api/v1/mechanisms/general"]
    addresses += [f"/bench-results/{path.name}" for path in sorted((REPO / "bench" / "results").iterdir())
                  if path.suffix in (".md", ".html")]
    for address in addresses:
        answer = client.get(address)
        assert answer.status_code == 200, address
        yield address, answer.text


def test_nothing_the_app_serves_names_a_source_by_file_number():
    """What a reader can open (pages in three languages, the scenes' JSON, the stored benchmark results and
    figures) cites no source by a file number: "seed 003", "seed-003", "003.md"."""
    hits = []
    for address, text in served_texts():
        for what in ("a seed's file number", "a notes file"):
            hits += [f"{address}: {match.group(0)}" for match in FORBIDDEN[what].finditer(text)]
    assert hits == []
