"""Every object of the thesis's catalogue rests stably in the MuJoCo world at its placement."""

from __future__ import annotations

import numpy as np
import pytest

from softpad.sim import GRAVITY_M_S2, get_object, object_names
from softpad.sim._mujoco_world import MujocoWorld
from softpad.trials._geometry import object_outlines_m

pytestmark = pytest.mark.mujoco

#: Force on a module equivalent to t_o = 50 Pa at the box's sealed sensitivity (0.70 kPa/N), N.
T_O_FORCE_N = 50.0 / 700.0


def _modules_under(name: str) -> set[int]:
    """Modules whose square lies partly under the object's top-view footprint (1 mm grid)."""
    from softpad.trials._geometry import point_in_polygon

    spec, pitch = get_object(name), 0.045
    polys = object_outlines_m(spec, spec.placement)
    under = set()
    for x in np.arange(0.0005, 3 * pitch, 1e-3):
        for y in np.arange(0.0005, 2 * pitch, 1e-3):
            if any(point_in_polygon((x, y), p) for p in polys):
                under.add(int(x // pitch) + 3 * (1 - int(y // pitch)) + 1)
    return under


@pytest.mark.parametrize("name", object_names())
def test_object_rests_on_its_modules(name: str) -> None:
    spec = get_object(name)
    world = MujocoWorld()
    world.place_object(spec)
    for _ in range(1000):
        world.step(1e-3)
    loads = world.module_forces_n()  # plain normal forces (the response weights them later)
    # the pad carries the whole weight: the normal forces sum to it where the object rests on
    # the domes' apexes (0.5 %: solver residual), a little more where it leans on their
    # flanks (the lying cylinder, across the gap between the rows, and the limes, on the
    # domes' edges: 3 %); loose parts may also rest partly on a non-sensitive line between
    # the domes (up to 5 % of their weight)
    weight = spec.mass_kg * GRAVITY_M_S2
    # objects reaching past the modules (the 192 mm banana's ends) rest partly on the rim
    polys = object_outlines_m(spec, spec.placement)
    overhangs = any(((p < 0) | (p > (0.135, 0.09))).any() for p in polys)
    low = 0.95 if spec.extra.get("loose_parts") or overhangs else 1 - 5e-3
    assert (
        weight * low <= loads.sum() <= weight * (1.05 if name in ("cylinder", "limes") else 1.005)
    )
    assert world.object_speed_m_s(name) < 1e-3
    # an object reaching past the pad dips towards the rim, 9 mm below the domes' tops
    assert world.object_pose(name).tilt_rad < (0.15 if overhangs else 0.1)
    # a module is loaded above t_o only where the object lies over it (which modules those
    # are, against the thesis's, is the prediction that docs/trials.md reports)
    loaded = {int(k) + 1 for k in np.flatnonzero(loads > T_O_FORCE_N)}
    assert loaded and loaded <= _modules_under(name)
