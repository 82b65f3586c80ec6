"""Every thesis object, placed by the simulator, is planned as in the seed's Table 6.1.

Loads come from the analytic world (footprints, mass distribution), pressures from the gas
physics of the box; the planner sees only the increments, like on the bench.
"""

from __future__ import annotations

import numpy as np
import pytest

from softpad.box import SimBox
from softpad.planning import plan_grasps
from softpad.sim import (
    AnalyticCharacteristic,
    AnalyticWorld,
    SensorParams,
    get_object,
    object_names,
)

NAMES = list(object_names())


def _increments(name: str) -> np.ndarray:
    world = AnalyticWorld()
    box = SimBox(
        world,
        sensor=SensorParams.ideal(),
        characteristic=AnalyticCharacteristic(),
        initial_pressure_pa=1100.0,
    )
    ref = box.read().pressures_pa[:6].copy()
    world.place_object(get_object(name))
    return box.read_many(3)[-1].pressures_pa[:6] - ref


@pytest.mark.parametrize("name", NAMES, ids=NAMES)
def test_noise_free_plan_matches_table_6_1(name: str) -> None:
    """Within 0.01 module units and the exact theta, on the modules the thesis reports."""
    spec = get_object(name)
    plans = plan_grasps(_increments(name))
    assert len(plans) == 1
    plan = plans[0]
    assert plan.modules == tuple(spec.expected_modules)
    assert spec.table_cog is not None and spec.table_theta is not None
    np.testing.assert_allclose(plan.cog, spec.table_cog, atol=0.01)
    np.testing.assert_allclose(plan.theta, spec.table_theta, atol=1e-9)


@pytest.mark.parametrize("name", NAMES, ids=NAMES)
def test_every_touched_module_clears_t_o_with_margin(name: str) -> None:
    """At least 20 Pa above t_o = 50 Pa, and untouched modules at least 15 Pa below it."""
    d = _increments(name)
    on = np.zeros(6, dtype=bool)
    on[np.array(get_object(name).expected_modules) - 1] = True
    assert (d[on] > 70.0).all(), d
    assert (d[~on] < 35.0).all(), d
