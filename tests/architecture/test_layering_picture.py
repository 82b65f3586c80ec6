"""The one architecture picture: drawn from ``softpad.layering``'s table, the same in README.md
and docs/architecture.md, and stating the table exactly."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

import softpad
from softpad import layering
from softpad.layering import ALLOWED_IMPORTS, BEGIN, END, drawn_edges, layering_picture

ROOT = Path(__file__).resolve().parents[2]
SRC = Path(softpad.__file__).parent


def test_every_sub_package_has_a_place_in_the_table() -> None:
    packages = {p.name for p in SRC.iterdir() if (p / "__init__.py").is_file()}
    assert packages == set(ALLOWED_IMPORTS)
    for package, allowed in ALLOWED_IMPORTS.items():
        assert allowed <= set(ALLOWED_IMPORTS), package
        assert package not in layering.below(package), f"{package} is in a cycle"


def test_the_picture_and_its_exceptions_state_the_table_exactly() -> None:
    """Read back from the drawn arrows and the listed exceptions, the table is the same."""
    drawn = drawn_edges()
    for package, allowed in ALLOWED_IMPORTS.items():
        reach: set[str] = set()
        todo = [low for low, high in drawn if high == package]
        while todo:
            p = todo.pop()
            if p not in reach:
                reach.add(p)
                todo += [low for low, high in drawn if high == p]
        assert reach - set(layering.not_drawn().get(package, [])) == allowed, package


@pytest.mark.parametrize("doc", ["README.md", "docs/architecture.md"])
def test_the_docs_show_the_generated_picture(doc: str) -> None:
    text = (ROOT / doc).read_text(encoding="utf-8")
    found = layering.pictures_in(text)
    assert len(found) == 1, f"{doc}: {len(found)} pictures between the markers"
    assert found[0] == layering_picture(), (
        f"{doc}'s picture is not the generated one: python -m softpad.layering --write {doc}"
    )
    assert text.count("```mermaid") == 1, f"{doc}: a second picture"


def test_a_changed_table_changes_the_picture(monkeypatch: pytest.MonkeyPatch) -> None:
    """The comparison above can fail: one more allowed import is a new arrow or exception."""
    before = layering_picture()
    table = dict(ALLOWED_IMPORTS)
    table["control"] = table["control"] | {"sim"}
    monkeypatch.setattr(layering, "ALLOWED_IMPORTS", table)
    after = layering_picture()
    assert after != before
    assert "`control` not config, fem, sim" in before
    assert "`control` not config, fem;" in after


def test_the_generator_writes_between_the_markers(tmp_path: Path) -> None:
    doc = tmp_path / "doc.md"
    doc.write_text(f"# Title\n\n{BEGIN}\nold picture\n{END}\n\nText after.\n")
    out = subprocess.run(
        [sys.executable, "-m", "softpad.layering", "--write", str(doc)],
        capture_output=True,
        text=True,
    )
    assert out.returncode == 0, out.stderr
    assert "updated" in out.stdout
    assert doc.read_text() == f"# Title\n\n{layering_picture()}\n\nText after.\n"
    again = subprocess.run(
        [sys.executable, "-m", "softpad.layering", "--write", str(doc)],
        capture_output=True,
        text=True,
    )
    assert "up to date" in again.stdout


def test_the_package_docstring_points_to_the_picture() -> None:
    """No third picture in ``softpad/__init__.py``: a pointer instead."""
    doc = softpad.__doc__ or ""
    assert "docs/architecture.md" in doc and "->" not in doc
