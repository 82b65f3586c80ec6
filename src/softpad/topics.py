"""The one table of SoftPad's topics: name, type, rate and QoS, and which outputs carry them.

Every output of a run reads its names and types from :data:`TOPICS`: the ROS 1 node and
``softpad run --ros`` (output ``"ros1"``), the ROS 2 node and ``softpad run --ros2``
(``"ros2"``), MCAP recordings (``"recording"``) and the Foxglove live view (``"live"``).
:func:`topics_for` gives the names and types one output must publish, so a test can check each
output against the table, and :func:`markdown_table` prints it into docs/ros.md
(``python -m softpad.topics``).

Types are ROS 2 names (``sensor_msgs/msg/FluidPressure``); :func:`ros1_type` gives the ROS 1
name. Standard types are used where one fits; SoftPad's own (events, valve commands, outcomes,
the grasp action) are defined in :data:`MESSAGE_DEFINITIONS`, the one source of the ROS 1 and
ROS 2 message packages and of the definitions recordings embed. ``tf2_msgs/msg/TFMessage``'s
definition is there too: the ROS 2 wheels on the package index have no ``tf2_msgs``, so the
ROS 2 build generates it from the upstream definition (same text, so the same type hash).

Frames: ``base`` -> ``softpad`` (the pad's pose, the installation's ``[pad.pose]``) ->
``softpad_module_K`` (each module's centre on the pad surface), :func:`static_frames`.

The module imports no other part of SoftPad (every layer may import it): it is data and text.
"""

from __future__ import annotations

import math
import sys
from dataclasses import dataclass
from typing import Any

#: The outputs of a run that publish topics.
OUTPUTS = ("ros1", "ros2", "recording", "live")

#: Frame of the pad: origin at its bottom-left corner, z up out of the pad (DESIGN.md).
PAD_FRAME = "softpad"
#: Default parent of :data:`PAD_FRAME`: the robot's base (the installation's pad pose).
BASE_FRAME = "base"

#: Per-module topic names hold this placeholder for the module number (1-based).
MODULE = "{k}"

MODULE_PRESSURE_TOPIC = "/softpad/module_{k}/pressure"
SUPPLY_TOPIC = "/softpad/supply/pressure"
#: Gauge pressures, Pa: modules 1..N, then the supply.
GAUGE_TOPIC = "/softpad/pressures"
#: Label of :data:`GAUGE_TOPIC`'s one dimension.
GAUGE_LABEL = "module_1..N_then_supply_pa"
CONTACT_TOPIC = "/softpad/contact"
PHASE_TOPIC = "/softpad/phase"
EVENT_TOPIC = "/softpad/events"
PLAN_TOPIC = "/softpad/plan/grasps"
OBJECT_TOPIC = "/softpad/plan/objects"
#: The live view's plan event (JSON schema ``softpad.Plan``; Foxglove only).
PLAN_DETAIL_TOPIC = "/softpad/plan"
OUTCOME_TOPIC = "/softpad/outcome"
VALVE_TOPIC = "/softpad/valves"
ROBOT_POSE_TOPIC = "/softpad/robot/pose"
ROBOT_COMMAND_TOPIC = "/softpad/robot/command"
DIAGNOSTICS_TOPIC = "/diagnostics"
TF_STATIC_TOPIC = "/tf_static"
#: The live view's picture of the pad (``foxglove.SceneUpdate``, Foxglove only).
PAD_TOPIC = "/softpad/pad"

#: The grasp action of the ROS 2 node (ROS 1: the actionlib action of the same name).
GRASP_ACTION = "/softpad/grasp"
GRASP_ACTION_TYPE = "softpad_msgs/action/Grasp"


@dataclass(frozen=True)
class Qos:
    """Quality of service of a topic.

    Parameters
    ----------
    depth
        History kept (ROS 2 ``KEEP_LAST`` depth; ROS 1 ``queue_size``).
    latched
        Late subscribers get the last ``depth`` messages (ROS 2 ``TRANSIENT_LOCAL``
        durability; ROS 1 ``latch=True``).
    reliable
        ROS 2 ``RELIABLE`` (else ``BEST_EFFORT``).
    """

    depth: int = 10
    latched: bool = False
    reliable: bool = True

    def __str__(self) -> str:
        durability = "transient local (latched)" if self.latched else "volatile"
        reliability = "reliable" if self.reliable else "best effort"
        return f"{reliability}, {durability}, depth {self.depth}"


