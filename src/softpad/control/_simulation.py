"""Run the closed loop on the simulated box with objects of the catalogue."""

from __future__ import annotations

from collections.abc import Sequence

from softpad.box import Box, SimBox, open_box
from softpad.control._execution import ExecutionParams, ExecutionResult, GraspExecution, Recorder
from softpad.control._robot import SimulatedRobot
from softpad.errors import InputError
from softpad.sim import AnalyticWorld, ObjectSpec, SimGripper, get_object, object_names

_REMOTE_WORLD = (
    "the simulated loop places objects and moves the gripper in the simulator's world, which "
    "must run in this process: use a sim:// box; a tcp:// box carries pressures and valves only "
    "(its world lives in the server), so use 'softpad box read' or 'softpad box inflate' on it"
)


def resolve_objects(names: Sequence[str] | None) -> list[ObjectSpec]:
    """Catalogue objects by name (``banana`` by default); InputError lists the known names."""
    names = list(names) if names else ["banana"]
    specs = [get_object(n) for n in names]
    if len(set(names)) != len(names):
        raise InputError(f"each object can be placed once, got {names}")
    return specs


def run_simulated(
    objects: Sequence[str] | None = None,
    box: Box | str = "sim://",
    params: ExecutionParams | None = None,
    recorder: Recorder | None = None,
    gripper: str | None = None,
) -> ExecutionResult:
    """Run the loop once on a simulated box with catalogue objects placed as in the thesis.

    Parameters
    ----------
    objects
        Catalogue names (``object-1`` .. ``object-6``, ``banana``, ``toy``, ``limes``,
        ``cylinder``, ``charger``); several objects lying on separate modules are planned and
        grasped one after the other. ``banana`` by default.
    box
        A :class:`~softpad.box.SimBox` or a ``sim://`` URL.
    params
        Loop parameters.
    recorder
        Receives frames and events.
    gripper
        Gripper mounting ``"10/4"``, ``"6/2"`` or ``"4/0"``; by default the first object's
        mounting in the catalogue (the thesis mounted the gripper per object, Section 6.3).

    Returns
    -------
    ExecutionResult
        The timeline and outcome; the box is closed on return unless it was passed in.
    """
    specs = resolve_objects(objects)
    if isinstance(box, str) and box.lower().startswith("tcp://"):
        raise InputError(_REMOTE_WORLD)
    owns = isinstance(box, str)
    b = open_box(box) if isinstance(box, str) else box
    try:
        if not isinstance(b, SimBox):
            raise InputError(f"{_REMOTE_WORLD} (got a {type(b).__name__})")
        world = b.world
        mounting = gripper or specs[0].gripper
        if isinstance(world, AnalyticWorld):
            world.gripper = SimGripper.mounting(mounting)
        robot = SimulatedRobot(world)

        def place() -> None:
            for s in specs:
                world.place_object(s)

        loop = GraspExecution(b, robot, world.layout, params, recorder, place)
        return loop.run()
    finally:
        if owns:
            b.close()


__all__ = ["object_names", "resolve_objects", "run_simulated"]
