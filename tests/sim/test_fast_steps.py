"""The MuJoCo world's compiled steps (src/softpad/sim/_fastworld.c, softpad.sim._mujoco_fast)
give the same world as the Python path, bit for bit, step by step through a grasp: placing,
descending (first touch), closing, lifting, a coasted hold, releasing and resting still, with
the box's heights and pressure changing every sample."""

from __future__ import annotations

import math

import numpy as np
import pytest
from mujoco_steps import DT, At, X, Y

import softpad.sim._mujoco_world as mujoco_world
from softpad.sim import GripperState
from softpad.sim._mujoco_model import MujocoGripper, ObjectModel, ObjectPart
from softpad.sim._mujoco_world import MujocoWorld
from softpad.trials import run_trial

pytestmark = pytest.mark.mujoco
fast = pytest.importorskip("softpad.sim._fastworld", reason="not built (make ext)")


def state(world: MujocoWorld) -> list[bytes]:
    """Everything the world's steps change, as bytes (bit-for-bit comparison)."""
    s, c = world.scene, world.coast
    d = s.data
    arrays = [d.qpos, d.qvel, d.act, d.qacc_warmstart, s.model.qpos_spring, world.module_loads_n()]
    out = [np.asarray(a, dtype=float).tobytes() for a in arrays]
    out.append(
        np.array([d.time, world.time_s, c.coasted_steps, c.armed, world.rested_steps]).tobytes()
    )
    touch = (world.first_touch_s, world.first_touch_z_m, world.tip_hit_object)
    out.append(repr((touch, world.gripper_state(), world.holding())).encode())
    return out


class Box:
    """Heights and pressure as a box hands them over, changing every sample."""

    def __init__(self) -> None:
        self.k = 0
        self.changing = True

    def step(self, world: MujocoWorld, seconds: float) -> None:
        for _ in range(round(seconds / DT)):
            self.k += 1 if self.changing else 0
            heights = 0.012 + 0.001 * np.sin(0.05 * self.k + np.arange(6))
            world.set_operating_pressure(2000.0 + 500.0 * math.sin(0.03 * self.k))
            world.step(DT, heights)


def grasp(world: MujocoWorld, seconds_per_move: float = 1.5) -> list[list[bytes]]:
    """A grasp of a brick in the pad's middle; the world's state after every sample."""
    box, states = Box(), []

    def move(z_m: float, width_m: float, speed_m_s: float, seconds: float) -> None:
        world.command_gripper(GripperState(X, Y, z_m, 0.0, width_m), speed_m_s)
        for _ in range(round(seconds / DT)):
            box.step(world, DT)
            states.append(state(world))

    part = ObjectPart("box", 0.05, (0, 0, 0.0155), size_m=(0.031,) * 3)
    world.place_object(ObjectModel("brick", (part,)), At(X, Y))
    world.coast_free_hand(True)
    world.coast_settled_until(1e9)
    move(0.06, 0.05, 0.2, 1.5)  # lowered onto the pad, then the hand comes over it
    world.reset_touch()
    move(0.009, 0.05, 0.05, seconds_per_move)  # the descent: a tip's first touch
    box.changing = False  # the box's heights settle (the hold can coast)
    move(0.009, 0.0, 0.05, seconds_per_move)  # closing on the brick
    move(0.06, world.gripper_state().width_m, 0.1, seconds_per_move)  # the lift
    move(0.06, world.gripper_state().width_m, 0.1, 4.0)  # the hold: coasted windows
    world.coast_settled_until(None)
    move(0.009, 0.05, 0.05, seconds_per_move)  # set down and released
    world.rest_while_still(True)
    move(0.009, 0.05, 0.05, 0.5)  # held still (a trial's valve check)
    return states


def test_the_compiled_steps_give_the_python_worlds_state_bit_for_bit() -> None:
    py = MujocoWorld(gripper=MujocoGripper(mounting="6/2"))
    py.compiled_steps(False)
    compiled = MujocoWorld(gripper=MujocoGripper(mounting="6/2"))
    assert compiled._fast is not None and py._fast is None
    a, b = grasp(py), grasp(compiled)
    assert len(a) == len(b) > 500
    for k, (sa, sb) in enumerate(zip(a, b, strict=True)):
        assert sa == sb, f"the worlds differ after sample {k}"
    # the scene went through what the compiled loop hands back to Python
    assert compiled.first_touch_s is not None and compiled.coast.coasted_steps > 100
    assert compiled.holding() is False and compiled.rested_steps > 100


def test_the_compiled_steps_run_most_steps(monkeypatch: pytest.MonkeyPatch) -> None:
    """The Python step is not taken where the compiled loop can run (a world that falls back
    to Python everywhere would pass the equality test above)."""
    world = MujocoWorld(gripper=MujocoGripper(mounting="6/2"))
    calls: list[int] = []
    real = MujocoWorld._mj_step

    def counted(self: MujocoWorld, ts: float, arm_still: bool) -> None:
        calls.append(1)
        real(self, ts, arm_still)

    monkeypatch.setattr(MujocoWorld, "_mj_step", counted)
    grasp(world, seconds_per_move=1.0)
    total = round(world.time_s / world.timestep_s)
    assert len(calls) < 0.15 * total, (len(calls), total)


