"""Run the closed loop on the simulated box with objects of the catalogue."""

from __future__ import annotations

from collections.abc import Sequence

from softpad.box import Box, SimBox, ZenohBox, open_box
from softpad.control._execution import ExecutionParams, ExecutionResult, GraspExecution, Recorder
from softpad.control._remote import RemoteRobot, has_simulation
from softpad.control._robot import SimulatedRobot
from softpad.errors import InputError
from softpad.sim import AnalyticWorld, ObjectSpec, SimGripper, get_object, object_names

_REMOTE_WORLD = (
    "the simulated loop places objects and moves the gripper in a simulator's world: use a "
    "sim:// box, or a zenoh:// box served by 'softpad box serve --sim' (which offers "
    "the world and robot); this box carries pressures and valves only"
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
        A :class:`~softpad.box.SimBox` or a ``sim://`` URL; or a ``zenoh://`` box whose daemon
        offers the simulator's world and robot (:func:`simulation_extensions`, as
        ``softpad box serve --sim`` does): the run is then identical.
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
    owns = isinstance(box, str)
    b = open_box(box) if isinstance(box, str) else box
    try:
        mounting = gripper or specs[0].gripper
        if isinstance(b, ZenohBox):  # a simulator served over the network: world and robot there
            if not has_simulation(b):
                raise InputError(_REMOTE_WORLD)
            remote = RemoteRobot(b, mounting)
            names = [s.name for s in specs]
            loop = GraspExecution(
                b, remote, remote.layout, params, recorder, lambda: remote.place(names)
            )
            return loop.run()
        if not isinstance(b, SimBox):
            raise InputError(f"{_REMOTE_WORLD} (got a {type(b).__name__})")
        world = b.world
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
