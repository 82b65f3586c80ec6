"""The grasp loop with a robot reached by URL (``ros1://``) and a box reached by URL."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from softpad.box import Box
from softpad.errors import HardwareFault


def run_with_robot(
    objects: Sequence[str] | None,
    box: Box | str,
    robot: Any,
    params: Any = None,
    recorder: Any = None,
    gripper: str | None = None,
    **parts: Any,
) -> Any:
    """Run the loop (:func:`softpad.harness.build_loop`) once on ``box`` with ``robot``;
    ``parts`` (``planner``, ``object_detector``, ``contact_detector``) replace the thesis's.

    When the box is a simulator served over ``zenoh://`` (``softpad sim arm-node`` or
    ``softpad box serve --sim``), the gripper mounting is set up and the catalogue
    ``objects`` are placed through its ``sim.setup``/``sim.place`` requests; on any other box a
    person places the object and the pad layout is the default 2 x 3.

    Returns
    -------
    ExecutionResult
        The timeline and outcome. A fault (box or arm lost) raises
        :class:`~softpad.errors.HardwareFault` after the box was made safe.
    """
    from softpad.box import open_box
    from softpad.harness import build_loop, resolve_objects

    names = [s.name for s in resolve_objects(objects)]
    owned = isinstance(box, str)
    b = open_box(box) if isinstance(box, str) else box
    try:
        with build_loop(
            b, robot, params=params, recorder=recorder, objects=names, gripper=gripper, **parts
        ) as loop:
            try:
                return loop.run()
            except HardwareFault as exc:
                # same exception (its safe state and faults kept), the phase named in the message
                exc.args = (f"run stopped in phase {loop.phase!r}: {exc}", *exc.args[1:])
                raise
    finally:
        if owned:
            b.close()