#: Every frame of the box: kept long enough for a subscriber that falls behind briefly.
STREAM = Qos(depth=50)
#: The last value for subscribers that join late (plans, phase, outcome).
LATCHED = Qos(depth=1, latched=True)
#: Events: every one matters (a recording keeps them all).
EVENTS = Qos(depth=100)


@dataclass(frozen=True)
class Topic:
    """One row of the topic table.

    Parameters
    ----------
    name
        ROS name; per-module topics hold ``{k}`` (:data:`MODULE`).
    type
        ROS 2 type name, ``package/msg/Name`` (``foxglove.*`` for Foxglove's own schemas).
    rate
        When it is published, in words (``box rate``, ``1 Hz``, ``on change``...).
    qos
        Its quality of service.
    outputs
        The outputs (:data:`OUTPUTS`) that carry it.
    content
        What it holds, with units.
    rate_hz
        The nominal rate, Hz, where it has one; ``None`` for the box's rate or event-driven.
    live_type
        The schema the live view (Foxglove) gives it where that is not ``type``
        (``foxglove.PosesInFrame``, ...); None: ``type`` (a JSON schema of the same shape).
    """

    name: str
    type: str
    rate: str
    qos: Qos
    outputs: frozenset[str]
    content: str
    rate_hz: float | None = None
    live_type: str | None = None

    @property
    def per_module(self) -> bool:
        """Whether there is one such topic per module."""
        return MODULE in self.name

    def names(self, n_modules: int) -> list[str]:
        """The topic's names on a pad of ``n_modules`` modules."""
        if not self.per_module:
            return [self.name]
        return [self.name.format(k=k) for k in range(1, n_modules + 1)]


_ALL = frozenset(OUTPUTS)
_ROS = frozenset({"ros1", "ros2"})

#: The topic table.
TOPICS: tuple[Topic, ...] = (
    Topic(
        MODULE_PRESSURE_TOPIC, "sensor_msgs/msg/FluidPressure", "box rate", STREAM, _ALL,
        "module K's absolute pressure, Pa (gauge + ambient), variance Pa^2, frame "
        "softpad_module_K",
    ),
    Topic(
        SUPPLY_TOPIC, "sensor_msgs/msg/FluidPressure", "box rate", STREAM, _ALL,
        "the supply's absolute pressure, Pa, frame softpad",
    ),
    Topic(
        GAUGE_TOPIC, "std_msgs/msg/Float64MultiArray", "box rate", STREAM, _ALL,
        f"gauge pressures, Pa: modules 1..N then the supply (dim label {GAUGE_LABEL})",
    ),
    Topic(
        CONTACT_TOPIC, "std_msgs/msg/Bool", "box rate", STREAM, _ROS,
        "true while the contact detector senses the fingers on the pad",
    ),
    Topic(
        PHASE_TOPIC, "std_msgs/msg/String", "on change", LATCHED, _ROS,
        "the grasp loop's phase as it enters it; watch while a node only watches",
    ),
    Topic(
        EVENT_TOPIC, "softpad_msgs/msg/Event", "on event", EVENTS, _ALL,
        "every event of the loop: kind and data (JSON, SI units)",
        live_type="softpad.Event",  # the data as a JSON object, not a string: Foxglove plots it
    ),
    Topic(
        PLAN_TOPIC, "geometry_msgs/msg/PoseArray", "on plan", LATCHED, _ALL,
        "one grasp per object: position = COG on the pad surface, yaw = theta (the jaws' "
        "closing direction), m and rad, frame softpad", live_type="foxglove.PosesInFrame",
    ),
    Topic(
        OBJECT_TOPIC, "geometry_msgs/msg/PoseArray", "on plan", LATCHED, _ALL,
        "one pose per object at its PCOM on the pad surface, m, frame softpad",
        live_type="foxglove.PosesInFrame",
    ),
    Topic(
        PLAN_DETAIL_TOPIC, "softpad.Plan", "on plan", Qos(depth=1), frozenset({"live"}),
        "the loop's plan event as JSON: every object's modules, PCOM, COG, theta, rule",
    ),
    Topic(
        OUTCOME_TOPIC, "softpad_msgs/msg/Outcome", "once per grasp loop", LATCHED, _ROS,
        "the end of a grasp loop: outcome, message, the summary as JSON (recordings: the "
        "events)",
    ),
    Topic(
        VALVE_TOPIC, "softpad_msgs/msg/ValveCommands", "on command", EVENTS,
        frozenset({"recording"}), "every channel's commanded valve state",
    ),
    Topic(
        ROBOT_POSE_TOPIC, "geometry_msgs/msg/PoseStamped", "20 Hz while a robot moves",
        STREAM, _ALL, "the gripper's measured pose, m and rad, frame softpad", rate_hz=20.0,
        live_type="foxglove.PoseInFrame",
    ),
    Topic(
        ROBOT_COMMAND_TOPIC, "geometry_msgs/msg/PoseStamped", "on command", EVENTS,
        frozenset({"recording"}), "the gripper's commanded pose, m and rad, frame softpad",
    ),
    Topic(
        DIAGNOSTICS_TOPIC, "diagnostic_msgs/msg/DiagnosticArray", "1 Hz", Qos(depth=10), _ROS,
        "link, rate and every channel (level, message, key/values)", rate_hz=1.0,
    ),
    Topic(
        TF_STATIC_TOPIC, "tf2_msgs/msg/TFMessage", "once (latched)", LATCHED, _ALL,
        "base -> softpad (the installation's pad pose) -> softpad_module_K",
        live_type="foxglove.FrameTransforms",
    ),
    Topic(
        PAD_TOPIC, "foxglove.SceneUpdate", "10 Hz", Qos(depth=1), frozenset({"live"}),
        "a picture of the pad: one box per module, height following its pressure",
        rate_hz=10.0,
    ),
)  # fmt: skip

