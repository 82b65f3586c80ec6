"""Stepping helpers shared by the MuJoCo world's tests (not a test module)."""

from __future__ import annotations

from softpad.layout import PadLayout
from softpad.sim import GripperState
from softpad.sim._mujoco_world import MujocoWorld

PITCH = PadLayout().pitch_m
X = Y = 1.5 * PITCH  # the pad's middle, between modules 2, 3, 5 and 6
DT = 1e-2  # the box's sample period at 100 Hz


class At:
    """A placement at (x_m, y_m), yaw 0 (what ``MujocoWorld.place_object`` reads)."""

    def __init__(self, x_m: float, y_m: float) -> None:
        self.x_m, self.y_m, self.yaw_rad = x_m, y_m, 0.0


def run(world: MujocoWorld, seconds: float) -> None:
    """Step the world ``seconds`` at the box's sample period."""
    for _ in range(round(seconds / DT)):
        world.step(DT)


def settle(world: MujocoWorld, seconds: float = 0.5) -> None:
    """Step the world ``seconds`` in 1 ms steps."""
    for _ in range(round(seconds / 1e-3)):
        world.step(1e-3)


def move_to(world: MujocoWorld, target: GripperState, speed_m_s: float, rest_s: float) -> None:
    """Command the hand and step until it has arrived (at most 5 s), then ``rest_s`` more."""
    world.command_gripper(target, speed_m_s)
    for _ in range(5000):
        now = world.gripper_state()
        if (
            max(abs(now.x_m - target.x_m), abs(now.y_m - target.y_m), abs(now.z_m - target.z_m))
            < 1e-6
        ):
            break
        world.step(1e-3)
    else:
        raise AssertionError(f"the hand did not reach {target} in 5 s")
    settle(world, rest_s)
