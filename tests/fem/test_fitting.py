"""Fitting recovers known parameters from synthetic data made by the model itself."""

from __future__ import annotations

import numpy as np
import pytest

from softpad.errors import InputError
from softpad.fem import (
    MeshOptions,
    ModuleSetup,
    compare_models,
    fit_material,
    get_material,
    inflation_sweep,
    read_measurements,
)

MESH = MeshOptions(4, 1)
PRESSURES = np.array([500.0, 1000.0, 2000.0, 3000.0])


def synthetic(material) -> np.ndarray:
    return inflation_sweep(
        ModuleSetup(material, mesh=MESH), np.concatenate([[0.0], PRESSURES])
    ).height_m[1:]


def test_fit_recovers_neo_hookean_shear_modulus() -> None:
    truth = get_material("neo-hookean").with_parameters(mu=30e3)
    result = fit_material(PRESSURES, synthetic(truth), "neo-hookean", mesh=MESH, max_evaluations=15)
    np.testing.assert_allclose(result.material.parameters["mu"], 30e3, rtol=2e-3)
    assert result.rmse_m < 1e-6 < result.initial_rmse_m


@pytest.mark.slow
def test_fit_recovers_yeoh_c1_and_c2() -> None:
    truth = get_material("yeoh").with_parameters(c1=20e3, c2=-0.5e3)
    result = fit_material(PRESSURES, synthetic(truth), "yeoh", free=("c1", "c2"), mesh=MESH)
    np.testing.assert_allclose(result.material.parameters["c1"], 20e3, rtol=5e-3)
    np.testing.assert_allclose(result.material.parameters["c2"], -0.5e3, rtol=0.1)
    assert result.rmse_m < 5e-6


def test_compare_ranks_the_generating_model_first() -> None:
    data = synthetic(get_material("yeoh"))
    result = compare_models(PRESSURES, data, ("neo-hookean", "ogden-1", "yeoh"), mesh=MESH)
    assert result.models[0] == "yeoh"
    assert result.rmse_m[0] < 1e-9
    assert np.all(np.diff(result.rmse_m) >= 0)


def test_fit_rejects_unknown_parameters() -> None:
    with pytest.raises(InputError, match="alpha9"):
        fit_material(PRESSURES, PRESSURES * 0, "ogden-1", free=("alpha9",), mesh=MESH)


def test_read_measurements(tmp_path) -> None:
    path = tmp_path / "m.csv"
    path.write_text("pressure_kpa,height_mm\n1.0,8.1\n0.5,6.0\n")
    p, h = read_measurements(path)
    np.testing.assert_allclose(p, [500.0, 1000.0])
    np.testing.assert_allclose(h, [6.0e-3, 8.1e-3])


@pytest.mark.parametrize(
    ("text", "fragment"),
    [
        ("pressure_kpa,height_mm\n1.0,abc\n0.5,6\n", "'abc'"),
        ("pressure,height\n1,2\n", "pressure_kpa,height_mm"),
        ("pressure_kpa,height_mm\n-1,2\n0.5,6\n", "-1.0 kPa"),
        ("pressure_kpa,height_mm\n1,2\n", "need >= 2"),
    ],
    ids=["malformed-number", "missing-columns", "negative-pressure", "too-few-rows"],
)
def test_bad_measurement_files(tmp_path, text: str, fragment: str) -> None:
    path = tmp_path / "bad.csv"
    path.write_text(text)
    with pytest.raises(InputError, match=fragment):
        read_measurements(path)
