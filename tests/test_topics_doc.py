"""docs/ros.md prints the topic table exactly as :mod:`softpad.topics` makes it (``python -m
softpad.topics --write docs/ros.md`` updates it)."""

from __future__ import annotations

from pathlib import Path

from softpad.topics import BEGIN, END, markdown_table

DOC = Path(__file__).resolve().parents[1] / "docs" / "ros.md"


def test_docs_show_the_tables_topics() -> None:
    text = DOC.read_text(encoding="utf-8")
    start, stop = text.index(BEGIN) + len(BEGIN), text.index(END)
    assert text[start:stop].strip() == markdown_table()
