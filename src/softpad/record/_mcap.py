"""MCAP recorder: every frame, valve command, robot pose, plan and event of a run, crash-safe.

The file is a rosbag2-compatible MCAP (profile ``ros2``, CDR, message definitions embedded)
written with ``mcap`` and ``mcap-ros2-support``, so ``ros2 bag info``, Foxglove, PlotJuggler and
``rosbags`` open it without SoftPad. Every message carries two clocks: the header stamp is the
box's time (:attr:`PressureFrame.t_s`), the MCAP ``log_time`` is the wall clock (UNIX ns).

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

from softpad.box import PressureFrame
from softpad.errors import InputError
from softpad.record import _schemas as S
from softpad.record._closing import ClosedOnExit

#: Longest wall time between two flushes of the file, seconds (the most a crash can lose).
FLUSH_PERIOD_S = 0.1

#: Chunk size, bytes: small, so a chunk closes by itself well within a flush period at 1 kHz.
CHUNK_SIZE = 32 * 1024

#: Smallest box-time spacing of recorded measured robot poses, seconds (20 Hz).
ROBOT_POSE_PERIOD_S = 0.05


def _stamp(t_s: float) -> dict[str, int]:
    sec = math.floor(t_s)
    return {"sec": int(sec), "nanosec": min(round((t_s - sec) * 1e9), 999_999_999)}


def _header(t_s: float, frame_id: str) -> dict[str, Any]:
    return {"stamp": _stamp(t_s), "frame_id": frame_id}


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
    ) -> None:
        from mcap.writer import CompressionType
        from mcap_ros2.writer import Writer

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
        self._write_metadata(metadata or {})

    # --- writing ----------------------------------------------------------------------
    def _schema(self, datatype: str) -> Any:
        s = self._schemas.get(datatype)
        if s is None:
            s = self._schemas[datatype] = self._writer.register_msgdef(datatype, S.msgdef(datatype))
        return s

    def _write(self, topic: str, datatype: str, message: dict[str, Any]) -> None:
        if self.closed:
            return
        self.last_log_ns = time.time_ns()
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
    def frame(self, frame: PressureFrame, phase: str) -> None:
        """Record one frame: a ``FluidPressure`` per channel and one for the supply."""
        t = frame.t_s
        self._t_s = t
        self._channels = frame.channels
        for k, p in enumerate(frame.pressures_pa, start=1):
            msg = {"header": _header(t, S.module_frame(k)), "fluid_pressure": float(p)}
            msg["variance"] = 0.0
            self._write(S.module_topic(k), "sensor_msgs/msg/FluidPressure", msg)
        supply = {"header": _header(t, "softpad_supply"), "fluid_pressure": float(frame.supply_pa)}
        supply["variance"] = 0.0
        self._write(S.SUPPLY_TOPIC, "sensor_msgs/msg/FluidPressure", supply)
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
                "header": _header(t, S.PAD_FRAME),
                "pose": _pose(s.x_m, s.y_m, s.z_m, s.yaw_rad),
            }
            self._write(S.ROBOT_POSE_TOPIC, "geometry_msgs/msg/PoseStamped", pose)

    def _valve_state(self, channel: int, command: str) -> list[str]:
        state = list(self._last_valves or ())
        if len(state) < max(channel, self._channels):
            state += ["closed"] * (max(channel, self._channels) - len(state))
        state[channel - 1] = command
        self._last_valves = tuple(state)
        return state

    def _valve_message(self, t: float, commands: list[str]) -> None:
        msg = {"header": _header(t, "softpad_box"), "commands": commands}
        self._write(S.VALVE_TOPIC, "softpad_msgs/msg/ValveCommands", msg)

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
            command = {"header": _header(t_s, S.PAD_FRAME), "pose": pose}
            self._write(S.ROBOT_COMMAND_TOPIC, "geometry_msgs/msg/PoseStamped", command)
        elif kind == "plan":
            self._plan_messages(t_s, data.get("objects", []))
        event = {"header": _header(t_s, "softpad"), "kind": kind, "data_json": json.dumps(data)}
        self._write(S.EVENT_TOPIC, "softpad_msgs/msg/Event", event)

    def _plan_messages(self, t: float, objects: list[dict[str, Any]]) -> None:
        grasps, pcoms = [], []
        for o in objects:
            (x, y), (u, v) = o["cog_m"], o["cog"]
            grasps.append(_pose(x, y, 0.0, float(o["theta"])))
            pitch = math.hypot(x, y) / math.hypot(u, v) if math.hypot(u, v) > 0 else 0.0
            pcoms.append(_pose(o["pcom"][0] * pitch, o["pcom"][1] * pitch, 0.0, 0.0))
        header = _header(t, S.PAD_FRAME)
        self._write(
            S.PLAN_TOPIC, "geometry_msgs/msg/PoseArray", {"header": header, "poses": grasps}
        )
        self._write(
            S.OBJECT_TOPIC, "geometry_msgs/msg/PoseArray", {"header": header, "poses": pcoms}
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
