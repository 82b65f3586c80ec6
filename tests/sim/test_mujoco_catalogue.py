"""Every object of the thesis's catalogue rests stably in the MuJoCo world at its placement."""

from __future__ import annotations

import numpy as np
import pytest

from softpad.sim import GRAVITY_M_S2, get_object, object_names
from softpad.sim._mujoco_world import MujocoWorld

pytestmark = pytest.mark.mujoco

#: Force on a module equivalent to t_o = 50 Pa at the box's sealed sensitivity (0.70 kPa/N), N.
T_O_FORCE_N = 50.0 / 700.0

#: Objects whose rigid-body rest differs from the thesis's module list, and why (none: the
#: cylinder's central bead stands 0.45 mm back from its end rims, so that its right-hand
#: modules carry about 0.1 N each, like the analytic world's; docs/make_objects.py).
_KNOWN_DIFFERENT: dict[str, tuple[int, ...]] = {}


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
    low = 0.95 if spec.extra.get("loose_parts") else 1 - 5e-3
    assert (
        weight * low <= loads.sum() <= weight * (1.05 if name in ("cylinder", "limes") else 1.005)
    )
    assert world.object_speed_m_s(name) < 1e-3
    assert world.object_pose(name).tilt_rad < 0.1
    loaded = tuple(int(k) + 1 for k in np.flatnonzero(loads > T_O_FORCE_N))
    assert loaded == _KNOWN_DIFFERENT.get(name, tuple(spec.expected_modules))
