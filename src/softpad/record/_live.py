"""Live view: a run's streams served to Foxglove over the Foxglove SDK's WebSocket server.

:class:`FoxgloveLive` is a ``softpad.control.Recorder`` (so it rides along any run through
:class:`softpad.record.Tee`) that publishes, to any number of connected viewers:

- ``/softpad/module_K/pressure``: each channel's pressure (JSON shaped like
  ``sensor_msgs/msg/FluidPressure``: ``header.stamp`` = box time, ``fluid_pressure`` in Pa);
- ``/softpad/supply/pressure``; ``/softpad/events`` (kind + data, SI); ``/softpad/plan``;
  ``/softpad/robot/pose`` (when a robot state source is given);
- ``/softpad/pad``: a ``foxglove.SceneUpdate`` picture of the pad, one box per module whose
  height follows its pressure, and the planned centre of grasp.

The server binds 127.0.0.1 only (SoftPad's network rule).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from typing import Any

from softpad import thesis
from softpad.box import PressureFrame
from softpad.record._closing import ClosedOnExit
from softpad.record._mcap import jsonable
from softpad.record._schemas import (
    EVENT_TOPIC,
    PAD_FRAME,
    ROBOT_POSE_TOPIC,
    SUPPLY_TOPIC,
    module_frame,
    module_topic,
)

#: Host the server binds (loopback only).
HOST = "127.0.0.1"

#: Topic of the pad picture (foxglove.SceneUpdate) and of the plan (JSON).
PAD_TOPIC = "/softpad/pad"
LIVE_PLAN_TOPIC = "/softpad/plan"

#: Smallest wall-time spacing of pad pictures, seconds (10 Hz).
PAD_PERIOD_S = 0.1

_PRESSURE_SCHEMA = {
    "type": "object",
    "title": "sensor_msgs/msg/FluidPressure",
    "properties": {
        "header": {
            "type": "object",
            "properties": {
                "stamp": {
                    "type": "object",
                    "properties": {"sec": {"type": "integer"}, "nsec": {"type": "integer"}},
                },
                "frame_id": {"type": "string"},
            },
        },
        "fluid_pressure": {"type": "number", "description": "gauge pressure, Pa"},
        "variance": {"type": "number"},
    },
}
_ANY_SCHEMA = {"type": "object"}


def _stamp(t_s: float) -> dict[str, int]:
    sec = math.floor(t_s)
    return {"sec": int(sec), "nsec": min(round((t_s - sec) * 1e9), 999_999_999)}


class FoxgloveLive(ClosedOnExit):
    """Serve a run live to Foxglove (a ``softpad.control.Recorder``).

    Parameters
    ----------
    port
        TCP port on 127.0.0.1 (0: a free one, see :attr:`port`).
    layout
        Pad layout for the pad picture (default the 2 x 3 prototype).
    robot_state
        Optional source of the measured robot state (``x_m, y_m, z_m, yaw_rad``).
    name
        Server name shown by Foxglove.
    """

    def __init__(
        self,
        port: int = 8765,
        layout: Any = None,
        robot_state: Callable[[], Any] | None = None,
        name: str = "softpad",
    ) -> None:
        import foxglove

        from softpad.layout import parse_layout

        self._fg = foxglove
        self.layout = layout or parse_layout("2x3")
        self._ctx = foxglove.Context()
        self.server = foxglove.start_server(name=name, host=HOST, port=port, context=self._ctx)
        self._channels: dict[str, Any] = {}
        self._robot_state = robot_state
        self._last_pad = -math.inf
        self._cog: tuple[float, float] | None = None
        self._reference: Any = None
        self.closed = False

    @property
    def port(self) -> int:
        """Port the server listens on."""
        return int(self.server.port)

    @property
    def url(self) -> str:
        """``ws://127.0.0.1:PORT``: what to open in Foxglove."""
        return f"ws://{HOST}:{self.port}"

    def _channel(self, topic: str, schema: dict[str, Any] = _ANY_SCHEMA) -> Any:
        ch = self._channels.get(topic)
        if ch is None:
            ch = self._channels[topic] = self._fg.Channel(topic, schema=schema, context=self._ctx)
        return ch

    def frame(self, frame: PressureFrame, phase: str) -> None:
        """Publish one frame (every channel, the supply, the pad picture at most at 10 Hz)."""
        if self.closed:
            return
        now = time.time_ns()
        stamp = _stamp(frame.t_s)
        for k, p in enumerate(frame.pressures_pa, start=1):
            msg: dict[str, Any] = {"header": {"stamp": stamp, "frame_id": module_frame(k)}}
            msg.update(fluid_pressure=float(p) if math.isfinite(p) else None, variance=0.0)
            self._channel(module_topic(k), _PRESSURE_SCHEMA).log(msg, log_time=now)
        supply: dict[str, Any] = {"header": {"stamp": stamp, "frame_id": "softpad_supply"}}
        supply.update(fluid_pressure=float(frame.supply_pa), variance=0.0)
        self._channel(SUPPLY_TOPIC, _PRESSURE_SCHEMA).log(supply, log_time=now)
        if self._robot_state is not None:
            s = self._robot_state()
            pose = {"x_m": s.x_m, "y_m": s.y_m, "z_m": s.z_m, "yaw_rad": s.yaw_rad, "phase": phase}
            self._channel(ROBOT_POSE_TOPIC).log({"stamp": stamp, **pose}, log_time=now)
        if (now * 1e-9) - self._last_pad >= PAD_PERIOD_S:
            self._last_pad = now * 1e-9
            self._pad_picture(frame, now)

    def event(self, t_s: float, kind: str, **data: Any) -> None:
        """Publish an event (and the plan on its own topic)."""
        if self.closed:
            return
        now = time.time_ns()
        data = jsonable(data)
        msg = {"stamp": _stamp(t_s), "kind": kind, "data": data}
        self._channel(EVENT_TOPIC).log(msg, log_time=now)
        if kind == "plan":
            self._channel(LIVE_PLAN_TOPIC).log(msg, log_time=now)
            objects = data.get("objects") or []
            self._cog = tuple(objects[0]["cog_m"]) if objects else None

    def _pad_picture(self, frame: PressureFrame, now_ns: int) -> None:
        from foxglove.messages import (
            Color,
            CubePrimitive,
            Pose,
            Quaternion,
            SceneEntity,
            SceneUpdate,
            SpherePrimitive,
            Vector3,
        )

        pitch = self.layout.pitch_m
        cubes = []
        for m in self.layout.modules:
            p = float(frame.pressures_pa[m - 1]) if m <= frame.channels else 0.0
            p = p if math.isfinite(p) else 0.0
            height = 0.002 + 0.01 * max(p, 0.0) / thesis.P0_PA  # about 9 mm at p0 (thesis)
            x, y = self.layout.center(m)
            level = min(max(p / 1500.0, 0.0), 1.0)
            cubes.append(
                CubePrimitive(
                    pose=Pose(
                        position=Vector3(x=x * pitch, y=y * pitch, z=height / 2),
                        orientation=Quaternion(x=0, y=0, z=0, w=1),
                    ),
                    size=Vector3(x=0.95 * pitch, y=0.95 * pitch, z=height),
                    color=Color(r=level, g=0.3, b=1.0 - level, a=0.9),
                )
            )
        spheres = []
        if self._cog is not None:
            spheres.append(
                SpherePrimitive(
                    pose=Pose(
                        position=Vector3(x=self._cog[0], y=self._cog[1], z=0.02),
                        orientation=Quaternion(x=0, y=0, z=0, w=1),
                    ),
                    size=Vector3(x=0.01, y=0.01, z=0.01),
                    color=Color(r=0, g=0, b=0, a=1),
                )
            )
        entity = SceneEntity(frame_id=PAD_FRAME, id="pad", cubes=cubes, spheres=spheres)
        self._scene_channel().log(SceneUpdate(entities=[entity]), log_time=now_ns)

    def _scene_channel(self) -> Any:
        ch = self._channels.get(PAD_TOPIC)
        if ch is None:
            from foxglove.channels import SceneUpdateChannel

            ch = self._channels[PAD_TOPIC] = SceneUpdateChannel(PAD_TOPIC, context=self._ctx)
        return ch

    def close(self) -> None:
        """Stop the server. Idempotent."""
        if not self.closed:
            self.closed = True
            self.server.stop()
