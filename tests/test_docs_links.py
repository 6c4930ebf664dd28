"""The documentation's promises: README.md is a front page (at most 15,000 bytes) and every relative link
in README.md and in the Markdown under docs/ (docs/results included) points at a file that exists."""

import pathlib
import re
import urllib.parse

import pytest

REPO = pathlib.Path(__file__).resolve().parents[1]
README = REPO / "README.md"
README_LIMIT = 15_000

# [text](target "title"), ![alt](target), [text](<target with spaces>); reference definitions [id]: target;
# <img src="target">, <a href="target">.
INLINE = re.compile(r"!?\[[^\]]*\]\(\s*(<[^>]*>|[^)\s]+)(?:\s+[\"'(][^)]*)?\)")
REFERENCE = re.compile(r"^\s{0,3}\[[^\]]+\]:\s*(<[^>]*>|\S+)", re.MULTILINE)
HTML = re.compile(r"<(?:img|a|source)\b[^>]*?\b(?:src|href)\s*=\s*[\"']([^\"']+)[\"']", re.IGNORECASE)
FENCE = re.compile(r"^(```|~~~).*?^\1[^\n]*$", re.MULTILINE | re.DOTALL)
CODE_SPAN = re.compile(r"(`+)(?!`).+?(?<!`)\1(?!`)", re.DOTALL)


def _pages():
    return [README] + sorted((REPO / "docs").rglob("*.md"))


def links(text: str) -> list[str]:
    """Every link target in a Markdown text, outside code blocks and code spans."""
    text = CODE_SPAN.sub("", FENCE.sub("", text))
    found = [m.group(1) for pattern in (INLINE, REFERENCE, HTML) for m in pattern.finditer(text)]
    return [t[1:-1] if t.startswith("<") and t.endswith(">") else t for t in found]


def relative_path(target: str) -> str | None:
    """The file part of a relative link ("" for an anchor on the same page); None for a link elsewhere."""
    parsed = urllib.parse.urlparse(target)
    if parsed.scheme or parsed.netloc or target.startswith("//"):
        return None  # http(s), mailto, ...
    return urllib.parse.unquote(parsed.path)


def test_the_link_reader_finds_every_kind_of_link_and_skips_code():
    text = ('[a](docs/a.md) ![b](docs/b.png "title") [c](<docs/c d.md>) [e](https://x.org/e) '
            '<img src="docs/f.png" width=400> `[g](docs/g.md)`\n\n[h]: docs/h.md\n\n```\n[i](docs/i.md)\n```\n')
    assert links(text) == ["docs/a.md", "docs/b.png", "docs/c d.md", "https://x.org/e", "docs/h.md", "docs/f.png"]
    assert relative_path("https://x.org/e") is None and relative_path("mailto:a@b.c") is None
    assert relative_path("docs/design.md#1-module-map") == "docs/design.md" and relative_path("#top") == ""


@pytest.mark.parametrize("page", _pages(), ids=lambda p: str(p.relative_to(REPO)))
def test_every_relative_link_points_at_a_file_that_exists(page):
    broken = []
    for target in links(page.read_text(encoding="utf-8")):
        path = relative_path(target)
        if path is None or path == "":
            continue
        resolved = (REPO / path.lstrip("/")) if path.startswith("/") else (page.parent / path)
        if not resolved.exists():
            broken.append(target)
    assert not broken, f"{page.relative_to(REPO)}: broken links {broken}"


def test_the_readme_is_a_front_page():
    size = README.stat().st_size
    assert size <= README_LIMIT, f"README.md is {size:,} bytes; at most {README_LIMIT:,} (move detail into docs/)"


def test_the_source_distribution_carries_what_the_readme_links_to():
    """README's links are relative; it says the source distribution carries docs/ (MANIFEST.in), so that they
    resolve there too. The wheel carries none of it (docs/ is outside the packages)."""
    manifest = (REPO / "MANIFEST.in").read_text().split("\n")
    assert "graft docs" in manifest and "include CHANGELOG.md LICENSE" in manifest
    readme = README.read_text(encoding="utf-8")
    targets = {relative_path(t) for t in links(readme)} - {None, ""}
    outside = sorted(t for t in targets if t.split("#")[0] not in ("CHANGELOG.md", "LICENSE")
                     and not t.startswith("docs/"))
    assert not outside, f"README links outside docs/, CHANGELOG.md and LICENSE, which the sdist may not carry: {outside}"
