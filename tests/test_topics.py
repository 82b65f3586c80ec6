"""The one topic table (:mod:`softpad.topics`): its rows, what each output carries, its frames."""

from __future__ import annotations

import math

import pytest

from softpad import topics as T
from softpad.layout import PadLayout, PadPose


def test_names_are_unique_and_absolute() -> None:
    names = [t.name for t in T.TOPICS]
    assert len(names) == len(set(names))
    assert all(n.startswith("/") for n in names)


@pytest.mark.parametrize("output", T.OUTPUTS)
def test_every_output_gets_its_module_topics_once_per_module(output: str) -> None:
    got = T.topics_for(output, 6)
    assert [n for n in got if "/module_" in n] == [
        f"/softpad/module_{k}/pressure" for k in range(1, 7)
    ]
    tf = "foxglove.FrameTransforms" if output == "live" else "tf2_msgs/msg/TFMessage"
    assert got[T.TF_STATIC_TOPIC] == tf


def test_what_each_output_carries() -> None:
    """The unified names (issue 48): one plan topic pair, supply and robot pose on the nodes."""
    ros = T.topics_for("ros2", 6)
    for name in (T.PLAN_TOPIC, T.OBJECT_TOPIC, T.SUPPLY_TOPIC, T.ROBOT_POSE_TOPIC, T.EVENT_TOPIC):
        assert name in ros
        assert T.topics_for("recording", 6)[name] == ros[name]
        assert name in T.topics_for("live", 6)
    assert T.topics_for("ros1", 6) == ros
    assert "/softpad/grasps" not in ros and "/softpad/plan" not in ros
    assert T.topics_for("live", 6)[T.PLAN_TOPIC] == "foxglove.PosesInFrame"
    assert T.OUTCOME_TOPIC not in T.topics_for("recording", 6)
    assert T.PAD_TOPIC in T.topics_for("live", 6) and T.PAD_TOPIC not in ros


def test_unknown_output_and_topic_are_named() -> None:
    with pytest.raises(ValueError, match="ros3"):
        T.topics_for("ros3", 6)
    with pytest.raises(KeyError, match="/nope"):
        T.topic("/nope")


@pytest.mark.parametrize(
    ("ros2", "ros1"),
    [
        ("sensor_msgs/msg/FluidPressure", "sensor_msgs/FluidPressure"),
        ("softpad_msgs/action/Grasp", "softpad_msgs/Grasp"),
    ],
    ids=["msg", "action"],
)
def test_ros1_type(ros2: str, ros1: str) -> None:
    assert T.ros1_type(ros2) == ros1


def test_every_own_type_is_defined() -> None:
    own = {t.type for t in T.TOPICS if t.type.startswith("softpad_msgs/")}
    assert own <= set(T.MESSAGE_DEFINITIONS)
    assert T.GRASP_ACTION_TYPE in T.MESSAGE_DEFINITIONS
    assert T.MESSAGE_DEFINITIONS[T.GRASP_ACTION_TYPE].count("---") == 2


def test_static_frames_place_the_pad_and_its_modules() -> None:
    pad = PadPose(0.4, -0.1, 0.02, math.pi / 2)
    frames = T.static_frames(PadLayout(2, 3, 0.045), pad, "world")
    assert frames[0] == ("world", "softpad", (0.4, -0.1, 0.02, math.pi / 2))
    parent, child, (x, y, z, yaw) = frames[3]  # module 3 at (2.5, 1.5) module units
    assert (parent, child) == ("softpad", "softpad_module_3")
    assert (x, y, z, yaw) == pytest.approx((2.5 * 0.045, 1.5 * 0.045, 0.0, 0.0))
    assert len(frames) == 7


def test_markdown_table_has_one_row_per_topic() -> None:
    lines = T.markdown_table().splitlines()
    assert len(lines) == 2 + len(T.TOPICS)
    assert "`/softpad/module_K/pressure`" in lines[2]
