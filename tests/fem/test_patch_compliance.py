"""``ModuleModel.patch_load_compliance`` (one tangent solve) against the nonlinear solve of a
small load on the same patch at the same pressure (an independent path: Newton on the full
residual)."""

from __future__ import annotations

import numpy as np
import pytest

from softpad.fem import LoadPatch, MeshOptions, ModuleGeometry, ModuleModel

pytestmark = pytest.mark.fem


@pytest.mark.parametrize("width_m", [0.045, 0.0225])
def test_patch_compliance_matches_a_small_load_solved(width_m: float) -> None:
    patch = LoadPatch("rectangle", 0.010, 0.010)
    model = ModuleModel(
        "neo-hookean",
        geometry=ModuleGeometry(width_m, 0.0015),
        mesh=MeshOptions(cells_in_plane=8),
        load_patch=patch,
        contact=True,
    )
    model.solve(1100.0, 0.0)
    compliance = model.patch_load_compliance(patch)
    w = model.patch_weights(patch)
    before = float(np.dot(w, model.displacement[:, 2]))
    load_n = 0.005  # 0.5 g: small against the centre's stiffness (tenths of N/mm)
    model.solve(1100.0, load_n)
    after = float(np.dot(w, model.displacement[:, 2]))
    assert (before - after) / load_n == pytest.approx(compliance, rel=0.03)
