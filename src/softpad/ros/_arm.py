"""``ros1://``: a :class:`softpad.control.Robot` whose arm and gripper are reached through ROS 1.

The arm contract (docs/ros.md) is two topics of standard messages, both in the pad frame
``softpad`` (metres, radians, m/s):

``/softpad_arm/command`` (std_msgs/Float64MultiArray, published by SoftPad)
    ``layout.dim[0].label`` names the command, ``data[0]`` is its id (1, 2, 3, ...; one
    counter per client), then the arguments: ``move_to`` [id, x, y, z, yaw, speed],
    ``descend`` [id, speed, min_z], ``stop`` [id], ``gripper`` [id, width, speed]. One topic
    keeps the commands in order (ROS orders messages per topic connection only).
``/softpad_arm/state`` (std_msgs/Float64MultiArray, published by the arm at >= 20 Hz)
    [x, y, z, yaw, width, moving, holding, done_id]: the tool pose, jaw width, 1.0 while a
    motion runs, 1.0 while the jaws hold an object, and the id of the last command the arm
    received and finished (motion done).

A command counts as under way from the moment it is sent until a state with ``done_id`` >= its
id and ``moving`` = 0 arrives; no state for ``stale_s`` means the arm is gone: every call then
raises :class:`~softpad.errors.HardwareFault`, and the grasp loop makes the box safe.
"""

from __future__ import annotations

import threading
import time
from typing import Any
from urllib.parse import parse_qs, urlsplit

from softpad.control import RobotState, ToolPose
from softpad.errors import HardwareFault, InputError

ARM_COMMAND_TOPIC = "/softpad_arm/command"
ARM_STATE_TOPIC = "/softpad_arm/state"
#: Fields of the state message, in order.
STATE_FIELDS = ("x_m", "y_m", "z_m", "yaw_rad", "width_m", "moving", "holding", "done_id")


class Ros1Robot:
    """The arm behind :data:`ARM_COMMAND_TOPIC` / :data:`ARM_STATE_TOPIC` (module docstring).

    Parameters
    ----------
    connect_timeout_s
        How long to wait for the arm's first state and its subscription, seconds.
    stale_s
        Longest silence of the state topic before the arm counts as lost, seconds.
    node_name
        Name of the rospy node created when this process has none yet.
    """

    def __init__(
        self, connect_timeout_s: float = 10.0, stale_s: float = 1.0, node_name: str = "softpad_run"
    ) -> None:
        from softpad.ros._rospy_path import require_master

        rospy = require_master()
        from std_msgs.msg import Float64MultiArray

        if not rospy.core.is_initialized():
            rospy.init_node(node_name, anonymous=True, disable_signals=True)
        self.stale_s = float(stale_s)
        self._lock = threading.Lock()
        self._state: tuple[float, ...] | None = None
        self._seen = 0.0
        self._sent = 0
        self._pub = rospy.Publisher(ARM_COMMAND_TOPIC, Float64MultiArray, queue_size=100)
        self._sub = rospy.Subscriber(ARM_STATE_TOPIC, Float64MultiArray, self._on_state)
        deadline = time.monotonic() + connect_timeout_s
        while self._state is None or self._pub.get_num_connections() < 1:
            if time.monotonic() > deadline:
                raise HardwareFault(
                    f"no arm answers on {ARM_STATE_TOPIC} / {ARM_COMMAND_TOPIC} within "
                    f"{connect_timeout_s:g} s (is an arm node running, e.g. 'softpad sim arm-node'?)"
                )
            time.sleep(0.02)

    def _on_state(self, msg: Any) -> None:
        if len(msg.data) != len(STATE_FIELDS):
            return  # malformed: ignored (the arm then goes stale)
        with self._lock:
            self._state = tuple(float(v) for v in msg.data)
            self._seen = time.monotonic()

    def _latest(self) -> tuple[float, ...]:
        with self._lock:
            s, seen = self._state, self._seen
        if s is None or time.monotonic() - seen > self.stale_s:
            raise HardwareFault(
                f"arm lost: no {ARM_STATE_TOPIC} for {self.stale_s:g} s (the arm node stopped?)"
            )
        return s

    def _send(self, op: str, *args: float, check: bool = True) -> None:
        from softpad.ros._messages import labelled_array

        if check:
            self._latest()  # refuse to command an arm that is gone
        self._sent += 1
        self._pub.publish(labelled_array([float(self._sent), *args], op))

    def move_to(self, pose: ToolPose, speed_m_s: float) -> None:
        self._send("move_to", pose.x_m, pose.y_m, pose.z_m, pose.yaw_rad, speed_m_s)

    def descend(self, speed_m_s: float, min_z_m: float) -> None:
        self._send("descend", speed_m_s, min_z_m)

    def stop(self) -> None:
        """Send stop, also to an arm that has gone silent (the loop stops it on any fault)."""
        self._send("stop", check=False)

    def set_gripper(self, width_m: float, speed_m_s: float) -> None:
        self._send("gripper", width_m, speed_m_s)

    def is_moving(self) -> bool:
        s = self._latest()
        return s[7] < self._sent or s[5] > 0.5

    def state(self) -> RobotState:
        return RobotState(*self._latest()[:5])

    def holding(self) -> bool:
        return self._latest()[6] > 0.5

    def close(self) -> None:
        """Unregister the topics."""
        self._pub.unregister()
        self._sub.unregister()


def open_robot(url: str) -> Ros1Robot:
    """Robot by URL: ``ros1://`` (options ``?timeout_s=10&stale_s=1``).

    ``sim://`` robots belong to a simulated box and are made by the simulated run itself;
    every scheme is reached through :func:`softpad.control.make_robot`.
    """
    parts = urlsplit(url)
    if parts.scheme == "sim":
        raise InputError(f"the simulated robot is plain sim:// (no options), got {url!r}")
    if parts.scheme != "ros1":
        raise InputError(f"unknown robot URL {url!r}: known schemes are sim:// and ros1://")
    if parts.netloc or parts.path not in ("", "/"):
        raise InputError(
            f"ros1:// takes no host or path (ROS_MASTER_URI names the master), got {url!r}"
        )
    opts = {k: v[-1] for k, v in parse_qs(parts.query).items()}
    return open_ros1_robot("", opts)


def open_ros1_robot(location: str, options: dict[str, str], context: object = None) -> Ros1Robot:
    """The ``ros1://`` factory of :data:`softpad.control.ROBOT_REGISTRY`: options
    ``timeout_s`` (arm state awaited at start, s) and ``stale_s`` (state older than this is a
    lost arm, s), each in (0, 3600)."""
    if location not in ("", "/"):
        raise InputError(
            f"ros1:// takes no host or path (ROS_MASTER_URI names the master), got {location!r}"
        )
    unknown = sorted(set(options) - {"timeout_s", "stale_s"})
    if unknown:
        raise InputError(f"unknown ros1:// option {unknown[0]!r}; known: timeout_s, stale_s")
    try:
        vals = {k: float(v) for k, v in options.items()}
    except ValueError:
        raise InputError(f"ros1:// options must be numbers, got {options}") from None
    if any(not 0 < v < 3600 for v in vals.values()):
        raise InputError(f"ros1:// options must be in (0, 3600) s, got {vals}")
    return Ros1Robot(vals.get("timeout_s", 10.0), vals.get("stale_s", 1.0))
