"""The installation's ``[pad.pose]`` reaches ``/tf_static`` of what ``softpad run`` writes
(issue 48: the pad stood at the base frame's origin whatever the installation said)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from softpad.cli.main import main

pytest.importorskip("mcap_ros2")


def _tf_static(path: Path) -> list[object]:
    from mcap_ros2.reader import read_ros2_messages

    return [m.ros_msg for m in read_ros2_messages(str(path), topics=["/tf_static"])]


def test_a_recording_places_the_pad_where_the_installation_says(tmp_path: Path, site: Any) -> None:
    out = tmp_path / "run.mcap"
    argv = ["run", "--objects", "object-5", "--hold-s", "0.5", "--config", str(site.path)]
    assert main([*argv, "--record", str(out), "--json"]) in (0, 1)
    # the recording holds exactly the table's names and types (softpad.topics)
    from mcap.reader import make_reader

    from softpad.topics import topics_for

    with out.open("rb") as f:
        summary = make_reader(f).get_summary()
    assert summary is not None
    schemas = {s.id: s.name for s in summary.schemas.values()}
    channels = {c.topic: schemas[c.schema_id] for c in summary.channels.values()}
    assert channels == topics_for("recording", 6)
    (msg,) = _tf_static(out)
    pad = msg.transforms[0]  # type: ignore[attr-defined]
    t, q = pad.transform.translation, pad.transform.rotation
    site.check_pad_transform(
        (pad.header.frame_id, pad.child_frame_id), (t.x, t.y, t.z), (q.x, q.y, q.z, q.w)
    )
    # the modules stay on the pad: softpad -> softpad_module_1 at (0.5, 1.5) module units
    m1 = msg.transforms[1]  # type: ignore[attr-defined]
    assert m1.child_frame_id == "softpad_module_1"
    assert (m1.transform.translation.x, m1.transform.translation.y) == pytest.approx(
        (0.5 * 0.045, 1.5 * 0.045)
    )


def test_without_an_installation_the_pad_is_at_the_origin(site: Any) -> None:
    from softpad.cli._installation import installed_pad_pose
    from softpad.layout import PadPose

    assert installed_pad_pose(None) == PadPose()
    pose = installed_pad_pose(str(site.path))
    assert (pose.x_m, pose.y_m, pose.z_m) == pytest.approx(site.xyz_m)
    assert pose.yaw_rad == pytest.approx(site.yaw_rad)
