"""softpad.record.export_recording: the table's format by suffix, a format named by option
needs its suffix, and what was written in words."""

from __future__ import annotations

import pytest

from softpad.errors import InputError
from softpad.record import export_recording


class _Run:
    def __init__(self) -> None:
        self.events = [(0.0, "phase", {}), (1.0, "outcome", {})]
        self.written: list[tuple[str, str]] = []

    def __len__(self) -> int:
        return 12

    def to_csv(self, path: str) -> None:
        self.written.append(("csv", path))

    def to_parquet(self, path: str) -> None:
        self.written.append(("parquet", path))


def test_the_table_format_follows_the_suffix() -> None:
    run = _Run()
    text, out = export_recording(run, "r.mcap", ("t.parquet", None, None))
    assert (out, run.written) == ("t.parquet", [("parquet", "t.parquet")])
    assert text == "12 frames and 2 events written to t.parquet"
    export_recording(run, "r.mcap", (None, "t.csv", None))
    assert run.written[-1] == ("csv", "t.csv")


@pytest.mark.parametrize(
    ("table", "message"),
    [
        ((None, "t.txt", None), "must end in its format's suffix, got 't.txt'"),
        (("t.txt", None, None), "--out must end in .csv or .parquet, got 't.txt'"),
        ((None, None, None), "give the file to export to"),
    ],
    ids=["csv-suffix", "out-suffix", "none"],
)
def test_a_table_without_its_suffix_is_refused(table, message) -> None:
    run = _Run()
    with pytest.raises(InputError, match=message):
        export_recording(run, "r.mcap", table)
    assert run.written == []
