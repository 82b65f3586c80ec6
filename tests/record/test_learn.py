"""``softpad learn`` reads a recording's metadata and events through its index, not its frames:
the same events and metadata as the full reader (what :func:`learned_trial` reads), and the
full reader for a file without an index."""

from __future__ import annotations

from pathlib import Path

import pytest

from softpad.record import RecordedRun, load_recording
from softpad.record._learn import _trial_events

DATA = Path(__file__).resolve().parents[1] / "data"


@pytest.mark.parametrize("name", ["banana.mcap", "cylinder.mcap"])
def test_the_index_gives_what_the_full_reader_gives(name: str) -> None:
    path = str(DATA / name)
    light, full = _trial_events(path), load_recording(path)
    assert not isinstance(light, RecordedRun)
    assert [(k, d) for _, k, d in light.events] == [(k, d) for _, k, d in full.events]
    assert light.metadata == {k: v for k, v in full.metadata.items() if k != "clock_offset_ns"}
    assert "plan" in [k for _, k, _ in light.events] and light.metadata["objects"]


def test_a_file_cut_short_goes_through_the_full_reader(tmp_path: Path) -> None:
    """The last third cut off (no summary, no index): the full reader reads what it can."""
    data = (DATA / "banana.mcap").read_bytes()
    cut = tmp_path / "cut.mcap"
    cut.write_bytes(data[: 2 * len(data) // 3])
    got = _trial_events(str(cut))
    assert isinstance(got, RecordedRun) and not got.complete


def test_a_recording_without_increments_is_named(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """tests/data's recordings predate the plan's increments: a clear error, exit 2."""
    from softpad.cli.main import main

    out = tmp_path / "c.toml"
    assert main(["learn", str(DATA / "banana.mcap"), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert "banana.mcap" in err and "no increments_pa" in err and not out.exists()
