"""The simulated robot: the control layer's :class:`~softpad.control.Robot` on a simulated world."""

from __future__ import annotations

import math
from dataclasses import dataclass

from softpad.control import RobotState, ToolPose
from softpad.errors import InputError
from softpad.sim import GripperState, World


@dataclass(frozen=True)
class TouchTruth:
    """Ground truth of one descent, read from the simulated world after it.

    Attributes
    ----------
    first_touch_s
        Box time of the first fingertip touch, seconds (None: the fingers touched nothing).
    first_touch_z_m
        Fingertip height at the first touch, metres.
    """

    first_touch_s: float | None
    first_touch_z_m: float | None


def _robot_state(s: GripperState) -> RobotState:
    return RobotState(s.x_m, s.y_m, s.z_m, s.yaw_rad, s.width_m)


class SimulatedRobot:
    """A kinematic robot driving the gripper of a simulated :class:`~softpad.sim.World`.

    Commands are non-blocking; the world advances with the box's reads. After each descent
    the world's first-touch record is appended to :attr:`touches` (ground truth for scoring).

    Parameters
    ----------
    world
        The world whose gripper this robot moves.
    max_opening_m
        Widest opening the robot commands, metres (the world clamps to the mounting's).
    """

    def __init__(self, world: World, max_opening_m: float = math.inf) -> None:
        self.world = world
        self.max_opening_m = max_opening_m
        self.touches: list[TouchTruth] = []
        self._target: GripperState | None = None
        self._last: GripperState | None = None
        self._fresh = False
        self._descending = False

    def _end_descent(self) -> None:
        if self._descending:
            w = self.world
            self.touches.append(TouchTruth(w.first_touch_s, w.first_touch_z_m))
            self._descending = False

    def _command(self, target: GripperState, speed_m_s: float) -> None:
        if not (math.isfinite(speed_m_s) and speed_m_s > 0):
            raise InputError(f"robot speed must be a positive number of m/s, got {speed_m_s!r}")
        self._target = target
        self._fresh = True
        self.world.command_gripper(target, speed_m_s)

    def move_to(self, pose: ToolPose, speed_m_s: float) -> None:
        self._end_descent()
        s = self.world.gripper_state()
        self._command(
            GripperState(pose.x_m, pose.y_m, pose.z_m, pose.yaw_rad, s.width_m), speed_m_s
        )

    def descend(self, speed_m_s: float, min_z_m: float) -> None:
        self._end_descent()
        s = self.world.gripper_state()
        self.world.reset_touch()
        self._command(GripperState(s.x_m, s.y_m, min_z_m, s.yaw_rad, s.width_m), speed_m_s)
        self._descending = True

    def stop(self) -> None:
        self._end_descent()
        s = self.world.gripper_state()
        self._target = s
        self.world.command_gripper(s, 0.0)

    def set_gripper(self, width_m: float, speed_m_s: float) -> None:
        self._end_descent()
        width_m = min(width_m, self.max_opening_m)
        s = self.world.gripper_state()
        self._command(GripperState(s.x_m, s.y_m, s.z_m, s.yaw_rad, width_m), speed_m_s)

    def is_moving(self) -> bool:
        s = self.world.gripper_state()
        if self._target is None or s == self._target:
            self._last = s
            return False
        moved = s != self._last
        self._last = s
        if self._fresh:  # a command was just given: allow one step before judging
            self._fresh = False
            return True
        return moved  # False when the jaws stopped on an object short of their target

    def state(self) -> RobotState:
        return _robot_state(self.world.gripper_state())

    def holding(self) -> bool:
        return self.world.holding()
