"""The module model: plate theory, mesh convergence, volume, reciprocity, contact, errors."""

from __future__ import annotations

import numpy as np
import pytest

from softpad.errors import InputError
from softpad.fem import (
    ConvergenceError,
    LoadPatch,
    MaterialModel,
    MeshOptions,
    ModuleGeometry,
    ModuleModel,
    plate_center_deflection_m,
)

COARSE = MeshOptions(6, 1)


def test_small_pressure_matches_clamped_plate_theory() -> None:
    """w_max = 0.00126 p a^4 / D, D = E t^3 / (12 (1 - nu^2)), E = 3 mu, nu -> 0.5.

    Triquadratic u/p/J hexahedra (no shear or volumetric locking at kappa = 1e5 mu) with one
    cell through the 1.5 mm thickness; the linear theory neglects transverse shear, which
    the solid model includes (about 1 % at a/t = 30), so the tolerance is 2.5 %.
    """
    pressure = 0.05  # Pa: w ~ 5 um << t
    model = ModuleModel("neo-hookean", mesh=MeshOptions(6, 1, "hex27"), contact=False)
    height = model.solve(pressure).height_m
    expected = plate_center_deflection_m(pressure, 0.045, 0.0015, 42e3)
    np.testing.assert_allclose(height, expected, rtol=0.025)


def test_plate_theory_coefficient_by_hand() -> None:
    d = 3 * 42e3 * 0.0015**3 / (12 * (1 - 0.25))
    np.testing.assert_allclose(
        plate_center_deflection_m(1.0, 0.045, 0.0015, 42e3), 0.00126 * 0.045**4 / d, rtol=1e-12
    )


@pytest.mark.slow
def test_centre_height_converges_under_mesh_refinement() -> None:
    """Heights at 1 kPa for 4, 8, 16 cells per quarter side: the differences shrink.

    The rate is modest (about 0.6 per halving) because of the thin bending layer at the
    clamped edge; see docs/fem.md for the full convergence table.
    """
    heights = []
    for n in (4, 8, 16):
        model = ModuleModel("neo-hookean", mesh=MeshOptions(n, 2), contact=False)
        heights.append(model.solve(1000.0).height_m)
    d1, d2 = abs(heights[1] - heights[0]), abs(heights[2] - heights[1])
    assert d2 < 0.8 * d1
    np.testing.assert_allclose(heights[2], heights[1], rtol=0.005)
    # and the converged value is the thesis-scale ~8 mm at 1 kPa (issue: ~8.3 mm at 1.1 kPa)
    np.testing.assert_allclose(heights[2], 7.95e-3, rtol=0.01)


@pytest.fixture(scope="module")
def inflated() -> ModuleModel:
    model = ModuleModel("neo-hookean", mesh=COARSE, load_patch=LoadPatch.square(0.015))
    model.solve(1000.0)
    return model


def test_compliance_from_tangent_matches_volume_difference(inflated: ModuleModel) -> None:
    """dV/dp from the tangent (g . K^-1 g) against a finite difference of the volume."""
    saved = inflated.checkpoint()
    v0 = inflated.volume_m3()
    _, compliance = inflated.pressure_sensitivity(with_compliance=True)
    inflated.solve(1010.0, 0.0)
    v1 = inflated.volume_m3()
    inflated.restore(saved)
    np.testing.assert_allclose(compliance, (v1 - v0) / 10.0, rtol=0.01)


def test_volume_change_of_a_small_load_follows_reciprocity(inflated: ModuleModel) -> None:
    """dV/dF = -(patch-weighted dw/dp) (Maxwell-Betti on the symmetric tangent)."""
    saved = inflated.checkpoint()
    v0 = inflated.volume_m3()
    dwdp = inflated.pressure_sensitivity()[:, 2]
    weights = inflated.load_patch_weights
    np.testing.assert_allclose(weights.sum(), 1.0, rtol=1e-12)
    force = 0.01
    predicted = -force * float(np.dot(weights, dwdp))
    inflated.solve(1000.0, force)
    change = inflated.volume_m3() - v0
    inflated.restore(saved)
    np.testing.assert_allclose(change, predicted, rtol=0.02)


def test_volume_is_a_dome_under_the_layer(inflated: ModuleModel) -> None:
    """Enclosed volume between the base area times the centre height and a third of it."""
    area = 0.045**2
    v = inflated.volume_m3()
    h = inflated.height_m
    assert 0.3 * area * h < v < 0.6 * area * h


