"""The thesis objects on the analytic world: what the planner makes of their pressures.

Loads come from the analytic world (footprints, mass distribution), pressures from the gas
physics of the box; the planner sees only the increments, like on the bench. The checks are
physical (where a symmetric object's centre is, which side its heavier part is on), not the
stored Table 6.1 values: how the predicted grasps compare with Table 6.1 is reported by
``softpad trials`` (``grasp_difference``) and docs/trials.md, and may differ.
"""

from __future__ import annotations

import numpy as np
import pytest

from softpad import thesis
from softpad.box import SimBox
from softpad.planning import plan_grasps
from softpad.sim import (
    AnalyticCharacteristic,
    AnalyticWorld,
    SensorParams,
    default_characteristic,
    get_object,
    object_footprint,
    object_names,
)

PITCH_M = 0.045
NAMES = list(object_names())


def _plans(name: str) -> list:
    world = AnalyticWorld()
    box = SimBox(world, sensor=SensorParams.ideal(), initial_pressure_pa=1100.0)
    ref = box.read().pressures_pa[:6].copy()
    world.place_object(get_object(name))
    return plan_grasps(box.read_many(3)[-1].pressures_pa[:6] - ref)


def _centre_and_com_units(name: str) -> tuple[np.ndarray, np.ndarray]:
    """The object's footprint centre (its frame's origin, placed) and its centre of mass, in
    module units, pad frame."""
    spec = get_object(name)
    p = spec.placement
    c, s = np.cos(p.yaw_rad), np.sin(p.yaw_rad)
    com = np.array(spec.com_m[:2])
    com_pad = np.array([p.x_m + c * com[0] - s * com[1], p.y_m + s * com[0] + c * com[1]])
    return np.array([p.x_m, p.y_m]) / PITCH_M, com_pad / PITCH_M


@pytest.mark.parametrize("name", ["object-1", "object-2", "object-3", "object-6"])
def test_symmetric_homogeneous_object_is_grasped_at_its_centre(name: str) -> None:
    """Seed, Section 6.3: "Objects 1, 2, 3, and 6 are symmetric and with homogeneous weight,
    thus they were grasped from the middle". Noise-free, the plan's COG lies on the object's
    centre within 0.02 module units (0.9 mm): equal loads either side give the mid-point."""
    plans = _plans(name)
    assert len(plans) == 1
    centre, _ = _centre_and_com_units(name)
    np.testing.assert_allclose(plans[0].cog, centre, atol=0.02)


@pytest.mark.parametrize("name", ["object-4", "object-5"])
def test_cog_moves_towards_the_heavier_part(name: str) -> None:
    """Seed: "For objects 4 and 5 ... the center of grasp is clearly placed closer to the
    heaviest part of the object". The COG lies on the segment from the object's centre towards
    its centre of mass, at least a quarter of the way and not past it by more than 0.1 units."""
    plans = _plans(name)
    assert len(plans) == 1
    centre, com = _centre_and_com_units(name)
    axis = com - centre
    along = float(np.dot(np.asarray(plans[0].cog) - centre, axis) / np.dot(axis, axis))
    assert 0.25 < along < 1.0 + 0.1 / float(np.linalg.norm(axis)), (plans[0].cog, centre, com)


def _increments(name: str, characteristic: object) -> tuple[np.ndarray, AnalyticWorld]:
    world = AnalyticWorld()
    box = SimBox(
        world,
        sensor=SensorParams.ideal(),
        characteristic=characteristic,  # type: ignore[arg-type]
        initial_pressure_pa=1100.0,
    )
    ref = box.read().pressures_pa[:6].copy()
    world.place_object(get_object(name))
    return box.read_many(3)[-1].pressures_pa[:6] - ref, world


@pytest.mark.parametrize("name", NAMES, ids=NAMES)
def test_increments_are_the_fem_response_of_the_footprint(name: str) -> None:
    """Every module's rise equals the cast pad FEM's small-load prediction from the object's
    contact forces, ``(C + diag G) dp = sum q a s_k(x)`` (softpad.fem.sealed_rises_pa, straight
    from the table), within 5 % (the packaged table against the exact
    tangent, and its bending for the heavier loads); the FEM table and the analytic
    characteristic built from the FEM's figures agree within 3 %."""
    from softpad.fem import sealed_rises_pa

    d, world = _increments(name, default_characteristic())
    fp = object_footprint(get_object(name), world.surface)
    cast = world.response.cast
    assert cast is not None and world.response.line_gain == 1.0
    pts = fp.points_m * (cast.pitch_m / thesis.MODULE_PITCH_M)
    fem = sealed_rises_pa(cast, pts, fp.pressure_pa * fp.area_m2, thesis.P0_PA)
    np.testing.assert_allclose(d, np.maximum(fem, 0.0), rtol=0.05, atol=2.0)
    analytic, _ = _increments(name, AnalyticCharacteristic())
    np.testing.assert_allclose(analytic, d, rtol=0.03, atol=2.0)
