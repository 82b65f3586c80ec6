"""The ROS 2 side's pieces that need no ROS 2: the interface packages written from the table,
the node's settings from an installation file, the run's watchers given the pad's pose."""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

import pytest

from softpad.ros2 import write_packages
from softpad.topics import MESSAGE_DEFINITIONS


def test_the_packages_hold_the_tables_definitions_and_their_dependencies(tmp_path: Path) -> None:
    dirs = {d.name: d for d in write_packages(tmp_path)}
    assert set(dirs) == {"tf2_msgs", "softpad_msgs"}
    tf = dirs["tf2_msgs"]
    assert (tf / "msg" / "TFMessage.msg").read_text() == MESSAGE_DEFINITIONS[
        "tf2_msgs/msg/TFMessage"
    ]
    assert "DEPENDENCIES geometry_msgs)" in (tf / "CMakeLists.txt").read_text()
    own = dirs["softpad_msgs"]
    files = sorted(p.relative_to(own).as_posix() for p in own.rglob("*.*") if p.parent != own)
    assert files == ["action/Grasp.action", "msg/Event.msg", "msg/Outcome.msg",
                     "msg/ValveCommands.msg"]  # fmt: skip
    cmake = (own / "CMakeLists.txt").read_text()
    deps = re.search(r"DEPENDENCIES ([a-z_ ]+)\)", cmake)
    assert deps is not None
    assert deps.group(1).split() == ["action_msgs", "geometry_msgs", "std_msgs"]
    xml = (own / "package.xml").read_text()
    assert "<member_of_group>rosidl_interface_packages</member_of_group>" in xml
    assert all(f"<depend>{d}</depend>" in xml for d in deps.group(1).split())


def test_the_node_reads_the_installation_file_in_its_units(site: Any) -> None:
    """TOML in mm, degrees and kPa -> the node's settings in m, rad and Pa (issue 48: the ROS
    node refused the installation file)."""
    from softpad.cli._ros2 import node_config

    site.path.write_text(site.path.read_text() + "[thresholds]\nt_o_kpa = 0.06\n")
    c = node_config(str(site.path))
    assert (c.pad.x_m, c.pad.y_m, c.pad.z_m) == pytest.approx(site.xyz_m)
    assert c.pad.yaw_rad == pytest.approx(site.yaw_rad)
    assert c.object_threshold_pa == pytest.approx(60.0)
    assert c.layout == "2x3"


def test_run_gives_its_watchers_the_installations_pose(site: Any) -> None:
    """The live view of ``softpad run --foxglove`` gets the installation's pose."""
    pytest.importorskip("foxglove")
    from softpad.box import open_box
    from softpad.cli._installation import installed_pad_pose
    from softpad.cli._run import _live

    pad = installed_pad_pose(str(site.path))
    with open_box("sim://") as box:
        live = _live(0, box, True, pad)
        try:
            assert live.pad == pad and live.pad.x_m == pytest.approx(site.xyz_m[0])
        finally:
            live.close()
