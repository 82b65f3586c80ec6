"""The world interface: what loads the modules.

A world holds the objects resting on the pad and the gripper, and tells the simulated box
which vertical force presses on each module. The analytic world (footprints and mass
distributions) and the MuJoCo world (rigid-body contact) both implement :class:`World`, so the
simulated box, the simulated robot and the trials do not care which one runs.

Frames and units: everything is in the pad frame (DESIGN.md), SI units. ``z`` is measured
from the pad's rigid base surface upward, so an inflated module's top sits at ``height_m``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol, runtime_checkable

import numpy as np
from numpy.typing import NDArray

from softpad.layout import PadLayout


@dataclass(frozen=True)
class GripperState:
    """Kinematic state of the parallel-jaw gripper, pad frame.

    Parameters
    ----------
    x_m, y_m
        Position of the gripper's centre (between the fingertips), metres.
    z_m
        Height of the fingertips' lower faces above the pad base, metres.
    yaw_rad
        Direction in which the jaws close, from the pad x axis (theta of the planner), radians.
    width_m
        Distance between the inner faces of the fingertips, metres.
    """

    x_m: float
    y_m: float
    z_m: float
    yaw_rad: float
    width_m: float


@runtime_checkable
class World(Protocol):
    """What the simulated box and robot need from a world. Owned by the box/closed-loop code."""

    @property
    def layout(self) -> PadLayout:
        """Geometry of the pad under the objects."""
        ...

    @property
    def time_s(self) -> float:
        """Simulated time, seconds."""
        ...

    def step(self, dt_s: float, module_heights_m: NDArray[np.float64]) -> None:
        """Advance the world by ``dt_s``; ``module_heights_m`` are the current module top heights."""
        ...

    def module_loads_n(self) -> NDArray[np.float64]:
        """Vertical force (N, >= 0) pressing on each module's sensitive area, shape (n_modules,)."""
        ...

    def set_gripper_target(self, target: GripperState) -> None:
        """Kinematic target of the gripper; the world moves it there (the robot sets speeds)."""
        ...

    def gripper_state(self) -> GripperState:
        """Current gripper state."""
        ...