def test_a_trial_is_the_same_with_and_without_the_compiled_steps(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """A whole simulated trial (object-3, seed 0 trial 0) gives the same result in every field
    with the compiled steps and weighting as with Python and NumPy only."""
    import softpad.sim._response as response
    from softpad.sim import get_object
    from softpad.trials._runner import trial_seed

    seed = trial_seed(0, "object-3", 0)
    on, _ = run_trial(get_object("object-3"), 0, seed)
    monkeypatch.setattr(mujoco_world, "FAST_STEPS_BUILT", False)
    monkeypatch.setattr(response, "_fastworld", None)
    off, _ = run_trial(get_object("object-3"), 0, seed)
    assert on.success is not None
    fields = [f for f in vars(on) if f != "wall_time_s"]
    assert [repr(getattr(on, f)) for f in fields] == [repr(getattr(off, f)) for f in fields]


def test_the_compiled_steps_can_be_switched_off_and_named_when_missing(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    world = MujocoWorld()
    world.compiled_steps(False)
    assert world._fast is None
    world.compiled_steps(True)
    assert world._fast is not None
    monkeypatch.setattr(mujoco_world, "FAST_STEPS_BUILT", False)
    with pytest.raises(Exception, match="make ext"):
        world.compiled_steps(True)
    assert MujocoWorld()._fast is None


@pytest.mark.parametrize(
    "kwargs",
    [{}, {"line_gain": 1.0}, {"seam_width_m": 0.0}, {"seam_width_m": 0.01, "line_gain": 2.5}],
)
def test_the_compiled_cast_weighting_gives_numpys_factors_bit_for_bit(kwargs: dict) -> None:
    """The cast pad's equivalent-load factors (PadResponse.point_factors) in compiled code
    equal NumPy's, bit for bit: random points over and off the pad, the table's nodes and its
    edges, the chambers' borders, at pressures inside, between and beyond the table's."""
    from softpad.sim._response import PadResponse

    r = PadResponse(**kwargs)
    assert r.pad_model == "cast" and r.cast is not None
    rng = np.random.default_rng(7)
    pts = rng.uniform(-0.01, 0.145, size=(1500, 2))
    scale = r.layout.pitch_m / r.cast.pitch_m
    nodes = np.stack(np.meshgrid(r.cast.x_axis_m, r.cast.y_axis_m[::7]), axis=-1).reshape(-1, 2)
    borders = r.module_centers_m() + 0.5 * r.chamber_side_m
    pts = np.concatenate([pts, nodes * scale, borders, [[0.0, 0.0], [np.nextafter(0, -1), 0.0]]])
    modules = rng.integers(0, r.layout.n_modules, size=len(pts))
    for pressure in (0.0, 1234.5, 2000.0, 1e5):
        r.compiled = False
        want = r.point_factors(modules, pts, pressure)
        r.compiled = True
        got = r.point_factors(modules, pts, pressure)
        assert got.tobytes() == want.tobytes(), pressure
        assert np.count_nonzero(want) > 0.5 * want.size


def test_the_compiled_weighting_of_a_periods_steps_gives_numpys_loads_bit_for_bit() -> None:
    """ContactSensing's weighting of a sample period's steps (each step's forces times the
    cast pad's factors, summed over its contacts in order, added up step by step) in compiled
    code equals NumPy's, bit for bit, for periods of 1-12 steps of 1-40 contacts each."""
    from softpad.sim._mujoco_contacts import ContactSensing
    from softpad.sim._response import PadResponse

    r = PadResponse(line_gain=2.0)
    rng = np.random.default_rng(3)
    for period in range(40):
        steps = []
        for _ in range(int(rng.integers(1, 13))):
            n = int(rng.integers(1, 41))
            ks = rng.integers(0, 6, size=n).tolist()
            fs = (rng.uniform(0.0, 5.0, size=n) * 10.0 ** rng.integers(-4, 2, size=n)).tolist()
            xy = rng.uniform(-0.005, 0.14, size=(n, 2)).tolist()
            steps.append((ks, fs, xy))
        loads = []
        pressure = float(rng.uniform(0.0, 4000.0))
        for compiled in (False, True):
            r.compiled = compiled
            sensing = ContactSensing(6, 0.1, r)
            sensing.pressure_pa = pressure
            sensing.add_steps([(list(a), list(b), [list(q) for q in c]) for a, b, c in steps], 1, 0)
            loads.append(sensing.mean_loads())
        assert loads[0] is not None and loads[1] is not None
        assert loads[1].tobytes() == loads[0].tobytes(), period
        assert np.count_nonzero(loads[0]) >= 3