_BY_NAME = {t.name: t for t in TOPICS}


def topic(name: str) -> Topic:
    """The row of topic ``name`` (per-module names with ``{k}``); KeyError names the known."""
    try:
        return _BY_NAME[name]
    except KeyError:
        raise KeyError(f"no topic {name!r} in the table; known: {', '.join(_BY_NAME)}") from None


def topics_for(output: str, n_modules: int) -> dict[str, str]:
    """Every topic name ``output`` publishes on a pad of ``n_modules`` modules -> its type: the
    ROS 2 type, or for ``"live"`` the Foxglove schema where it differs (``live_type``);
    ValueError for an unknown output."""
    if output not in OUTPUTS:
        raise ValueError(f"unknown output {output!r}; known: {', '.join(OUTPUTS)}")
    out = {}
    for t in TOPICS:
        if output in t.outputs:
            kind = t.live_type if output == "live" and t.live_type else t.type
            out.update({n: kind for n in t.names(n_modules)})
    return out


def module_topic(k: int) -> str:
    """Topic of module ``k``'s pressure (1-based): ``/softpad/module_K/pressure``."""
    return MODULE_PRESSURE_TOPIC.format(k=k)


def module_frame(k: int) -> str:
    """Frame of module ``k`` (1-based), at its centre on the pad surface: ``softpad_module_K``."""
    return f"softpad_module_{k}"


def ros1_type(ros2_type: str) -> str:
    """The ROS 1 name of a ROS 2 message type: ``pkg/msg/Name`` -> ``pkg/Name``."""
    package, _, name = ros2_type.rpartition("/")
    return f"{package.split('/')[0]}/{name}"


def static_frames(
    layout: Any, pad: Any, base_frame: str = BASE_FRAME
) -> list[tuple[str, str, tuple[float, float, float, float]]]:
    """``(parent, child, (x, y, z, yaw))`` of every static frame, metres and radians: the pad
    in ``base_frame`` (``pad``: a :class:`softpad.layout.PadPose`), then each module's centre on
    the pad surface (``layout``: a :class:`softpad.layout.PadLayout`)."""
    out = [(base_frame, PAD_FRAME, (pad.x_m, pad.y_m, pad.z_m, pad.yaw_rad))]
    for k in range(1, layout.n_modules + 1):
        x, y = layout.center(k)
        out.append((PAD_FRAME, module_frame(k), (x * layout.pitch_m, y * layout.pitch_m, 0.0, 0.0)))
    return [(p, c, tuple(float(v) for v in xyzw)) for p, c, xyzw in out]  # type: ignore[misc]


def quaternion_z(yaw_rad: float) -> tuple[float, float, float, float]:
    """Quaternion (x, y, z, w) of a rotation by ``yaw_rad`` about z."""
    return 0.0, 0.0, math.sin(yaw_rad / 2.0), math.cos(yaw_rad / 2.0)


