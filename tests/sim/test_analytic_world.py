"""Analytic world: object loads, fingertips on modules vs lines, gripper kinematics, grasping."""

from __future__ import annotations

import numpy as np
import pytest

from softpad.errors import InputError
from softpad.sim import (
    AnalyticWorld,
    GripperState,
    PadResponse,
    SimGripper,
    World,
    fingertip_overlap,
    get_object,
    object_footprint,
)

H = np.full(6, 9e-3)  # module heights at 1.1 kPa


def _descend(
    world: AnalyticWorld, x: float, y: float, yaw: float, to_z: float = 0.001, steps: int = 400
) -> None:
    s = world.gripper_state()
    world._state = GripperState(x, y, 0.02, yaw, s.width_m)  # start just above the pad
    world.command_gripper(GripperState(x, y, to_z, yaw, s.width_m), 0.05)
    for _ in range(steps):
        world.step(0.001, H)


def test_is_a_world() -> None:
    assert isinstance(AnalyticWorld(), World)


def test_object_loads_are_its_contact_forces_weighted_by_the_fem_response() -> None:
    """Each module's load is the sum over the footprint of q a s_k(x) / s_ref,k (reciprocity),
    s_k read here point by point from the cast pad's FEM table (its frame scaled to the pad)."""
    w = AnalyticWorld()
    spec = get_object("object-4")
    w.place_object(spec)
    w.step(0.01, H)
    loads = w.module_loads_n()
    fp = object_footprint(spec, w.surface)
    np.testing.assert_allclose(fp.weight_fraction.sum(), 1.0, rtol=1e-3)
    cast, p = w.response.cast, w.operating_pressure_pa
    assert cast is not None and w.response.line_gain == 1.0
    s = cast.influence(fp.points_m * (cast.pitch_m / 0.045), p)
    expect = (fp.pressure_pa * fp.area_m2) @ s / w.response.reference_influences(p)
    np.testing.assert_allclose(loads, np.maximum(expect, 0.0), rtol=1e-9, atol=1e-12)
    assert set(np.flatnonzero(loads > 0.01) + 1) == {1, 4}
    assert loads[0] > loads[3]  # heavier part over module 1


def test_fingertip_share_follows_the_response_centre_to_seam() -> None:
    """The clamped modules (the old response, still available): a tip's share is its mean
    s / s_ref on its own module only, a small fraction on the seam."""
    w = AnalyticWorld(response=PadResponse(pad_model="clamped"))
    r, p = w.response.response, w.operating_pressure_pa
    centre = fingertip_overlap(
        (0.0675, 0.0225), 0.0, (0.008, 0.016), w.surface, response=w.response, pressure_pa=p
    )
    expect = r.mean_influence((0, 0), (0.008, 0.016), p) / r.reference_influence(p)
    np.testing.assert_allclose(centre, np.eye(6)[4] * expect, rtol=1e-9)
    assert expect > 1.0  # a small tip at the centre squeezes more than the 30 mm patch
    seam = fingertip_overlap(
        (0.045, 0.0225), 0.0, (0.002, 0.016), w.surface, response=w.response, pressure_pa=p
    )
    assert seam[3] == pytest.approx(seam[4]) and seam.sum() < 0.06 * expect  # clamped edges
    area = fingertip_overlap((0.0675, 0.0225), 0.0, (0.008, 0.016), w.surface)
    np.testing.assert_allclose(area, np.eye(6)[4])  # no response: plain area fractions


@pytest.mark.parametrize("yaw", [np.pi / 2])
def test_descending_fingertip_on_a_seam_is_barely_sensed(yaw: float) -> None:
    """A gripper with 2 mm tips: one tip centred on module 4/5, or on the 4|5 seam."""
    g = SimGripper(max_width_m=0.06, min_width_m=0.0, tip_thickness_m=0.002, tip_width_m=0.002)
    sensed = []
    for x in (0.0675 - 0.032, 0.045):
        w = AnalyticWorld(gripper=g)
        # jaws close along y: the tips sit at y = 22.5 mm +- 31 mm: one on the pad, one off it
        _descend(w, x, 0.0225 + 0.031, yaw)
        sensed.append(w.module_loads_n().sum())
    assert sensed[0] > 0.05 and sensed[1] < 0.1 * sensed[0]  # FEM: s falls to 0 at the clamp


