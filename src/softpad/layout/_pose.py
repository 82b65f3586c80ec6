"""Pose of the pad in the robot base frame."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from softpad.errors import check_finite


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
        for name in ("x_m", "y_m", "z_m", "yaw_rad"):
            check_finite(f"pad pose {name}", getattr(self, name))

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
