"""What a pad publishes on ROS 1, from the node's own watch and from the grasp loop.

:class:`PadPublishers` owns the pad's topics, exactly the ``ros1`` rows of the one topic table
(:mod:`softpad.topics`, docs/ros.md): every frame (paced to the wall clock when a simulated
box runs faster), the supply, the plan's grasps and objects, contact, the loop's phase,
events and outcome, the robot's pose while a simulated arm moves, diagnostics once a second
and the static transforms. :class:`LoopPublisher` is a
:class:`softpad.control.Recorder`: given to :class:`~softpad.control.GraspExecution`, it
publishes what the loop does through them, so ``softpad ros node``'s ``~grasp`` and
``softpad run --ros`` show the same topics. Translation only: no decision is made here.
"""

from __future__ import annotations

import json
import math
import time
import warnings
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from softpad import thesis
from softpad import topics as T
from softpad.box import PressureFrame
from softpad.layout import PadLayout, PadPose

#: The loop's phase (std_msgs/String, latched): ``adjust``, ``wait_object``, ``descend``, ...
PHASE_TOPIC = T.PHASE_TOPIC
#: The end of each grasp loop (softpad_msgs/Outcome, latched): ``outcome``, ``message`` and
#: ``summary_json``, ``softpad run --json``'s object (``outcome``, ``objects``, ``grasps``,
#: ``phases``, ...), or ``{"outcome": "fault"|"error"|"canceled", "message", ...}``.
OUTCOME_TOPIC = T.OUTCOME_TOPIC
#: Every event of the node's watch and of the grasp loop (``softpad_msgs/Event``: ``kind`` and
#: its data as JSON, SI units), as recordings hold them on the same topic.
EVENT_TOPIC = T.EVENT_TOPIC
#: Wall time between two diagnostics messages, seconds.
DIAGNOSTICS_PERIOD_S = 1.0


def init_node(rospy: Any, name: str) -> None:
    """Make this process a ROS node named ``name`` (anonymous) unless it is one already."""
    if not rospy.core.is_initialized():
        rospy.init_node(name, anonymous=True, disable_signals=True)


