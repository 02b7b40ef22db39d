"""The documentation's links resolve, and the code cites only pages that exist.

* Every relative Markdown link ``[text](target)`` in README.md and docs/**/*.md points to an
  existing file or folder, and its ``#anchor``, when the target is a Markdown page, to one of that
  page's headings (GitHub's slugs: lower case, punctuation dropped, spaces to hyphens).
* Every ``docs/....md`` path written in a Python file of src/, tests/, benchmarks/ or docs/scripts/
  (docstrings and comments), or as text in the Markdown files, exists (paths from the repository root).
* No Python file in src/ cites ``METHOD.md`` (a file of the project brief, not of the repository) or
  one of our pages by a section number ("docs/performance.md sec. 8"): a page and its heading's
  words are cited instead, so that a renumbering cannot leave a wrong pointer.

Each check is shown to be able to fail on a made-up example.
"""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
#: [text](target) and ![alt](target); the target ends at whitespace or ')'
LINK = re.compile(r"!?\[[^\]]*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
#: a docs page named in code, e.g. ``docs/notes/edgewise_damping.md``
DOCS_PATH = re.compile(r"docs/[\w./-]*?\.md")
#: one of our pages cited by a section number: "x.md sec. 4", "x.md`` section 1", "x.md §11"
SECTION_CITATION = re.compile(r"\.md`{0,2},?\s*(?:sec(?:tion)?s?\.?\s*\d|§\s*\d)")


def markdown_files() -> list[Path]:
    return [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]


def _text(path: Path) -> str:
    return re.sub(r"```.*?```", "", path.read_text(encoding="utf-8"), flags=re.S)  # no code blocks


def anchors(path: Path) -> set[str]:
    """The heading anchors of Markdown file ``path`` as GitHub makes them (repeats get -1, -2 ...)."""
    seen: dict[str, int] = {}
    out = set()
    for heading in re.findall(r"^#{1,6}\s+(.*?)\s*#*\s*$", _text(path), flags=re.M):
        slug = re.sub(r"[^\w\- ]", "", heading.strip().lower()).replace(" ", "-")
        n = seen.get(slug, 0)
        seen[slug] = n + 1
        out.add(slug if n == 0 else f"{slug}-{n}")
    return out


def broken_links(path: Path) -> list[str]:
    """The relative link targets of Markdown file ``path`` whose file, or heading, does not exist."""
    broken = []
    for target in LINK.findall(_text(path)):
        if re.match(r"[a-z][a-z0-9+.-]*:", target, re.I):
            continue                                    # http:, mailto:
        file, _, anchor = target.partition("#")
        dest = path.parent / file if file else path
        if not dest.exists():
            broken.append(target)
        elif anchor and dest.suffix == ".md" and anchor not in anchors(dest):
            broken.append(target)
    return broken


def python_files(*folders: str) -> list[Path]:
    return [p for f in folders for p in sorted((ROOT / f).rglob("*.py"))]


def test_link_check_can_fail(tmp_path):
    page = tmp_path / "page.md"
    (tmp_path / "there.md").write_text("# Title\n## 2. The model: `x.py`\n## Notes\n## Notes\n", encoding="utf-8")
    page.write_text("# Page\n[a](there.md#2-the-model-xpy) [b](missing.md) ![c](fig/none.png) "
                    "[d](https://x.org/y.md) [e](#page) [f](#nowhere) [g](there.md#notes-1) "
                    "[h](there.md#notes-2)\n```\n[i](in_code.md)\n```\n", encoding="utf-8")
    assert broken_links(page) == ["missing.md", "fig/none.png", "#nowhere", "there.md#notes-2"]


def test_every_relative_markdown_link_resolves():
    broken = {str(p.relative_to(ROOT)): b for p in markdown_files() if (b := broken_links(p))}
    assert not broken, f"links to missing files: {broken}"


def test_every_docs_page_named_in_code_exists():
    missing = {}
    for path in python_files("src", "tests", "benchmarks", "docs/scripts") + markdown_files():
        if path == Path(__file__).resolve():
            continue                                    # this file's examples
        for name in set(DOCS_PATH.findall(path.read_text(encoding="utf-8"))):
            if not (ROOT / name).exists():
                missing.setdefault(str(path.relative_to(ROOT)), []).append(name)
    assert not missing, f"docs pages named in code that do not exist: {missing}"


def test_section_citation_pattern_can_fail():
    for bad in ("docs/performance.md sec. 8", "``docs/performance.md`` section 1", "verification.md §11",
                "campbell.md, sec.4"):
        assert SECTION_CITATION.search(bad), bad
    assert not SECTION_CITATION.search("docs/campbell.md, 'Modes in the field's terms'")


def test_src_cites_no_missing_file_and_no_section_number():
    offenders = []
    for path in python_files("src"):
        for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            if "METHOD.md" in line or SECTION_CITATION.search(line):
                offenders.append(f"{path.relative_to(ROOT)}:{n}: {line.strip()}")
    assert not offenders, "\n".join(offenders)
