"""What a pad publishes on ROS 2 (rclpy): the ``ros2`` rows of :data:`softpad.topics.TOPICS`.

:class:`Ros2Publishers` makes one publisher per row of the topic table that names the ROS 2
output, with the row's type and QoS, so the node publishes exactly the table's names and types.
It offers the methods of :class:`softpad.ros.PadPublishers` (``frame``, ``plans``, ``contact``,
``phase``, ``outcome``, ``diagnostics``, ``static_frames``...), so the one
:class:`softpad.ros.LoopPublisher` and the pad node's loop drive either. Translation only.
"""

from __future__ import annotations

import importlib
import json
import math
import time
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from softpad import thesis
from softpad import topics as T
from softpad.box import PressureFrame
from softpad.layout import PadLayout, PadPose

#: Wall time between two diagnostics messages, seconds.
DIAGNOSTICS_PERIOD_S = 1.0


def message_class(type_name: str) -> Any:
    """The rclpy message class of a ROS 2 type name ``pkg/msg/Name``."""
    package, kind, name = type_name.split("/")
    return getattr(importlib.import_module(f"{package}.{kind}"), name)


def qos_profile(qos: T.Qos) -> Any:
    """rclpy's QoSProfile of a row of the table."""
    from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy

    return QoSProfile(
        history=HistoryPolicy.KEEP_LAST,
        depth=qos.depth,
        reliability=ReliabilityPolicy.RELIABLE if qos.reliable else ReliabilityPolicy.BEST_EFFORT,
        durability=DurabilityPolicy.TRANSIENT_LOCAL if qos.latched else DurabilityPolicy.VOLATILE,
    )


def _header(stamp: Any, frame_id: str) -> Any:
    from std_msgs.msg import Header

    return Header(stamp=stamp, frame_id=frame_id)


def _pose(x: float, y: float, z: float, yaw: float) -> Any:
    from geometry_msgs.msg import Point, Pose, Quaternion

    qx, qy, qz, qw = T.quaternion_z(yaw)
    return Pose(
        position=Point(x=float(x), y=float(y), z=float(z)),
        orientation=Quaternion(x=qx, y=qy, z=qz, w=qw),
    )


