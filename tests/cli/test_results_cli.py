"""softpad results --quick: every quoted result rerun, written with commit, date, machine and
the command of each."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from softpad.cli.main import main
from softpad.trials import RESULTS


@pytest.mark.slow
@pytest.mark.mujoco
def test_quick_results_file(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "results.md"
    assert main(["results", "--quick", "--out", str(out), "--workers", "1", "--json"]) == 0
    ran = json.loads(capsys.readouterr().out)
    assert [r["exit"] for r in ran["results"]] == [0] * len(RESULTS)
    text = out.read_text()
    for key in ("- commit: ", "- date: ", "- machine: ", "- size: quick"):
        assert key in text
    for spec in RESULTS:
        assert f"## {spec.name}" in text
        assert f"Command: `softpad {' '.join(spec.quick)}" in text
    assert "failed (exit" not in text
    assert "| Experiment 2 held, all objects | 52/55 |" in text


def test_existing_output_needs_force(tmp_path: Path) -> None:
    out = tmp_path / "results.md"
    out.write_text("keep")
    assert main(["results", "--quick", "--out", str(out)]) == 2
    assert out.read_text() == "keep"


@pytest.mark.parametrize("size", ["argv", "full", "quick"])
def test_every_command_parses(size: str) -> None:
    """Each result's command line is valid for the parser (no work is run)."""
    from softpad.cli.main import build_parser

    parser = build_parser()
    for spec in RESULTS:
        parser.parse_args(list(getattr(spec, size)))
