"""Checks of a trial campaign's recordings before it runs."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any


def check_trial_recordings(
    base: str | None, specs: Sequence[Any], trials: int, force: bool
) -> None:
    """Refuse, before any trial runs, a ``--record`` base whose trial files exist (unless
    ``force``) or that is not a ``.mcap`` name.

    Parameters
    ----------
    base
        The recordings' base name (``FILE.mcap``), or None (nothing recorded).
    specs
        The objects tried (their names name the files).
    trials
        Trials per object.
    force
        Overwrite existing trial files.
    """
    if not base:
        return
    from softpad.record import check_output
    from softpad.trials._runner import trial_recording_path

    check_output(base, force=True)  # the name itself: .mcap, existing folder
    for spec in specs:
        for k in range(trials):
            check_output(trial_recording_path(base, spec.name, k), force)


__all__ = ["check_trial_recordings"]
