"""The valve check that ends a trial with the MuJoCo world held still
(``TrialConfig.still_valve_check``, the default) against every step solved: the same result,
field for field (the wall time excepted), and the check's 3 s of steps not solved."""

from __future__ import annotations

import dataclasses
from typing import Any

import pytest

from softpad.sim import get_object
from softpad.sim._mujoco_world import MujocoWorld
from softpad.trials import TrialConfig, run_trial, trial_seed

pytestmark = pytest.mark.mujoco


def _fields(name: str, still: bool) -> dict[str, Any]:
    config = TrialConfig(still_valve_check=still)
    result, _ = run_trial(get_object(name), 0, trial_seed(0, name, 0), config)
    d = dataclasses.asdict(result)
    del d["wall_time_s"]
    return d


@pytest.mark.parametrize("name", ["object-3", "limes"])
def test_a_still_valve_check_changes_no_trial_result(
    name: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    worlds: list[MujocoWorld] = []
    original = MujocoWorld.__init__

    def kept(self: MujocoWorld, *args: Any, **kwargs: Any) -> None:
        original(self, *args, **kwargs)
        worlds.append(self)

    # each world counts its steps held still (the Python steps and the compiled ones alike)
    monkeypatch.setattr(MujocoWorld, "__init__", kept)
    stepped = _fields(name, False)
    assert worlds and not sum(w.rested_steps for w in worlds)
    worlds.clear()
    still = _fields(name, True)
    assert still == stepped
    # the valve check's pulses and sealed watch: about 3.5 s of 2 ms steps held still
    assert sum(w.rested_steps for w in worlds) > 1000
