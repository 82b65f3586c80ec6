"""The grasp loop against a simulator served over zenoh (``zenoh://``).

A ``zenoh://`` box carries pressures and valves only. To run the whole simulated loop through
it, the daemon serving a :class:`~softpad.box.SimBox` also offers the simulator's world and
robot as queryables ``PREFIX/ext/OP`` (:func:`simulation_extensions`; ``softpad box serve
--sim`` adds them), and the controlling client drives them with :class:`RemoteRobot`:

=====================  =================================================  =====================
request                fields                                             reply
=====================  =================================================  =====================
``sim.setup``          ``gripper`` (``"10/4"``, ``"6/2"``, ``"4/0"``)      ``layout`` [rows, cols,
                                                                          pitch_m]
``sim.place``          ``objects`` (catalogue names)                      nothing more
``robot.move_to``      ``x_m``, ``y_m``, ``z_m``, ``yaw_rad``,             nothing more
                       ``speed_m_s``
``robot.descend``      ``speed_m_s``, ``min_z_m``                         nothing more
``robot.stop``                                                            nothing more
``robot.set_gripper``  ``width_m``, ``speed_m_s``                         nothing more
``robot.is_moving``                                                       ``moving``
``robot.state``                                                           ``state`` [x_m, y_m,
                                                                          z_m, yaw_rad, width_m]
``robot.holding``                                                         ``holding``
``robot.touches``                                                         ``touches`` [[t_s, z_m]
                                                                          or null per descent]
=====================  =================================================  =====================

The services are bounded so that a request cannot hold the daemon's sampling and safety loop
(each runs under its lock): at most :data:`MAX_SERVED_OBJECTS` objects on the served pad, names
of at most 64 characters, every request at most ``MAX_PAYLOAD_BYTES`` and 8 levels deep (the
daemon checks before parsing); a hardware box offers no services at all (the daemon refuses).

Every robot request maps one to one onto the served :class:`SimulatedRobot`, so a run over
``zenoh://`` gives the run on the same ``sim://`` box in-process (tested). A real robot
would not be served this way: it has its own controller behind the :class:`Robot` protocol.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

from softpad.box import SimBox, ZenohBox
from softpad.control import RobotState, ToolPose
from softpad.errors import HardwareFault, InputError
from softpad.harness._robot import SimulatedRobot, TouchTruth
from softpad.layout import PadLayout
from softpad.sim import AnalyticWorld, SimGripper, get_object

Handler = Callable[[dict[str, Any]], dict[str, Any]]

#: Extension requests a served simulator offers (see the module docstring).
SIMULATION_OPS = (
    "sim.setup",
    "sim.place",
    "robot.move_to",
    "robot.descend",
    "robot.stop",
    "robot.set_gripper",
    "robot.is_moving",
    "robot.state",
    "robot.holding",
    "robot.touches",
)


#: Most objects a served simulator holds on its pad (the thesis's scenes have at most four;
#: each placement costs the world a footprint, so the bound bounds a request's time).
MAX_SERVED_OBJECTS = 8


def _number(msg: dict[str, Any], key: str) -> float:
    v = msg.get(key)
    if isinstance(v, bool) or not isinstance(v, int | float) or not math.isfinite(v):
        raise InputError(f"{msg.get('op')}: {key} must be a finite number, got {v!r}")
    return float(v)


def simulation_extensions(box: SimBox) -> dict[str, Handler]:
    """Protocol extensions exposing ``box``'s world and a :class:`SimulatedRobot` on it.

    Pass them to :class:`~softpad.box.BoxDaemon` (``services=``).
    """
    sim = _SimulationService(box)
    return {
        "sim.setup": sim.setup,
        "sim.place": sim.place,
        "robot.move_to": sim.commanding(sim.move_to),
        "robot.descend": sim.commanding(sim.descend),
        "robot.stop": sim.commanding(lambda msg: sim.robot.stop()),
        "robot.set_gripper": sim.commanding(sim.set_gripper),
        "robot.is_moving": sim.is_moving,
        "robot.state": sim.state,
        "robot.holding": lambda msg: {"holding": bool(sim.robot.holding())},
        "robot.touches": sim.touches,
    }


class _SimulationService:
    """The handlers of :func:`simulation_extensions`: a served box's world and the simulated
    robot on it (replaced by each ``sim.setup``).

    The served robot judges motion once per simulation step ("stopped" = no change since the
    previous step); a client polling several times within one step gets the same answer.
    """

    def __init__(self, box: SimBox) -> None:
        self.box = box
        self.world = box.world
        self.robot = SimulatedRobot(self.world)
        self._judged_at: float | None = None
        self._moving = True
        self._placed_here = 0  # objects this service placed (a world that cannot count them)

    def commanding(self, fn: Callable[[dict[str, Any]], None]) -> Handler:
        """A handler running ``fn`` and forgetting the last motion judgement."""

        def handler(msg: dict[str, Any]) -> dict[str, Any]:
            fn(msg)
            self._judged_at = None
            return {}

        return handler

    def setup(self, msg: dict[str, Any]) -> dict[str, Any]:
        mounting = msg.get("gripper")
        if mounting is not None:
            gripper = SimGripper.mounting(str(mounting))
            if isinstance(self.world, AnalyticWorld):
                self.world.gripper = gripper
        self.robot = SimulatedRobot(self.world)
        self._judged_at = None
        lay = self.world.layout
        return {"layout": [lay.rows, lay.cols, lay.pitch_m]}

    def place(self, msg: dict[str, Any]) -> dict[str, Any]:
        names = msg.get("objects")
        if not isinstance(names, list) or not all(
            isinstance(n, str) and len(n) <= 64 for n in names
        ):
            raise InputError(
                f"sim.place: objects must be a list of names (64 characters at most), "
                f"got {str(names)[:80]!r}"
            )
        after = self._on_pad() + len(names)
        if after > MAX_SERVED_OBJECTS:
            raise InputError(
                f"sim.place: {len(names)} objects would make {after} on the served pad; "
                f"the limit is {MAX_SERVED_OBJECTS}"
            )
        specs = [get_object(n) for n in names]  # every name checked before placing any
        for s in specs:
            self.world.place_object(s)
        self._placed_here += len(specs)
        return {}

    def _on_pad(self) -> int:
        if isinstance(self.world, AnalyticWorld):
            return len(self.world.objects)
        return self._placed_here

    def is_moving(self, msg: dict[str, Any]) -> dict[str, Any]:
        if self._judged_at != self.box.time_s:
            self._moving = bool(self.robot.is_moving())
            self._judged_at = self.box.time_s
        return {"moving": self._moving}

    def move_to(self, msg: dict[str, Any]) -> None:
        pose = ToolPose(*(_number(msg, k) for k in ("x_m", "y_m", "z_m", "yaw_rad")))
        self.robot.move_to(pose, _number(msg, "speed_m_s"))

    def descend(self, msg: dict[str, Any]) -> None:
        self.robot.descend(_number(msg, "speed_m_s"), _number(msg, "min_z_m"))

    def set_gripper(self, msg: dict[str, Any]) -> None:
        self.robot.set_gripper(_number(msg, "width_m"), _number(msg, "speed_m_s"))

    def state(self, msg: dict[str, Any]) -> dict[str, Any]:
        s = self.robot.state()
        return {"state": [s.x_m, s.y_m, s.z_m, s.yaw_rad, s.width_m]}

    def touches(self, msg: dict[str, Any]) -> dict[str, Any]:
        return {
            "touches": [
                None if t.first_touch_s is None else [t.first_touch_s, t.first_touch_z_m]
                for t in self.robot.touches
            ]
        }


def has_simulation(box: ZenohBox) -> bool:
    """True when ``box`` has a simulated world behind it (:attr:`~softpad.box.Box.simulated`)
    and its daemon also serves the simulated robot (every request of :data:`SIMULATION_OPS`)."""
    return box.simulated and set(SIMULATION_OPS) <= set(box.info.get("services", []))


def _floats(reply: dict[str, Any], key: str, n: int) -> list[float]:
    v = reply.get(key)
    if (
        not isinstance(v, list)
        or len(v) != n
        or not all(
            isinstance(x, int | float) and not isinstance(x, bool) and math.isfinite(x) for x in v
        )
    ):
        raise HardwareFault(f"served robot: {key} must be {n} finite numbers, got {v!r}")
    return [float(x) for x in v]


class RemoteRobot:
    """The :class:`Robot` of a simulator served over ``zenoh://`` (see the module docstring).

    Every call is a query to ``PREFIX/ext/OP``; it takes control of the box (only the
    controlling client may move the served robot).

    Parameters
    ----------
    box
        An open :class:`~softpad.box.ZenohBox` whose daemon offers :data:`SIMULATION_OPS`.
    gripper
        Gripper mounting to set up (``"10/4"``, ``"6/2"``, ``"4/0"``); None keeps the served one.
    """

    def __init__(self, box: ZenohBox, gripper: str | None = None) -> None:
        if not has_simulation(box):
            raise InputError(
                f"box at {box.address} serves no simulated world and robot "
                "(start it with 'softpad box serve --sim')"
            )
        self.box = box
        box.take_control()
        reply = self._call("sim.setup", gripper=gripper)
        rows, cols, pitch = _floats(reply, "layout", 3)
        #: Layout of the served pad.
        self.layout = PadLayout(int(rows), int(cols), pitch)

    def _call(self, op: str, **fields: Any) -> dict[str, Any]:
        return self.box.request(f"ext/{op}", **fields)

    def place(self, names: list[str]) -> None:
        """Place catalogue objects on the served pad."""
        self._call("sim.place", objects=list(names))

    def move_to(self, pose: ToolPose, speed_m_s: float) -> None:
        self._call(
            "robot.move_to",
            x_m=pose.x_m,
            y_m=pose.y_m,
            z_m=pose.z_m,
            yaw_rad=pose.yaw_rad,
            speed_m_s=speed_m_s,
        )

    def descend(self, speed_m_s: float, min_z_m: float) -> None:
        self._call("robot.descend", speed_m_s=speed_m_s, min_z_m=min_z_m)

    def stop(self) -> None:
        self._call("robot.stop")

    def set_gripper(self, width_m: float, speed_m_s: float) -> None:
        self._call("robot.set_gripper", width_m=width_m, speed_m_s=speed_m_s)

    def is_moving(self) -> bool:
        return self._call("robot.is_moving").get("moving") is True

    def state(self) -> RobotState:
        return RobotState(*_floats(self._call("robot.state"), "state", 5))

    def holding(self) -> bool:
        return self._call("robot.holding").get("holding") is True

    def touches(self) -> list[TouchTruth]:
        """Ground truth of every descent so far (simulation only; scores a run)."""
        out = []
        for t in self._call("robot.touches").get("touches") or []:
            if t is None:
                out.append(TouchTruth(None, None))
            else:
                ts, z = _floats({"t": t}, "t", 2)
                out.append(TouchTruth(ts, z))
        return out
