"""Coasting while only the hand moves (MujocoWorld.coast_free_hand,
softpad.sim._mujoco_clearance): the clearance is a lower bound of the hand's true distance to
every other geom, a descent coasts while the hand is clear and still touches down when and
where the fully stepped world does."""

from __future__ import annotations

import math

import numpy as np
import pytest
from mujoco_steps import At, X, Y, run

from softpad.sim import GripperState
from softpad.sim._mujoco_clearance import CLEARANCE_MARGIN_M
from softpad.sim._mujoco_model import MujocoGripper, ObjectModel, ObjectPart
from softpad.sim._mujoco_world import MujocoWorld

pytestmark = pytest.mark.mujoco


def brick_on_pad(brick: bool = True) -> MujocoWorld:
    """A 50 g Duplo 2x2 brick set down on the pad and settled (none: ``brick`` False), the
    6/2 jaws open 60 mm high above it."""
    world = MujocoWorld(gripper=MujocoGripper(mounting="6/2"))
    if brick:
        part = ObjectPart("box", 0.05, (0, 0, 0.0155), size_m=(0.031,) * 3)
        world.place_object(ObjectModel("brick", (part,)), At(X, Y))
    world.command_gripper(GripperState(X, Y, 0.06, 0.0, 0.06), 0.2)
    run(world, 2.0)
    return world


def true_distance_m(world: MujocoWorld) -> float:
    """MuJoCo's own distance from the hand's collidable geoms to every other collidable geom
    (the table plane left out: the pad's base lies on it)."""
    import mujoco

    s = world.scene
    m, d = s.model, s.data
    mujoco.mj_forward(m, d)
    hand = [g for g in range(m.ngeom) if m.body_rootid[m.geom_bodyid[g]] == s.hand_body]
    other = [
        g
        for g in range(m.ngeom)
        if m.body_rootid[m.geom_bodyid[g]] != s.hand_body and m.geom_type[g] != 0
    ]
    fromto = np.zeros(6)
    return min(mujoco.mj_geomDistance(m, d, a, b, 1.0, fromto) for a in hand for b in other)


@pytest.mark.parametrize("z_m", [0.06, 0.045, 0.036])
def test_clearance_is_a_lower_bound_of_the_true_distance(z_m: float) -> None:
    from softpad.sim._mujoco_clearance import HandClearance

    world = brick_on_pad()
    world.command_gripper(GripperState(X, Y, z_m, 0.0, 0.06), 0.2)
    run(world, 0.5)
    s = world.scene
    clearance = HandClearance(s.model, s.hand_body)
    true = true_distance_m(world)
    clearance.update(s.data, s.qpos[s.hand_q])
    # a bound: never more than the truth; informative: within 8 mm of it (boxes around the
    # fingers' and soles' geoms)
    assert true - 8e-3 <= clearance.clearance_m <= true + 1e-9
    # the hand's travel since the update is taken off
    hand = np.array(s.qpos[s.hand_q], dtype=float)
    assert clearance.clear(hand) == (clearance.clearance_m > CLEARANCE_MARGIN_M)
    hand[2] -= clearance.clearance_m
    assert not clearance.clear(hand)


def descend_onto_pad(free: bool) -> tuple[MujocoWorld, int]:
    """The open jaws descend onto the empty, settled pad at 0.05 m/s until the fingertips are
    2 mm below the module tops' rest height; the world coasts while the hand is clear when
    ``free`` (a brick on the pad jitters by 1e-4 rad/s here, too much to coast: the pad's
    module tops alone settle). Returns the world and the steps it coasted."""
    world = brick_on_pad(brick=False)
    world.reset_touch()
    world.coast_free_hand(free)
    world.coast_settled_until(math.inf if free else None)
    before = world.coast.coasted_steps
    world.command_gripper(GripperState(X, Y, -0.002, 0.0, 0.06), 0.05)
    run(world, 1.6)
    world.coast_free_hand(False)
    world.coast_settled_until(None)
    return world, world.coast.coasted_steps - before


def test_descent_coasts_while_clear_and_touches_down_as_stepped() -> None:
    stepped, none = descend_onto_pad(False)
    coasted, n = descend_onto_pad(True)
    assert none == 0
    assert n >= 250  # at least one coasting window while the hand was clear
    # the touch is found from real steps in both (the coasting stopped 3 mm before it)
    assert stepped.first_touch_s is not None and coasted.first_touch_s is not None
    assert abs(coasted.first_touch_s - stepped.first_touch_s) <= 2 * stepped.timestep_s
    assert stepped.first_touch_z_m is not None and coasted.first_touch_z_m is not None
    assert abs(coasted.first_touch_z_m - stepped.first_touch_z_m) <= 2e-4
    # the module tops end where the stepped world has them (0.1 mm) and carry its loads
    q = stepped.scene.module_q
    np.testing.assert_allclose(coasted.scene.qpos[q], stepped.scene.qpos[q], atol=1e-4)
    np.testing.assert_allclose(coasted.module_loads_n(), stepped.module_loads_n(), atol=0.05)
