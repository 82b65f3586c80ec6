"""SoftPad's ROS 1 packages as files: the URDF against the frames the node publishes, the
message definitions against the recordings', the launch and rviz files against the node's
names, and the installation file read into the node's settings (no roscore needed)."""

from __future__ import annotations

import math
import shutil
import subprocess
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from softpad.layout import parse_layout
from softpad.ros._msgs import _action_messages, ros_packages_dir
from softpad.ros._urdf import pad_urdf

ROOT = Path(__file__).resolve().parents[2]
PACKAGES = ros_packages_dir()
SHIPPED_URDF = PACKAGES / "softpad_ros" / "urdf" / "softpad_2x3.urdf"


def _joints(urdf: str) -> dict[str, tuple[str, tuple[float, ...]]]:
    """child link -> (parent link, origin xyz) of every joint."""
    root = ET.fromstring(urdf)
    out = {}
    for j in root.iter("joint"):
        xyz = tuple(float(v) for v in j.find("origin").attrib["xyz"].split())  # type: ignore[union-attr]
        out[j.find("child").attrib["link"]] = (j.find("parent").attrib["link"], xyz)  # type: ignore[union-attr]
    return out


def test_shipped_urdf_is_the_generated_one() -> None:
    assert SHIPPED_URDF.read_text() == pad_urdf(parse_layout("2x3"))


@pytest.mark.parametrize("layout", ["2x3", "3x4", "1x1"], ids=["2x3", "3x4", "1x1"])
def test_urdf_has_one_link_per_module_at_the_node_frames(layout: str) -> None:
    """Each module's joint puts its link where /tf_static puts its frame (the recordings'
    static frames, the same as the node's): module centre x = (c + 0.5) pitch, y = (R - 1 - r +
    0.5) pitch on the pad surface."""
    from softpad.layout import PadPose
    from softpad.record._schemas import static_frames

    pad = parse_layout(layout, 0.05)
    joints = _joints(pad_urdf(pad))
    frames = {child: (parent, xyz) for parent, child, xyz in static_frames(pad, PadPose())[1:]}
    assert set(joints) == set(frames) and len(joints) == pad.n_modules
    for child, (parent, xyz) in joints.items():
        assert parent == frames[child][0] == "softpad"
        np_xyz = frames[child][1][:3]
        assert xyz == pytest.approx(np_xyz, abs=1e-9), child
    k = pad.n_modules  # the last module: bottom-right
    assert joints[f"softpad_module_{k}"][1][:2] == pytest.approx(
        ((pad.cols - 0.5) * 0.05, 0.5 * 0.05)
    )


@pytest.mark.skipif(not shutil.which("check_urdf"), reason="liburdfdom-tools not installed")
@pytest.mark.parametrize("layout", ["2x3", "4x4"], ids=["2x3", "4x4"])
def test_check_urdf_reads_the_pad(layout: str, tmp_path: Path) -> None:
    path = tmp_path / "pad.urdf"
    path.write_text(pad_urdf(parse_layout(layout)))
    r = subprocess.run(["check_urdf", str(path)], capture_output=True, text=True, check=False)
    assert r.returncode == 0, r.stdout + r.stderr
    n = parse_layout(layout).n_modules
    assert f"root Link: softpad has {n} child(ren)" in r.stdout


def test_message_files_are_the_topic_tables_definitions() -> None:
    """softpad_msgs' .msg and .action files are the table's definitions (softpad.topics,
    which the ROS 2 package and the recordings use), character for character."""
    from softpad.topics import MESSAGE_DEFINITIONS

    own = {k: v for k, v in MESSAGE_DEFINITIONS.items() if k.startswith("softpad_msgs/")}
    assert len(own) == 4
    for full, text in own.items():
        _, kind, name = full.split("/")
        ext = "action" if kind == "action" else "msg"
        assert (PACKAGES / "softpad_msgs" / ext / f"{name}.{ext}").read_text() == text, full


