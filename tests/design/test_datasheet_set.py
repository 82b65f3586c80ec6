"""The third held-out object set (datasheet-eval): sources, fit on the pad, mountings, physics.

Nothing here plans or grasps: the set is for evaluation only (docs/planner.md), so the tests
check what the set is, not how a planner does on it.
"""

from __future__ import annotations

import math
import tomllib
from importlib import resources

import numpy as np
import pytest

from softpad import thesis
from softpad.design import example_object_set, object_set_from_dict
from softpad.errors import InputError
from softpad.trials._geometry import ANYWHERE_OVERHANG_M, anywhere_placement, footprint_box_m

SET = example_object_set("datasheet-eval")
RAW = tomllib.loads(
    resources.files("softpad")
    .joinpath("data", "object_sets", "datasheet-eval.toml")
    .read_text(encoding="utf-8")
)
PAD_M = (
    thesis.PROTOTYPE_COLS * thesis.MODULE_PITCH_M,
    thesis.PROTOTYPE_ROWS * thesis.MODULE_PITCH_M,
)
NAMES = [o.name for o in SET.objects]
#: The margin between the narrowest side and the mounting's widest opening (make_eval_objects).
MARGIN_M = 0.010


def test_the_set_has_ten_objects_each_with_its_source() -> None:
    assert len(SET.objects) == 10 and len(set(NAMES)) == 10
    for entry in RAW["object"]:
        assert len(entry.get("source", "")) > 40, entry["name"]  # a document and its figures


@pytest.mark.parametrize("name", NAMES)
def test_every_object_fits_the_pad_anywhere(name: str) -> None:
    """Placed for 20 seeds, the footprint stays on the pad (5 mm of overhang) and its centre
    keeps off the pad's centre (the rule of issue 45's placements)."""
    obj = next(o for o in SET.objects if o.name == name)
    assert obj.placement == "anywhere"
    w, h = PAD_M
    m = ANYWHERE_OVERHANG_M + 1e-9
    for seed in range(20):
        x, y, yaw = anywhere_placement(obj.spec, seed, PAD_M)
        x0, x1, y0, y1 = footprint_box_m(obj.spec, yaw)
        assert -m <= x + x0 and x + x1 <= w + m, (seed, x, x0, x1)
        assert -m <= y + y0 and y + y1 <= h + m, (seed, y, y0, y1)


@pytest.mark.parametrize("name", NAMES)
def test_every_object_has_the_narrowest_mounting_that_closes_across_it(name: str) -> None:
    obj = next(o for o in SET.objects if o.name == name)
    x0, x1, y0, y1 = footprint_box_m(obj.spec, 0.0)
    narrow = min(x1 - x0, y1 - y0)
    fits = [
        k
        for k, (hi, lo) in sorted(
            thesis.GRIPPER_MOUNTINGS_M.items(), key=lambda kv: kv[1][0]
        )  # narrowest opening first
        if lo < narrow and narrow + MARGIN_M <= hi + 1e-9
    ]
    assert fits and obj.spec.gripper == fits[0], (narrow, fits)


@pytest.mark.parametrize("name", NAMES)
def test_every_object_weighs_more_than_the_pad_can_miss(name: str) -> None:
    """At least 20 g: well above the selection rule's 5 g and the pad's minimum detectable mass
    (thesis about 6 g, the FEM 9.4 g at 1.1 kPa); the lightest is the 24 g squash ball."""
    obj = next(o for o in SET.objects if o.name == name)
    assert obj.spec.mass_kg >= 0.020


@pytest.mark.mujoco
@pytest.mark.parametrize("name", NAMES)
def test_every_object_comes_to_rest_on_the_pad(name: str) -> None:
    """In the MuJoCo world, put down where four modules meet: within 1.5 s it lies still on
    the pad, inside its edges and no higher than its own height above the module tops, and
    the modules feel it (at least 30 % of its weight: the seams between chambers carry the
    rest of what lies on them). The world accepts spheres, standing and lying cylinders and
    boxes of the set."""
    from softpad.sim import MujocoWorld, Placement

    obj = next(o for o in SET.objects if o.name == name)
    world = MujocoWorld()
    world.place_object(obj.spec, Placement(PAD_M[0] / 2, PAD_M[1] / 2, 0.3))
    for _ in range(750):
        world.step(2e-3)
    pose = world.object_pose(name)
    assert world.object_speed_m_s(name) < 0.01
    assert 0 <= pose.x_m <= PAD_M[0] and 0 <= pose.y_m <= PAD_M[1]
    assert -0.01 <= pose.z_m <= 0.02
    assert float(np.sum(world.module_loads_n())) >= 0.3 * obj.spec.mass_kg * 9.81


def _one(**entry: object) -> object:
    doc = {"schema": "softpad-object-set/1", "object": [{"name": "x", "mass_g": 50, **entry}]}
    return object_set_from_dict(doc).objects[0].spec.parts[0]


def test_a_sphere_rests_on_its_lowest_point() -> None:
    part = _one(shape="sphere", diameter_mm=40)
    assert part.shape == "sphere" and part.radius_m == pytest.approx(0.02)
    assert part.pos_m == pytest.approx((0.0, 0.0, 0.02))


def test_a_standing_cylinder_stands_on_its_end_face() -> None:
    part = _one(shape="cylinder", diameter_mm=76.2, length_mm=25.4, standing=True)
    assert part.axis == "z" and part.pos_m[2] == pytest.approx(0.0127)
    lying = _one(shape="cylinder", diameter_mm=76.2, length_mm=25.4)
    assert lying.axis == "x" and lying.pos_m[2] == pytest.approx(0.0381)


@pytest.mark.parametrize(
    ("entry", "message"),
    [
        ({"shape": "cylinder", "diameter_mm": 30, "length_mm": 50, "standing": "yes"}, "standing"),
        ({"shape": "cone", "diameter_mm": 30}, "'box', 'cylinder' or 'sphere'"),
        ({"shape": "sphere", "diameter_mm": 0.04}, "metres given as millimetres"),
    ],
    ids=["standing-not-bool", "unknown-shape", "sphere-in-metres"],
)
def test_bad_shapes_are_named(entry: dict, message: str) -> None:
    with pytest.raises(InputError, match=message):
        _one(**entry)


def test_sphere_volume_sanity() -> None:
    """The densities the sources imply are those of the materials (0.3-2 g/cm^3: hollow rubber
    0.7, cork and leather 0.8, solid rubber 1.1, phenolic resin 1.7): a check on transcription slips in the set."""
    for o in SET.objects:
        part = o.spec.parts[0]
        if part.shape == "sphere":
            volume_cm3 = 4 / 3 * math.pi * (part.radius_m * 100) ** 3
            assert 0.3 <= o.spec.mass_kg * 1e3 / volume_cm3 <= 2.0, o.name
