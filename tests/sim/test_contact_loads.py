"""The MuJoCo world's module loads, read from MuJoCo's contact arrays and weighted once per
sample period (issue 38), equal those of the plain per-step computation: every contact's
``mj_contactForce`` normal, weighted by the FEM response at the step's pressure, per-step
loads summed and averaged over the period."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("mujoco")

from softpad.sim import Placement, get_object
from softpad.sim._mujoco_contacts import ContactSensing
from softpad.sim._mujoco_world import MujocoWorld

pytestmark = pytest.mark.mujoco


def _reference_loads(sensing: ContactSensing, scene) -> tuple[np.ndarray, np.ndarray]:
    """One step's equivalent loads and plain normal forces the plain way (a contact at a
    time, as before issue 38)."""
    import mujoco

    d, m = scene.data, scene.model
    n = sensing._n
    ks, fs, pts = [], [], []
    force = np.zeros(6)
    for i in range(d.ncon):
        c = d.contact[i]
        g1, g2 = int(c.geom1), int(c.geom2)
        gm = scene.geom_module
        k = gm[g1] if gm[g1] >= 0 else gm[g2]
        if k >= 0:
            mujoco.mj_contactForce(m, d, i, force)
            ks.append(int(k))
            fs.append(abs(force[0]))
            pts.append(c.pos[:2].copy())
    if not ks:
        return np.zeros(n), np.zeros(n)
    k, f = np.array(ks), np.array(fs)
    plain = np.bincount(k, weights=f, minlength=n).astype(float)
    shares = sensing.response.point_factors(k, np.array(pts), sensing.pressure_pa)
    return (f[:, None] * shares).sum(axis=0), plain


@pytest.mark.parametrize("name", ["charger", "banana"])
def test_period_loads_equal_the_per_step_computation(name: str, monkeypatch) -> None:
    world = MujocoWorld()
    # the Python steps, whose update is checked step by step here (the compiled steps give the
    # same world: tests/sim/test_fast_steps.py)
    world.compiled_steps(False)
    spec = get_object(name)
    world.place_object(spec, Placement(spec.placement.x_m, spec.placement.y_m))
    steps: list[np.ndarray] = []
    plain: list[np.ndarray] = []
    update = ContactSensing.update

    def checked(self, s, *args):  # the reference loads of every MuJoCo step, as it happens
        update(self, s, *args)
        loads, forces = _reference_loads(self, s)
        steps.append(loads)
        plain.append(forces)

    monkeypatch.setattr(ContactSensing, "update", checked)
    compared = 0
    for period in range(60):
        if period == 30:
            world.set_operating_pressure(1500.0)  # a new pressure between periods
        steps.clear()
        world.step(1e-2)
        want = sum(steps, np.zeros(len(steps[0]))) / len(steps)
        np.testing.assert_allclose(world.module_loads_n(), want, rtol=1e-12, atol=1e-12)
        np.testing.assert_allclose(world.module_forces_n(), plain[-1], rtol=1e-12, atol=1e-12)
        compared += int(want.any())
    assert compared >= 30  # the object rested on the pad: loads were compared, not zeros
