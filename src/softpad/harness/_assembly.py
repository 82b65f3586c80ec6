"""The one assembly of the grasp loop: :func:`build_loop`.

Every entry point (``softpad run``, the ROS nodes, trials, design sweeps) builds its
:class:`~softpad.control.GraspExecution` here, from a box, a robot, the installation's
settings and the registered parts. Whether the box has a simulated world behind it is asked
once, of the box (:attr:`softpad.box.Box.simulated`); :func:`world_access` then reaches that
world the same way in-process (``sim://``) and over ``zenoh://`` (a served simulator's
``sim.setup``/``sim.place`` requests).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from types import TracebackType
from typing import Any

from softpad.box import Box, ZenohBox, simulator_of
from softpad.control import (
    AdjustmentResult,
    ExecutionParams,
    ExecutionResult,
    GraspExecution,
    InflationParams,
    Recorder,
    Robot,
    make_robot,
)
from softpad.errors import HardwareFault, InputError
from softpad.harness._remote import RemoteRobot
from softpad.harness._robot import SimulatedRobot, TouchTruth
from softpad.layout import GripperSpec, PadLayout
from softpad.planning import Planner, PlannerParams, planner_for
from softpad.sensing import (
    ContactDetector,
    ObjectDetector,
    make_contact_detector,
    make_object_detector,
)
from softpad.sim import AnalyticWorld, SimGripper, get_object


class WorldAccess:
    """The simulated world behind a box (:func:`world_access`): set up the gripper mounting,
    place catalogue objects."""

    def setup(self, mounting: str | None) -> PadLayout:
        """Mount the gripper ``"10/4"``, ``"6/2"`` or ``"4/0"`` (None keeps the one mounted)
        and return the pad's layout."""
        raise NotImplementedError

    def place(self, names: Sequence[str]) -> None:
        """Place the catalogue objects ``names`` on the pad."""
        raise NotImplementedError


class _InProcessWorld(WorldAccess):
    def __init__(self, world: Any) -> None:
        self.world = world

    def setup(self, mounting: str | None) -> PadLayout:
        if mounting is not None and isinstance(self.world, AnalyticWorld):
            self.world.gripper = SimGripper.mounting(mounting)
        layout: PadLayout = self.world.layout
        return layout

    def place(self, names: Sequence[str]) -> None:
        for spec in [get_object(n) for n in names]:  # every name checked before placing any
            self.world.place_object(spec)


class _ServedWorld(WorldAccess):
    def __init__(self, box: ZenohBox) -> None:
        self.box = box

    def setup(self, mounting: str | None) -> PadLayout:
        self.box.take_control()  # only the controlling client may call the services
        reply = self.box.request("ext/sim.setup", gripper=mounting).get("layout")
        if not (isinstance(reply, list) and len(reply) == 3 and _finite(reply)):
            raise HardwareFault(f"served simulator: layout must be 3 finite numbers, got {reply!r}")
        rows, cols, pitch = reply
        return PadLayout(int(rows), int(cols), float(pitch))

    def place(self, names: Sequence[str]) -> None:
        self.box.take_control()
        self.box.request("ext/sim.place", objects=list(names))


def _finite(values: list[Any]) -> bool:
    return all(
        isinstance(v, int | float) and not isinstance(v, bool) and math.isfinite(v) for v in values
    )


def world_access(box: Box) -> WorldAccess | None:
    """The simulated world behind ``box`` (None when :attr:`~softpad.box.Box.simulated` is
    False): in this process for ``sim://`` and any view of it, through the served requests
    for a ``zenoh://`` simulator.

    Parameters
    ----------
    box
        An open box.

    Returns
    -------
    WorldAccess or None
        Setting up the gripper and placing objects on that world.
    """
    if not box.simulated:
        return None
    sim = simulator_of(box)
    if sim is not None:
        return _InProcessWorld(sim.world)
    if isinstance(box, ZenohBox):
        return _ServedWorld(box)
    return None


