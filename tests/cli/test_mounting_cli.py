"""``--mounting`` on the commands that run trials: parsed, refused when bad or doubled."""

from __future__ import annotations

import pytest

from softpad.cli.main import build_parser, main


@pytest.mark.parametrize("command", ["trials", "compare", "design", "validate"])
def test_every_trial_command_takes_mounting_auto(command: str) -> None:
    args = build_parser().parse_args([command, "--mounting", "auto"])
    assert args.mounting == "auto"
    assert build_parser().parse_args([command]).mounting is None  # each object's own


def test_bad_or_doubled_mountings_are_refused(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["trials", "--mounting", "7/3"]) == 2
    assert "invalid choice: '7/3'" in capsys.readouterr().err
    assert main(["design", "--gripper", "6/2", "--mounting", "auto", "--quick"]) == 2
    assert "not both" in capsys.readouterr().err
