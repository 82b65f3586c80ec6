"""Pose of the pad in the robot base frame."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from softpad.errors import MM_AS_M, check_finite, check_range

#: Farthest a pad (or an object on it) may lie from the robot's base, metres: beyond it a
#: length is a unit mix-up (millimetres given as metres).
POSE_LIMIT_M = 10.0


@dataclass(frozen=True)
class PadPose:
    """Rigid transform from the pad frame to the robot base frame.

    Parameters
    ----------
    x_m, y_m, z_m
        Position of the pad-frame origin (bottom-left corner of the pad, on its top surface)
        in the robot base frame, metres.
    yaw_rad
        Rotation of the pad's x axis about the base z axis, radians.
    """

    x_m: float = 0.0
    y_m: float = 0.0
    z_m: float = 0.0
    yaw_rad: float = 0.0

    def __post_init__(self) -> None:
        for name in ("x_m", "y_m", "z_m"):  # the installation file's limit (PadSettings)
            check_range(
                f"pad pose {name}", getattr(self, name), -POSE_LIMIT_M, POSE_LIMIT_M, "m", MM_AS_M
            )
        check_finite("pad pose yaw_rad", self.yaw_rad)

    @property
    def rotation(self) -> NDArray[np.float64]:
        """3x3 rotation matrix pad -> base."""
        c, s = np.cos(self.yaw_rad), np.sin(self.yaw_rad)
        return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])

    def to_base(self, point_pad_m: tuple[float, ...] | NDArray[np.float64]) -> NDArray[np.float64]:
        """Map a pad-frame point (x, y) or (x, y, z) in metres to the robot base frame."""
        p = np.zeros(3)
        q = np.asarray(point_pad_m, dtype=float)
        p[: q.size] = q
        return self.rotation @ p + np.array([self.x_m, self.y_m, self.z_m])

    def yaw_to_base(self, theta_pad_rad: float) -> float:
        """Direction of grasp in the pad frame -> gripper yaw in the base frame, in (-pi, pi]."""
        a = theta_pad_rad + self.yaw_rad
        return float(np.arctan2(np.sin(a), np.cos(a)))