@dataclass
class BuiltLoop:
    """A grasp loop built by :func:`build_loop`: run it once, read its ground truth, close it.

    Attributes
    ----------
    execution
        The assembled loop (its ``phase`` names where a fault stopped it).
    robot
        The arm it drives (not the execution's recording view of it).
    owns_robot
        True when :func:`build_loop` made the robot from a URL: :meth:`close` closes it.
    """

    execution: GraspExecution
    robot: Robot
    owns_robot: bool = False

    @property
    def layout(self) -> PadLayout:
        """The pad the loop works on."""
        return self.execution.layout

    @property
    def phase(self) -> str:
        """The loop's current phase."""
        return str(self.execution.phase)

    def run(self) -> ExecutionResult:
        """Run the loop once (:meth:`softpad.control.GraspExecution.run`)."""
        return self.execution.run()

    def touches(self) -> tuple[TouchTruth, ...] | None:
        """Ground truth of every descent (simulated arms only; it scores a run), else None."""
        if isinstance(self.robot, SimulatedRobot):
            return tuple(self.robot.touches)
        if isinstance(self.robot, RemoteRobot):
            return tuple(self.robot.touches())
        return None

    def close(self) -> None:
        """Close the robot when the loop made it (a ``ros1://`` arm's connection)."""
        close = getattr(self.robot, "close", None)
        if self.owns_robot and close is not None:
            close()

    def __enter__(self) -> BuiltLoop:
        return self

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        self.close()


def build_loop(
    box: Box, robot: Robot | str | None = None, *, installation: Any = None,
    params: ExecutionParams | None = None, planner: Planner | str | None = None,
    contact_detector: ContactDetector | str | None = None,
    object_detector: ObjectDetector | str | None = None, objects: Sequence[str] | None = None,
    gripper: str | None = None, layout: PadLayout | None = None,
    recorder: Recorder | None = None, place_objects: Callable[[], None] | None = None,
    adjusted: AdjustmentResult | None = None,
) -> BuiltLoop:  # fmt: skip
    """Build the grasp loop (:class:`~softpad.control.GraspExecution`) on ``box``: the one
    place every entry point assembles it.

    Parameters
    ----------
    box
        An open box; on a simulated one (:attr:`~softpad.box.Box.simulated`) the gripper is
        mounted and ``objects`` are placed on its world.
    robot
        An arm, a robot URL (``ros1://``; :meth:`BuiltLoop.close` closes it), or None or
        ``"sim://"``: the simulated box's own arm (in-process, or served over ``zenoh://``).
    installation
        A :class:`softpad.config.Installation` (:func:`execution_params`); its gripper
        mounting and pad are the defaults of ``gripper`` and ``layout``.
    params
        Loop parameters; None: the installation's, else the thesis's.
    planner, contact_detector, object_detector
        Parts or their registered names, made for the box's sample rate, the pad, the
        gripper and the loop's thresholds; None: the thesis's.
    objects
        Catalogue objects placed on a simulated world when the loop waits for them (on a
        real box a person places them); the first one's mounting is the default gripper.
    gripper
        Gripper mounting ``"10/4"``, ``"6/2"`` or ``"4/0"``; None: the installation's, else
        the first object's, else the one mounted.
    layout
        The pad; None: the simulated world's, else the installation's, else 2 x 3.
    recorder, place_objects, adjusted
        As :class:`~softpad.control.GraspExecution` takes them (``place_objects`` replaces
        the placing of ``objects``).

    Returns
    -------
    BuiltLoop
        The loop, its robot and the robot's ground truth.
    """
    params = execution_params(params, installation)
    mounting = _mounting(gripper, installation, objects)
    world = world_access(box)
    pad = world.setup(mounting) if world is not None else _installed_pad(installation)
    layout = layout or pad
    spec = GripperSpec.from_mounting(mounting) if mounting is not None else None
    arm, owns = _robot(robot, box, layout, spec)
    parts = _parts(planner, contact_detector, object_detector, box, layout, spec, params)
    execution = GraspExecution(
        box, arm, layout, params, recorder=recorder, adjusted=adjusted,
        place_objects=place_objects or _placer(world, objects), **parts,
    )  # fmt: skip
    return BuiltLoop(execution, arm, owns)


