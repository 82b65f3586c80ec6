"""Coasting through a settled hold (softpad.sim._mujoco_coast): the held object's pose follows
the fully stepped world, and a slip that starts while the world coasts is still simulated."""

from __future__ import annotations

import numpy as np
import pytest
from mujoco_steps import DT, At, X, Y, run

from softpad.sim import GripperState
from softpad.sim._mujoco_coast import COAST_STEPS, HoldCoast
from softpad.sim._mujoco_model import MujocoGripper, ObjectModel, ObjectPart
from softpad.sim._mujoco_world import MujocoWorld

pytestmark = pytest.mark.mujoco


def move(world: MujocoWorld, z_m: float, width_m: float, speed_m_s: float, rest_s: float) -> None:
    world.command_gripper(GripperState(X, Y, z_m, 0.0, width_m), speed_m_s)
    run(world, 3.0 + rest_s)


def lifted_brick() -> MujocoWorld:
    """A 50 g Duplo 2x2 brick squeezed by the 6/2 jaws and lifted 51 mm (as in
    test_mujoco_world's holding test), at the start of its hold."""
    world = MujocoWorld(gripper=MujocoGripper(mounting="6/2"))
    part = ObjectPart("box", 0.05, (0, 0, 0.0155), size_m=(0.031,) * 3)
    world.place_object(ObjectModel("brick", (part,)), At(X, Y))
    run(world, 1.0)
    move(world, 0.02, 0.05, 0.2, 0.0)
    move(world, 0.009, 0.05, 0.05, 0.0)
    move(world, 0.009, 0.0, 0.05, 0.5)
    move(world, 0.06, world.gripper_state().width_m, 0.1, 0.0)
    assert world.holding()
    return world


def hold(
    world: MujocoWorld,
    seconds: float,
    coast: bool,
    slip_at_s: float | None = None,
    friction: float = 0.0,
) -> None:
    """Hold for ``seconds`` (coasting allowed up to 1 s before the end when ``coast``); at
    ``slip_at_s`` the fingers' friction drops to ``friction`` unannounced (no command: the
    world must find the slip from its own velocities)."""
    t0 = world.time_s
    world.coast_settled_until(t0 + seconds - 1.0 if coast else None)
    while world.time_s - t0 < seconds - 1e-9:
        if slip_at_s is not None and world.time_s - t0 >= slip_at_s:
            slippery(world, friction)
            slip_at_s = None
        world.step(DT)
    world.coast_settled_until(None)


def slippery(world: MujocoWorld, friction: float) -> None:
    """Fingers and brick at sliding friction ``friction`` (MuJoCo takes a contact's friction
    as the larger of its two geoms')."""
    s = world.scene
    geoms = [
        *s.finger,
        *(g for g in range(s.model.ngeom) if s.model.geom_bodyid[g] in s.body_object),
    ]
    s.model.geom_friction[geoms, 0] = friction


def test_a_settled_hold_coasts_and_ends_where_the_stepped_one_does() -> None:
    """Most of a 15 s hold of a settled brick is coasted, and the brick ends within 20 um and
    1 mrad of the fully stepped world's brick (its creep in the jaws carried on), held."""
    ref, fast = lifted_brick(), lifted_brick()
    hold(ref, 15.0, coast=False)
    hold(fast, 15.0, coast=True)
    assert ref.coast.coasted_steps == 0
    assert fast.coast.coasted_steps > 0.6 * 15.0 / ref.timestep_s
    a, b = ref.object_pose("brick"), fast.object_pose("brick")
    np.testing.assert_allclose([b.x_m, b.y_m, b.z_m], [a.x_m, a.y_m, a.z_m], atol=20e-6)
    assert abs(b.yaw_rad - a.yaw_rad) < 1e-3 and abs(b.tilt_rad - a.tilt_rad) < 1e-3
    assert fast.holding() and ref.holding()
    assert abs(fast.gripper_state().width_m - ref.gripper_state().width_m) <= 1e-5


@pytest.mark.parametrize(
    "friction",
    [0.005, pytest.param(0.0115, marks=pytest.mark.slow)],
    ids=["fast-slip", "slow-slip"],
)
def test_a_slip_that_starts_while_coasting_is_simulated(friction: float) -> None:
    """The fingers' friction drops 6 s into the hold, while the world coasts (the brick's
    weight, 0.49 N, against 2 x 20 N of grip needs 0.012): the coasting world finds the slip at
    its next check and the brick falls out of the jaws onto the pad as in the stepped world.
    Without the checks (coasting through), the brick would still hang in the jaws."""
    ref, fast = lifted_brick(), lifted_brick()
    hold(ref, 15.0, coast=False, slip_at_s=6.0, friction=friction)
    hold(fast, 15.0, coast=True, slip_at_s=6.0, friction=friction)
    assert fast.coast.coasted_steps >= COAST_STEPS  # it was coasting when the slip began
    assert not ref.holding() and not fast.holding()
    # both bricks fell the 51 mm back onto the pad
    z_ref, z_fast = ref.object_pose("brick").z_m, fast.object_pose("brick").z_m
    assert abs(z_fast - z_ref) < 5e-3, (z_ref, z_fast)
    # the check is what catches it: a world that coasts on regardless keeps the brick up
    blind = lifted_brick()
    blind.coast_settled_until(blind.time_s + 20.0)
    run(blind, 2.0)  # settled and coasting
    assert blind.coast.coasted_steps > 0
    slippery(blind, friction)
    for _ in range(1300):  # 13 s with the checks disabled
        blind.coast._left = COAST_STEPS  # never verify
        blind.step(DT)
    assert blind.object_pose("brick").z_m - z_ref > 0.04


def test_coasting_needs_steady_velocities_over_a_window() -> None:
    """The rule itself: steady velocities over VERIFY_STEPS steps start COAST_STEPS coasted
    steps; a velocity that changes by more than STEADY_DV, a moving arm or the end of the
    allowed time stop it."""
    from softpad.sim._mujoco_coast import STEADY_DV, VERIFY_STEPS

    c = HoldCoast(np.array([0, 1]))
    v = np.array([1e-4, -2e-4, 5.0])  # dof 2 is the hand's: ignored
    c.allow(10.0)
    for _ in range(VERIFY_STEPS):
        c.observe(v, 1.0, True)
        assert not c.coasts(1.0, True)
    c.observe(v, 1.0, True)
    assert c.qvel is not None and c.qvel[2] == 0.0 and c.qvel[0] == v[0]
    assert c.coasts(1.0, True) and not c.coasts(1.0, False)  # the arm moves: stop
    c.allow(10.0)
    for k in range(VERIFY_STEPS + 1):  # accelerating by 2 STEADY_DV over the window
        c.observe(v + np.array([2 * STEADY_DV * k / VERIFY_STEPS, 0.0, 0.0]), 1.0, True)
    assert not c.coasts(1.0, True)
    for _ in range(VERIFY_STEPS + 1):
        c.observe(v, 10.0, True)  # past the allowed time
    assert not c.coasts(10.0, True)
