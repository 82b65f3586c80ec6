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
  :meth:`World.gripper_state` and :meth:`World.jaws_settled` (whether it holds something it
  tells from its own jaw opening; :meth:`World.holding`, the contacts' truth, only scores);
* the simulation set-up calls :meth:`World.place_object` (e.g. when the execution state
  machine waits for an object) and :meth:`World.remove_objects`.

Frames and units: everything is in the pad frame (DESIGN.md), SI units. ``z`` is measured
from the pad's rigid base surface upward, so an inflated module's top sits at ``height_m``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Protocol, runtime_checkable

import numpy as np
from numpy.typing import NDArray

from softpad.errors import InputError
from softpad.layout import PadLayout
from softpad.sim._objects import ObjectSpec, Placement
from softpad.sim._response import ModuleResponse, PadResponse


@dataclass(frozen=True)
class GripperState:
    """Kinematic state of the parallel-jaw gripper, pad frame."""

    #: Position of the gripper's centre (between the fingertips), metres.
    x_m: float
    #: Position of the gripper's centre (between the fingertips), metres.
    y_m: float
    #: Height of the fingertips' lower faces above the pad base, metres.
    z_m: float
    #: Direction in which the jaws close, from the pad x axis (theta of the planner), radians.
    yaw_rad: float
    #: Distance between the inner faces of the fingertips, metres.
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

    def jaws_settled(self) -> bool:
        """False while jaws stopped on an object are still building up their grip (the
        gripper's own "motion in progress" status, as a Robotiq or Sawyer gripper reports
        until its force is reached); True otherwise."""
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


class PadWorld:
    """What the analytic and the MuJoCo world share: the pad, its FEM response, the simulated
    clock and a probe block pressed on the chambers (:meth:`press`).

    Parameters
    ----------
    layout
        Pad geometry (2 x 3, 45 mm by default).
    response
        FEM module response (the packaged one by default); its chamber side fixes the seams.
    """

    def __init__(
        self, layout: PadLayout | None, response: ModuleResponse | PadResponse | None
    ) -> None:
        self._layout = layout or PadLayout()
        # a PadResponse as it is (a seam of its own: softpad.sim._uncertain)
        self.response = (
            response if isinstance(response, PadResponse) else PadResponse(self._layout, response)
        )
        self._time_s = 0.0
        self._probe: tuple[tuple[float, float], tuple[float, float], float, float] | None = None
        self._probe_loads = np.zeros(self._layout.n_modules)

    def jaws_settled(self) -> bool:
        """True: a world whose jaws stop where they meet an object has no grip to build up."""
        return True

    @property
    def layout(self) -> PadLayout:
        """Geometry of the pad."""
        return self._layout

    @property
    def time_s(self) -> float:
        """Simulated time, seconds."""
        return self._time_s

    def press(
        self,
        center_m: tuple[float, float],
        size_m: tuple[float, float],
        force_n: float,
        yaw_rad: float = 0.0,
    ) -> None:
        """Press a rigid flat block on the pad: ``force_n`` spread uniformly over a rectangle
        (``size_m`` = sides along its x and y, rotated by ``yaw_rad``) centred at ``center_m``
        (pad frame); replaces the previous block. ``force_n = 0`` lifts it."""
        for name, v in (
            ("force", force_n),
            ("yaw", yaw_rad),
            *zip(("x", "y"), center_m, strict=True),
        ):
            if not math.isfinite(v):
                raise InputError(f"probe {name} must be finite, got {v!r}")
        if force_n < 0:
            raise InputError(f"probe force must be >= 0 N, got {force_n:g} N")
        if min(size_m) <= 0 or not all(math.isfinite(v) for v in size_m):
            raise InputError(f"probe footprint sides must be > 0 m, got {size_m}")
        self._probe = (center_m, size_m, force_n, yaw_rad) if force_n > 0 else None
        self._update_probe()

    def _update_probe(self) -> None:
        """Put the loads of the probe block on the modules (each world at its operating
        pressure, with :meth:`_probe_loads_at`)."""
        raise NotImplementedError

    def _probe_loads_at(self, pressure_pa: float) -> NDArray[np.float64]:
        """Equivalent loads of the probe block on every module at ``pressure_pa``, N."""
        if self._probe is None:
            return np.zeros(self._layout.n_modules)
        center, size, force, yaw = self._probe
        return self.response.rect_equivalent_loads(center, size, force, pressure_pa, yaw)