def test_action_expands_as_genaction_does() -> None:
    """``Grasp.action`` -> the seven messages of actionlib's convention, the goal, result and
    feedback parts in place and the wrappers' fields in genaction's order."""
    text = (PACKAGES / "softpad_msgs" / "action" / "Grasp.action").read_text()
    msgs = _action_messages("Grasp", text)
    assert set(msgs) == {
        "GraspGoal", "GraspResult", "GraspFeedback", "GraspActionGoal", "GraspActionResult",
        "GraspActionFeedback", "GraspAction",
    }  # fmt: skip
    assert "float64 hold_s" in msgs["GraspGoal"] and "string phase" in msgs["GraspFeedback"]
    assert "string outcome" in msgs["GraspResult"] and "---" not in msgs["GraspResult"]
    assert msgs["GraspActionGoal"].split() == [
        "Header", "header", "actionlib_msgs/GoalID", "goal_id", "GraspGoal", "goal",
    ]  # fmt: skip
    with pytest.raises(ValueError, match="goal, result and feedback"):
        _action_messages("Bad", "float64 a\n---\nfloat64 b\n")


def test_launch_and_rviz_files_name_what_the_node_publishes() -> None:
    """pad.launch runs the package's node script, rviz shows the node's topics in its frames,
    and view.launch loads the shipped URDF."""
    import yaml

    pkg = PACKAGES / "softpad_ros"
    launch = ET.parse(pkg / "launch" / "pad.launch").getroot()
    (node,) = launch.iter("node")
    assert (node.attrib["pkg"], node.attrib["type"], node.attrib["name"]) == (
        "softpad_ros", "softpad_node", "softpad",
    )  # fmt: skip
    script = pkg / "scripts" / "softpad_node"
    assert script.stat().st_mode & 0o111, "the node script must be executable"
    params = {p.attrib["name"] for p in node.iter("param")}
    from softpad.ros import CONFIG_KEYS

    assert params <= set(CONFIG_KEYS), params - set(CONFIG_KEYS)
    view = (pkg / "launch" / "view.launch").read_text()
    assert "urdf/softpad_2x3.urdf" in view and "rviz/softpad.rviz" in view
    rviz = yaml.safe_load((pkg / "rviz" / "softpad.rviz").read_text())
    displays = rviz["Visualization Manager"]["Displays"]
    topics = {d["Topic"] for d in displays if "Topic" in d}
    assert topics == {"/softpad/plan/objects", "/softpad/plan/grasps"}
    assert rviz["Visualization Manager"]["Global Options"]["Fixed Frame"] == "base"
    from softpad.topics import topics_for

    published = topics_for("ros1", 6)
    assert all(published[t] == "geometry_msgs/msg/PoseArray" for t in topics)


def test_installation_file_gives_the_node_settings_in_si(tmp_path: Path) -> None:
    """examples/site.toml (mm, degrees, kPa) -> the node's settings in m, rad, Pa."""
    from softpad.cli._ros import installation_settings
    from softpad.ros import NodeConfig

    text = (ROOT / "examples" / "site.toml").read_text().replace("yaw_deg = 0.0", "yaw_deg = 90.0")
    site = tmp_path / "site.toml"
    site.write_text(text)
    c = NodeConfig().updated(installation_settings(str(site)))
    assert (c.pad.x_m, c.pad.y_m, c.pad.z_m) == pytest.approx((0.4, -0.1, 0.02))
    assert c.pad.yaw_rad == pytest.approx(math.pi / 2)
    assert c.pitch_m == pytest.approx(0.045) and c.layout == "2x3"
    assert c.object_threshold_pa == pytest.approx(50.0)
    assert c.contact_threshold_pa == pytest.approx(90.0)
    assert c.ambient_pressure_pa == pytest.approx(101325.0)


def test_node_refuses_a_json_config_with_one_line(tmp_path: Path) -> None:
    from softpad.cli.main import main

    f = tmp_path / "pad.json"
    f.write_text("{}")
    with pytest.raises(Exception, match="installation file \\(TOML"):
        from softpad.cli._ros import installation_settings

        installation_settings(str(f))
    assert main(["ros", "node", "--config", str(f)]) != 0