class PadPublishers:
    """The pad's topics of one ROS node (module docstring).

    Parameters
    ----------
    rospy
        The imported rospy, its node initialised.
    layout
        The pad (one pressure topic per module).
    box_url
        Named in the diagnostics.
    ambient_pressure_pa
        Added to the gauge readings in ``sensor_msgs/FluidPressure`` (absolute), Pa.
    """

    def __init__(
        self,
        rospy: Any,
        layout: PadLayout,
        box_url: str,
        ambient_pressure_pa: float = thesis.AMBIENT_PRESSURE_PA,
    ) -> None:
        self.rospy, self.layout, self.n = rospy, layout, layout.n_modules
        self.box_url, self.ambient_pressure_pa = box_url, ambient_pressure_pa
        self._box: Any = None
        #: Whether frames are paced to the wall clock (an in-process simulated box only).
        self.pace = False
        #: The fault the diagnostics report as the link's ERROR, None while healthy.
        self.fault: str | None = None
        self.frames, self.last_t = 0, 0.0
        self._last_pressures = np.zeros(self.n)
        self._next_diag = 0.0
        #: The robot's measured pose (``x_m, y_m, z_m, yaw_rad``), published at the table's
        #: rate while set (a simulated arm's, during a grasp).
        self.robot_state: Callable[[], Any] | None = None
        self._next_pose = -math.inf
        self._make_publishers()
        self.reset_pace()

    @property
    def box(self) -> Any:
        """The box whose rate and valves the diagnostics report (set once it is open). Its
        frames are paced when it is an in-process simulated box (lock-step, faster than real
        time); a served or hardware box sends them at its own rate, and pacing those would only
        add latency to the loop's reads."""
        return self._box

    @box.setter
    def box(self, box: Any) -> None:
        from softpad.box import simulator_of

        self._box = box
        self.pace = simulator_of(box) is not None

    def _make_publishers(self) -> None:
        """One publisher per name of the table's ``ros1`` rows, its type and QoS (latched:
        ``latch``; depth: the queue)."""
        #: Publisher of every topic of the table's ``ros1`` output, by name.
        self.pub: dict[str, Any] = {}
        for t in T.TOPICS:
            if "ros1" not in t.outputs:
                continue
            cls = message_class(t.type)
            for name in t.names(self.n):
                if name == OUTCOME_TOPIC:  # synchronous: the end of a run reaches its
                    with warnings.catch_warnings():  # subscribers before the process ends
                        warnings.simplefilter("ignore", SyntaxWarning)  # rospy's advice
                        self.pub[name] = self.rospy.Publisher(
                            name, cls, queue_size=None, latch=True
                        )
                    continue
                self.pub[name] = self.rospy.Publisher(
                    name, cls, queue_size=t.qos.depth, latch=t.qos.latched
                )

    def static_frames(self, pad: PadPose, base_frame: str) -> None:
        """``base_frame`` -> ``softpad`` (the pad's pose) and ``softpad`` -> each module."""
        from softpad.ros import _messages as m

        stamp = self.rospy.Time.now()
        tf = m.static_transform(stamp, pad, base_frame)
        tf.transforms.extend(m.module_transforms(stamp, self.layout))
        self.pub[T.TF_STATIC_TOPIC].publish(tf)

    def reset_pace(self) -> None:
        """Start pacing afresh: the next frame's box time counts from the wall time now."""
        self._wall0: float | None = None
        self._box0 = 0.0
        self._rate_window: list[float] = []

    def frame(self, frame: PressureFrame) -> None:
        """Publish one frame (an in-process simulated box paced to the wall clock when it runs
        ahead of it), and the diagnostics when their period has passed."""
        from softpad.ros import _messages as m

        now = time.monotonic()
        if self._wall0 is None:
            self._wall0, self._box0 = now, frame.t_s
        ahead = (frame.t_s - self._box0) - (now - self._wall0)
        if self.pace and ahead > 0:
            time.sleep(ahead)
        self.frames += 1
        self.last_t = frame.t_s
        self._rate_window = [*self._rate_window[-199:], time.monotonic()]
        stamp = self.rospy.Time.now()
        p = frame.pressures_pa[: self.n]
        for k in range(1, self.n + 1):
            msg = m.fluid_pressure(stamp, k, float(p[k - 1]), self.ambient_pressure_pa)
            self.pub[T.module_topic(k)].publish(msg)
        supply = m.fluid_pressure(stamp, 0, float(frame.supply_pa), self.ambient_pressure_pa)
        supply.header.frame_id = T.PAD_FRAME
        self.pub[T.SUPPLY_TOPIC].publish(supply)
        self.pub[T.GAUGE_TOPIC].publish(m.labelled_array([*p, frame.supply_pa], T.GAUGE_LABEL))
        self._last_pressures = p
        self._robot_pose(stamp, frame.t_s)
        if time.monotonic() >= self._next_diag:
            self.diagnostics()

    def _robot_pose(self, stamp: Any, t_s: float) -> None:
        """The robot's measured pose at the table's rate (box time) while :attr:`robot_state`
        is set."""
        from geometry_msgs.msg import PoseStamped

        from softpad.ros import _messages as m

        if self.robot_state is None or t_s < self._next_pose:
            return
        self._next_pose = t_s + 1.0 / (T.topic(T.ROBOT_POSE_TOPIC).rate_hz or 20.0)
        s = self.robot_state()
        msg = PoseStamped(pose=m.pose(s.x_m, s.y_m, s.z_m, getattr(s, "yaw_rad", 0.0)))
        msg.header.stamp, msg.header.frame_id = stamp, T.PAD_FRAME
        self.pub[T.ROBOT_POSE_TOPIC].publish(msg)

    def plans(self, plans: Sequence[dict[str, Any]]) -> None:
        """Objects and grasps of ``plans`` (:meth:`softpad.planning.GraspPlan.to_dict`)."""
        from softpad.ros import _messages as m

        stamp = self.rospy.Time.now()
        self.pub[T.OBJECT_TOPIC].publish(m.pose_array(stamp, m.object_poses(plans, self.layout)))
        self.pub[T.PLAN_TOPIC].publish(m.pose_array(stamp, m.grasp_poses(plans)))

    def contact(self, touching: bool) -> None:
        from std_msgs.msg import Bool

        self.pub[T.CONTACT_TOPIC].publish(Bool(bool(touching)))

    def phase(self, name: str) -> None:
        from std_msgs.msg import String

        self.pub[T.PHASE_TOPIC].publish(String(name))

    def event(self, t_s: float, kind: str, data: dict[str, Any]) -> None:
        """One event on :data:`EVENT_TOPIC`: ``kind`` and ``data`` as JSON (non-finite numbers
        as null), stamped now, in the pad frame; ``t_s`` (box time, s) joins the data."""
        from softpad.ros._messages import PAD_FRAME
        from softpad.ros._msgs import ensure_messages

        msg = ensure_messages().Event(
            kind=kind, data_json=json.dumps(_jsonable(dict(data, t_s=t_s)))
        )
        msg.header.stamp, msg.header.frame_id = self.rospy.Time.now(), PAD_FRAME
        self.pub[T.EVENT_TOPIC].publish(msg)

    def outcome(self, summary: dict[str, Any]) -> None:
        """The end of a grasp loop (``softpad_msgs/Outcome``): its ``outcome``, ``message``
        and the whole summary as JSON (non-finite numbers as null)."""
        from softpad.ros._msgs import ensure_messages

        msg = ensure_messages().Outcome(
            outcome=str(summary.get("outcome", "")), message=str(summary.get("message") or ""),
            summary_json=json.dumps(_jsonable(summary)),
        )  # fmt: skip
        msg.header.stamp, msg.header.frame_id = self.rospy.Time.now(), T.PAD_FRAME
        self.pub[OUTCOME_TOPIC].publish(msg)

    def diagnostics(self) -> None:
        """``/diagnostics``: the link (ERROR with :attr:`fault`), the rate, every channel."""
        from diagnostic_msgs.msg import DiagnosticArray

        from softpad.ros import _messages as m

        self._next_diag = time.monotonic() + DIAGNOSTICS_PERIOD_S
        w = self._rate_window
        rate = (len(w) - 1) / (w[-1] - w[0]) if len(w) > 1 and w[-1] > w[0] else 0.0
        nominal = float(self.box.sample_rate_hz) if self.box is not None else math.nan
        link = m.diagnostic_status(
            2 if self.fault else 0, "softpad: link", self.fault or "OK", box=self.box_url,
            frames=self.frames,
        )  # fmt: skip
        rate_ok = self.fault is None and rate >= 0.8 * nominal
        rate_st = m.diagnostic_status(
            0 if rate_ok else 1, "softpad: rate", "OK" if rate_ok else "below the box rate",
            rate_hz=f"{rate:.1f}", nominal_hz=f"{nominal:g}",
        )  # fmt: skip
        status = [link, rate_st, *(self._channel_status(k) for k in range(1, self.n + 1))]
        msg = DiagnosticArray(status=status)
        msg.header.stamp = self.rospy.Time.now()
        self.pub[T.DIAGNOSTICS_TOPIC].publish(msg)

    def _channel_status(self, k: int) -> Any:
        from softpad.control import DEFAULT_MAX_PRESSURE_PA
        from softpad.ros import _messages as m

        p = float(self._last_pressures[k - 1])
        bad = not math.isfinite(p) or p > DEFAULT_MAX_PRESSURE_PA
        valves = getattr(self.box, "valves", None)
        valve = valves[k - 1].value if valves is not None else "?"
        return m.diagnostic_status(
            2 if bad else 0, f"softpad: channel {k}", "no valid reading or over the maximum"
            if bad else "OK", pressure_pa=f"{p:.1f}", valve=valve,
        )  # fmt: skip


