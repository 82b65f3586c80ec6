"""The front page: README.md fits a screen and starts with the two set-up commands; its links
resolve; its headline figures come from docs/results.md once ``make results`` has written it.
(Every shell block of README.md and docs/*.md runs in tests/test_docs.py.)"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

#: The front page fits a screen or two (issue 36).
README_MAX_LINES = 120


def test_the_readme_fits_a_screen_and_starts_with_the_two_commands() -> None:
    text = (ROOT / "README.md").read_text()
    lines = text.splitlines()
    assert len(lines) <= README_MAX_LINES, f"README.md has {len(lines)} lines (limit 120)"
    first = re.search(r"```bash\n(.*?)```", text, flags=re.S)
    assert first is not None
    commands = [ln.split("#")[0].strip() for ln in first.group(1).splitlines()]
    assert commands[:2] == ["make demo", "make test"], commands


def test_every_doc_the_readme_links_exists() -> None:
    text = (ROOT / "README.md").read_text()
    links = re.findall(r"\]\(([^)#]+\.md)(?:#[^)]*)?\)", text)
    assert len(links) >= 10
    missing = [link for link in links if link != "docs/results.md" and not (ROOT / link).is_file()]
    assert not missing, missing


def headline_figures() -> list[str]:
    """The README's headline figures: the bold spans with a digit in its figures section."""
    text = (ROOT / "README.md").read_text()
    section = text.split("## Headline figures", 1)[1].split("\n## ", 1)[0]
    return [f for f in re.findall(r"\*\*(.+?)\*\*", section) if re.search(r"\d", f)]


def test_the_readme_quotes_only_figures_of_docs_results() -> None:
    """Issue 33: README.md quotes only figures that ``softpad results`` wrote."""
    figures = headline_figures()
    assert len(figures) >= 3
    results = ROOT / "docs" / "results.md"
    if not results.is_file():
        pytest.skip("docs/results.md not written yet (make results)")
    text = results.read_text()
    absent = [f for f in figures if f not in text]
    assert not absent, (
        f"README.md's headline figures {absent} are not in docs/results.md: quote the figures "
        "of docs/results.md (and its commit) in README.md"
    )
