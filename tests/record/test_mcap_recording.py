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
        modules = sorted(t for t in by_topic if t.startswith("/softpad/module_"))
        # the 2 x 3 pad's six modules, not the 8-channel box's unused channels 7 and 8
        assert modules == [f"/softpad/module_{k}/pressure" for k in range(1, 7)]
        for topic in modules:
            assert by_topic[topic].msgtype == "sensor_msgs/msg/FluidPressure"
        assert by_topic["/softpad/robot/pose"].msgtype == "geometry_msgs/msg/PoseStamped"
        assert by_topic["/softpad/plan/grasps"].msgtype == "geometry_msgs/msg/PoseArray"
        assert by_topic["/softpad/valves"].msgtype == "softpad_msgs/msg/ValveCommands"
        assert by_topic["/softpad/events"].msgtype == "softpad_msgs/msg/Event"

        def messages(topic: str) -> list:
            return [
                reader.deserialize(raw, c.msgtype)
                for c, _, raw in reader.messages([by_topic[topic]])
            ]

        m2 = messages("/softpad/module_2/pressure")
        plans = messages("/softpad/plan/grasps")
        valves = messages("/softpad/valves")
        events = messages("/softpad/events")
    # module 2 carries object 5: inflated to p0 = 1.1 kPa (within t_adj = 30 Pa), loaded above
    # it; FluidPressure is absolute: 101.325 kPa of standard atmosphere + 1.1 kPa = 102.4 kPa
    p = np.array([m.fluid_pressure for m in m2]) - 101325.0
    assert m2[0].header.frame_id == "softpad_module_2"
    assert abs(np.median(p[len(p) // 2 :]) - 1100.0) < 400.0 and p.max() > 1100.0 + 50.0
    assert m2[-1].variance == pytest.approx(8.0**2 + 3.0**2 + (10e3 / 4096) ** 2 / 12)
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


def test_rosbags_sees_absolute_pressures_tf_and_the_recorded_clock(recording: Path) -> None:
    """The issue's acceptance: absolute pressures near 102.4 kPa, a tf for every module,
    stamps spanning the run's box-time duration (not the seconds it took to compute)."""
    from rosbags.highlevel import AnyReader

    from softpad.record import load_recording

    run = load_recording(recording)
    with AnyReader([recording]) as reader:
        by_topic = {c.topic: c for c in reader.connections}

        def decoded(topic: str) -> list[tuple[int, object]]:
            c = by_topic[topic]
            return [(t, reader.deserialize(raw, c.msgtype)) for _, t, raw in reader.messages([c])]

        m5 = decoded("/softpad/module_5/pressure")
        tf = decoded("/tf_static")
        gauge = decoded("/softpad/pressures")
    # before anything touches it, module 5 sits at p0 = 1.1 kPa gauge = 102.425 kPa absolute
    adjusted = [m.fluid_pressure for t, m in m5 if (t - m5[0][0]) * 1e-9 < run.duration_s / 2]
    assert abs(np.median(adjusted[-50:]) - 102425.0) < 60.0
    # the gauge array: modules 1..6 then the supply, Pa, the same readings less the ambient
    assert len(gauge[-1][1].data) == 7
    assert gauge[-1][1].data[4] == pytest.approx(m5[-1][1].fluid_pressure - 101325.0, abs=1e-6)
    # stamps and log times on the recorded clock: they span the run's box-time duration
    stamps = np.array([m.header.stamp.sec + 1e-9 * m.header.stamp.nanosec for _, m in m5])
    log_s = np.array([t for t, _ in m5]) * 1e-9
    assert stamps[-1] - stamps[0] == pytest.approx(run.duration_s, abs=2e-3)
    assert log_s[-1] - log_s[0] == pytest.approx(run.duration_s, abs=2e-3)
    assert run.duration_s > 8.0 and stamps[0] > 1.7e9  # UNIX time, not seconds from 0
    # /tf_static: base -> softpad -> softpad_module_K for the six modules, 45 mm pitch
    (_, msg), *_ = tf
    edges = {(t.header.frame_id, t.child_frame_id): t.transform.translation for t in msg.transforms}
    assert ("base", "softpad") in edges
    for k in range(1, 7):
        assert ("softpad", f"softpad_module_{k}") in edges
    module_4 = edges[("softpad", "softpad_module_4")]  # bottom-left: centre (0.5, 0.5) modules
    assert (module_4.x, module_4.y) == pytest.approx((0.0225, 0.0225))


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
    log_t = [msg.log_time for _, _, msg, _ in poses]
    assert np.all(np.diff(box_t) > 0) and log_t[0] >= start_ns and np.all(np.diff(log_t) >= 0)
    # one clock: the header stamp is the log time (ns)
    stamps = [m.header.stamp.sec * 10**9 + m.header.stamp.nanosec for _, _, _, m in poses]
    assert stamps == log_t
    # the gripper starts above the pad and comes down to touch it: z falls by centimetres
    z = np.array([m.pose.position.z for _, _, _, m in poses])
    assert z.max() - z.min() > 0.02


def test_existing_file_is_never_overwritten_silently(recording: Path, capsys) -> None:
    size = recording.stat().st_size
    assert main(["run", "--hold-s", "1", "--record", str(recording)]) == 2
    assert "exists; add --force to overwrite it" in capsys.readouterr().err
    assert recording.stat().st_size == size