def test_load_without_pressure_rests_on_the_base() -> None:
    model = ModuleModel("neo-hookean", mesh=COARSE)
    state = model.solve(0.0, 1.0)
    assert abs(state.height_m) < 1e-5
    assert state.volume_m3 < 1e-9
    assert state.contact_area_m2 > 0.5 * 0.045**2


def test_quarter_model_is_left_right_symmetric_when_mirrored() -> None:
    model = ModuleModel("neo-hookean", mesh=MeshOptions(3, 1), contact=False)
    model.solve(200.0)
    points, cells, disp = model.full_mesh()
    assert cells.shape == (4 * model.mesh.ncells, 8)
    # a point and its mirror image carry mirrored displacements
    i = np.argmax(points[:, 0] + points[:, 1])
    j = np.flatnonzero(np.all(np.isclose(points, points[i] * [-1, -1, 1]), axis=1))[0]
    np.testing.assert_allclose(disp[j], disp[i] * [-1, -1, 1], atol=1e-15)


def test_vtu_file_is_written(tmp_path) -> None:
    import meshio

    model = ModuleModel("neo-hookean", mesh=MeshOptions(3, 1), contact=False)
    model.solve(300.0)
    path = tmp_path / "module.vtu"
    model.write_vtu(str(path))
    mesh = meshio.read(path)
    assert mesh.point_data["displacement"].shape == (len(mesh.points), 3)
    centre_top = np.flatnonzero(np.all(np.isclose(mesh.points, [0.0, 0.0, 0.0015]), axis=1))
    np.testing.assert_allclose(
        mesh.point_data["displacement"][centre_top, 2], model.height_m, rtol=1e-9
    )


def test_pressure_beyond_a_pressure_maximum_raises_naming_the_pressure() -> None:
    """FElupe's Ogden convention (2 mu/alpha^2) read with the thesis's set 1 moduli is far
    softer and its inflation curve has a pressure maximum near 2 kPa (issue 5)."""
    p = {"mu1": 22e3, "mu2": 0.4e3, "mu3": -2e3, "alpha1": 1.3, "alpha2": 5.0, "alpha3": -2.0}
    converted = {**p, **{f"mu{i}": 2 * p[f"mu{i}"] / p[f"alpha{i}"] for i in (1, 2, 3)}}
    material = MaterialModel("ogden-1-felupe-convention", "ogden", converted)
    model = ModuleModel(material, mesh=MeshOptions(3, 1), contact=False)
    with pytest.raises(ConvergenceError, match=r"beyond pressure \d+\.\d Pa") as info:
        model.solve(3000.0)
    assert "3000.0 Pa" in str(info.value)


@pytest.mark.parametrize(
    ("kwargs", "fragment"),
    [
        ({"pressure_pa": -10.0}, "-10.0 Pa"),
        ({"pressure_pa": float("nan")}, "nan"),
        ({"pressure_pa": 100.0, "load_n": -1.0}, "-1.0 N"),
    ],
    ids=["negative-pressure", "nan-pressure", "negative-load"],
)
def test_bad_loads_are_input_errors(kwargs: dict[str, float], fragment: str) -> None:
    model = ModuleModel("neo-hookean", mesh=MeshOptions(2, 1), contact=False)
    with pytest.raises(InputError, match=fragment):
        model.solve(**kwargs)


@pytest.mark.parametrize(
    ("width", "thickness", "fragment"),
    [(0.045, 0.0, "thickness must be > 0"), (0.045, -1e-3, "-0.001"), (0.0, 1e-3, "width")],
    ids=["zero-thickness", "negative-thickness", "zero-width"],
)
def test_bad_geometry_is_an_input_error(width: float, thickness: float, fragment: str) -> None:
    with pytest.raises(InputError, match=fragment):
        ModuleGeometry(width, thickness)


def test_bad_mesh_options_are_input_errors() -> None:
    with pytest.raises(InputError, match="hex20"):
        MeshOptions(4, 1, "hex20")
    with pytest.raises(InputError, match="cells_in_plane"):
        MeshOptions(0, 1)
    with pytest.raises(InputError, match="grading"):
        MeshOptions(4, 1, "hex8", 1.0)