def test_gripper_moves_at_the_commanded_speed() -> None:
    w = AnalyticWorld()
    s = w.gripper_state()
    w.command_gripper(GripperState(s.x_m, s.y_m, s.z_m - 0.05, s.yaw_rad, s.width_m), 0.05)
    for _ in range(500):
        w.step(0.001, H)
    np.testing.assert_allclose(w.gripper_state().z_m, s.z_m - 0.025, atol=1e-9)


def test_first_touch_is_where_the_tip_meets_the_module_top() -> None:
    w = AnalyticWorld(gripper=SimGripper.mounting("6/2"))
    _descend(w, 0.0675, 0.045, np.pi / 2)  # tips at y = 11 and 79 mm, in modules 5 and 2
    assert w.first_touch_z_m is not None
    np.testing.assert_allclose(w.first_touch_z_m, 9e-3, atol=0.05e-3 + 1e-12)


def test_grasp_lift_and_release() -> None:
    w = AnalyticWorld(gripper=SimGripper.mounting("6/2"))
    w.place_object(get_object("object-1"))  # brick along y at (112.5, 45) mm
    w._state = GripperState(0.1125, 0.045, 0.01, 0.0, 0.06)
    w.command_gripper(GripperState(0.1125, 0.045, 0.01, 0.0, 0.0), 0.05)
    for _ in range(100):
        w.step(0.01, H)
    np.testing.assert_allclose(w.gripper_state().width_m, 0.0317, atol=2.1e-3)  # brick width
    assert not w.holding()
    w.command_gripper(GripperState(0.1125, 0.045, 0.08, 0.0, 0.0), 0.1)
    for _ in range(100):
        w.step(0.01, H)
    assert w.holding()
    np.testing.assert_allclose(w.module_loads_n(), 0.0, atol=1e-12)  # lifted off the pad
    w.command_gripper(GripperState(0.1125, 0.045, 0.08, 0.0, 0.06), 0.1)
    for _ in range(10):
        w.step(0.01, H)
    assert not w.holding() and w.objects == ()


def test_unsupported_object_is_refused() -> None:
    from softpad.sim import Placement

    with pytest.raises(InputError, match="not supported"):
        AnalyticWorld().place_object(get_object("object-1"), Placement(0.5, 0.5))


def test_unknown_gripper_mounting() -> None:
    with pytest.raises(InputError, match=r"10/4, 6/2, 4/0 \(or wide, medium, narrow\)"):
        SimGripper.mounting("8/3")


def test_object_wider_than_the_open_jaws_is_not_grasped() -> None:
    """COG planned so that a jaw lands on the object: closing catches nothing."""
    w = AnalyticWorld(gripper=SimGripper.mounting("4/0"))
    w.place_object(get_object("object-3"))  # 127 mm long along x, centred at (67.5, 67.5) mm
    w._state = GripperState(0.0675, 0.0675, 0.01, 0.0, 0.04)  # jaws close along x: 4 cm apart
    w.command_gripper(GripperState(0.0675, 0.0675, 0.01, 0.0, 0.0), 0.05)
    for _ in range(100):
        w.step(0.01, H)
    w.command_gripper(GripperState(0.0675, 0.0675, 0.08, 0.0, 0.0), 0.1)
    for _ in range(100):
        w.step(0.01, H)
    assert not w.holding()


@pytest.mark.parametrize(("ours", "lead"), [("10/4", "wide"), ("6/2", "medium"), ("4/0", "narrow")])
def test_mountings_match_the_layout_gripper(ours: str, lead: str) -> None:
    from softpad.layout import GripperSpec

    assert SimGripper.mounting(ours).geometry == GripperSpec.from_config(lead)
    assert SimGripper.mounting(lead) == SimGripper.mounting(ours)
    assert SimGripper.from_spec(GripperSpec.from_config(lead)) == SimGripper.mounting(ours)
