"""softpad.ros.installation_settings: the node's settings of an installation (SI), its box
link's URL only where the link connects, the pitch left out for the ROS 2 node."""

from __future__ import annotations

import math

import pytest

from softpad.config import parse_installation
from softpad.ros import CONFIG_KEYS, installation_settings


def test_the_settings_are_the_installations_in_si() -> None:
    inst = parse_installation(
        {"pad": {"rows": 3, "cols": 4, "pitch_mm": 40.0, "pose": {"x_mm": 120, "yaw_deg": 90}},
         "gripper": {"mounting": "6/2"}}
    )  # fmt: skip
    s = installation_settings(inst)
    assert set(s) <= set(CONFIG_KEYS) and "box" not in s
    assert s["layout"] == "3x4" and s["pitch_m"] == pytest.approx(0.040)
    assert s["pad_x_m"] == pytest.approx(0.120) and s["pad_yaw_rad"] == pytest.approx(math.pi / 2)
    assert s["object_threshold_pa"] == inst.thresholds.object_threshold_pa
    assert s["gripper"] == "6/2"
    assert "pitch_m" not in installation_settings(inst, pitch=False)


def test_a_connecting_link_is_the_nodes_box() -> None:
    inst = parse_installation({"link": {"connect": ["tcp/127.0.0.1:7450"]}})
    assert inst.box_url == "zenoh://127.0.0.1:7450/softpad/box"
    assert installation_settings(inst)["box"] == inst.box_url


def test_given_options_override_only_where_given() -> None:
    from softpad.ros import given_settings

    assert given_settings(None, box=None, place="", robot="sim://") == {"robot": "sim://"}
    assert given_settings(0.0, box="sim://") == {"hold_s": 0.0, "box": "sim://"}
