"""``softpad box monitor --foxglove``: a websocket client receives the module pressures."""

from __future__ import annotations

import asyncio
import base64
import json
import re
import struct
import subprocess
import sys
from typing import Any

import numpy as np
import pytest

pytest.importorskip("foxglove")
websockets = pytest.importorskip("websockets")

#: Subprotocols of the Foxglove WebSocket protocol: the classic one (Foxglove Studio before the
#: SDK, Lichtblick, @foxglove/ws-protocol clients) and the Foxglove SDK's (today's app).
SUBPROTOCOLS = ("foxglove.websocket.v1", "foxglove.sdk.v1")


async def _receive(
    url: str, topic: str, n: int, subprotocol: str
) -> tuple[dict, dict[str, dict], list[bytes]]:
    """The server's info, its channels (once ``topic`` and /tf_static are advertised) and the
    payloads of the first ``n`` messages of ``topic`` a subscriber gets."""
    from websockets.asyncio.client import connect

    async with connect(url, subprotocols=[subprotocol], open_timeout=30) as ws:
        assert ws.subprotocol == subprotocol
        channels: dict[str, dict] = {}
        info: dict = {}
        while topic not in channels or "/tf_static" not in channels:
            msg = json.loads(await asyncio.wait_for(ws.recv(), 30))
            if msg["op"] == "serverInfo":
                info = msg
            elif msg["op"] == "advertise":
                channels.update({c["topic"]: c for c in msg["channels"]})
        sub = {"op": "subscribe", "subscriptions": [{"id": 7, "channelId": channels[topic]["id"]}]}
        await ws.send(json.dumps(sub))
        received: list[bytes] = []
        while len(received) < n:
            data = await asyncio.wait_for(ws.recv(), 30)
            if isinstance(data, bytes) and data[0] == 0x01:  # message data
                sub_id, _log_time = struct.unpack_from("<IQ", data, 1)
                assert sub_id == 7
                received.append(data[13:])
        return info, channels, received


async def _receive_pressures(
    url: str, topic: str, n: int, subprotocol: str
) -> tuple[dict, dict[str, dict], list[dict]]:
    info, channels, payloads = await _receive(url, topic, n, subprotocol)
    return info, channels, [json.loads(p) for p in payloads]


def _monitor(*extra: str) -> tuple[subprocess.Popen[str], str]:
    """``softpad box monitor --foxglove --port 0`` in a child process, and its viewer URL
    from the first line it prints."""
    entry = "import sys; from softpad.cli.main import main; sys.exit(main(sys.argv[1:]))"
    argv = ["-c", entry, "box", "monitor", "--foxglove", "--port", "0", *extra]
    child = subprocess.Popen([sys.executable, *argv], stdout=subprocess.PIPE, text=True)
    assert child.stdout is not None
    line = child.stdout.readline()  # the first line names the box and the server (issue 51)
    found = re.search(r"to Foxglove at (ws://127\.0\.0\.1:\d+)", line)
    if not (line.startswith("softpad box monitor: the simulated box sim://") and found):
        child.terminate()
        child.wait(timeout=30)
        raise AssertionError(line)
    return child, found.group(1)


@pytest.mark.parametrize("subprotocol", SUBPROTOCOLS)
def test_monitor_serves_module_pressures_to_a_websocket_client(subprotocol: str) -> None:
    child, url = _monitor("--box", "sim://?inflated_kpa=1.1&noise=0")
    try:
        topic = "/softpad/module_3/pressure"
        info, channels, msgs = asyncio.run(_receive_pressures(url, topic, 5, subprotocol))
    finally:
        child.terminate()
        child.wait(timeout=30)
    assert info["name"] == "softpad" and "time" in info["capabilities"]  # the recorded clock
    assert [m["header"]["frame_id"] for m in msgs] == ["softpad_module_3"] * 5
    # only the 2 x 3 pad's modules, not the box's channels 7 and 8
    modules = sorted(t for t in channels if t.startswith("/softpad/module_"))
    assert modules == [f"/softpad/module_{k}/pressure" for k in range(1, 7)]
    schema = json.loads(channels[topic]["schema"])
    assert set(schema["properties"]["header"]["properties"]["stamp"]["properties"]) == {
        "sec",
        "nanosec",
    }  # ROS 2's field names
    # inflated to 1.1 kPa without noise: every reading is p0 within 1 Pa, absolute (FluidPressure)
    for m in msgs:
        assert m["fluid_pressure"] == pytest.approx(101325.0 + 1100.0, abs=1.0)
    stamps = [m["header"]["stamp"]["sec"] + 1e-9 * m["header"]["stamp"]["nanosec"] for m in msgs]
    assert np.all(np.diff(stamps) > 0) and stamps[0] > 1.7e9  # the recorded clock (UNIX)


def _decoded(channel: dict, payload: bytes) -> Any:
    """``payload`` decoded with the protobuf schema the server advertised for ``channel``
    (Google's protobuf runtime, as a Foxglove viewer decodes it)."""
    from google.protobuf import descriptor_pb2, descriptor_pool, message_factory

    assert channel["encoding"] == "protobuf", channel["encoding"]
    files = descriptor_pb2.FileDescriptorSet.FromString(base64.b64decode(channel["schema"]))
    pool = descriptor_pool.DescriptorPool()
    for f in files.file:
        pool.Add(f)
    message = message_factory.GetMessageClass(pool.FindMessageTypeByName(channel["schemaName"]))
    return message.FromString(payload)