def message_class(ros2_type: str) -> Any:
    """The ROS 1 message class of the table's type ``pkg/msg/Name``: Debian's message
    packages, SoftPad's own (``softpad_msgs``) generated by :func:`softpad.ros.ensure_messages`."""
    import importlib

    package, _, name = ros2_type.split("/")
    if package == "softpad_msgs":
        from softpad.ros._msgs import ensure_messages

        return getattr(ensure_messages(), name)
    return getattr(importlib.import_module(f"{package}.msg"), name)


def _jsonable(value: Any) -> Any:
    """``value`` with NaN and infinities as None (JSON has no such numbers)."""
    if isinstance(value, float):
        return value if math.isfinite(value) else None
    if isinstance(value, dict):
        return {k: _jsonable(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_jsonable(v) for v in value]
    return value


class GraspCancelled(KeyboardInterrupt):
    """A grasp cancelled through the grasp action, raised from :meth:`LoopPublisher.frame`.

    :class:`~softpad.control.GraspExecution` answers it as it answers Ctrl-C: it stops the
    arm, reaches the box's verified safe state (inflation valves closed, channels vented) and
    re-raises it. Hence a :class:`KeyboardInterrupt`: the loop knows no ROS and needs no
    second way of being stopped.
    """


#: Phases that end a sensed contact (the fingers leave the pad or go elsewhere).
_UNTOUCHED = ("approach", "release", "valve_check", "done")


class LoopPublisher:
    """A :class:`softpad.control.Recorder` publishing a grasp loop through ``publishers``.

    Every frame: the pressures and ``/softpad/contact`` (true from the loop's ``contact``
    event until the grasp's ``release``, or the next ``approach`` after a landing). Each phase
    on :data:`PHASE_TOPIC`; the plan on ``/softpad/plan/objects`` and ``/softpad/plan/grasps``, the
    latter again when an ``approach`` tries another grasp of an object (a retry); a fault as
    the link's ERROR and on :data:`OUTCOME_TOPIC`, where :meth:`finish` puts the loop's result
    and :meth:`error` a loop that could not go on.
    """

    def __init__(self, publishers: PadPublishers) -> None:
        self.publishers = publishers
        self.touching = False
        self._plans: list[dict[str, Any]] = []
        #: Called with each phase and its box time, s (the grasp action's feedback).
        self.on_phase: Callable[[str, float], None] | None = None
        #: True when the loop is to stop (the grasp action's cancel): :class:`GraspCancelled`.
        self.cancel_requested: Callable[[], bool] | None = None

    def frame(self, frame: PressureFrame, phase: str) -> None:
        self.publishers.frame(frame)
        self.publishers.contact(self.touching)
        # not while the loop goes to its safe state: that is what the cancel asks for
        if phase != "safe" and self.cancel_requested is not None and self.cancel_requested():
            self.cancel_requested = None
            raise GraspCancelled(f"grasp cancelled in phase {phase!r}")

    def event(self, t_s: float, kind: str, **data: Any) -> None:
        pubs = self.publishers
        pubs.event(t_s, kind, data)
        if kind == "phase":
            if data["phase"] in _UNTOUCHED:
                self.touching = False
            if data["phase"] == "approach":
                self._approach(data)
            pubs.phase(str(data["phase"]))
            if self.on_phase is not None:
                self.on_phase(str(data["phase"]), t_s)
        elif kind == "plan":
            self._plans = [dict(p) for p in data["objects"]]
            pubs.plans(self._plans)
        elif kind == "contact":
            self.touching = True
        elif kind == "fault":
            pubs.fault = str(data.get("message"))
            pubs.diagnostics()
            pubs.outcome({"outcome": "fault", "t_s": t_s, **data})

    def _approach(self, data: dict[str, Any]) -> None:
        """The grasp of the object on ``modules`` about to be tried: republished when it is
        not the planned one (a retry's)."""
        for p in self._plans:
            if p["modules"] == data.get("modules") and (
                p["cog"] != data.get("cog") or p["theta"] != data.get("theta")
            ):
                x, y = self.publishers.layout.to_metres(tuple(data["cog"]))
                p.update(cog=list(data["cog"]), theta=data["theta"], cog_m=[float(x), float(y)])
                self.publishers.plans(self._plans)

    def finish(self, result: Any) -> None:
        """Publish the loop's result (:class:`softpad.control.ExecutionResult`)."""
        self.publishers.outcome(result.to_dict())

    def error(self, message: str) -> None:
        """Publish that the loop could not go on (no object in time, nothing to grasp)."""
        self.publishers.outcome({"outcome": "error", "message": message})

    def cancelled(self, message: str) -> None:
        """Publish a loop cancelled on request and now in the safe state: the link is healthy
        again (the loop reported the stop as its fault ``interrupted``)."""
        self.publishers.fault = None
        self.publishers.outcome({"outcome": "canceled", "message": message})


def watch_loop(
    layout: PadLayout,
    box: Any,
    box_url: str,
    node_name: str = "softpad_run",
    pad: PadPose | None = None,
    base_frame: str = "base",
) -> LoopPublisher:
    """A :class:`LoopPublisher` for a grasp loop run by this process (``softpad run
    --ros``): this process becomes the ROS node ``node_name`` (anonymous) unless it is one,
    and publishes the pad's topics, the static transforms with the pad at ``pad`` in
    ``base_frame`` (the installation's ``[pad.pose]``; None: the origin). InputError when no
    ROS master answers."""
    from softpad.ros._rospy_path import require_master

    rospy = require_master()
    init_node(rospy, node_name)
    from softpad.box import simulator_of

    pubs = PadPublishers(rospy, layout, box_url)
    pubs.box = box
    sim = simulator_of(box)
    if sim is not None:  # the simulated arm's measured pose, as recordings take it
        pubs.robot_state = sim.world.gripper_state
    pubs.static_frames(pad or PadPose(), base_frame)
    return LoopPublisher(pubs)