def _mounting(gripper: str | None, installation: Any, objects: Sequence[str] | None) -> str | None:
    """The gripper mounting: the one given, the installation's, the first object's, or None."""
    mounting = gripper or getattr(installation, "gripper_mounting", None)
    if mounting is None and objects:
        mounting = get_object(objects[0]).gripper
    return mounting


def _placer(world: WorldAccess | None, objects: Sequence[str] | None) -> Callable[[], None] | None:
    """Placing ``objects`` on the simulated world, None when there is none or nothing to place."""
    if world is None or not objects:
        return None
    names = list(objects)
    return lambda: world.place(names)


def execution_params(params: ExecutionParams | None, installation: Any) -> ExecutionParams:
    """``params`` with the installation's adjustment tolerance and maximum pressure (the
    site's own), or, when ``params`` is None, all of the installation's thresholds.

    Parameters
    ----------
    params
        Loop parameters, or None for the installation's (the thesis's without one).
    installation
        A :class:`softpad.config.Installation` or None.

    Returns
    -------
    ExecutionParams
        The parameters the loop runs with.
    """
    if installation is None:
        return params or ExecutionParams()
    th = installation.thresholds
    if params is None:
        params = ExecutionParams(
            planner=PlannerParams(object_threshold_pa=th.object_threshold_pa),
            contact_threshold_pa=th.contact_threshold_pa,
            filter_length=th.filter_window,
        )
    inflation: InflationParams = dataclasses.replace(
        params.inflation,
        tolerance_pa=th.adjust_tolerance_pa,
        max_pressure_pa=th.max_pressure_pa,
        filter_length=params.filter_length,
    )
    return dataclasses.replace(params, inflation=inflation)


def _installed_pad(installation: Any) -> PadLayout:
    pad = getattr(installation, "pad", None)
    if pad is None:
        return PadLayout()
    return PadLayout(pad.rows, pad.cols, pad.pitch_m)


def _robot(
    robot: Robot | str | None, box: Box, layout: PadLayout, spec: GripperSpec | None
) -> tuple[Robot, bool]:
    """The arm and whether the loop owns it (made from a URL)."""
    if isinstance(robot, str) and robot.rstrip("/").lower() != "sim:":
        return make_robot(robot, box=box, layout=layout, gripper=spec), True
    if robot is not None and not isinstance(robot, str):
        return robot, False
    sim = simulator_of(box)
    if sim is not None:
        return SimulatedRobot(sim.world), False
    if isinstance(box, ZenohBox) and box.simulated:
        return RemoteRobot(box), False
    raise InputError(
        f"no robot for a {type(box).__name__}: the simulated arm needs a simulated box "
        "(sim://, or a zenoh:// box served by 'softpad box serve --sim'); give a robot URL "
        "(ros1://) for any other box"
    )


def _parts(
    planner: Planner | str | None,
    contact: ContactDetector | str | None,
    objects: ObjectDetector | str | None,
    box: Box,
    layout: PadLayout,
    spec: GripperSpec | None,
    params: ExecutionParams,
) -> dict[str, Any]:
    """The loop's parts, each named one made by its registry (None: the loop's default)."""
    rate = float(box.sample_rate_hz)
    fields = dict(
        contact_threshold_pa=params.contact_threshold_pa,
        object_threshold_pa=params.planner.object_threshold_pa,
        window=params.filter_length,
    )
    if isinstance(contact, str) or (contact is None and isinstance(planner, str)):
        contact = make_contact_detector(contact or "thesis", rate, layout, gripper=spec, **fields)
    if isinstance(objects, str):
        objects = make_object_detector(objects, rate, layout, gripper=spec, **fields)
    if isinstance(planner, str):
        assert contact is not None
        planner = planner_for(planner, spec, params.planner, contact, rate, layout)
    return {"planner": planner, "contact_detector": contact, "object_detector": objects}


__all__ = ["BuiltLoop", "WorldAccess", "build_loop", "execution_params", "world_access"]
