"""A coarser MuJoCo step (``TrialConfig.mujoco_timestep_s``, 3 ms here) against the 2 ms world
the trials run: the contacts' time constant is tied to the step (2 x step, so 6 ms), which
softens every contact by (6/4)^2 = 2.25 in stiffness. A resting object's height and loads and
a squeezed brick lifted with the hand stay put (the bounds are the physical argument of
docs/benchmarks.md, issue 50's fourth round, made executable; each fails if the step outgrows
what the model's springs and servos allow: an object bouncing or popping off the pad, the jaws
sinking into it). What does not stay put is why the trials keep 2 ms: some squeezed objects
never come to rest in the jaws at 3 or 4 ms (the last tests)."""

from __future__ import annotations

import numpy as np
import pytest
from mujoco_steps import move_to, settle

from softpad.errors import InputError
from softpad.layout import PadLayout
from softpad.sim import GripperState, Placement, get_object
from softpad.sim._mujoco_coast import COAST_STEPS, VERIFY_STEPS, HoldCoast
from softpad.sim._mujoco_model import MujocoGripper, ObjectModel, ObjectPart
from softpad.sim._mujoco_world import MujocoWorld
from softpad.trials import TrialConfig

pytestmark = pytest.mark.mujoco

PITCH = PadLayout().pitch_m

#: The coarser MuJoCo step measured here, seconds (the trials' is 2 ms).
COARSE_S = 3e-3
#: A resting object sits this close to where it sits in the 2 ms world, metres: its contacts
#: sink 3-6 um at 2 ms and 7-13 um at 3 ms (the depth goes with the time constant squared;
#: measured 2.5-6 um lower for five catalogue objects), next to the module spring's ~1 mm
#: under an object.
REST_HEIGHT_M = 15e-6
#: Deepest contact of a brick squeezed by the 20 N jaws at 3 ms, metres (0.11 mm at 2 ms,
#: 0.23 mm measured at 3 ms, 0.36 mm at 4 ms); a step beyond the servo's stability would ram
#: the jaws deeper.
SQUEEZE_DEPTH_M = 0.3e-3


def _rested(name: str, timestep_s: float) -> tuple[float, float, float]:
    """Height (mean of the last second), top speed in the last second and the summed module
    loads of catalogue object ``name`` 4 s after being placed on the pad."""
    world = MujocoWorld(timestep_s=timestep_s)
    world.place_object(get_object(name))
    heights, speed = [], 0.0
    for k in range(4000):
        world.step(1e-3)
        if k >= 3000:
            heights.append(world.object_pose(name).z_m)
            speed = max(speed, world.object_speed_m_s(name))
    return float(np.mean(heights)), speed, float(world.module_loads_n().sum())


@pytest.mark.parametrize("name", ["limes", "object-3"])
def test_a_resting_object_sits_where_it_sits_at_2_ms(name: str) -> None:
    z2, _, load2 = _rested(name, 2e-3)
    z3, speed3, load3 = _rested(name, COARSE_S)
    assert abs(z3 - z2) < REST_HEIGHT_M
    assert z3 <= z2  # softer contacts sink, never lift
    np.testing.assert_allclose(load3, load2, rtol=5e-3)  # the weight, carried alike
    assert speed3 < 1e-5  # at rest: no bouncing, no popping off the domes


def _squeezed_and_lifted(timestep_s: float) -> tuple[float, float, bool]:
    """Deepest contact of a 50 g brick squeezed by the 6/2 jaws, its rise when the hand
    lifts by 51 mm, and whether it is carried."""
    world = MujocoWorld(gripper=MujocoGripper(mounting="6/2"), timestep_s=timestep_s)
    x = y = 1.5 * PITCH
    # a 50 g Duplo-sized brick, 31 mm cube
    brick = ObjectModel("brick", (ObjectPart("box", 0.05, (0, 0, 0.0155), size_m=(0.031,) * 3),))
    world.place_object(brick, Placement(x, y, 0.0))
    settle(world, 1.0)
    move_to(world, GripperState(x, y, 0.02, 0.0, 0.05), 0.2, 0.2)
    move_to(world, GripperState(x, y, 0.009, 0.0, 0.05), 0.05, 0.2)
    move_to(world, GripperState(x, y, 0.009, 0.0, 0.0), 0.05, 0.8)
    d = world.scene.data
    depth = -min(float(d.contact.dist[i]) for i in range(d.ncon))
    z0 = world.object_pose("brick").z_m
    move_to(world, GripperState(x, y, 0.06, 0.0, world.gripper_state().width_m), 0.1, 1.0)
    return depth, world.object_pose("brick").z_m - z0, world.holding()


