"""Run the closed loop on the simulated box with objects of the catalogue, and score it."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from softpad.box import Box, open_box
from softpad.control import ExecutionParams, ExecutionResult, Recorder, Robot
from softpad.errors import InputError
from softpad.harness._assembly import build_loop
from softpad.harness._robot import TouchTruth
from softpad.sim import ObjectSpec, get_object, object_names

_REMOTE_WORLD = (
    "the simulated loop places objects and moves the gripper in a simulator's world: use a "
    "sim:// box, or a zenoh:// box served by 'softpad box serve --sim' (which offers "
    "the world and robot); this box carries pressures and valves only"
)


def resolve_objects(names: Sequence[str] | None) -> list[ObjectSpec]:
    """Catalogue objects by name (``object-5`` when None); InputError lists the known names."""
    if isinstance(names, str):
        raise InputError(
            f"objects must be a list of names, got the string {names!r}: use [{names!r}]"
        )
    if names is not None and len(names) == 0:
        raise InputError("no object given: name at least one catalogue object")
    names = list(names) if names else ["object-5"]
    specs = [get_object(n) for n in names]
    if len(set(names)) != len(names):
        raise InputError(f"each object can be placed once, got {names}")
    return specs


@dataclass(frozen=True)
class SimulatedRun:
    """A run of the loop on the simulator: what the controller saw, and the ground truth.

    Attributes
    ----------
    result
        The execution's own result (pad data, plans, outcomes).
    touches
        Ground truth of each grasp's descent, in grasp order.
    """

    result: ExecutionResult
    touches: tuple[TouchTruth, ...]

    @property
    def outcome(self) -> str:
        """Overall outcome of the execution."""
        return self.result.outcome

    def _touch(self, grasp: int) -> TouchTruth:
        """The ground-truth touch of a grasp's last descent (a grasp retried after landing on
        its object descended more than once)."""
        return self.touches[sum(g.attempts for g in self.result.grasps[: grasp + 1]) - 1]

    def contact_delay_s(self, grasp: int = 0) -> float | None:
        """Detection time minus first-touch time of a grasp, seconds (None when unknown)."""
        g, t = self.result.grasps[grasp], self._touch(grasp)
        if g.detected_at_s is None or t.first_touch_s is None:
            return None
        return g.detected_at_s - t.first_touch_s

    def finger_travel_m(self, grasp: int = 0) -> float | None:
        """Downward travel of the fingertips from first touch to the stop, metres."""
        g, t = self.result.grasps[grasp], self._touch(grasp)
        if g.detected_at_s is None or t.first_touch_z_m is None or g.stop_z_m is None:
            return None
        return t.first_touch_z_m - g.stop_z_m

    def to_dict(self) -> dict[str, Any]:
        """The execution's dict with each grasp's ground truth added (SI units)."""
        d = self.result.to_dict()
        for i, g in enumerate(d["grasps"]):
            delay, travel = self.contact_delay_s(i), self.finger_travel_m(i)
            g["first_touch_s"] = self._touch(i).first_touch_s
            g["contact_delay_s"] = None if delay is None else round(delay, 4)
            g["finger_travel_m"] = None if travel is None else round(travel, 6)
        first = d["grasps"][0] if d["grasps"] else {}
        d["contact_delay_s"] = first.get("contact_delay_s")
        d["finger_travel_m"] = first.get("finger_travel_m")
        return d


def run_simulated(
    objects: Sequence[str] | None = None,
    box: Box | str = "sim://",
    params: ExecutionParams | None = None,
    recorder: Recorder | None = None,
    gripper: str | None = None,
    robot: Robot | None = None,
    **parts: Any,
) -> SimulatedRun:
    """Run the loop once on a simulated box with catalogue objects placed as in the thesis.

    Parameters
    ----------
    objects
        Catalogue names (``object-1`` .. ``object-6``, ``banana``, ``toy``, ``limes``,
        ``cylinder``, ``charger``); several objects lying on separate modules are planned and
        grasped one after the other. ``object-5`` when None.
    box
        A simulated box (a :class:`~softpad.box.SimBox`, its layers or a view of it) or a
        ``sim://`` URL; or a ``zenoh://`` box whose daemon
        offers the simulator's world and robot (``softpad box serve --sim``).
    params
        Loop parameters.
    recorder
        Receives frames and events.
    gripper
        Gripper mounting ``"10/4"``, ``"6/2"`` or ``"4/0"``; by default the first object's
        mounting in the catalogue (the thesis mounted the gripper per object, Section 6.3).
    robot
        The arm on an in-process simulated box (:func:`softpad.control.make_robot`, e.g. a
        registered ``--robot`` URL); None: :class:`SimulatedRobot` on the box's world. The
        touches' ground truth comes from a :class:`SimulatedRobot` (or a subclass) only.
    parts
        ``planner``, ``object_detector``, ``contact_detector`` for :class:`GraspExecution`.

    Returns
    -------
    SimulatedRun
        The run and its ground truth; the box is closed on return unless it was passed in.
    """
    specs = resolve_objects(objects)
    owns = isinstance(box, str)
    b = open_box(box) if isinstance(box, str) else box
    try:
        if not b.simulated:
            raise InputError(f"{_REMOTE_WORLD} (got a {type(b).__name__})")
        with build_loop(
            b, robot, params=params, objects=[s.name for s in specs], recorder=recorder,
            gripper=gripper or specs[0].gripper, **parts,
        ) as loop:  # fmt: skip
            result = loop.run()
            touches = loop.touches()
        if touches is None:  # an arm without ground truth
            touches = tuple(TouchTruth(None, None) for _ in result.grasps)
        return SimulatedRun(result, touches)
    finally:
        if owns:
            b.close()


__all__ = ["SimulatedRun", "object_names", "resolve_objects", "run_simulated"]
