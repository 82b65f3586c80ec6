"""Coasting through the settled hold (``TrialConfig.coast_settled_hold``, the default) against
the reference that solves every MuJoCo step: every field of every TrialResult equal (the wall
time excepted) but the simulated time, within :data:`SIM_TIME_TOLERANCE_S`, the thesis's 15 s
hold. A handful of trials here, Experiment 2's seeds 0-1 and
randomised labs in the slow suite (docs/trials.md gives the figures)."""

from __future__ import annotations

import dataclasses
from typing import Any

import pytest

from softpad.sim import _mujoco_coast as coast_module
from softpad.sim import get_object
from softpad.trials import TrialConfig, run_trial, trial_seed

pytestmark = pytest.mark.mujoco

#: The trial's simulated time may end a few box samples apart: after the hold the robot's
#: release waits on its own jaw reading (10 um steps), and the jaws' creep carried on at a
#: constant rate in the coasted part of the hold reads a step apart now and then (3 of 110
#: trials of Experiment 2's seeds 0-1 ended 10, 10 and 30 ms later). Nothing the trial is scored
#: on comes after the hold.
SIM_TIME_TOLERANCE_S = 0.1

OBJECTS = (
    "object-1",
    "object-2",
    "object-3",
    "object-4",
    "object-5",
    "object-6",
    "banana",
    "toy",
    "limes",
    "cylinder",
    "charger",
)


def _fields(name: str, seed: int, trial: int, coast: bool, randomize: bool) -> dict[str, Any]:
    # the hold's coasting alone: every other step solved (coast_free_hand changes results
    # within a tolerance, docs/benchmarks.md; with it on in both runs the can below happens to
    # end alike, by the chaos of its edge grasp, not because the hold's coasting is exact)
    config = TrialConfig(coast_settled_hold=coast, randomize=randomize, coast_free_hand=False)
    result, _ = run_trial(get_object(name), trial, trial_seed(seed, name, trial), config)
    d = dataclasses.asdict(result)
    del d["wall_time_s"]
    return d


class _Coasted:
    """The coasted steps of the trials run after it was made (every world's ``HoldCoast``
    counts its own, in the Python steps and the compiled ones alike)."""

    def __init__(self, monkeypatch: pytest.MonkeyPatch) -> None:
        self.coasts: list[coast_module.HoldCoast] = []
        original = coast_module.HoldCoast.__init__

        def kept(c: coast_module.HoldCoast, *args: Any, **kwargs: Any) -> None:
            original(c, *args, **kwargs)
            self.coasts.append(c)

        monkeypatch.setattr(coast_module.HoldCoast, "__init__", kept)

    def __len__(self) -> int:
        return sum(c.coasted_steps for c in self.coasts)


def _coasted(monkeypatch: pytest.MonkeyPatch) -> _Coasted:
    """Counts the coasted steps of the trials run after it."""
    return _Coasted(monkeypatch)


def _assert_equivalent(name: str, seed: int, trials: range, randomize: bool = False) -> None:
    for k in trials:
        ref = _fields(name, seed, k, False, randomize)
        fast = _fields(name, seed, k, True, randomize)
        t_ref, t_fast = ref.pop("sim_time_s"), fast.pop("sim_time_s")
        diff = {f: (ref[f], fast[f]) for f in ref if ref[f] != fast[f]}
        assert not diff, f"{name} seed {seed} trial {k}: {diff}"
        assert abs(t_fast - t_ref) <= SIM_TIME_TOLERANCE_S, (name, seed, k, t_ref, t_fast)


@pytest.mark.parametrize(("name", "trial"), [("banana", 0), ("charger", 1)])
def test_coasting_the_hold_changes_no_trial_result(
    name: str, trial: int, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Two of Experiment 2's seed-0 trials: the same result with and without coasting, and
    more than 6 s of the 15 s hold coasted (3,000 steps of 2 ms)."""
    steps = _coasted(monkeypatch)
    _assert_equivalent(name, 0, range(trial, trial + 1))
    assert len(steps) * TrialConfig().mujoco_timestep_s > 6.0


#: Since the fingertips' friction reaches MuJoCo (issue 45: 0.5, not the objects' 0.8), the can
#: of seed 0, trial 2 slips slowly in the hold: stepped it ends 'slipped_during_hold', coasted
#: 'object_outside_jaws' (both failures; the cause differs). Coasting at a steady slip is not
#: exact there; strict, so that the case fails once coasting is made exact again (issue 50).
_SLIPS_IN_THE_HOLD = pytest.mark.xfail(
    reason="coasting a slowly slipping can changes its failure's cause (issue 50)", strict=True
)


@pytest.mark.slow
@pytest.mark.parametrize(
    ("name", "seed"),
    [
        pytest.param(n, s, marks=_SLIPS_IN_THE_HOLD, id=f"{n}-{s}")
        if (n, s) == ("cylinder", 0)
        else pytest.param(n, s, id=f"{n}-{s}")
        for s in (0, 1)
        for n in OBJECTS
    ],
)
def test_coasting_changes_no_result_of_experiment_2(name: str, seed: int) -> None:
    """Experiment 2's seeds 0 and 1 (110 trials): every result equal."""
    _assert_equivalent(name, seed, range(5))


@pytest.mark.slow
@pytest.mark.parametrize("name", OBJECTS)
def test_coasting_changes_no_result_in_randomised_labs(name: str) -> None:
    """Seed 2 with every uncertain input drawn (fingertip friction down to 0.3, grip force
    down to 10 N: the labs where objects slip): every result equal."""
    _assert_equivalent(name, 2, range(5), randomize=True)
