"""No ground truth in the loop: the controller's commands depend only on what a real system sees.

The world holds the real object; the trial's ``truth`` (the geometry the simulated lab scores
with, and the only place where the lab knows the object's shape) is swapped for a different
object after placement. The pressures are the same, so the loop's commands, their times and
the opening the robot applied must be the same too. (Before issue 10 the robot opened its jaws
to the true object's extent plus 10 mm a side, and both cases here failed: checked by patching
that rule back in.)
"""

from __future__ import annotations

from typing import Any

import pytest

from softpad.sim import get_object
from softpad.trials import TrialConfig, run_trial, trial_execution_params


class _Commands:
    """A recorder that keeps the robot's commands and the loop's decisions, with their times."""

    def __init__(self) -> None:
        self.events: list[tuple[float, str, dict[str, Any]]] = []

    def frame(self, frame: Any, phase: str) -> None:
        pass

    def event(self, t_s: float, kind: str, **data: Any) -> None:
        if kind in ("robot", "plan", "contact", "no_contact", "outcome"):
            self.events.append((round(t_s, 9), kind, data))


def _run(name: str, truth: str | None) -> tuple[Any, list[Any]]:
    rec = _Commands()
    cfg = TrialConfig(trial_execution_params(hold_s=0.5))
    result, _ = run_trial(
        get_object(name),
        seed=11,
        config=cfg,
        truth=None if truth is None else get_object(truth),
        recorder=rec,
    )
    return result, rec.events


@pytest.mark.parametrize(
    ("name", "other"),
    [("object-1", "charger"), ("object-4", "object-6")],
    ids=["brick-as-charger", "stack-as-long-bricks"],
)
def test_swapping_the_true_geometry_changes_no_command(name: str, other: str) -> None:
    result, events = _run(name, None)
    swapped, events_swapped = _run(name, other)
    assert [e for e in events if e[1] == "robot"], "the loop commanded the robot"
    assert events_swapped == events
    assert swapped.opening_m == result.opening_m
    assert swapped.cog == result.cog and swapped.theta == result.theta
    # the jaws open to the mounting's width, whatever the object
    assert result.opening_m == pytest.approx(0.06)