#: SoftPad's own interface definitions (ROS 2 ``.msg``/``.action`` text; the ROS 1 package uses
#: the same fields), and ``tf2_msgs/msg/TFMessage`` (upstream's definition, for the ROS 2
#: build: no wheel provides it).
MESSAGE_DEFINITIONS: dict[str, str] = {
    "softpad_msgs/msg/Event": (
        "# One event of a SoftPad run (phase change, contact, plan, fault...).\n"
        "std_msgs/Header header\n"
        "string kind\n"
        "# event data as a JSON object, SI units (pascals, metres, radians, seconds)\n"
        "string data_json\n"
    ),
    "softpad_msgs/msg/ValveCommands": (
        "# Commanded state of every channel's valves, channel 1 first.\n"
        "std_msgs/Header header\n"
        "# one of: closed, inflate, deflate\n"
        "string[] commands\n"
    ),
    "softpad_msgs/msg/Outcome": (
        "# The end of one grasp loop.\n"
        "std_msgs/Header header\n"
        "# held, dropped, missed, landed, contact_not_detected, fault, error or canceled\n"
        "string outcome\n"
        "# why, for fault, error and canceled\n"
        "string message\n"
        "# the loop's summary (softpad run --json), SI units\n"
        "string summary_json\n"
    ),
    "softpad_msgs/action/Grasp": (
        "# Grasp the objects on the pad, one after the other, and hold each (the grasp loop).\n"
        "# hold time, s; 0: the node's hold_s\n"
        "float64 hold_s\n"
        "---\n"
        "# held, dropped, missed, landed, contact_not_detected, fault, error or canceled\n"
        "string outcome\n"
        "# why, for fault, error and canceled\n"
        "string message\n"
        "# the grasps tried, on the pad surface in frame softpad: COG, m; yaw = theta, rad\n"
        "geometry_msgs/PoseArray grasps\n"
        "# the loop's summary (softpad run --json), SI units\n"
        "string result_json\n"
        "---\n"
        "# the loop's phase as it enters it (adjust, wait_object, approach, descend, ...)\n"
        "string phase\n"
        "# box time, s\n"
        "float64 t_s\n"
    ),
    "tf2_msgs/msg/TFMessage": "geometry_msgs/TransformStamped[] transforms\n",
}


def markdown_table() -> str:
    """The topic table as Markdown (docs/ros.md prints it)."""
    head = (
        "| topic | type | rate | QoS | outputs | content |\n| --- | --- | --- | --- | --- | --- |"
    )
    rows = [
        f"| `{t.name.replace(MODULE, 'K')}` | `{t.type}` | {t.rate} | {t.qos} | "
        f"{', '.join(o for o in OUTPUTS if o in t.outputs)} | {t.content}"
        f"{f' (live view: `{t.live_type}`)' if t.live_type else ''} |"
        for t in TOPICS
    ]
    return "\n".join([head, *rows])


__all__ = [
    "BASE_FRAME",
    "BEGIN",
    "CONTACT_TOPIC",
    "DIAGNOSTICS_TOPIC",
    "END",
    "EVENTS",
    "EVENT_TOPIC",
    "GAUGE_LABEL",
    "GAUGE_TOPIC",
    "GRASP_ACTION",
    "GRASP_ACTION_TYPE",
    "LATCHED",
    "MESSAGE_DEFINITIONS",
    "MODULE",
    "MODULE_PRESSURE_TOPIC",
    "OBJECT_TOPIC",
    "OUTCOME_TOPIC",
    "OUTPUTS",
    "PAD_FRAME",
    "PAD_TOPIC",
    "PHASE_TOPIC",
    "PLAN_DETAIL_TOPIC",
    "PLAN_TOPIC",
    "ROBOT_COMMAND_TOPIC",
    "ROBOT_POSE_TOPIC",
    "STREAM",
    "SUPPLY_TOPIC",
    "TF_STATIC_TOPIC",
    "TOPICS",
    "VALVE_TOPIC",
    "Qos",
    "Topic",
    "markdown_table",
    "module_frame",
    "module_topic",
    "quaternion_z",
    "ros1_type",
    "static_frames",
    "topic",
    "topics_for",
    "write_table",
]

#: The markers around the printed table in a Markdown file (docs/ros.md).
BEGIN = "<!-- topic table: generated by python -m softpad.topics; do not edit -->"
END = "<!-- end of topic table -->"


def write_table(path: str) -> bool:
    """Replace the table between :data:`BEGIN` and :data:`END` in ``path``; True if it
    changed."""
    from pathlib import Path

    f = Path(path)
    text = f.read_text(encoding="utf-8")
    start, stop = text.index(BEGIN) + len(BEGIN), text.index(END)
    new = f"{text[:start]}\n{markdown_table()}\n{text[stop:]}"
    if new != text:
        f.write_text(new, encoding="utf-8")
    return new != text


if __name__ == "__main__":  # python -m softpad.topics [--write FILE.md ...]
    if sys.argv[1:2] == ["--write"]:
        for name in sys.argv[2:]:
            print(f"{name}: {'updated' if write_table(name) else 'up to date'}")
    else:
        print(markdown_table())
    sys.exit(0)
