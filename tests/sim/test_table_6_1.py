"""The thesis's objects on the simulated pad: increments from the FEM response, plans against
Table 6.1 as a prediction with a stated tolerance.

Loads come from the analytic world (footprints, mass distribution, FEM module response),
pressures from the gas physics of the box; the planner sees only the increments, like on the
bench.
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

NAMES = list(object_names())
#: Largest distance between the simulator's and Table 6.1's centre of grasp, module units.
COG_TOLERANCE = 0.1


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
    """Every module's rise equals the FEM's small-load prediction from the object's contact
    forces, sum of q a s(x) / (dV/dp + gas), within 5 % (the packaged table against the exact
    tangent, and its bending for the heavier loads); the FEM table and the analytic
    characteristic built from the FEM's figures agree within 3 %."""
    d, world = _increments(name, default_characteristic())
    fp = object_footprint(get_object(name), world.surface)
    r, resp = world.response.response, world.response
    idx, local = resp.locate(fp.points_m)
    s = np.where(idx >= 0, r.influence(local, thesis.P0_PA), 0.0)
    squeeze = np.bincount(idx[idx >= 0], (fp.pressure_pa * fp.area_m2 * s)[idx >= 0], minlength=6)
    fem = squeeze * r.sealed_rise_per_newton(thesis.P0_PA)
    np.testing.assert_allclose(d, fem, rtol=0.05, atol=2.0)
    analytic, _ = _increments(name, AnalyticCharacteristic())
    np.testing.assert_allclose(analytic, d, rtol=0.03, atol=2.0)


@pytest.mark.parametrize("name", NAMES, ids=NAMES)
def test_noise_free_plan_against_table_6_1(name: str) -> None:
    """Where the simulator sees the thesis's modules, its plan is within COG_TOLERANCE module
    units and the exact theta of Table 6.1. The cylinder (88.9 g on six modules) is the known
    miss: its right-hand columns rise about 30-40 Pa, below t_o, so only modules 1 and 4 are
    seen (the thesis reports one of five cylinder trials with four modules seen)."""
    spec = get_object(name)
    plans = plan_grasps(_increments(name, default_characteristic())[0])
    assert len(plans) == 1
    plan = plans[0]
    assert set(plan.modules) <= set(spec.expected_modules)
    if plan.modules != tuple(spec.expected_modules):
        assert name == "cylinder"
        return
    assert spec.table_cog is not None and spec.table_theta is not None
    assert float(np.hypot(*(np.asarray(plan.cog) - spec.table_cog))) <= COG_TOLERANCE
    np.testing.assert_allclose(plan.theta, spec.table_theta, atol=1e-9)
