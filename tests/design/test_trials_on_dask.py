"""``softpad trials --scheduler``: the seeds' trials as Dask tasks give the trials of
``run_experiment`` (trial seeds do not depend on where a trial ran)."""

from __future__ import annotations

import json

import pytest

from softpad.cli.main import main

pytestmark = [pytest.mark.mujoco, pytest.mark.slow]


def test_trials_on_a_local_dask_cluster_match_the_process_pool(
    capsys: pytest.CaptureFixture[str],
) -> None:
    common = [
        "trials",
        "--objects",
        "banana",
        "--trials",
        "1",
        "--seeds",
        "0-1",
        "--hold-s",
        "1",
        "--json",
        "--no-progress",
    ]
    assert main([*common, "--workers", "1"]) == 0
    pool = json.loads(capsys.readouterr().out)
    assert main([*common, "--workers", "1", "--scheduler", "local"]) == 0
    dask = json.loads(capsys.readouterr().out)
    assert dask["seeds"] == pool["seeds"] == [0, 1]
    ta = [{k: v for k, v in t.items() if k != "wall_time_s"} for t in pool["trials"]]
    tb = [{k: v for k, v in t.items() if k != "wall_time_s"} for t in dask["trials"]]
    assert len(ta) == 2 and ta == tb


def test_trials_scheduler_must_be_loopback(capsys: pytest.CaptureFixture[str]) -> None:
    assert (
        main(
            ["trials", "--objects", "banana", "--trials", "1", "--scheduler", "tcp://10.1.1.1:8786"]
        )
        == 2
    )
    assert "127.0.0.1" in capsys.readouterr().err
