from __future__ import annotations

import numpy as np
import pytest

from softpad.errors import LayoutError
from softpad.layout import GripperSpec, PadLayout, PadPose, parse_layout


def test_thesis_numbering_on_2x3() -> None:
    layout = PadLayout()
    assert layout.center(1) == (0.5, 1.5)
    assert layout.center(3) == (2.5, 1.5)
    assert layout.center(4) == (0.5, 0.5)
    assert layout.center(5) == (1.5, 0.5)
    np.testing.assert_array_equal(layout.centers[1], [1.5, 1.5])


@pytest.mark.parametrize(
    ("module", "expected"),
    [(1, (2, 4, 5)), (2, (1, 3, 4, 5, 6)), (5, (1, 2, 3, 4, 6)), (6, (2, 3, 5))],
    ids=["corner-1", "central-2", "central-5", "corner-6"],
)
def test_eight_neighbourhood(module: int, expected: tuple[int, ...]) -> None:
    assert PadLayout().neighbours(module) == expected


def test_connected_groups_split_non_adjacent_modules() -> None:
    layout = PadLayout()
    assert layout.connected_groups([1, 3, 4, 6]) == [(1, 4), (3, 6)]
    assert layout.connected_groups([1, 5, 3]) == [(1, 3, 5)]


def test_general_layout_centres_follow_design_formula() -> None:
    layout = PadLayout(3, 4)
    for k in layout.modules:
        r, c = (k - 1) // 4, (k - 1) % 4
        assert layout.center(k) == (c + 0.5, (3 - 1 - r) + 0.5)


def test_module_containing_and_units() -> None:
    layout = PadLayout(pitch_m=0.05)
    assert layout.module_containing(0.2, 1.9) == 1
    assert layout.module_containing(2.9, 0.1) == 6
    assert layout.module_containing(-0.1, 0.5) is None
    np.testing.assert_allclose(layout.to_metres((1.0, 2.0)), [0.05, 0.1])
    np.testing.assert_allclose(layout.to_units(layout.to_metres((1.3, 0.7))), [1.3, 0.7])


@pytest.mark.parametrize("text", ["2y3", "0x3", "x3", "", "2x3x4", "-1x2"])
def test_bad_layout_strings(text: str) -> None:
    with pytest.raises(LayoutError, match=r"layout|rows|cols"):
        parse_layout(text)


def test_bad_module_number_names_the_limit() -> None:
    with pytest.raises(LayoutError, match="from 1 to 6"):
        PadLayout().center(7)


def test_pad_pose_maps_plan_to_robot_target() -> None:
    pose = PadPose(x_m=0.5, y_m=-0.2, z_m=0.1, yaw_rad=np.pi / 2)
    np.testing.assert_allclose(pose.to_base((0.045, 0.0)), [0.5, -0.2 + 0.045, 0.1], atol=1e-15)
    assert pose.yaw_to_base(np.pi / 2) == pytest.approx(np.pi)


def test_fingertips_straddle_the_cog_along_theta() -> None:
    g = GripperSpec.from_config("wide")
    a, b = g.fingertip_centres((0.0, 0.0), 0.0)
    assert a[0] == pytest.approx(0.05 + g.tip_thickness_m / 2) and a[1] == pytest.approx(0.0)
    assert b[0] == pytest.approx(-a[0])
