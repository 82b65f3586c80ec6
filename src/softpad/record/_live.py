"""Live view: a run's streams served to Foxglove over the Foxglove SDK's WebSocket server.

:class:`FoxgloveLive` is a ``softpad.control.Recorder`` (so it rides along any run through
:class:`softpad.record.Tee`) that publishes, to any number of connected viewers:

- ``/softpad/module_K/pressure`` for each module of the pad: JSON shaped like ROS 2's
  ``sensor_msgs/msg/FluidPressure`` (``header.stamp.sec/nanosec`` on the recorded clock,
  ``fluid_pressure`` absolute in Pa, ``variance``), as in recordings;
- ``/softpad/pressures``: the gauge readings, Pa (modules, then the supply);
- ``/softpad/supply/pressure``; ``/softpad/events`` (kind + data, SI); ``/softpad/plan`` (the
  plan event: each object's modules, PCOM, COG, theta, rule), each with a JSON schema naming
  its fields and units;
- ``/softpad/plan/grasps`` and ``/softpad/plan/objects`` (``foxglove.PosesInFrame`` in the pad
  frame: COG with yaw = theta, PCOM) and ``/softpad/robot/pose`` (``foxglove.PoseInFrame``, when
  a robot state source is given): the topics a recording holds under those names (as ROS 2
  ``PoseArray``/``PoseStamped``), so docs/foxglove-layout.json's 3D panel draws both alike;
- ``/tf_static``: ``foxglove.FrameTransforms`` base -> softpad -> softpad_module_K;
- ``/softpad/pad``: a ``foxglove.SceneUpdate`` picture of the pad, one box per module whose
  height follows its pressure, and the planned centre of grasp.

Clients: the Foxglove SDK's server speaks the subprotocol ``foxglove.sdk.v1`` only (today's
Foxglove app); older Foxglove Studio, Lichtblick and other clients of the classic
``foxglove.websocket.v1`` get HTTP 400 from it. So the public port is a small relay
(``websockets``) that accepts either subprotocol and passes every frame, both ways, to the SDK's
server on a private loopback port (the two protocols share their messages). Both bind
127.0.0.1 only (SoftPad's network rule).
"""

from __future__ import annotations

import asyncio
import math
import threading
import time
from collections.abc import Callable
from typing import Any

from softpad import thesis
from softpad.box import PressureFrame
from softpad.errors import InputError
from softpad.record._closing import ClosedOnExit
from softpad.record._mcap import jsonable
from softpad.record._schemas import (
    EVENT_TOPIC,
    GAUGE_LABEL,
    GAUGE_TOPIC,
    OBJECT_TOPIC,
    PAD_FRAME,
    PLAN_TOPIC,
    ROBOT_POSE_TOPIC,
    SUPPLY_TOPIC,
    TF_STATIC_TOPIC,
    module_frame,
    module_topic,
    static_frames,
)

#: Host the server binds (loopback only).
HOST = "127.0.0.1"

#: Topic of the pad picture (foxglove.SceneUpdate) and of the plan (JSON).
PAD_TOPIC = "/softpad/pad"
LIVE_PLAN_TOPIC = "/softpad/plan"

#: Smallest wall-time spacing of pad pictures (and of the static transforms), seconds (10 Hz).
PAD_PERIOD_S = 0.1

#: WebSocket subprotocols the public port accepts: the classic protocol and the SDK's.
SUBPROTOCOLS = ("foxglove.websocket.v1", "foxglove.sdk.v1")

