"""``softpad trials --record``: one MCAP per trial, each replayable."""

from __future__ import annotations

import pytest

from softpad.cli.main import main
from softpad.record import compare_replay, load_recording

pytestmark = pytest.mark.mujoco


def test_every_trial_is_recorded_and_replays(tmp_path, capsys) -> None:
    base = tmp_path / "exp.mcap"
    argv = ["trials", "--objects", "banana", "--trials", "2", "--hold-s", "0.5", "--workers", "1"]
    assert main([*argv, "--no-progress", "--record", str(base)]) == 0
    files = sorted(tmp_path.glob("exp-banana-t*.mcap"))
    assert [f.name for f in files] == ["exp-banana-t1.mcap", "exp-banana-t2.mcap"]
    for f in files:
        run = load_recording(f)
        assert run.metadata["command"] == "trials" and run.robot_poses.shape[0] > 10
        assert compare_replay(run)["same"]
    capsys.readouterr()
    assert main([*argv, "--record", str(base)]) == 2  # never overwritten silently
    assert "refusing to overwrite" in capsys.readouterr().err
