"""The ``--record FILE.mcap`` option shared by ``run``, ``trials`` and ``demo``
(:func:`softpad.record.open_recorder`, :func:`softpad.trials.check_trial_recordings`)."""

from __future__ import annotations

from typing import Any


def add_record_option(p: Any, per_trial: bool = False) -> None:
    """Add ``--record FILE.mcap`` and ``--force`` to a sub-command's parser."""
    what = "every frame, valve command, robot pose, plan and event as MCAP (ROS 2 types)"
    if per_trial:
        what = f"record every trial: {what}, one file per trial, FILE-OBJECT-tK.mcap"
    p.add_argument("--record", metavar="FILE.mcap", help=what if per_trial else f"record {what}")
    p.add_argument("--force", action="store_true", help="overwrite an existing --record file")