_PRESSURE_SCHEMA = {
    "type": "object",
    "title": "sensor_msgs/msg/FluidPressure",
    "properties": {
        "header": {
            "type": "object",
            "properties": {
                "stamp": {
                    "type": "object",
                    "properties": {"sec": {"type": "integer"}, "nanosec": {"type": "integer"}},
                },
                "frame_id": {"type": "string"},
            },
        },
        "fluid_pressure": {"type": "number", "description": "absolute pressure, Pa"},
        "variance": {"type": "number", "description": "Pa^2"},
    },
}
_GAUGE_SCHEMA = {
    "type": "object",
    "title": "std_msgs/msg/Float64MultiArray",
    "properties": {
        "layout": {"type": "object"},
        "data": {"type": "array", "items": {"type": "number"}, "description": "gauge, Pa"},
    },
}
_STAMP_SCHEMA = {
    "type": "object",
    "description": "box time on the recorded clock (UNIX)",
    "properties": {"sec": {"type": "integer"}, "nanosec": {"type": "integer"}},
    "required": ["sec", "nanosec"],
}
_XY = {"type": "array", "items": {"type": "number"}, "minItems": 2, "maxItems": 2}
#: One object's plan, as :meth:`softpad.planning.GraspPlan.to_dict` gives it.
_OBJECT_SCHEMA = {
    "type": "object",
    "properties": {
        "modules": {"type": "array", "items": {"type": "integer"}, "description": "1-based"},
        "pcom": {**_XY, "description": "pressure centre of mass, module units"},
        "cog": {**_XY, "description": "centre of grasp, module units"},
        "cog_m": {**_XY, "description": "centre of grasp in the pad frame, m"},
        "theta": {"type": "number", "description": "closing direction from the pad's x, rad"},
        "rule": {"type": "string", "description": "the planner's rule"},
        "tentative": {"type": "boolean"},
    },
    "required": ["modules", "pcom", "cog", "theta"],
}
_EVENT_SCHEMA = {
    "type": "object",
    "title": "softpad.Event",
    "description": "one event of the run (softpad_msgs/msg/Event in recordings)",
    "properties": {
        "stamp": _STAMP_SCHEMA,
        "kind": {
            "type": "string",
            "description": "phase, adjusted, reference, object_seen, plan, contact, "
            "no_contact, valve, robot, outcome, fault, safe_state, ...",
        },
        "data": {
            "type": "object",
            "description": "the event's data, SI units (Pa, m, rad, s); fields by kind",
            "additionalProperties": True,
        },
    },
    "required": ["stamp", "kind", "data"],
}
_PLAN_SCHEMA = {
    "type": "object",
    "title": "softpad.Plan",
    "description": "the loop's plan event: every object's grasp, in grasp order",
    "properties": {
        "stamp": _STAMP_SCHEMA,
        "kind": {"type": "string", "const": "plan"},
        "data": {
            "type": "object",
            "properties": {
                "objects": {"type": "array", "items": _OBJECT_SCHEMA},
                "increments_pa": {
                    "type": "array",
                    "items": {"type": "number"},
                    "description": "filtered increments dP_i the plan used, Pa",
                },
            },
            "required": ["objects"],
            "additionalProperties": True,
        },
    },
    "required": ["stamp", "kind", "data"],
}


def _stamp(ns: int) -> dict[str, int]:
    sec, nanosec = divmod(int(ns), 1_000_000_000)
    return {"sec": sec, "nanosec": nanosec}


class _Relay:
    """A WebSocket relay on 127.0.0.1:``port`` that accepts :data:`SUBPROTOCOLS` and passes
    every frame both ways to the SDK's server at ``upstream`` (its own thread and event loop)."""

    def __init__(self, port: int, upstream: str) -> None:
        self.upstream = upstream
        self.loop = asyncio.new_event_loop()
        self._ready = threading.Event()
        self._error: BaseException | None = None
        self._stop: asyncio.Event | None = None
        self.port = 0
        self.thread = threading.Thread(target=self._run, args=(port,), daemon=True)
        self.thread.start()
        self._ready.wait(30.0)
        if self._error is not None:
            raise InputError(f"cannot serve Foxglove on 127.0.0.1:{port}: {self._error}")

    def _run(self, port: int) -> None:
        asyncio.set_event_loop(self.loop)
        try:
            self.loop.run_until_complete(self._serve(port))
        except BaseException as exc:  # reported by __init__ (port in use, ...)
            self._error = exc
            self._ready.set()
        finally:
            self.loop.close()

    async def _serve(self, port: int) -> None:
        from websockets.asyncio.server import serve
        from websockets.typing import Subprotocol

        protocols = [Subprotocol(p) for p in SUBPROTOCOLS]
        self._stop = asyncio.Event()
        async with serve(self._client, HOST, port, subprotocols=protocols, max_size=None) as srv:
            self.port = int(next(iter(srv.sockets)).getsockname()[1])
            self._ready.set()
            await self._stop.wait()

    async def _client(self, client: Any) -> None:
        from websockets.asyncio.client import connect
        from websockets.exceptions import ConnectionClosed
        from websockets.typing import Subprotocol

        sdk = [Subprotocol("foxglove.sdk.v1")]
        async with connect(self.upstream, subprotocols=sdk, max_size=None) as server:

            async def pump(src: Any, dst: Any) -> None:
                try:
                    async for frame in src:
                        await dst.send(frame)
                except ConnectionClosed:
                    pass

            tasks = [
                asyncio.ensure_future(pump(client, server)),
                asyncio.ensure_future(pump(server, client)),
            ]
            await asyncio.wait(tasks, return_when=asyncio.FIRST_COMPLETED)
            for t in tasks:
                t.cancel()

    def close(self) -> None:
        if self._stop is not None and self.loop.is_running():
            self.loop.call_soon_threadsafe(self._stop.set)
        self.thread.join(10.0)


