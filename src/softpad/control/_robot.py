"""Robot interface of the grasp execution, and the simulated robot.

Commands are non-blocking: the execution state machine issues a command, then keeps reading
the box (which, in simulation, advances the clock and the world) and polls the robot. All
poses are in the pad frame (metres, radians; DESIGN.md); a real-robot adapter turns them into
base-frame targets with :class:`softpad.layout.PadPose`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Protocol, runtime_checkable

from softpad.errors import InputError
from softpad.sim import GripperState, World

#: Reach of the simulated arm around the pad's origin in x and y, metres (pad frame).
WORKSPACE_XY_M = 1.0
#: Lowest and highest fingertip height of the simulated arm, metres (pad frame).
WORKSPACE_Z_M = (-0.01, 1.0)
#: Widest gripper opening that may be commanded, metres (wider commands are clamped to the
#: mounting's maximum by the gripper; a parallel jaw never opens wider than this).
MAX_COMMAND_WIDTH_M = 1.0
#: Fastest commanded arm or jaw speed, m/s.
MAX_SPEED_M_S = 2.0


def check_target(x_m: float, y_m: float, z_m: float, width_m: float) -> None:
    """Raise InputError unless a target lies in the simulated arm's workspace.

    Finite coordinates within +/- ``WORKSPACE_XY_M`` in x and y, a height within
    ``WORKSPACE_Z_M`` and a gripper width within 0 .. ``MAX_COMMAND_WIDTH_M``.
    """
    for name, v, lo, hi in (
        ("x_m", x_m, -WORKSPACE_XY_M, WORKSPACE_XY_M),
        ("y_m", y_m, -WORKSPACE_XY_M, WORKSPACE_XY_M),
        ("z_m", z_m, *WORKSPACE_Z_M),
        ("width_m", width_m, 0.0, MAX_COMMAND_WIDTH_M),
    ):
        if not (math.isfinite(v) and lo <= v <= hi):
            raise InputError(f"robot target {name} must be within {lo:g}..{hi:g} m, got {v!r}")


@dataclass(frozen=True)
class ToolPose:
    """Target of the gripper, pad frame.

    Parameters
    ----------
    x_m, y_m
        Centre between the fingertips, metres.
    z_m
        Height of the fingertips' lower faces above the pad base, metres.
    yaw_rad
        Direction in which the jaws close (theta), radians.
    """

    x_m: float
    y_m: float
    z_m: float
    yaw_rad: float

    def __post_init__(self) -> None:
        for n in ("x_m", "y_m", "z_m", "yaw_rad"):
            if not math.isfinite(getattr(self, n)):
                raise InputError(f"tool pose {n} must be finite, got {getattr(self, n)!r}")


@runtime_checkable
class Robot(Protocol):
    """What the execution state machine needs from a robot arm with a parallel-jaw gripper."""

    def move_to(self, pose: ToolPose, speed_m_s: float) -> None:
        """Start a straight-line move to ``pose`` at ``speed_m_s`` (jaws keep their width)."""
        ...

    def descend(self, speed_m_s: float, min_z_m: float) -> None:
        """Start moving straight down at ``speed_m_s``, stopping by itself at ``min_z_m``."""
        ...

    def stop(self) -> None:
        """Stop the arm where it is."""
        ...

    def set_gripper(self, width_m: float, speed_m_s: float) -> None:
        """Start opening/closing the jaws towards ``width_m`` (they stop on an object)."""
        ...

    def is_moving(self) -> bool:
        """True while a commanded motion (arm or jaws) is under way."""
        ...

    def state(self) -> GripperState:
        """Current pose and jaw width."""
        ...

    def holding(self) -> bool:
        """True when the gripper carries an object (jaw-width sensing on a real gripper)."""
        ...

    def first_touch(self) -> tuple[float, float] | None:
        """Ground truth in simulation: (time s, fingertip height m) of the first fingertip
        touch of the current descent; None when unknown (real hardware) or not touched yet."""
        ...


class SimulatedRobot:
    """A kinematic robot driving the gripper of a simulated :class:`~softpad.sim.World`.

    Parameters
    ----------
    world
        The world whose gripper this robot moves (its clock is advanced by the box).
    """

    def __init__(self, world: World) -> None:
        self.world = world
        self._target: GripperState | None = None
        self._last: GripperState | None = None
        self._fresh = False

    def _command(self, target: GripperState, speed_m_s: float) -> None:
        if not (math.isfinite(speed_m_s) and 0 < speed_m_s <= MAX_SPEED_M_S):
            raise InputError(
                f"robot speed must be > 0 and at most {MAX_SPEED_M_S:g} m/s, got {speed_m_s!r}"
            )
        check_target(target.x_m, target.y_m, target.z_m, target.width_m)
        self._target = target
        self._fresh = True
        self.world.command_gripper(target, speed_m_s)

    def move_to(self, pose: ToolPose, speed_m_s: float) -> None:
        s = self.world.gripper_state()
        self._command(
            GripperState(pose.x_m, pose.y_m, pose.z_m, pose.yaw_rad, s.width_m), speed_m_s
        )

    def descend(self, speed_m_s: float, min_z_m: float) -> None:
        s = self.world.gripper_state()
        reset = getattr(self.world, "reset_touch", None)
        if reset is not None:
            reset()
        self._command(GripperState(s.x_m, s.y_m, min_z_m, s.yaw_rad, s.width_m), speed_m_s)

    def stop(self) -> None:
        s = self.world.gripper_state()
        self._target = s
        self.world.command_gripper(s, 0.0)

    def set_gripper(self, width_m: float, speed_m_s: float) -> None:
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

    def state(self) -> GripperState:
        return self.world.gripper_state()

    def holding(self) -> bool:
        return self.world.holding()

    def first_touch(self) -> tuple[float, float] | None:
        t = getattr(self.world, "first_touch_s", None)
        z = getattr(self.world, "first_touch_z_m", None)
        if t is None or z is None:
            return None
        return float(t), float(z)
