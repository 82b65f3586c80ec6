"""The MuJoCo world: loads from contact forces, non-sensitive lines, kinematic gripper."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pytest
from mujoco_steps import move_to, settle

from softpad.errors import InputError
from softpad.layout import PadLayout
from softpad.sim import GripperState, World
from softpad.sim._mujoco_model import GRAVITY_M_S2, MujocoGripper, ObjectModel, ObjectPart
from softpad.sim._mujoco_world import MujocoWorld


@dataclass(frozen=True)
class Placement:
    x_m: float
    y_m: float
    yaw_rad: float = 0.0


pytestmark = pytest.mark.mujoco

PITCH = PadLayout().pitch_m


def brick(name: str = "brick", mass_kg: float = 0.0126) -> ObjectModel:
    """A Lego Duplo 2x2 brick, 31 x 31 x 31 mm (thesis: 12.6 g, 42 x 31 x 31 mm for a 2x4)."""
    return ObjectModel(name, (ObjectPart("box", mass_kg, (0, 0, 0.0155), size_m=(0.031,) * 3),))


def test_is_a_world() -> None:
    assert isinstance(MujocoWorld(), World)


@pytest.mark.parametrize("module", [1, 2, 3, 4, 5, 6], ids=lambda k: f"module{k}")
def test_resting_brick_loads_only_its_module_weighted_by_the_response(module: int) -> None:
    world = MujocoWorld(objects=(brick(),))
    x, y = PadLayout().to_metres(PadLayout().center(module))
    world.place_object(brick(), Placement(x, y))
    settle(world)
    forces, loads = world.module_forces_n(), world.module_loads_n()
    expected = np.zeros(6)
    expected[module - 1] = 0.0126 * GRAVITY_M_S2
    # static equilibrium: the contact forces carry the weight (1 % for solver residuals)
    np.testing.assert_allclose(forces, expected, rtol=0.01, atol=1e-4)
    # the brick rests on the dome's apex: each newton there squeezes the chamber as much as
    # s(0) / s_ref newtons on the characteristic's 30 mm patch (FEM response, within 10 mm)
    r, p, k = world.response, world.operating_pressure_pa, module - 1
    top = r.factors([(x, y)], p)[0, k]
    edge = min(r.factors([(x + 0.010, y), (x - 0.010, y)], p)[:, k])
    ratio = loads[k] / forces[k]
    assert edge <= ratio <= top + 1e-9
    # the cast layer passes a central load to the neighbours by under 1 %
    assert np.abs(np.delete(loads, k)).max() < 0.01 * loads[k]


def test_a_one_step_contact_peak_reaches_the_chamber_as_its_share_of_the_period() -> None:
    """The loads a box sample sees are the mean over the MuJoCo steps of its period (five 2 ms
    steps at 100 Hz): a contact force that one solver step puts on module 1 (40 N, as when
    jaws close on an object) counts a fifth, not in full as the last step's force would.
    Two identical worlds, one with the extra contact in the period's last step: the samples
    differ by the fifth of its equivalent loads (module 1's; a trace on its neighbours)."""
    loads = []
    for spike in (False, True):
        world = MujocoWorld(objects=(brick(),))
        x, y = PadLayout().to_metres(PadLayout().center(2))
        world.place_object(brick(), Placement(x, y))
        settle(world)
        world.compiled_steps(False)  # the Python steps' update (same world: test_fast_steps.py)
        sensing = world._sensing
        update, steps = sensing.update, []

        def spiky(*args, _update=update, _steps=steps, _spike=spike, _s=sensing) -> None:
            _update(*args)
            _steps.append(1)
            if _spike and len(_steps) == 5:  # the period's last step: 40 N at module 1's centre
                centre = _s._centres[0][None, :]
                _s._pending.append((np.array([0]), np.array([40.0]), centre))

        sensing.update = spiky  # type: ignore[method-assign]
        world.step(0.01)
        assert len(steps) == 5
        loads.append(world.module_loads_n())
    r, p = sensing.response, sensing.pressure_pa
    share = 40.0 * r.point_factors([0], sensing._centres[:1], p)[0] / 5  # every module's
    np.testing.assert_allclose(loads[1] - loads[0], share, rtol=1e-9, atol=1e-12)
    assert share[0] > 100 * np.delete(share, 0).max()  # module 1's, a trace on the others
    assert loads[0][1] == pytest.approx(0.0126 * GRAVITY_M_S2, rel=0.5)  # the brick on module 2


def test_heavier_part_loads_its_module_more() -> None:
    """A bar across modules 1 and 2 with a heavy insert over module 1 (like the cylinder)."""
    light, heavy = 0.010, 0.030
    bar = ObjectModel(
        "bar",
        (
            ObjectPart("box", light, (-0.0225, 0, 0.01), size_m=(0.045, 0.03, 0.02)),
            ObjectPart("box", heavy, (0.0225, 0, 0.01), size_m=(0.045, 0.03, 0.02)),
        ),
    )
    world = MujocoWorld(objects=(bar,))
    # heavy half over module 1 (x = 0.5 units): yaw pi turns the bar around
    world.place_object(bar, Placement(PITCH, 1.5 * PITCH, np.pi))
    settle(world, 1.5)
    loads = world.module_forces_n()
    total = (light + heavy) * GRAVITY_M_S2
    np.testing.assert_allclose(loads.sum(), total, rtol=0.01)
    np.testing.assert_allclose(loads[2:], 0.0, atol=1e-6)
    # the bar's COM is 11.25 mm from the middle towards module 1. Point supports at the module
    # centres (the PCOM model, Eq. 6.1) would give module 1 a share of 0.75; the flat rigid
    # tops carry the bar nearer their outer edges (x = 4.5 and 85.5 mm: 0.64 by the lever
    # rule), and MuJoCo's contact points settle between that and an even split.
    assert 0.55 < loads[0] / total < 0.75


def descend_fingers(world: MujocoWorld, x_m: float, y_m: float, width_m: float) -> float:
    """Lower the open gripper (theta = 0) at 0.05 m/s until the tips are 0.5 mm above the base;
    return the largest module load seen, N."""
    z = 0.02
    world.set_gripper_target(GripperState(x_m, y_m, z, 0.0, width_m))
    settle(world, 0.1)
    peak = 0.0
    while z > 0.0005:
        z -= 0.05e-3
        world.set_gripper_target(GripperState(x_m, y_m, z, 0.0, width_m))
        world.step(1e-3)
        peak = max(peak, float(world.module_loads_n().max()))
    return peak


def test_fingertips_on_the_seams_are_barely_sensed() -> None:
    """The gripper's tips (GripperSpec, 6.5 x 16 mm) 45 mm apart: centred on modules 4 and 5 (x = 0.75 and
    1.75 units) against centred on the seams at x = 1 and 2 units, where they press the
    clamped edges of the domes: the FEM response there is a small fraction of the centre's."""
    peaks = []
    for x_units in (1.25, 1.5):
        gripper = MujocoGripper(mounting="10/4")
        world = MujocoWorld(gripper=gripper)
        width = PITCH - gripper.tip_thickness_m  # tip centres 45 mm apart
        peaks.append(descend_fingers(world, x_units * PITCH, 0.5 * PITCH, width))
    # t_g = 90 Pa is about 0.13 N of equivalent load at the box's 670 Pa/N
    assert peaks[0] > 0.2
    assert peaks[1] < 0.15 * peaks[0]


def test_fingertip_across_the_row_seam_touches_both_domes_and_is_weakly_sensed() -> None:
    """Tips (16 mm wide) centred on the seam between rows (y = 1 unit, modules 2 and 5), like
    object 1's thesis grasp: both domes' flanks carry them, near their clamped edges."""
    world = MujocoWorld(gripper=MujocoGripper(mounting="10/2"))
    across = descend_fingers(world, 1.5 * PITCH, 1.0 * PITCH, 0.020)
    assert world.gripper_contacts().sole_on_modules == ((2, 5), (2, 5))
    inside = descend_fingers(
        MujocoWorld(gripper=MujocoGripper(mounting="10/2")), 1.5 * PITCH, 1.5 * PITCH, 0.020
    )
    assert 0.0 < across < 0.5 * inside


@pytest.mark.parametrize(("asked", "got"), [(1.0, 0.06), (0.0, 0.02)], ids=["open", "close"])
def test_gripper_width_is_clamped_to_the_mounting(asked: float, got: float) -> None:
    """The execution opens with 1 m and closes with 0 m: the jaws go to the mounting's limits."""
    world = MujocoWorld(gripper=MujocoGripper(mounting="6/2"))
    world.command_gripper(GripperState(0.05, 0.05, 0.05, 0.0, asked), 0.2)
    settle(world, 0.6)
    # closing fully is force-limited: an empty jaw stops on its joint limit (1 mm past)
    np.testing.assert_allclose(world.gripper_state().width_m, got, atol=3e-3)


def test_bad_gripper_target_is_rejected() -> None:
    with pytest.raises(InputError, match="gripper speed"):
        MujocoWorld().command_gripper(GripperState(0.05, 0.05, 0.05, 0.0, 0.05), -1.0)


def test_object_without_parts_is_rejected() -> None:
    with pytest.raises(InputError, match="no parts"):
        MujocoWorld().place_object(ObjectModel("nothing", ()), Placement(0.0, 0.0))


def test_bad_heights_are_rejected() -> None:
    with pytest.raises(InputError, match="module heights"):
        MujocoWorld().step(1e-3, [0.008] * 5)


def test_simulated_box_on_mujoco_world_conforms() -> None:
    """The box contract holds with the MuJoCo world underneath (frames, valves, close)."""
    from softpad.box import SimBox, check_conformance

    check_conformance(SimBox(MujocoWorld(), seed=1, initial_pressure_pa=1100.0))


@pytest.mark.parametrize("tip_width_m", [0.010, 0.016], ids=["tip-10mm", "tip-16mm"])
def test_holding_a_lifted_brick(tip_width_m: float) -> None:
    """Squeezed by both jaws and off the pad: held; back on the pad: not.

    The hand reaches each pose before the next command (the robot's moves are sequential): a
    version of this test that closed the jaws while the hand was still 25 mm above its target
    pushed the brick into the dome with the closed fingers until it flipped out and was caught
    by chance (held with the 10 mm tips, slipping with 16 mm)."""
    world = MujocoWorld(gripper=MujocoGripper(mounting="6/2", tip_width_m=tip_width_m))
    world.place_object(brick(mass_kg=0.05), Placement(1.5 * PITCH, 1.5 * PITCH))
    settle(world, 1.0)
    x, y = 1.5 * PITCH, 1.5 * PITCH
    move_to(world, GripperState(x, y, 0.02, 0.0, 0.05), 0.2, 0.2)
    move_to(world, GripperState(x, y, 0.009, 0.0, 0.05), 0.05, 0.2)
    assert not world.holding()
    move_to(world, GripperState(x, y, 0.009, 0.0, 0.0), 0.05, 0.8)
    assert min(world.gripper_contacts().finger_on_object_n) > 5.0  # force-limited squeeze
    # squeezed flat, face to face: the jaws closed to the brick's 31 mm (less the contacts'
    # 0.1 mm penetration each side), the brick neither pushed off its dome nor turned
    np.testing.assert_allclose(world.gripper_state().width_m, 0.031, atol=0.5e-3)
    pose = world.object_pose("brick")
    np.testing.assert_allclose([pose.x_m, pose.y_m], [x, y], atol=0.5e-3)
    assert pose.tilt_rad < np.radians(1.0)
    z0 = pose.z_m
    move_to(world, GripperState(x, y, 0.06, 0.0, world.gripper_state().width_m), 0.1, 1.0)
    assert world.holding()
    # rose with the hand (51 mm), no slip beyond 1 mm
    np.testing.assert_allclose(world.object_pose("brick").z_m - z0, 0.051, atol=1e-3)


def test_closing_jaws_move_at_the_commanded_speed() -> None:
    """Closing fully, the opening shrinks at the commanded 0.05 m/s (5 mm in 0.1 s, within
    1 mm for the servo's lag), not at the force limit over the joint damping (0.5 m/s each
    jaw, 100 mm/s of opening), which is how the jaws met objects before: a banana's end
    struck at that speed was driven into the pad to the sensor's full scale."""
    world = MujocoWorld(gripper=MujocoGripper(mounting="6/2"))
    settle(world, 0.2)
    w0 = world.gripper_state().width_m
    world.command_gripper(GripperState(0.05, 0.05, 0.15, 0.0, 0.0), 0.05)
    settle(world, 0.1)
    np.testing.assert_allclose(w0 - world.gripper_state().width_m, 0.005, atol=1e-3)


def test_jaws_stopped_on_an_object_settle_only_at_the_grip_force() -> None:
    """Jaws blocked by a brick report "still moving" (jaws_settled False) while their force
    grows with the setpoint (servo gain x speed = 100 N/s), and settled once each jaw presses
    with at least 95 % of the 20 N grip force."""
    world = MujocoWorld(gripper=MujocoGripper(mounting="6/2"))
    x, y = 1.5 * PITCH, 1.5 * PITCH
    world.place_object(brick(mass_kg=0.05), Placement(x, y))
    settle(world, 1.0)
    move_to(world, GripperState(x, y, 0.02, 0.0, 0.05), 0.2, 0.2)
    move_to(world, GripperState(x, y, 0.009, 0.0, 0.05), 0.05, 0.2)
    assert world.jaws_settled()  # not closing
    world.command_gripper(GripperState(x, y, 0.009, 0.0, 0.0), 0.05)
    blocked_unsettled = 0
    for _ in range(1500):
        before = world.gripper_state().width_m
        world.step(1e-3)
        if world.gripper_state().width_m == before and not world.jaws_settled():
            blocked_unsettled += 1
        if world.jaws_settled():
            break
    else:
        raise AssertionError("the jaws never settled on the brick within 1.5 s")
    assert blocked_unsettled > 20  # stalled on the brick for a while before the force was there
    assert min(world.gripper_contacts().finger_on_object_n) > 0.9 * 20.0
    np.testing.assert_allclose(world.gripper_state().width_m, 0.031, atol=0.5e-3)
