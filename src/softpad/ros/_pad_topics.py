"""The pad's topics, built once for ROS 1 and ROS 2.

:class:`PadTopics` turns frames, plans, phases, events, outcomes, diagnostics and the static
transforms into the standard and ``softpad_msgs`` messages of the topic table
(:mod:`softpad.topics`) and publishes them through ``self.pub``. Both ROS versions name their
message modules alike (``std_msgs.msg``, ``geometry_msgs.msg``, ...) and both take keyword
arguments, so one body serves rospy's genpy classes and rclpy's; a subclass only makes the
publishers, stamps messages with its clock and finds ``softpad_msgs``
(:class:`softpad.ros.PadPublishers` for ROS 1, :class:`softpad.ros2.Ros2Publishers` for ROS 2).
Translation only: no decision is made here.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from softpad import thesis
from softpad import topics as T
from softpad.box import PressureFrame
from softpad.layout import PadLayout, PadPose
from softpad.ros import _messages as m

#: Wall time between two diagnostics messages, seconds.
DIAGNOSTICS_PERIOD_S = 1.0


class PadTopics:
    """The pad's topics of one node, whatever its ROS (module docstring).

    Parameters
    ----------
    layout
        The pad (one pressure topic per module).
    box_url
        Named in the diagnostics.
    ambient_pressure_pa
        Added to the gauge readings in ``sensor_msgs/FluidPressure`` (absolute), Pa.
    """

    def __init__(
        self,
        layout: PadLayout,
        box_url: str,
        ambient_pressure_pa: float = thesis.AMBIENT_PRESSURE_PA,
    ) -> None:
        self.layout, self.n = layout, layout.n_modules
        self.box_url, self.ambient_pressure_pa = box_url, float(ambient_pressure_pa)
        self._box: Any = None
        #: Whether frames are paced to the wall clock (an in-process simulated box only).
        self.pace = False
        #: The fault the diagnostics report as the link's ERROR, None while healthy.
        self.fault: str | None = None
        #: The robot's measured pose (``x_m, y_m, z_m, yaw_rad``), published at the table's
        #: rate while set (a simulated arm's, during a grasp).
        self.robot_state: Callable[[], Any] | None = None
        self.frames, self.last_t = 0, 0.0
        self._last_pressures = np.zeros(self.n)
        self._next_diag = 0.0
        self._next_pose = -math.inf
        #: Publisher of every topic name of the table's rows for this output, by name.
        self.pub: dict[str, Any] = {}
        self.reset_pace()

    def stamp(self) -> Any:
        """The node's clock now, as a message stamp (the subclass's ROS)."""
        raise NotImplementedError

    def softpad_messages(self) -> Any:
        """The module holding ``softpad_msgs``' message classes (``Event``, ``Outcome``)."""
        raise NotImplementedError

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

    def watch_run(self, box: Any, pad: PadPose | None, base_frame: str) -> None:
        """Set up for a run of this process on ``box`` (``softpad run --ros/--ros2``): its
        diagnostics and pacing, a simulated arm's measured pose (as recordings take it) and
        the static frames with the pad at ``pad`` in ``base_frame`` (None: the origin)."""
        from softpad.box import simulator_of

        self.box = box
        sim = simulator_of(box)
        if sim is not None:
            self.robot_state = sim.world.gripper_state
        self.static_frames(pad or PadPose(), base_frame)

    def static_frames(self, pad: PadPose, base_frame: str) -> None:
        """``/tf_static``: ``base_frame`` -> ``softpad`` (the pad's pose) -> each module."""
        frames = T.static_frames(self.layout, pad, base_frame)
        self.pub[T.TF_STATIC_TOPIC].publish(m.static_transforms(self.stamp(), frames))

    def reset_pace(self) -> None:
        """Start pacing afresh: the next frame's box time counts from the wall time now."""
        self._wall0: float | None = None
        self._box0 = 0.0
        self._rate_window: list[float] = []

    def frame(self, frame: PressureFrame) -> None:
        """Publish one frame (an in-process simulated box paced to the wall clock when it runs
        ahead of it), the robot's pose at its rate, and the diagnostics when their period has
        passed."""
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
        p = np.asarray(frame.pressures_pa[: self.n], dtype=float)
        ambient = self.ambient_pressure_pa
        for k in range(1, self.n + 1):
            msg = m.fluid_pressure(stamp, T.module_frame(k), float(p[k - 1]), ambient)
            self.pub[T.module_topic(k)].publish(msg)
        supply = m.fluid_pressure(stamp, T.PAD_FRAME, float(frame.supply_pa), ambient)
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

        if self.robot_state is None or t_s < self._next_pose:
            return
        self._next_pose = t_s + 1.0 / (T.topic(T.ROBOT_POSE_TOPIC).rate_hz or 20.0)
        s = self.robot_state()
        pose = m.pose(s.x_m, s.y_m, s.z_m, getattr(s, "yaw_rad", 0.0))
        msg = PoseStamped(header=m.header(stamp, T.PAD_FRAME), pose=pose)
        self.pub[T.ROBOT_POSE_TOPIC].publish(msg)

    def plans(self, plans: Sequence[dict[str, Any]]) -> None:
        """Objects and grasps of ``plans`` (:meth:`softpad.planning.GraspPlan.to_dict`)."""
        stamp = self.stamp()
        self.pub[T.OBJECT_TOPIC].publish(m.pose_array(stamp, m.object_poses(plans, self.layout)))
        self.pub[T.PLAN_TOPIC].publish(m.pose_array(stamp, m.grasp_poses(plans)))

    def contact(self, touching: bool) -> None:
        from std_msgs.msg import Bool

        self.pub[T.CONTACT_TOPIC].publish(Bool(data=bool(touching)))

    def phase(self, name: str) -> None:
        from std_msgs.msg import String

        self.pub[T.PHASE_TOPIC].publish(String(data=name))

    def event(self, t_s: float, kind: str, data: dict[str, Any]) -> None:
        """One event on ``/softpad/events`` (``softpad_msgs/Event``): ``kind`` and ``data``
        as JSON (non-finite numbers as null, SI units), stamped now, in the pad frame;
        ``t_s`` (box time, s) joins the data."""
        import json

        msg = self.softpad_messages().Event(
            header=m.header(self.stamp(), T.PAD_FRAME), kind=kind,
            data_json=json.dumps(m.jsonable({"t_s": t_s, **data})),
        )  # fmt: skip
        self.pub[T.EVENT_TOPIC].publish(msg)

    def outcome(self, summary: dict[str, Any]) -> None:
        """The end of a grasp loop (``softpad_msgs/Outcome``): its ``outcome``, ``message``
        and the whole summary as JSON (``softpad run --json``'s object, or ``{"outcome":
        "fault"|"error"|"canceled", "message", ...}``; non-finite numbers as null)."""
        import json

        msg = self.softpad_messages().Outcome(
            header=m.header(self.stamp(), T.PAD_FRAME),
            outcome=str(summary.get("outcome", "")), message=str(summary.get("message") or ""),
            summary_json=json.dumps(m.jsonable(summary)),
        )  # fmt: skip
        self.pub[T.OUTCOME_TOPIC].publish(msg)

    def diagnostics(self) -> None:
        """``/diagnostics``: the link (ERROR with :attr:`fault`), the rate, every channel."""
        from diagnostic_msgs.msg import DiagnosticArray

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
        msg = DiagnosticArray(header=m.header(self.stamp(), ""), status=status)
        self.pub[T.DIAGNOSTICS_TOPIC].publish(msg)

    def _channel_status(self, k: int) -> Any:
        from softpad.control import DEFAULT_MAX_PRESSURE_PA

        p = float(self._last_pressures[k - 1])
        bad = not math.isfinite(p) or p > DEFAULT_MAX_PRESSURE_PA
        valves = getattr(self.box, "valves", None)
        valve = valves[k - 1].value if valves is not None else "?"
        return m.diagnostic_status(
            2 if bad else 0, f"softpad: channel {k}", "no valid reading or over the maximum"
            if bad else "OK", pressure_pa=f"{p:.1f}", valve=valve,
        )  # fmt: skip
