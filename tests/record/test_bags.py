"""``softpad log export --rosbag2 DIR | --rosbag1 FILE.bag``, read back WITHOUT SoftPad code:
the rosbag2 directory with ``rosbags``, the ROS 1 bag with Debian's ``rosbag`` (python3-rosbag,
run by the system's Python, where ROS 1 lives; skipped with the reason where it is missing).

The issue's acceptance on each: absolute pressures near 102.4 kPa (p0 = 1.1 kPa over the
standard atmosphere), a transform for every module, stamps spanning the run's recorded (box)
duration, six module topics on the 2 x 3 pad of an 8-channel box.
"""

from __future__ import annotations

import json
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from softpad.cli.main import main
from softpad.record import load_recording

pytest.importorskip("rosbags")

MODULES = [f"/softpad/module_{k}/pressure" for k in range(1, 7)]
P0_ABSOLUTE_PA = 101325.0 + 1100.0


@pytest.fixture(scope="module")
def recording(tmp_path_factory: pytest.TempPathFactory) -> Path:
    path = tmp_path_factory.mktemp("bags") / "run.mcap"
    argv = ["run", "--object", "object-5", "--hold-s", "1", "--record", str(path), "--box"]
    assert main([*argv, "sim://?seed=2"]) == 0
    return path


def _check(summary: dict, duration_s: float) -> None:
    """The acceptance on a bag's summary: topics, pressures, frames, stamps."""
    modules = sorted(t for t in summary["topics"] if t.startswith("/softpad/module_"))
    assert modules == MODULES
    # module 5 (no object on it) sits at p0 once adjusted: the median of its first half
    assert summary["module_5_adjusted_pa"] == pytest.approx(P0_ABSOLUTE_PA, abs=60.0)
    assert set(summary["tf_children"]) == {"softpad"} | {f"softpad_module_{k}" for k in range(1, 7)}
    assert summary["tf_parents"]["softpad"] == "base"
    assert summary["stamp_span_s"] == pytest.approx(duration_s, abs=2e-3)
    assert summary["time_span_s"] == pytest.approx(duration_s, abs=2e-3)
    assert summary["first_stamp_s"] > 1.7e9  # UNIX time on the recorded clock


