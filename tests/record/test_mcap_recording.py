"""MCAP recordings of ``softpad run --record``, read WITHOUT SoftPad code (rosbags, mcap)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from softpad.cli.main import main

pytest.importorskip("rosbags")
pytest.importorskip("mcap_ros2")


@pytest.fixture(scope="module")
def recording(tmp_path_factory) -> Path:
    path = tmp_path_factory.mktemp("rec") / "run.mcap"
    argv = ["run", "--object", "object-5", "--hold-s", "1", "--record", str(path), "--box"]
    assert main([*argv, "sim://?seed=2"]) == 0
    return path


def test_rosbags_reads_every_stream(recording: Path) -> None:
    from rosbags.highlevel import AnyReader

    with AnyReader([recording]) as reader:
        by_topic = {c.topic: c for c in reader.connections}
        for k in range(1, 9):
            c = by_topic[f"/softpad/module_{k}/pressure"]
            assert c.msgtype == "sensor_msgs/msg/FluidPressure"
        assert by_topic["/softpad/robot/pose"].msgtype == "geometry_msgs/msg/PoseStamped"
        assert by_topic["/softpad/plan/grasps"].msgtype == "geometry_msgs/msg/PoseArray"
        assert by_topic["/softpad/valves"].msgtype == "softpad_msgs/msg/ValveCommands"
        assert by_topic["/softpad/events"].msgtype == "softpad_msgs/msg/Event"
        m2 = [
            reader.deserialize(raw, c.msgtype)
            for c, _, raw in reader.messages([by_topic["/softpad/module_2/pressure"]])
        ]
        plans = [
            reader.deserialize(raw, c.msgtype)
            for c, _, raw in reader.messages([by_topic["/softpad/plan/grasps"]])
        ]
        valves = [
            reader.deserialize(raw, c.msgtype)
            for c, _, raw in reader.messages([by_topic["/softpad/valves"]])
        ]
        events = [
            reader.deserialize(raw, c.msgtype)
            for c, _, raw in reader.messages([by_topic["/softpad/events"]])
        ]
    # module 2 carries object 5: inflated to p0 = 1.1 kPa (within t_adj = 30 Pa), loaded above it
    p = np.array([m.fluid_pressure for m in m2])
    assert m2[0].header.frame_id == "softpad_module_2"
    assert abs(np.median(p[len(p) // 2 :]) - 1100.0) < 400.0 and p.max() > 1100.0 + 50.0
    # the grasp topic carries the plan event's COG in metres and theta as the yaw: object 5 on
    # the top row's axis (y = 1.5 module units = 67.5 mm), jaws across the row (pi/2)
    kinds0 = [e.kind for e in events]
    planned = json.loads(events[kinds0.index("plan")].data_json)["objects"][0]
    pose = plans[0].poses[0]
    np.testing.assert_allclose(
        [pose.position.x, pose.position.y], np.array(planned["cog"]) * 0.045, atol=0.5e-3
    )
    np.testing.assert_allclose(pose.position.y, 0.0675, atol=0.5e-3)
    yaw = 2 * np.arctan2(pose.orientation.z, pose.orientation.w)
    np.testing.assert_allclose(yaw, np.pi / 2, atol=1e-9)
    assert any("inflate" in v.commands for v in valves) and valves[-1].commands == ["closed"] * 8
    kinds = [e.kind for e in events]
    for kind in ("phase", "adjusted", "reference", "object_seen", "plan", "contact", "outcome"):
        assert kind in kinds
    contact = json.loads(events[kinds.index("contact")].data_json)
    assert set(contact["modules"]) <= {4, 5, 6}  # the jaw on the pad comes down on the bottom row


def test_mcap_reader_sees_ros2_profile_metadata_and_two_clocks(recording: Path) -> None:
    from mcap.reader import make_reader
    from mcap_ros2.decoder import DecoderFactory

    with open(recording, "rb") as f:
        reader = make_reader(f, decoder_factories=[DecoderFactory()])
        assert reader.get_header().profile == "ros2"
        meta = {m.name: dict(m.metadata) for m in reader.iter_metadata()}["softpad"]
        assert (
            json.loads(meta["objects"]) == ["object-5"]
            and json.loads(meta["box"]) == "sim://?seed=2"
        )
        for key in ("software_version", "wall_clock_start", "params"):
            assert key in meta
        start_ns = json.loads(meta["wall_clock_start_ns"])
        poses = list(reader.iter_decoded_messages(topics=["/softpad/robot/pose"]))
    assert len(poses) > 10
    box_t = [m.header.stamp.sec + 1e-9 * m.header.stamp.nanosec for _, _, _, m in poses]
    wall = [msg.log_time for _, _, msg, _ in poses]
    assert np.all(np.diff(box_t) > 0) and wall[0] >= start_ns and np.all(np.diff(wall) >= 0)
    # the gripper starts above the pad and comes down to touch it: z falls by centimetres
    z = np.array([m.pose.position.z for _, _, _, m in poses])
    assert z.max() - z.min() > 0.02


def test_existing_file_is_never_overwritten_silently(recording: Path, capsys) -> None:
    size = recording.stat().st_size
    assert main(["run", "--hold-s", "1", "--record", str(recording)]) == 2
    assert "exists; add --force to overwrite it" in capsys.readouterr().err
    assert recording.stat().st_size == size
