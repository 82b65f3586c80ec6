"""Holding the MuJoCo world still (``MujocoWorld.rest_while_still``, a trial's valve check):
no step solved while the arm stands, the loads and poses held, the time running on; a
command to the arm steps the world for real again."""

from __future__ import annotations

import numpy as np
import pytest

from softpad.layout import PadLayout
from softpad.sim import GripperState
from softpad.sim._mujoco_model import ObjectModel, ObjectPart
from softpad.sim._mujoco_world import MujocoWorld

pytestmark = pytest.mark.mujoco

PITCH = PadLayout().pitch_m
DT = 1e-2  # the box's sample period at 100 Hz


class _At:
    def __init__(self, x_m: float, y_m: float) -> None:
        self.x_m, self.y_m, self.yaw_rad = x_m, y_m, 0.0


def _resting_brick() -> MujocoWorld:
    """A 50 g brick settled on the pad's centre module row for 1.5 s (the hand high above)."""
    world = MujocoWorld()
    part = ObjectPart("box", 0.05, (0, 0, 0.0155), size_m=(0.031,) * 3)
    world.place_object(ObjectModel("brick", (part,)), _At(1.5 * PITCH, 1.5 * PITCH))
    for _ in range(150):
        world.step(DT)
    return world


class _Steps:
    """MuJoCo steps solved since it was made or cleared (MuJoCo's own count of ``mj_step``
    calls: the world's Python and compiled steps alike)."""

    def __init__(self, world: MujocoWorld) -> None:
        self._data = world.scene.data
        self.clear()

    def _count(self) -> int:
        import mujoco

        return int(self._data.timer[mujoco.mjtTimer.mjTIMER_STEP].number)

    def clear(self) -> None:
        self._start = self._count()

    def __len__(self) -> int:
        return self._count() - self._start


def _count_steps(world: MujocoWorld) -> _Steps:
    """The MuJoCo steps solved from now on."""
    return _Steps(world)


def test_a_resting_world_solves_no_step_and_holds_its_loads() -> None:
    world = _resting_brick()
    loads = world.module_loads_n()
    assert loads.sum() > 0.3  # the brick's weight (0.49 N) rests on the modules
    pose = world.object_pose("brick")
    t0, mj_t0 = world.time_s, world.scene.data.time
    calls = _count_steps(world)
    world.rest_while_still(True)
    heights = np.full(world.layout.n_modules, 0.012)
    for _ in range(100):
        world.step(DT, heights)
    assert not calls
    np.testing.assert_array_equal(world.module_loads_n(), loads)
    assert world.object_pose("brick") == pose
    assert world.time_s == pytest.approx(t0 + 1.0, abs=1e-9)
    assert world.scene.data.time == pytest.approx(mj_t0 + 1.0, abs=1e-9)
    # the module springs still follow the box's heights (as in every step)
    spring = world.scene.qpos_spring[world.scene.module_q]
    assert np.all(np.abs(spring - heights) < np.abs(world.pad.free_height_m - heights))


def test_a_moving_arm_or_rest_switched_off_steps_the_world() -> None:
    world = _resting_brick()
    calls = _count_steps(world)
    world.rest_while_still(True)
    s = world.gripper_state()
    world.command_gripper(GripperState(s.x_m, s.y_m, s.z_m - 0.01, s.yaw_rad, s.width_m), 0.05)
    world.step(DT)
    assert len(calls) == 5  # 2 ms steps in a 10 ms sample period
    world.rest_while_still(False)
    world.command_gripper(world.gripper_state(), 0.0)  # stop: the arm stands
    calls.clear()
    world.step(DT)
    assert len(calls) == 5