@pytest.mark.parametrize("subprotocol", SUBPROTOCOLS)
def test_the_live_view_stands_the_pad_where_the_installation_says(
    subprotocol: str, site: Any
) -> None:
    """``box monitor --foxglove --config site.toml``: /tf_static, as a viewer decodes it from
    the advertised schema, carries the installation's ``[pad.pose]`` (issue 48: the pad stood
    at the base's origin), the modules on the pad."""
    pytest.importorskip("google.protobuf")
    child, url = _monitor("--box", "sim://", "--config", str(site.path))
    try:
        _info, channels, (payload,) = asyncio.run(_receive(url, "/tf_static", 1, subprotocol))
    finally:
        child.terminate()
        child.wait(timeout=30)
    assert channels["/tf_static"]["schemaName"] == "foxglove.FrameTransforms"
    pad, *modules = _decoded(channels["/tf_static"], payload).transforms
    t, q = pad.translation, pad.rotation
    site.check_pad_transform(
        (pad.parent_frame_id, pad.child_frame_id), (t.x, t.y, t.z), (q.x, q.y, q.z, q.w)
    )
    assert [m.child_frame_id for m in modules] == [f"softpad_module_{k}" for k in range(1, 7)]
    assert {m.parent_frame_id for m in modules} == {"softpad"}
    # module 1's centre at (0.5, 1.5) module pitches in the pad frame (45 mm modules)
    assert (modules[0].translation.x, modules[0].translation.y) == pytest.approx(
        (0.5 * 0.045, 1.5 * 0.045)
    )


def test_monitor_without_foxglove_prints_plain_lines_into_a_pipe(capsys) -> None:
    """Into a pipe or file (capsys is not a terminal): the line naming the box, a header, then
    one plain line per period (no carriage returns), the pad's six modules only."""
    from softpad.cli.main import main

    assert main(["box", "monitor", "--box", "sim://", "--count", "20", "--period-s", "0.05"]) == 0
    out = capsys.readouterr().out
    assert "\r" not in out
    first, header, *lines = out.splitlines()
    assert first.startswith("softpad box monitor: the simulated box sim://")
    assert header.split() == [
        "seq", "t_s", *[f"m{k}_kpa" for k in range(1, 7)], "supply_kpa", "frames/s",
        "p50_ms", "p99_ms", "lost",
    ]  # fmt: skip
    assert [int(line.split()[0]) for line in lines] == [5, 10, 15, 20]  # 100 Hz, 0.05 s
    assert all(len(line.split()) == len(header.split()) for line in lines)
    assert [line.split()[-1] for line in lines] == ["0"] * 4


async def _advertised(url: str, topics: set[str]) -> dict[str, dict]:
    """The channels a new client is advertised, once ``topics`` are among them."""
    from websockets.asyncio.client import connect

    async with connect(url, subprotocols=["foxglove.websocket.v1"], open_timeout=30) as ws:
        channels: dict[str, dict] = {}
        while not topics <= set(channels):
            msg = json.loads(await asyncio.wait_for(ws.recv(), 30))
            if msg["op"] == "advertise":
                channels.update({c["topic"]: c for c in msg["channels"]})
        return channels


def test_live_view_advertises_typed_schemas_and_the_recordings_plan_topics() -> None:
    """Events, the plan and the robot pose are advertised with schemas that name their fields
    (not ``{"type": "object"}``); the plan also as the recordings' /softpad/plan/grasps and
    /softpad/plan/objects, and the robot pose, in Foxglove's pose types the 3D panel draws."""
    from types import SimpleNamespace

    from softpad.box import PressureFrame
    from softpad.record import FoxgloveLive

    state = SimpleNamespace(x_m=0.05, y_m=0.04, z_m=0.1, yaw_rad=0.3)
    live = FoxgloveLive(port=0, robot_state=lambda: state)
    try:
        live.frame(PressureFrame(t_s=0.5, pressures_pa=np.full(8, 1100.0), supply_pa=0.0), "plan")
        plan = {"modules": [1, 2], "pcom": [1.0, 1.5], "cog": [1.0, 1.5], "theta": 0.5,
                "cog_m": [0.045, 0.0675], "rule": "n2"}  # fmt: skip
        live.event(0.6, "plan", objects=[plan], increments_pa=[60.0] * 6)
        from softpad.topics import topics_for

        channels = asyncio.run(_advertised(live.url, set(topics_for("live", 6))))
    finally:
        live.close()
    events = json.loads(channels["/softpad/events"]["schema"])
    assert set(events["properties"]) == {"stamp", "kind", "data"}
    assert events["properties"]["stamp"]["required"] == ["sec", "nanosec"]
    planned = json.loads(channels["/softpad/plan"]["schema"])
    item = planned["properties"]["data"]["properties"]["objects"]["items"]
    assert {"modules", "pcom", "cog", "cog_m", "theta", "rule"} <= set(item["properties"])
    assert "rad" in item["properties"]["theta"]["description"]
    assert channels["/softpad/robot/pose"]["schemaName"] == "foxglove.PoseInFrame"
    for topic in ("/softpad/plan/grasps", "/softpad/plan/objects"):
        assert channels[topic]["schemaName"] == "foxglove.PosesInFrame", topic
    # exactly the topic table's live names and schema names (softpad.topics)
    from softpad.topics import topics_for

    assert {t: c["schemaName"] for t, c in channels.items()} == topics_for("live", 6)