def _jsonable(value: Any) -> Any:
    """``value`` with NaN and infinities as None, NumPy values as Python ones."""
    if isinstance(value, float | np.floating):
        return float(value) if math.isfinite(value) else None
    if isinstance(value, np.integer):
        return int(value)
    if isinstance(value, np.ndarray):
        return _jsonable(value.tolist())
    if isinstance(value, dict):
        return {str(k): _jsonable(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_jsonable(v) for v in value]
    if hasattr(value, "value") and hasattr(value, "name"):  # an Enum member
        return value.value
    return value


class Ros2Publishers:
    """The pad's topics on one rclpy node (module docstring).

    Parameters
    ----------
    node
        The rclpy node.
    layout
        The pad (one pressure topic per module).
    box_url
        Named in the diagnostics.
    ambient_pressure_pa
        Added to the gauge readings in ``sensor_msgs/FluidPressure`` (absolute), Pa.
    """

    def __init__(
        self,
        node: Any,
        layout: PadLayout,
        box_url: str,
        ambient_pressure_pa: float = thesis.AMBIENT_PRESSURE_PA,
    ) -> None:
        self.node, self.layout, self.n = node, layout, layout.n_modules
        self.box_url, self.ambient_pressure_pa = box_url, float(ambient_pressure_pa)
        self._box: Any = None
        #: Whether frames are paced to the wall clock (an in-process simulated box only).
        self.pace = False
        #: The fault the diagnostics report as the link's ERROR, None while healthy.
        self.fault: str | None = None
        #: The measured pose of the robot, sampled at the table's rate while set.
        self.robot_state: Callable[[], Any] | None = None
        #: Called with (phase, box time) at every phase (the grasp action's feedback).
        self.on_phase: Callable[[str, float], None] | None = None
        self.frames, self.last_t = 0, 0.0
        self._last_pressures = np.zeros(self.n)
        self._next_diag = 0.0
        self._next_pose = 0.0
        #: Publisher of every topic name of the table's ``ros2`` output.
        self.pub: dict[str, Any] = {}
        for t in T.TOPICS:
            if "ros2" in t.outputs:
                cls = message_class(t.type)
                for name in t.names(self.n):
                    self.pub[name] = node.create_publisher(cls, name, qos_profile(t.qos))
        self.reset_pace()

    @property
    def box(self) -> Any:
        """The box whose rate and valves the diagnostics report; frames of an in-process
        simulated box are paced to the wall clock (as the ROS 1 node does)."""
        return self._box

    @box.setter
    def box(self, box: Any) -> None:
        from softpad.box import simulator_of

        self._box = box
        self.pace = simulator_of(box) is not None

    def stamp(self) -> Any:
        """The node's clock now, as a message stamp."""
        return self.node.get_clock().now().to_msg()

    def static_frames(self, pad: PadPose, base_frame: str) -> None:
        """``/tf_static``: ``base_frame`` -> ``softpad`` (the pad's pose) -> each module."""
        from geometry_msgs.msg import Quaternion, Transform, TransformStamped, Vector3
        from tf2_msgs.msg import TFMessage

        stamp, out = self.stamp(), []
        for parent, child, (x, y, z, yaw) in T.static_frames(self.layout, pad, base_frame):
            qx, qy, qz, qw = T.quaternion_z(yaw)
            rotation = Quaternion(x=qx, y=qy, z=qz, w=qw)
            out.append(
                TransformStamped(
                    header=_header(stamp, parent),
                    child_frame_id=child,
                    transform=Transform(translation=Vector3(x=x, y=y, z=z), rotation=rotation),
                )
            )
        self.pub[T.TF_STATIC_TOPIC].publish(TFMessage(transforms=out))

    def reset_pace(self) -> None:
        """Start pacing afresh: the next frame's box time counts from the wall time now."""
        self._wall0: float | None = None
        self._box0 = 0.0
        self._rate_window: list[float] = []

    def _pressure(self, stamp: Any, frame_id: str, gauge_pa: float) -> Any:
        from sensor_msgs.msg import FluidPressure

        return FluidPressure(
            header=_header(stamp, frame_id),
            fluid_pressure=float(gauge_pa) + self.ambient_pressure_pa,
            variance=thesis.SENSOR_VARIANCE_PA2,
        )

    def frame(self, frame: PressureFrame) -> None:
        """Publish one frame (an in-process simulated box paced to the wall clock), the
        robot's pose at its rate, and the diagnostics when their period has passed."""
        from std_msgs.msg import Float64MultiArray, MultiArrayDimension

        now = time.monotonic()
        if self._wall0 is None:
            self._wall0, self._box0 = now, frame.t_s
        ahead = (frame.t_s - self._box0) - (now - self._wall0)
        if self.pace and ahead > 0:
            time.sleep(ahead)
        self.frames += 1
        self.last_t = frame.t_s
        self._rate_window = [*self._rate_window[-199:], time.monotonic()]
        stamp = self.stamp()
        p = frame.pressures_pa[: self.n]
        for k in range(1, self.n + 1):
            msg = self._pressure(stamp, T.module_frame(k), float(p[k - 1]))
            self.pub[T.module_topic(k)].publish(msg)
        self.pub[T.SUPPLY_TOPIC].publish(self._pressure(stamp, T.PAD_FRAME, frame.supply_pa))
        data = [float(v) for v in [*p, frame.supply_pa]]
        dim = MultiArrayDimension(label=T.GAUGE_LABEL, size=len(data), stride=len(data))
        array = Float64MultiArray(data=data)
        array.layout.dim = [dim]
        self.pub[T.GAUGE_TOPIC].publish(array)
        self._last_pressures = np.asarray(p, dtype=float)
        self._robot_pose(stamp, frame.t_s)
        if time.monotonic() >= self._next_diag:
            self.diagnostics()

    def _robot_pose(self, stamp: Any, t_s: float) -> None:
        from geometry_msgs.msg import PoseStamped

        rate = T.topic(T.ROBOT_POSE_TOPIC).rate_hz or 20.0
        if self.robot_state is None or t_s < self._next_pose:
            return
        self._next_pose = t_s + 1.0 / rate
        s = self.robot_state()
        pose = _pose(s.x_m, s.y_m, s.z_m, getattr(s, "yaw_rad", 0.0))
        self.pub[T.ROBOT_POSE_TOPIC].publish(
            PoseStamped(header=_header(stamp, T.PAD_FRAME), pose=pose)
        )

    def plans(self, plans: Sequence[dict[str, Any]]) -> None:
        """Grasps and objects of ``plans`` (:meth:`softpad.planning.GraspPlan.to_dict`)."""
        from geometry_msgs.msg import PoseArray

        header = _header(self.stamp(), T.PAD_FRAME)
        grasps = [_pose(p["cog_m"][0], p["cog_m"][1], 0.0, float(p["theta"])) for p in plans]
        pcoms = [self.layout.to_metres(tuple(p["pcom"])) for p in plans]
        objects = [_pose(float(x), float(y), 0.0, 0.0) for x, y in pcoms]
        self.pub[T.PLAN_TOPIC].publish(PoseArray(header=header, poses=grasps))
        self.pub[T.OBJECT_TOPIC].publish(PoseArray(header=header, poses=objects))

    def contact(self, touching: bool) -> None:
        from std_msgs.msg import Bool

        self.pub[T.CONTACT_TOPIC].publish(Bool(data=bool(touching)))

    def phase(self, name: str) -> None:
        from std_msgs.msg import String

        self.pub[T.PHASE_TOPIC].publish(String(data=name))
        if self.on_phase is not None:
            self.on_phase(name, self.last_t)

    def event(self, t_s: float, kind: str, data: dict[str, Any]) -> None:
        """``/softpad/events``: one event of the loop, its data as JSON (SI units)."""
        from softpad_msgs.msg import Event

        msg = Event(header=_header(self.stamp(), T.PAD_FRAME), kind=kind)
        msg.data_json = json.dumps(_jsonable({"t_s": t_s, **data}))
        self.pub[T.EVENT_TOPIC].publish(msg)

    def outcome(self, summary: dict[str, Any]) -> None:
        """``/softpad/outcome``: the end of a grasp loop (``summary`` as ``softpad run
        --json`` gives it, or ``{"outcome": "fault"|"error"|"canceled", "message", ...}``)."""
        from softpad_msgs.msg import Outcome

        msg = Outcome(header=_header(self.stamp(), T.PAD_FRAME))
        msg.outcome = str(summary.get("outcome", ""))
        msg.message = str(summary.get("message", "") or "")
        msg.summary_json = json.dumps(_jsonable(summary))
        self.pub[T.OUTCOME_TOPIC].publish(msg)

    def diagnostics(self) -> None:
        """``/diagnostics``: the link (ERROR with :attr:`fault`), the rate, every channel."""
        from diagnostic_msgs.msg import DiagnosticArray

        self._next_diag = time.monotonic() + DIAGNOSTICS_PERIOD_S
        w = self._rate_window
        rate = (len(w) - 1) / (w[-1] - w[0]) if len(w) > 1 and w[-1] > w[0] else 0.0
        nominal = float(self.box.sample_rate_hz) if self.box is not None else math.nan
        link = _status(
            2 if self.fault else 0, "softpad: link", self.fault or "OK", box=self.box_url,
            frames=self.frames,
        )  # fmt: skip
        rate_ok = self.fault is None and rate >= 0.8 * nominal
        rate_st = _status(
            0 if rate_ok else 1, "softpad: rate", "OK" if rate_ok else "below the box rate",
            rate_hz=f"{rate:.1f}", nominal_hz=f"{nominal:g}",
        )  # fmt: skip
        status = [link, rate_st, *(self._channel_status(k) for k in range(1, self.n + 1))]
        msg = DiagnosticArray(header=_header(self.stamp(), ""), status=status)
        self.pub[T.DIAGNOSTICS_TOPIC].publish(msg)

    def _channel_status(self, k: int) -> Any:
        from softpad.control import DEFAULT_MAX_PRESSURE_PA

        p = float(self._last_pressures[k - 1])
        bad = not math.isfinite(p) or p > DEFAULT_MAX_PRESSURE_PA
        valves = getattr(self.box, "valves", None)
        valve = valves[k - 1].value if valves is not None else "?"
        return _status(
            2 if bad else 0, f"softpad: channel {k}", "no valid reading or over the maximum"
            if bad else "OK", pressure_pa=f"{p:.1f}", valve=valve,
        )  # fmt: skip


def _status(level: int, name: str, message: str, **values: object) -> Any:
    """diagnostic_msgs/DiagnosticStatus (level 0 OK, 1 WARN, 2 ERROR) with key/values."""
    from diagnostic_msgs.msg import DiagnosticStatus, KeyValue

    return DiagnosticStatus(
        level=bytes([level]),
        name=name,
        message=message,
        hardware_id="softpad",
        values=[KeyValue(key=k, value=str(v)) for k, v in values.items()],
    )
