"""User-facing wording and links of the documentation.

* No page of docs/, README.md, or docstring, comment or data file of the package refers to the
  internal spec (``models.md``) or to tracker items ("issue 3"); the physics of the studies is in
  docs/studies.md.
* Every relative Markdown link in docs/*.md and README.md points to an existing file, and every
  ``#anchor`` into a Markdown page to one of its headings (GitHub's slugs).
"""

from __future__ import annotations

import ast
import io
import re
import tokenize
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
PACKAGE = ROOT / "bearingsim"

FORBIDDEN = {
    "the internal spec models.md": re.compile(r"models\.md", re.I),
    "a tracker item (issue <N>)": re.compile(r"\bissue\s+(?:[0-9]+|[A-Z])\b", re.I),
}

FENCE = re.compile(r"^\s*(```|~~~)")
LINK = re.compile(r"!?\[(?:[^\]\[]|\[[^\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
INLINE_CODE = re.compile(r"(`+).*?\1")


def _rel(path: Path) -> str:
    return str(path.relative_to(ROOT))


def _python_texts(path: Path) -> list[tuple[int, str]]:
    """Docstrings (module, class, function and attribute docstrings: every string statement)
    and comments of one module, with their line numbers."""
    source = path.read_text(encoding="utf-8")
    texts = [(node.lineno, node.value.value) for node in ast.walk(ast.parse(source))
             if isinstance(node, ast.Expr) and isinstance(node.value, ast.Constant)
             and isinstance(node.value.value, str)]
    texts += [(tok.start[0], tok.string)
              for tok in tokenize.generate_tokens(io.StringIO(source).readline)
              if tok.type == tokenize.COMMENT]
    return texts


def _package_texts() -> list[tuple[str, int, str]]:
    texts = []
    for path in sorted(PACKAGE.rglob("*.py")):
        texts += [(_rel(path), line, text) for line, text in _python_texts(path)]
    for pattern in ("*.toml", "*.csv", "*.md"):
        for path in sorted(PACKAGE.rglob(pattern)):
            texts.append((_rel(path), 1, path.read_text(encoding="utf-8")))
    return texts


def _offences(texts) -> list[str]:
    found = []
    for where, line, text in texts:
        for what, pattern in FORBIDDEN.items():
            for match in pattern.finditer(text):
                at = line + text.count("\n", 0, match.start())
                found.append(f"{where}:{at}: {what}: {match.group(0)!r}")
    return found


@pytest.mark.parametrize("page", PAGES, ids=[p.name for p in PAGES])
def test_pages_do_not_cite_the_internal_spec_or_tracker_items(page):
    assert _offences([(_rel(page), 1, page.read_text(encoding="utf-8"))]) == []


def test_package_docstrings_and_comments_do_not_cite_the_internal_spec_or_tracker_items():
    texts = _package_texts()
    assert len(texts) > 500
    assert _offences(texts) == []


def test_the_wording_check_catches_what_it_should():
    assert _offences([("x", 1, "see models.md section C"), ("y", 3, "a\n(Issue 3 audit)"),
                      ("z", 1, "issue T"), ("w", 1, "an issue with 3 balls; issues 3")]) == [
        "x:1: the internal spec models.md: 'models.md'",
        "y:4: a tracker item (issue <N>): 'Issue 3'",
        "z:1: a tracker item (issue <N>): 'issue T'",
    ]
    texts = _python_texts(Path(__file__))
    assert any("Docstrings (module, class" in text for _, text in texts)
    assert any("# a comment" in text for _, text in texts)  # a comment


def slug(heading: str) -> str:
    """GitHub's anchor of a heading: lowercase, punctuation other than '-' and '_' dropped,
    spaces to '-'."""
    text = INLINE_CODE.sub(lambda m: m.group(0).strip("`"), heading.strip())
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", text)  # a link's text only
    text = re.sub(r"[^\w\- ]", "", text.lower())
    return text.replace(" ", "-")


def anchors(page: Path) -> set[str]:
    """Anchors of every heading of a Markdown page (duplicates get -1, -2, ... as on GitHub)."""
    seen: dict[str, int] = {}
    result = set()
    in_code = False
    for line in page.read_text(encoding="utf-8").splitlines():
        if FENCE.match(line):
            in_code = not in_code
            continue
        match = re.match(r"^ {0,3}#{1,6}\s+(.*?)\s*#*\s*$", line)
        if in_code or not match:
            continue
        base = slug(match.group(1))
        count = seen.get(base, 0)
        seen[base] = count + 1
        result.add(base if count == 0 else f"{base}-{count}")
    return result


def links(page: Path) -> list[tuple[int, str]]:
    """(line, target) of every Markdown link and image outside code blocks and inline code."""
    found = []
    in_code = False
    for number, line in enumerate(page.read_text(encoding="utf-8").splitlines(), 1):
        if FENCE.match(line):
            in_code = not in_code
            continue
        if in_code:
            continue
        for match in LINK.finditer(INLINE_CODE.sub("", line)):
            found.append((number, match.group(1)))
    return found


def test_slugs_follow_github():
    assert slug("C. Deep-groove ball bearing dynamics") == "c-deep-groove-ball-bearing-dynamics"
    assert slug("8. Deep-groove model: work-precision (2 ms; RK4)") == (
        "8-deep-groove-model-work-precision-2-ms-rk4")
    assert slug("Quasi-static balls (`dynamic`)") == "quasi-static-balls-dynamic"
    assert slug("The ball row") == "the-ball-row"


@pytest.mark.parametrize("page", PAGES, ids=[p.name for p in PAGES])
def test_relative_links_resolve(page):
    broken = []
    for line, target in links(page):
        if re.match(r"^[a-z][a-z0-9+.-]*:", target, re.I):  # http:, https:, mailto:
            continue
        path, _, anchor = target.partition("#")
        resolved = (page.parent / path).resolve() if path else page
        if not resolved.exists():
            broken.append(f"{page.name}:{line}: {target}: no such file")
        elif anchor and resolved.suffix == ".md" and anchor not in anchors(resolved):
            broken.append(f"{page.name}:{line}: {target}: no heading with that anchor")
    assert broken == []


def test_the_link_check_sees_the_links_of_the_index():
    targets = [target for _, target in links(ROOT / "docs" / "index.md")]
    assert "studies.md" in targets
    assert "studies.md#c-deep-groove-ball-bearing-dynamics" in targets
    assert {"a-double-layer-bearings", "b-duplex-angular-contact-pairs",
            "c-deep-groove-ball-bearing-dynamics"} <= anchors(ROOT / "docs" / "studies.md")