class FoxgloveLive(ClosedOnExit):
    """Serve a run live to Foxglove (a ``softpad.control.Recorder``).

    Parameters
    ----------
    port
        TCP port on 127.0.0.1 (0: a free one, see :attr:`port`).
    layout
        Pad layout (default the 2 x 3 prototype): its modules are published, and pictured.
    pad
        Pose of the pad in the base frame (``/tf_static``), default the identity.
    ambient_pa
        Ambient pressure added to gauge readings in ``FluidPressure``, Pa.
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
        pad: Any = None,
        ambient_pa: float = thesis.AMBIENT_PRESSURE_PA,
    ) -> None:
        import foxglove

        from softpad.layout import PadPose, parse_layout

        self._fg = foxglove
        self.layout = layout or parse_layout("2x3")
        self.pad = pad or PadPose()
        self.ambient_pa = float(ambient_pa)
        self._ctx = foxglove.Context()
        # capability "time": the server broadcasts the recorded clock (box time mapped onto the
        # wall clock at the first frame), so viewers follow the box's time, not their own
        self.server = foxglove.start_server(
            name=name, host=HOST, port=0, context=self._ctx,
            capabilities=[foxglove.Capability.Time],
        )  # fmt: skip
        try:
            self._relay = _Relay(port, f"ws://{HOST}:{self.server.port}")
        except BaseException:
            self.server.stop()
            raise
        self._offset_ns: int | None = None
        self._channels: dict[str, Any] = {}
        self._robot_state = robot_state
        self._last_pad = -math.inf
        self._cog: tuple[float, float] | None = None
        self._reference: Any = None
        self.closed = False

    @property
    def port(self) -> int:
        """Port viewers connect to (either subprotocol)."""
        return self._relay.port

    @property
    def url(self) -> str:
        """``ws://127.0.0.1:PORT``: what to open in Foxglove."""
        return f"ws://{HOST}:{self.port}"

    def _channel(self, topic: str, schema: dict[str, Any]) -> Any:
        ch = self._channels.get(topic)
        if ch is None:
            ch = self._channels[topic] = self._fg.Channel(topic, schema=schema, context=self._ctx)
        return ch

    def _stamp(self, t_s: float) -> dict[str, int]:
        """Box time on the recorded clock (the wall clock at the first frame), as a stamp."""
        if self._offset_ns is None:
            self._offset_ns = time.time_ns() - round(t_s * 1e9)
        return _stamp(self._offset_ns + round(t_s * 1e9))

    def _pressure(self, stamp: dict[str, int], frame_id: str, gauge_pa: float) -> dict[str, Any]:
        p = float(gauge_pa) + self.ambient_pa
        return {
            "header": {"stamp": stamp, "frame_id": frame_id},
            "fluid_pressure": p if math.isfinite(p) else None,
            "variance": thesis.SENSOR_VARIANCE_PA2,
        }

    def frame(self, frame: PressureFrame, phase: str) -> None:
        """Publish one frame (each module of the pad, the supply, the gauge readings; the pad
        picture and the static transforms at most at 10 Hz)."""
        if self.closed:
            return
        now = time.time_ns()
        stamp = self._stamp(frame.t_s)
        gauge = [float(p) for p in frame.pressures_pa[: self.layout.n_modules]]
        for k, p in enumerate(gauge, start=1):
            msg = self._pressure(stamp, module_frame(k), p)
            self._channel(module_topic(k), _PRESSURE_SCHEMA).log(msg, log_time=now)
        supply = self._pressure(stamp, PAD_FRAME, frame.supply_pa)
        self._channel(SUPPLY_TOPIC, _PRESSURE_SCHEMA).log(supply, log_time=now)
        data = [v if math.isfinite(v) else None for v in [*gauge, float(frame.supply_pa)]]
        dim = {"label": GAUGE_LABEL, "size": len(data), "stride": len(data)}
        array = {"layout": {"dim": [dim], "data_offset": 0}, "data": data}
        self._channel(GAUGE_TOPIC, _GAUGE_SCHEMA).log(array, log_time=now)
        if self._robot_state is not None:
            s = self._robot_state()
            pose = self._fg.messages.PoseInFrame(
                timestamp=self._fg_stamp(stamp), frame_id=PAD_FRAME,
                pose=self._fg_pose(s.x_m, s.y_m, s.z_m, s.yaw_rad),
            )  # fmt: skip
            self._typed(ROBOT_POSE_TOPIC, "PoseInFrameChannel").log(pose, log_time=now)
        if (now * 1e-9) - self._last_pad >= PAD_PERIOD_S:
            self._last_pad = now * 1e-9
            self._pad_picture(frame, now)
            self._transforms(now)
            self.server.broadcast_time(stamp["sec"] * 1_000_000_000 + stamp["nanosec"])

    def event(self, t_s: float, kind: str, **data: Any) -> None:
        """Publish an event (and the plan on its own topic)."""
        if self.closed:
            return
        now = time.time_ns()
        data = jsonable(data)
        stamp = self._stamp(t_s)
        msg = {"stamp": stamp, "kind": kind, "data": data}
        self._channel(EVENT_TOPIC, _EVENT_SCHEMA).log(msg, log_time=now)
        if kind == "plan":
            self._channel(LIVE_PLAN_TOPIC, _PLAN_SCHEMA).log(msg, log_time=now)
            objects = data.get("objects") or []
            self._cog = tuple(objects[0]["cog_m"]) if objects else None
            self._plan_poses(stamp, objects, now)

    def _fg_stamp(self, stamp: dict[str, int]) -> Any:
        return self._fg.messages.Timestamp(stamp["sec"], stamp["nanosec"])

    def _fg_pose(self, x: float, y: float, z: float, yaw: float) -> Any:
        from foxglove.messages import Pose, Quaternion, Vector3

        q = Quaternion(x=0, y=0, z=math.sin(yaw / 2), w=math.cos(yaw / 2))
        return Pose(position=Vector3(x=x, y=y, z=z), orientation=q)

    def _typed(self, topic: str, channel_class: str) -> Any:
        """The SDK's typed channel ``channel_class`` (``foxglove.channels``) of ``topic``."""
        ch = self._channels.get(topic)
        if ch is None:
            import foxglove.channels

            kind = getattr(foxglove.channels, channel_class)
            ch = self._channels[topic] = kind(topic, context=self._ctx)
        return ch

    def _plan_poses(self, stamp: dict[str, int], objects: list[Any], now_ns: int) -> None:
        """The plan as a recording holds it: grasps (COG, yaw = theta) and objects (PCOM) in
        the pad frame, here as ``foxglove.PosesInFrame``."""
        pitch = self.layout.pitch_m
        grasps = [
            self._fg_pose(o["cog_m"][0], o["cog_m"][1], 0.0, float(o["theta"])) for o in objects
        ]
        pcoms = [
            self._fg_pose(o["pcom"][0] * pitch, o["pcom"][1] * pitch, 0.0, 0.0) for o in objects
        ]
        for topic, poses in ((PLAN_TOPIC, grasps), (OBJECT_TOPIC, pcoms)):
            msg = self._fg.messages.PosesInFrame(
                timestamp=self._fg_stamp(stamp), frame_id=PAD_FRAME, poses=poses
            )
            self._typed(topic, "PosesInFrameChannel").log(msg, log_time=now_ns)

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

    def _transforms(self, now_ns: int) -> None:
        """``/tf_static`` as ``foxglove.FrameTransforms`` (repeated: viewers join any time)."""
        from foxglove.messages import FrameTransform, FrameTransforms, Quaternion, Vector3

        out = []
        for parent, child, (x, y, z, yaw) in static_frames(self.layout, self.pad):
            q = Quaternion(x=0, y=0, z=math.sin(yaw / 2), w=math.cos(yaw / 2))
            out.append(
                FrameTransform(
                    parent_frame_id=parent,
                    child_frame_id=child,
                    translation=Vector3(x=x, y=y, z=z),
                    rotation=q,
                )
            )
        ch = self._channels.get(TF_STATIC_TOPIC)
        if ch is None:
            from foxglove.channels import FrameTransformsChannel

            ch = self._channels[TF_STATIC_TOPIC] = FrameTransformsChannel(
                TF_STATIC_TOPIC, context=self._ctx
            )
        ch.log(FrameTransforms(transforms=out), log_time=now_ns)

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
            self._relay.close()
            self.server.stop()
