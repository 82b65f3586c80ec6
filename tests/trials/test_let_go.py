"""A held object is put back on the pad and let go without a pressure spike.

Before, the simulated robot reported an opening finished once the jaws had not moved for a
read, which a grip still relaxing does; the loop then lifted the arm with the object in its
jaws and dropped it from up to 12 cm: on development seeds 1000-1005 (gripper-aware planner,
adaptive detector, randomised labs) 6 of 31 held trials of six Table 6.1 objects faulted in
``release`` at the configured maximum or the sensor's 10 kPa full scale. Here the toy and the
charger (two heavy, lopsided objects) at seeds 0-7, same pair and labs: on the old robot a
held toy read 10 kPa (seed 4). Now no held trial of them reaches the trials' configured
maximum (9.5 kPa: a gripper pressing an object into the pad reads above the 3 kPa inflation
maximum; ``trial_execution_params``).
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from softpad.sim import get_object
from softpad.trials import TrialConfig, run_trial, trial_execution_params, trial_seed

pytestmark = [pytest.mark.mujoco, pytest.mark.slow]

SEEDS = range(8)


class _Release:
    """The highest module pressure read while the held object is put down and let go, and
    the faults of the run."""

    def __init__(self) -> None:
        self.peak_pa = 0.0
        self.faults: list[dict[str, Any]] = []

    def frame(self, frame: Any, phase: str) -> None:
        if phase == "release":
            self.peak_pa = max(self.peak_pa, float(np.nanmax(frame.pressures_pa)))

    def event(self, t_s: float, kind: str, **data: Any) -> None:
        if kind == "fault":
            self.faults.append(data)


@pytest.mark.parametrize("name", ["toy", "charger"])
def test_held_objects_are_let_go_under_the_rated_maximum(name: str) -> None:
    config = TrialConfig(
        trial_execution_params(hold_s=15),
        planner="gripper-aware",
        detector="adaptive",
        randomize=True,
    )
    limit_pa = config.execution.inflation.max_pressure_pa
    held = []
    for seed in SEEDS:
        watch = _Release()
        result, _ = run_trial(
            get_object(name), 0, trial_seed(seed, name, 0), config, recorder=watch
        )
        if result.success:
            held.append((seed, watch.peak_pa, watch.faults))
    assert len(held) >= 3, held  # enough held grasps to judge the release
    for seed, peak_pa, faults in held:
        assert peak_pa < limit_pa, (seed, peak_pa)
        assert not faults, (seed, faults)
