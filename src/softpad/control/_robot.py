"""Robot interface of the grasp execution: target poses, the robot's state, the protocol.

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


@dataclass(frozen=True)
class ToolPose:
    """Target of the gripper, pad frame."""

    #: Centre between the fingertips, metres.
    x_m: float
    #: Centre between the fingertips, metres.
    y_m: float
    #: Height of the fingertips' lower faces above the pad base, metres.
    z_m: float
    #: Direction in which the jaws close (theta), radians.
    yaw_rad: float

    def __post_init__(self) -> None:
        for n in ("x_m", "y_m", "z_m", "yaw_rad"):
            if not math.isfinite(getattr(self, n)):
                raise InputError(f"tool pose {n} must be finite, got {getattr(self, n)!r}")


@dataclass(frozen=True)
class RobotState:
    """Where the gripper is, as the robot itself measures it (pad frame): the fields of
    :class:`ToolPose` (metres, radians) and ``width_m``, the distance between the fingertips'
    inner faces, metres."""

    x_m: float
    y_m: float
    z_m: float
    yaw_rad: float
    width_m: float

    @property
    def pose(self) -> ToolPose:
        """The pose part of the state."""
        return ToolPose(self.x_m, self.y_m, self.z_m, self.yaw_rad)


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

    def state(self) -> RobotState:
        """Current pose and jaw width."""
        ...

    def holding(self) -> bool:
        """True when the gripper reports holding something: its jaws, closed, stopped short
        of their fully closed opening (and its force, where the gripper gives it). Only the
        robot's own sensing: a simulated robot does not ask the world's contacts."""
        ...


class RobotWrapper:
    """A :class:`Robot` that forwards every call to the robot it wraps (``inner``): subclass it
    and override the calls to watch or change (as :class:`softpad.box.BoxWrapper` for boxes);
    what is not overridden reaches ``inner`` unchanged."""

    def __init__(self, inner: Robot) -> None:
        self.inner = inner

    def move_to(self, pose: ToolPose, speed_m_s: float) -> None:
        self.inner.move_to(pose, speed_m_s)

    def descend(self, speed_m_s: float, min_z_m: float) -> None:
        self.inner.descend(speed_m_s, min_z_m)

    def stop(self) -> None:
        self.inner.stop()

    def set_gripper(self, width_m: float, speed_m_s: float) -> None:
        self.inner.set_gripper(width_m, speed_m_s)

    def is_moving(self) -> bool:
        return self.inner.is_moving()

    def state(self) -> RobotState:
        return self.inner.state()

    def holding(self) -> bool:
        return self.inner.holding()