def test_a_squeezed_brick_is_lifted_as_at_2_ms() -> None:
    depth2, rise2, held2 = _squeezed_and_lifted(2e-3)
    depth3, rise3, held3 = _squeezed_and_lifted(COARSE_S)
    assert held2 and held3
    assert depth2 < depth3 < SQUEEZE_DEPTH_M
    assert abs(rise3 - rise2) < 0.2e-3  # no extra slip in the jaws while lifting


@pytest.mark.parametrize(
    ("name", "seed", "trial"), [("toy", 0, 2), ("object-3", 0, 1)], ids=["toy-0-2", "object-3-0-1"]
)
def test_squeezed_objects_come_to_rest_in_the_jaws_at_the_trials_step(
    name: str, seed: int, trial: int
) -> None:
    """Why the trials stay at 2 ms: two of Experiment 2's grasps whose squeezed object never
    comes to rest at a coarser step. At 4 ms the toy (seed 0 trial 2), at 3 ms the Duplo plate
    (seed 0 trial 1) sits between jaws pressing at the full 20 N while the opening swings by
    several millimetres for 20 s (an oscillation of the step, not of the physics): the
    robot's close never ends (``box_fault``). At 2 ms both close in about a second and are
    held. Fails if the trials' default step is made coarser than these grasps allow."""
    from softpad.trials import run_trial, trial_seed

    result, _ = run_trial(get_object(name), trial, trial_seed(seed, name, trial), TrialConfig())
    assert result.cause != "box_fault", result.detail
    assert result.success


@pytest.mark.parametrize(
    ("timestep_s", "verify", "coast"), [(2e-3, 25, 250), (3e-3, 17, 167), (4e-3, 12, 125)]
)
def test_coasting_windows_keep_their_durations(timestep_s: float, verify: int, coast: int) -> None:
    """The hold's verification (0.05 s) and coasting (0.5 s) windows are durations: a coarser
    world checks and coasts over the same simulated time as the 2 ms one did (within a step)."""
    c = HoldCoast(np.array([0]), timestep_s)
    assert (c.verify_steps, c.coast_steps) == (verify, coast)
    half = timestep_s / 2 + 1e-12
    assert abs(c.verify_steps * timestep_s - VERIFY_STEPS * 2e-3) <= half
    assert abs(c.coast_steps * timestep_s - COAST_STEPS * 2e-3) <= half


def test_trials_run_mujoco_at_the_configured_step() -> None:
    """The trial's world takes its step from the configuration (2 ms unless told), and a step
    outside 0.5-5 ms is refused by name."""
    from softpad.trials._loop import _Trial

    for config, step in (
        (TrialConfig(), 2e-3),
        (TrialConfig(mujoco_timestep_s=COARSE_S), COARSE_S),
    ):
        trial = _Trial(get_object("limes"), (0.06, 0.04, 0.0), 1, config, None, None)
        assert trial.world.timestep_s == pytest.approx(step)
        assert abs(trial.world.coast.coast_steps * step - 0.5) <= step / 2
    with pytest.raises(InputError, match="mujoco_timestep_s"):
        TrialConfig(mujoco_timestep_s=0.02)


def test_the_arms_move_says_whether_it_stands_at_rest() -> None:
    """The world's step loop takes the arm's rest from ``move`` (asked once a step): it must be
    ``at_rest()`` after the move, or a moving hand would be coasted or held still."""
    from softpad.sim._mujoco_arm import KinematicArm

    gripper = MujocoGripper(mounting="6/2")
    arm = KinematicArm(np.array([0.05, 0.05, 0.15, 0.0]), gripper.max_width_m)
    assert arm.move(2e-3) and arm.at_rest()
    arm.command((0.05, 0.05, 0.1, 0.0), gripper.max_width_m, 0.0, 0.2, gripper)
    answers = []
    for _ in range(1000):
        answers.append(arm.move(2e-3))
        assert answers[-1] == arm.at_rest()
    assert not answers[0] and answers[-1]  # moving at first, arrived within 2 s
