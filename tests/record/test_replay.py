"""Replay: the regression recordings in tests/data/, the replay:// box, ``softpad replay``."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from softpad.box import ConnectionLost, check_conformance, open_box
from softpad.cli.main import main
from softpad.errors import InputError
from softpad.record import ReplayBox, compare_replay, load_recording

DATA = Path(__file__).resolve().parents[1] / "data"
RECORDINGS = sorted(DATA.glob("*.mcap"))


def test_there_are_regression_recordings() -> None:
    assert len(RECORDINGS) >= 3


@pytest.mark.parametrize("path", RECORDINGS, ids=[p.stem for p in RECORDINGS])
def test_replay_reproduces_plan_and_contact_sample(path: Path) -> None:
    d = compare_replay(path)
    assert d["plan"]["recorded"], "a regression case must hold a plan"
    assert d["plan"]["same"], (d["plan"]["recorded"], d["plan"]["now"])
    assert d["contacts"] and all(c["same"] for c in d["contacts"]), d["contacts"]
    assert d["same"]


def test_replay_notices_a_change_of_the_contact_threshold() -> None:
    run = load_recording(DATA / "banana.mcap")
    run.metadata["params"]["contact_threshold_pa"] = (
        3 * run.metadata["params"]["contact_threshold_pa"]
    )
    d = compare_replay(run)
    assert d["plan"]["same"] and not d["same"]
    c = d["contacts"][0]
    assert c["now"] is None or c["now"]["t_s"] > c["recorded"]["t_s"]


def test_replay_uses_the_recorded_planner_and_detector(tmp_path: Path, capsys) -> None:
    """A run of the gripper-aware planner and the adaptive CUSUM that retried a grasp (the can,
    first grasped along its length) replays with those parts: the same plan and the same
    contact sample on both descents. Read as a thesis run it is not the same; an unknown part
    name in the metadata is named."""
    path = tmp_path / "can.mcap"
    argv = ["run", "--objects", "cylinder", "--hold-s", "0", "--box", "sim://?seed=1"]
    argv += ["--planner", "gripper-aware", "--detector", "adaptive", "--record", str(path)]
    assert main(argv) == 0
    capsys.readouterr()
    run = load_recording(path)
    assert (run.metadata["planner"], run.metadata["contact_detector"]) == (
        "gripper-aware",
        "adaptive",
    )
    d = compare_replay(run)
    assert len(d["contacts"]) == 2 and d["same"], d
    assert [e["attempt"] for _, e in run.events_of("retry")] == [1]
    run.metadata["planner"] = run.metadata["contact_detector"] = "thesis"
    assert not compare_replay(run)["same"]
    run.metadata["planner"] = "magic"
    with pytest.raises(InputError, match="unknown planner 'magic'"):
        compare_replay(run)


def test_replay_box_passes_conformance() -> None:
    check_conformance(open_box(f"replay://{DATA / 'banana.mcap'}"))


def test_replay_box_plays_the_recorded_frames_and_keeps_valve_commands() -> None:
    run = load_recording(DATA / "cylinder.mcap")
    with open_box(f"replay://{DATA / 'cylinder.mcap'}?speed=recorded") as box:
        assert isinstance(box, ReplayBox) and box.speed == 1.0
        assert box.channels == 6 and box.sample_rate_hz == pytest.approx(100.0)
        frames = box.read_many(3)
        box.set_valve(2, "inflate")
        assert box.commands == [(frames[-1].t_s, 2, box.valves[1])]
    np.testing.assert_array_equal([f.t_s for f in frames], run.t_s[:3])
    np.testing.assert_array_equal(frames[2].pressures_pa, run.pressures_pa[2])
    fast = ReplayBox(run)
    fast.read_many(len(run))
    with pytest.raises(ConnectionLost, match="ended"):
        fast.read()


@pytest.mark.parametrize(
    ("url", "message"),
    [
        ("replay://", "needs a file"),
        ("replay://nowhere.mcap", "does not exist"),
        (f"replay://{DATA / 'banana.mcap'}?speed=-1", "factor must be > 0"),
        (f"replay://{DATA / 'banana.mcap'}?speed=warp", "'fast', 'recorded'"),
        (f"replay://{DATA / 'banana.mcap'}?loop=1", "unknown replay:// option 'loop'"),
    ],
    ids=["empty", "missing", "negative", "word", "option"],
)
def test_bad_replay_urls(url: str, message: str) -> None:
    with pytest.raises(InputError, match=message):
        open_box(url)


def test_replay_cli_json_and_text(capsys) -> None:
    path = DATA / "object-1_object-4.mcap"
    assert main(["replay", str(path), "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert len(d["plan"]["now"]) == 2 and len(d["contacts"]) == 2
    assert main(["replay", str(path)]) == 0
    out = capsys.readouterr().out
    assert "plan: same" in out and "verdict: today's code decides what was recorded" in out


def test_foxglove_layout_plots_the_recorded_topics(tmp_path: Path) -> None:
    """docs/foxglove-layout.json reads only topics a recording holds (the live view publishes
    them too): the gauge array's six modules and the supply, the events, and in its 3D panel
    /tf_static, the planned grasps and objects and the robot's pose; it follows the pad frame."""
    from rosbags.highlevel import AnyReader

    from softpad.cli.main import main
    from softpad.record._live import PAD_TOPIC

    layout = json.loads((DATA.parents[1] / "docs" / "foxglove-layout.json").read_text())
    configs = layout["configById"].values()
    paths = [p["value"] for cfg in configs for p in cfg.get("paths", [])]
    assert sorted(paths) == [f"/softpad/pressures.data[{k}]" for k in range(7)]
    pad = layout["configById"]["3D!softpadpad"]
    read = {p.split(".")[0] for p in paths} | set(pad["topics"])
    read |= {cfg["topicPath"] for cfg in configs if "topicPath" in cfg}
    assert PAD_TOPIC not in read  # the live view's picture: recordings do not hold it
    path = tmp_path / "run.mcap"
    assert main(["run", "--hold-s", "0.5", "--record", str(path), "--box", "sim://?seed=3"]) == 0
    with AnyReader([path]) as reader:
        by_topic = {c.topic: c for c in reader.connections}
        # every topic the layout reads is in the recording, and the 3D panel's are ones it draws
        assert read <= set(by_topic), read - set(by_topic)
        drawn = {"tf2_msgs/msg/TFMessage", "geometry_msgs/msg/PoseArray"}
        drawn.add("geometry_msgs/msg/PoseStamped")
        assert {by_topic[t].msgtype for t in pad["topics"]} <= drawn
        c = by_topic["/softpad/pressures"]
        _, _, raw = next(iter(reader.messages([c])))
        assert len(reader.deserialize(raw, c.msgtype).data) == 7  # six modules + the supply
        c = by_topic["/tf_static"]
        _, _, raw = next(iter(reader.messages([c])))
        frames = {t.child_frame_id for t in reader.deserialize(raw, c.msgtype).transforms}
    assert pad["followTf"] in frames
