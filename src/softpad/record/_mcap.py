"""MCAP recorder: every frame, valve command, robot pose, plan and event of a run, crash-safe.

The file is a rosbag2-compatible MCAP (profile ``ros2``, CDR, message definitions embedded)
written with ``mcap`` and ``mcap-ros2-support``, so ``ros2 bag info``, Foxglove, PlotJuggler and
``rosbags`` open it without SoftPad. Header stamps and the MCAP ``log_time`` are both on the
recorded clock: the box's time (:attr:`PressureFrame.t_s`) mapped onto the wall clock at the
run's start (UNIX ns; the offset is the ``softpad_clock`` metadata record), so a simulated run
that lasted 27.8 s of box time spans 27.8 s on playback however fast it was computed.

Pressures: ``sensor_msgs/msg/FluidPressure`` is absolute (its definition), so each module's
message carries the gauge reading plus the ambient pressure (the installation's, default the
standard atmosphere) and the sensor model's variance; the gauge readings themselves are on
``/softpad/pressures`` (Pa, modules then the supply). Only the pad's modules are recorded
(a 6-module pad on an 8-channel box: 6 topics), with ``/tf_static`` placing each
``softpad_module_K`` on the pad ``softpad`` in ``base``.

Crash safety: the writer closes its chunk and flushes the file with the first message written
after :data:`FLUSH_PERIOD_S` of wall time since the last flush, so a ``kill -9`` loses at most
that much plus one interval between messages (a frame period);
:func:`softpad.record.recover` (run by ``softpad log``) rewrites such a file with an index.
"""

from __future__ import annotations

import json
import math
import time
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from softpad import thesis
from softpad.box import PressureFrame
from softpad.errors import InputError
from softpad.layout import PadLayout, PadPose, parse_layout
from softpad.record import _schemas as S
from softpad.record._closing import ClosedOnExit

#: Longest wall time between two flushes of the file, seconds (the most a crash can lose).
FLUSH_PERIOD_S = 0.1

#: Chunk size, bytes: small, so a chunk closes by itself well within a flush period at 1 kHz.
CHUNK_SIZE = 32 * 1024

#: Smallest box-time spacing of recorded measured robot poses, seconds (20 Hz).
ROBOT_POSE_PERIOD_S = 0.05


def _stamp_ns(ns: int) -> dict[str, int]:
    sec, nanosec = divmod(int(ns), 1_000_000_000)
    return {"sec": sec, "nanosec": nanosec}


def _pose(x: float, y: float, z: float, yaw: float) -> dict[str, Any]:
    return {
        "position": {"x": float(x), "y": float(y), "z": float(z)},
        "orientation": {"x": 0.0, "y": 0.0, "z": math.sin(yaw / 2), "w": math.cos(yaw / 2)},
    }