def test_rosbag2_directory_reads_back_with_rosbags(recording: Path, tmp_path: Path) -> None:
    from rosbags.highlevel import AnyReader

    out = tmp_path / "run_bag"
    assert main(["log", "export", str(recording), "--rosbag2", str(out)]) == 0
    assert (out / "metadata.yaml").is_file()
    with AnyReader([out]) as reader:
        by_topic = {c.topic: c for c in reader.connections}

        def decoded(topic: str) -> list[tuple[int, object]]:
            c = by_topic[topic]
            return [(t, reader.deserialize(raw, c.msgtype)) for _, t, raw in reader.messages([c])]

        m5, tf = decoded(MODULES[4]), decoded("/tf_static")
        qos = by_topic["/tf_static"].ext.offered_qos_profiles
    stamps = [m.header.stamp.sec + 1e-9 * m.header.stamp.nanosec for _, m in m5]
    transforms = tf[0][1].transforms
    p = np.array([m.fluid_pressure for _, m in m5])
    summary = {
        "topics": list(by_topic),
        "module_5_adjusted_pa": float(np.median(p[len(p) // 4 : len(p) // 2])),
        "tf_children": [t.child_frame_id for t in transforms],
        "tf_parents": {t.child_frame_id: t.header.frame_id for t in transforms},
        "stamp_span_s": stamps[-1] - stamps[0],
        "time_span_s": (m5[-1][0] - m5[0][0]) * 1e-9,
        "first_stamp_s": stamps[0],
    }
    _check(summary, load_recording(recording).duration_s)
    assert qos[0].durability.name == "TRANSIENT_LOCAL"  # latched, as tf_static is in ROS 2


#: Run by the system's Python 3 with Debian's rosbag: the same summary as above, as JSON.
_ROSBAG1_READER = """
import json, sys
import rosbag
with rosbag.Bag(sys.argv[1]) as bag:
    topics = list(bag.get_type_and_topic_info().topics)
    m5 = [(t.to_sec(), m) for _, m, t in bag.read_messages(topics=["/softpad/module_5/pressure"])]
    tf = [m for _, m, _ in bag.read_messages(topics=["/tf_static"])][0].transforms
    latched = [c.header.get("latching") == b"1" for c in bag._get_connections(topics=["/tf_static"])]
    events = [m.header.seq for _, m, _ in bag.read_messages(topics=["/softpad/events"])]
p = sorted(m.fluid_pressure for _, m in m5[len(m5) // 4 : len(m5) // 2])
stamps = [m.header.stamp.to_sec() for _, m in m5]
print(json.dumps({
    "topics": topics,
    "module_5_adjusted_pa": p[len(p) // 2],
    "tf_children": [t.child_frame_id for t in tf],
    "tf_parents": {t.child_frame_id: t.header.frame_id for t in tf},
    "stamp_span_s": stamps[-1] - stamps[0],
    "time_span_s": m5[-1][0] - m5[0][0],
    "first_stamp_s": stamps[0],
    "type": m5[0][1]._type,
    "tf_static_latched": latched,
    "seq": {"module_5": [m.header.seq for _, m in m5], "events": events},
}))
"""


def _debian_rosbag() -> str | None:
    python = shutil.which("python3", path="/usr/bin")
    if python is None:
        return None
    probe = subprocess.run([python, "-c", "import rosbag"], capture_output=True, check=False)
    return python if probe.returncode == 0 else None


def test_mcap_offers_tf_static_latched(recording: Path) -> None:
    """The recording itself (no export): its /tf_static channel carries rosbag2's
    ``offered_qos_profiles`` metadata, transient-local depth 1, which ``ros2 bag play`` reads
    to republish it latched; the other channels offer nothing."""
    from mcap.reader import make_reader
    from rosbags.highlevel import AnyReader

    with recording.open("rb") as f:
        channels = {c.topic: c for c in make_reader(f).get_summary().channels.values()}  # type: ignore[union-attr]
    assert "offered_qos_profiles" in channels["/tf_static"].metadata
    assert [t for t, c in channels.items() if c.metadata] == ["/tf_static"]
    with AnyReader([recording]) as reader:
        by_topic = {c.topic: c for c in reader.connections}
        (qos,) = by_topic["/tf_static"].ext.offered_qos_profiles
    assert (qos.durability.name, qos.reliability.name, qos.depth) == (
        "TRANSIENT_LOCAL", "RELIABLE", 1,
    )  # fmt: skip


def test_rosbag1_reads_back_with_debians_rosbag(recording: Path, tmp_path: Path) -> None:
    out = tmp_path / "run.bag"
    assert main(["log", "export", str(recording), "--rosbag1", str(out), "--json"]) == 0
    python = _debian_rosbag()
    if python is None:
        pytest.skip("Debian's python3-rosbag is not installed (make ros-deps, as root)")
    done = subprocess.run(
        [python, "-c", _ROSBAG1_READER, str(out)],
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
        env={"PATH": "/usr/bin:/bin"},
    )
    assert done.returncode == 0, done.stderr
    summary = json.loads(done.stdout)
    assert summary["type"] == "sensor_msgs/FluidPressure"
    assert summary["tf_static_latched"] == [True]  # rosbag play latches it
    # each topic's headers numbered as rospy's publisher numbers them: 1, 2, 3, ...
    for topic, seq in summary["seq"].items():
        assert len(seq) > 10 and seq == list(range(1, len(seq) + 1)), topic
    _check(summary, load_recording(recording).duration_s)


def test_export_refuses_an_existing_bag_and_a_wrong_name(
    recording: Path, tmp_path: Path, capsys
) -> None:
    out = tmp_path / "run.bag"
    out.write_bytes(b"")
    assert main(["log", "export", str(recording), "--rosbag1", str(out)]) == 2
    assert "exists" in capsys.readouterr().err
    assert main(["log", "export", str(recording), "--rosbag1", str(tmp_path / "x.mcap")]) == 2
    assert ".bag" in capsys.readouterr().err
