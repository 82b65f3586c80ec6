"""The world interface: what loads the modules.

A world holds the objects resting on the pad and the gripper, and tells the simulated box
which vertical force presses on each module. The analytic world (footprints and mass
distributions, :class:`~softpad.sim.AnalyticWorld`) and the MuJoCo world (rigid-body contact)
both implement :class:`World`, so the simulated box, the simulated robot and the trials do not
care which one runs.

Who calls what (the simulated box is the clock master, see docs/box-and-simulator.md):

* the simulated box calls :meth:`World.step` once per sample period with the module top
  heights of the previous step, then reads :meth:`World.module_loads_n`;
* the simulated robot calls :meth:`World.command_gripper` (kinematic target and speed),
  :meth:`World.gripper_state` and :meth:`World.holding`;
* the simulation set-up calls :meth:`World.place_object` (e.g. when the execution state
  machine waits for an object) and :meth:`World.remove_objects`.

Frames and units: everything is in the pad frame (DESIGN.md), SI units. ``z`` is measured
from the pad's rigid base surface upward, so an inflated module's top sits at ``height_m``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol, runtime_checkable

import numpy as np
from numpy.typing import NDArray

from softpad.layout import PadLayout
from softpad.sim._objects import ObjectSpec, Placement


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
    """What the simulated box and robot need from a world.

    Implementations: :class:`softpad.sim.AnalyticWorld`, :class:`softpad.sim.MujocoWorld`.
    Keep this small: every method here is needed by the box or the simulated robot.
    """

    @property
    def layout(self) -> PadLayout:
        """Geometry of the pad under the objects (module k is box channel k)."""
        ...

    @property
    def time_s(self) -> float:
        """Simulated time, seconds (advanced only by :meth:`step`)."""
        ...

    def step(self, dt_s: float, module_heights_m: NDArray[np.float64]) -> None:
        """Advance the world by ``dt_s`` seconds.

        Parameters
        ----------
        dt_s
            Time step, seconds (one sample period of the box).
        module_heights_m
            Current top height of every module, shape (n_modules,), metres; the world's
            surface for objects and fingertips.
        """
        ...

    def module_loads_n(self) -> NDArray[np.float64]:
        """Vertical force (N, >= 0) pressing on each module's sensitive area, shape (n_modules,)."""
        ...

    def command_gripper(self, target: GripperState, speed_m_s: float) -> None:
        """Move the gripper towards ``target`` in a straight line at ``speed_m_s``.

        The jaws' width changes at the same speed. A new command replaces the previous one;
        commanding the current state stops the gripper.
        """
        ...

    def gripper_state(self) -> GripperState:
        """Current gripper state."""
        ...

    def holding(self) -> bool:
        """True when an object is between the closed jaws and is carried by the gripper."""
        ...

    @property
    def first_touch_s(self) -> float | None:
        """Ground truth of the current descent: box time of the first fingertip touch, s
        (None before it); scores a trial, never seen by the controller."""
        ...

    @property
    def first_touch_z_m(self) -> float | None:
        """Ground truth: fingertip height at the first touch, m (None before it)."""
        ...

    def reset_touch(self) -> None:
        """Forget the first-touch record (the simulated robot calls it before a descent)."""
        ...

    def place_object(self, spec: ObjectSpec, placement: Placement | None = None) -> None:
        """Put an object on the pad (at ``spec.placement`` by default)."""
        ...

    def remove_objects(self) -> None:
        """Take every object off the pad and out of the gripper."""
        ...