def jsonable(value: Any) -> Any:
    """``value`` with NumPy arrays/scalars, tuples and enums turned into JSON types."""
    if isinstance(value, dict):
        return {str(k): jsonable(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [jsonable(v) for v in value]
    if isinstance(value, np.ndarray):
        return jsonable(value.tolist())
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, float) and not math.isfinite(value):
        return None
    if hasattr(value, "value") and hasattr(value, "name"):  # an Enum member
        return value.value
    return value


def check_output(path: str | Path, force: bool = False) -> Path:
    """``path`` as a Path if a recording may be written there; InputError names the problem."""
    p = Path(path)
    if p.suffix != ".mcap":
        raise InputError(f"recordings are MCAP files ending in .mcap, got {str(p)!r}")
    if p.exists() and not force:
        raise InputError(f"{str(p)!r} exists; refusing to overwrite it (choose another name)")
    if not p.parent.exists():
        raise InputError(f"directory {str(p.parent)!r} of the recording does not exist")
    return p


class McapRecorder(ClosedOnExit):
    """Record a run into an MCAP file (a ``softpad.control.Recorder``).

    Parameters
    ----------
    path
        Output ``.mcap`` file; an existing file is refused unless ``force``.
    metadata
        Run facts stored as the ``softpad`` metadata record (parameters, seed, objects, box
        URL, installation file...); values are JSON-encoded. The software version, the
        format tag and the wall-clock start are added.
    force
        Overwrite an existing file.
    valves
        Optional source of the box's commanded valve states (e.g. ``lambda: box.valves``),
        polled at every frame: a change is recorded on ``/softpad/valves``. Not needed with
        :class:`softpad.control.GraspExecution`, which reports every command as a ``valve``
        event (channel, command); polling stops at the first such event.
    robot_state
        Optional source of the measured robot state (an object with ``x_m, y_m, z_m,
        yaw_rad, width_m``), recorded on ``/softpad/robot/pose`` at most every
        :data:`ROBOT_POSE_PERIOD_S` of box time.
    flush_period_s
        Longest wall time between flushes, seconds.
    layout
        The pad (``PadLayout`` or ``"RxC"``); default the metadata's ``layout``, else 2 x 3.
        Only its modules are recorded.
    pad
        Pose of the pad in the base frame (``/tf_static``); default the identity.
    ambient_pa
        Ambient pressure added to gauge readings in ``FluidPressure``, Pa; default the
        metadata's ``ambient_pressure_pa``, else :data:`softpad.thesis.AMBIENT_PRESSURE_PA`.
    variance_pa2
        ``FluidPressure.variance``, Pa^2 (default the sensor model's).

    Notes
    -----
    Use as a context manager or call :meth:`close`; a file that was never closed (crash) is
    still readable up to its last flush (see :func:`softpad.record.recover`).
    """

    def __init__(
        self,
        path: str | Path,
        metadata: dict[str, Any] | None = None,
        *,
        force: bool = False,
        valves: Callable[[], Sequence[Any]] | None = None,
        robot_state: Callable[[], Any] | None = None,
        flush_period_s: float = FLUSH_PERIOD_S,
        layout: PadLayout | str | None = None,
        pad: PadPose | None = None,
        ambient_pa: float | None = None,
        variance_pa2: float = thesis.SENSOR_VARIANCE_PA2,
    ) -> None:
        from mcap.writer import CompressionType
        from mcap_ros2.writer import Writer

        metadata = dict(metadata or {})
        layout = layout if layout is not None else metadata.get("layout") or "2x3"
        self.layout = parse_layout(layout) if isinstance(layout, str) else layout
        self.pad = pad or PadPose()
        ambient = metadata.get("ambient_pressure_pa") if ambient_pa is None else ambient_pa
        self.ambient_pa = float(thesis.AMBIENT_PRESSURE_PA if ambient is None else ambient)
        self.variance_pa2 = float(variance_pa2)
        metadata.update(
            layout=self.layout.name,
            modules=self.layout.n_modules,
            ambient_pressure_pa=self.ambient_pa,
            pressure_variance_pa2=self.variance_pa2,
        )
        self.path = check_output(path, force)
        self._file = open(self.path, "wb")
        self._writer = Writer(self._file, chunk_size=CHUNK_SIZE, compression=CompressionType.ZSTD)
        self._schemas: dict[str, Any] = {}
        self._valves_source = valves
        self._robot_source = robot_state
        self._last_valves: tuple[str, ...] | None = None
        self._last_pose_t = -math.inf
        self._flush_period_s = float(flush_period_s)
        self._last_flush = time.monotonic()
        self._t_s = 0.0
        self._channels = 0
        self.closed = False
        self.messages = 0
        self.last_log_ns = 0
        #: Recorded clock: box time t_s is stamped offset_ns + t_s * 1e9 (set by the first message).
        self.offset_ns: int | None = None
        self._write_metadata(metadata)

    # --- writing ----------------------------------------------------------------------
    def _schema(self, datatype: str) -> Any:
        s = self._schemas.get(datatype)
        if s is None:
            s = self._schemas[datatype] = self._writer.register_msgdef(datatype, S.msgdef(datatype))
        return s

    def _ns(self, t_s: float) -> int:
        """The recorded clock at box time ``t_s``, UNIX ns (fixes the offset on first use)."""
        if self.offset_ns is None:
            self.offset_ns = time.time_ns() - round(t_s * 1e9)
            self._writer.add_metadata(S.CLOCK_RECORD, {"offset_ns": str(self.offset_ns)})
            self._tf_static(t_s)
        return self.offset_ns + round(t_s * 1e9)

    def _header(self, t_s: float, frame_id: str) -> dict[str, Any]:
        return {"stamp": _stamp_ns(self._ns(t_s)), "frame_id": frame_id}

    def _tf_static(self, t_s: float) -> None:
        transforms = []
        for parent, child, (x, y, z, yaw) in S.static_frames(self.layout, self.pad):
            transforms.append(
                {
                    "header": self._header(t_s, parent),
                    "child_frame_id": child,
                    "transform": {
                        "translation": {"x": x, "y": y, "z": z},
                        "rotation": _pose(0, 0, 0, yaw)["orientation"],
                    },
                }
            )
        tf = {"transforms": transforms}
        self._latched_channel(S.TF_STATIC_TOPIC, "tf2_msgs/msg/TFMessage")
        self._write(S.TF_STATIC_TOPIC, "tf2_msgs/msg/TFMessage", tf, t_s)

    def _latched_channel(self, topic: str, datatype: str) -> None:
        """Register ``topic``'s channel with the QoS of a latched topic in its metadata
        (``offered_qos_profiles``, as rosbag2 writes it), so ``ros2 bag play`` republishes it
        transient-local and a late subscriber still gets it."""
        from softpad.record._bags import latched_qos_yaml

        ids = self._writer._channel_ids  # mcap_ros2's Writer registers channels on first use
        if topic not in ids:
            ids[topic] = self._writer._writer.register_channel(
                topic=topic, message_encoding="cdr", schema_id=self._schema(datatype).id,
                metadata={"offered_qos_profiles": latched_qos_yaml()},
            )  # fmt: skip

    def _write(self, topic: str, datatype: str, message: dict[str, Any], t_s: float) -> None:
        if self.closed:
            return
        self.last_log_ns = self._ns(t_s)
        self._writer.write_message(topic, self._schema(datatype), message, self.last_log_ns)
        self.messages += 1
        now = time.monotonic()
        if now - self._last_flush >= self._flush_period_s:
            self.flush()

    def flush(self) -> None:
        """Close the open chunk and push everything written so far to the file."""
        if not self.closed:
            self._writer._writer.flush()  # mcap's Writer.flush: ends the chunk, flushes the stream
            self._last_flush = time.monotonic()

    def _write_metadata(self, metadata: dict[str, Any]) -> None:
        from softpad import __version__

        record = {k: json.dumps(jsonable(v)) for k, v in metadata.items()}
        record.update(
            format=json.dumps(S.RECORDING_FORMAT),
            software_version=json.dumps(__version__),
            wall_clock_start=json.dumps(time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime())),
            wall_clock_start_ns=json.dumps(time.time_ns()),
        )
        self._writer.add_metadata("softpad", record)

    # --- Recorder hook ------------------------------------------------------------------
    def _pressure(self, t: float, frame_id: str, gauge_pa: float) -> dict[str, Any]:
        """``FluidPressure``: absolute (gauge + ambient), NaN kept for a missing reading."""
        absolute = float(gauge_pa) + self.ambient_pa
        header = self._header(t, frame_id)
        return {"header": header, "fluid_pressure": absolute, "variance": self.variance_pa2}

    def frame(self, frame: PressureFrame, phase: str) -> None:
        """Record one frame: an absolute ``FluidPressure`` per module of the pad and one for
        the supply, and the gauge readings as one array on ``/softpad/pressures``."""
        t = frame.t_s
        self._t_s = t
        self._channels = frame.channels
        gauge = [float(p) for p in frame.pressures_pa[: self.layout.n_modules]]
        for k, p in enumerate(gauge, start=1):
            msg = self._pressure(t, S.module_frame(k), p)
            self._write(S.module_topic(k), "sensor_msgs/msg/FluidPressure", msg, t)
        supply = self._pressure(t, S.PAD_FRAME, frame.supply_pa)
        self._write(S.SUPPLY_TOPIC, "sensor_msgs/msg/FluidPressure", supply, t)
        data = [*gauge, float(frame.supply_pa)]
        dim = {"label": S.GAUGE_LABEL, "size": len(data), "stride": len(data)}
        array = {"layout": {"dim": [dim], "data_offset": 0}, "data": data}
        self._write(S.GAUGE_TOPIC, "std_msgs/msg/Float64MultiArray", array, t)
        self._poll(t)

    def _poll(self, t: float) -> None:
        if self._valves_source is not None:
            commands = tuple(str(jsonable(c)) for c in self._valves_source())
            if commands != self._last_valves:
                self._last_valves = commands
                self._valve_message(t, list(commands))
        if self._robot_source is not None and t - self._last_pose_t >= ROBOT_POSE_PERIOD_S:
            self._last_pose_t = t
            s = self._robot_source()
            pose = {
                "header": self._header(t, S.PAD_FRAME),
                "pose": _pose(s.x_m, s.y_m, s.z_m, s.yaw_rad),
            }
            self._write(S.ROBOT_POSE_TOPIC, "geometry_msgs/msg/PoseStamped", pose, t)

    def _valve_state(self, channel: int, command: str) -> list[str]:
        state = list(self._last_valves or ())
        if len(state) < max(channel, self._channels):
            state += ["closed"] * (max(channel, self._channels) - len(state))
        state[channel - 1] = command
        self._last_valves = tuple(state)
        return state

    def _valve_message(self, t: float, commands: list[str]) -> None:
        msg = {"header": self._header(t, S.PAD_FRAME), "commands": commands}
        self._write(S.VALVE_TOPIC, "softpad_msgs/msg/ValveCommands", msg, t)

    def event(self, t_s: float, kind: str, **data: Any) -> None:
        """Record an event on ``/softpad/events``; plans, valves and robot commands also typed."""
        data = jsonable(data)
        if kind == "valves":
            self._valves_source = None  # the execution reports them: stop polling
            self._valve_message(t_s, [str(c) for c in data.get("commands", [])])
        elif kind == "valve":  # one channel's command: record the state of every channel
            self._valves_source = None
            self._valve_message(t_s, self._valve_state(int(data["channel"]), str(data["command"])))
        elif kind == "robot" and all(k in data for k in ("x_m", "y_m", "z_m")):
            pose = _pose(data["x_m"], data["y_m"], data["z_m"], data.get("yaw_rad", 0.0))
            command = {"header": self._header(t_s, S.PAD_FRAME), "pose": pose}
            self._write(S.ROBOT_COMMAND_TOPIC, "geometry_msgs/msg/PoseStamped", command, t_s)
        elif kind == "plan":
            self._plan_messages(t_s, data.get("objects", []))
        event = {"header": self._header(t_s, S.PAD_FRAME), "kind": kind}
        event["data_json"] = json.dumps(data)
        self._write(S.EVENT_TOPIC, "softpad_msgs/msg/Event", event, t_s)

    def _plan_messages(self, t: float, objects: list[dict[str, Any]]) -> None:
        grasps, pcoms = [], []
        for o in objects:
            (x, y), (u, v) = o["cog_m"], o["cog"]
            grasps.append(_pose(x, y, 0.0, float(o["theta"])))
            pitch = math.hypot(x, y) / math.hypot(u, v) if math.hypot(u, v) > 0 else 0.0
            pcoms.append(_pose(o["pcom"][0] * pitch, o["pcom"][1] * pitch, 0.0, 0.0))
        header = self._header(t, S.PAD_FRAME)
        self._write(
            S.PLAN_TOPIC, "geometry_msgs/msg/PoseArray", {"header": header, "poses": grasps}, t
        )
        self._write(
            S.OBJECT_TOPIC, "geometry_msgs/msg/PoseArray", {"header": header, "poses": pcoms}, t
        )

    # --- closing ------------------------------------------------------------------------
    def close(self) -> None:
        """Write the summary and index and close the file. Idempotent."""
        if self.closed:
            return
        try:
            self._writer.finish()
        finally:
            self.closed = True
            self._file.close()
