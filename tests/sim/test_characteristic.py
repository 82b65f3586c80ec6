"""Module characteristic: analytic fit, tabulated interpolation, file errors, default choice."""

from __future__ import annotations

import json

import numpy as np
import pytest

from softpad import thesis
from softpad.errors import InputError
from softpad.sim import (
    AnalyticCharacteristic,
    ChamberBank,
    ModuleCharacteristic,
    TabulatedCharacteristic,
    default_characteristic,
    default_response,
    sealed_sensitivity_pa_n,
)
from softpad.sim import _characteristic as charmod

G = 9.80665


def test_analytic_meets_the_fem_figures() -> None:
    """V, dV/dp at 1.1 kPa and the sealed rise per newton on the 30 mm patch are the FEM's
    (softpad fem response), h = 9 mm (seed Section 6.3)."""
    c = AnalyticCharacteristic()
    r = default_response()
    i = list(r.pressure_pa).index(1100.0)
    np.testing.assert_allclose(
        c.volume_m3(1100.0, 0.0), r.volume_m3[i] + thesis.CHAMBER_GAP_VOLUME_M3, rtol=2e-3
    )
    np.testing.assert_allclose(c.volume_slope_m3_pa(1100.0, 0.0), r.compliance_m3_pa[i], rtol=2e-3)
    np.testing.assert_allclose(c.height_m(1100.0, 0.0), 9.0e-3, rtol=1e-9)
    fem = r.reference_influence_m3_n[i] * r.sealed_rise_per_newton(1100.0)
    np.testing.assert_allclose(sealed_sensitivity_pa_n(AnalyticCharacteristic()), fem, rtol=0.02)
    assert isinstance(c, ModuleCharacteristic)


def test_analytic_slope_matches_finite_difference() -> None:
    c = AnalyticCharacteristic()
    p = np.array([-200.0, 10.0, 500.0, 1100.0, 2500.0])
    f = np.array([0.0, 0.1, 0.0, 0.3, 1.0])
    h = 1e-3
    fd = (c.volume_m3(p + h, f) - c.volume_m3(p - h, f)) / (2 * h)
    np.testing.assert_allclose(c.volume_slope_m3_pa(p, f), fd, rtol=1e-5)


@pytest.mark.parametrize("pressure_pa", [500.0, 1100.0, 2000.0, 2800.0])
def test_sealed_sensitivity_of_the_fem_table_is_the_fem_response(pressure_pa: float) -> None:
    """The packaged table's sealed rise per newton on its 30 mm patch equals the FEM's
    reciprocity figure s_ref / (dV/dp + gas) within 6 % (the table's chords over 100 Pa rows
    against the exact tangent: 5.4 % at 0.5 kPa where V(p) bends most, < 2 % from 0.9 kPa);
    at 0 N the difference is one-sided, not halved by the table's clamp at F = 0."""
    r = default_response()
    fem = r.reference_influence_m3_n[list(r.pressure_pa).index(pressure_pa)]
    fem *= r.sealed_rise_per_newton(pressure_pa)
    got = sealed_sensitivity_pa_n(default_characteristic(), pressure_pa)
    np.testing.assert_allclose(got, fem, rtol=0.06 if pressure_pa < 900 else 0.02)


def test_sealed_module_keeps_rising_with_the_load() -> None:
    """No saturation (the old 0..3 N table stopped at 3.19 kPa): within the table (to 6 N)
    the rise follows the FEM; beyond it the extra load is carried over the 30 x 30 mm patch,
    1.1 kPa per newton."""
    bank = ChamberBank(1, 1, default_characteristic())
    bank.set_state(np.array([1100.0]))
    closed = np.zeros(1, dtype=bool)
    out = []
    for f in (2.0, 3.0, 4.0, 6.0, 7.0, 9.0):
        bank.step(1e-3, closed, closed, np.array([f]), 0.0, False)
        out.append(bank.pressure_pa[0])
    assert np.all(np.diff(out) > 0)
    # (the membrane around the pressed-flat patch still gives a little: 10 %)
    np.testing.assert_allclose((out[5] - out[4]) / 2.0, 1 / 0.03**2, rtol=0.1)


@pytest.mark.slow
def test_sealed_module_under_newtons_matches_the_fem_sealed_chamber() -> None:
    """3-5 N on the 30 mm patch: the table's gas law against the FEM's own sealed chamber
    (contact with the base solved by the finite elements) within 3 %."""
    from softpad.fem import LoadPatch, sealed_chamber_study

    masses = (0.3, 0.4, 0.5)
    fem = sealed_chamber_study(masses_kg=masses, footprint=LoadPatch.square(0.03))
    bank = ChamberBank(1, 1, default_characteristic())
    bank.set_state(np.array([1100.0]))
    closed = np.zeros(1, dtype=bool)
    for m, rise in zip(masses, fem.delta_pressure_pa, strict=True):
        bank.step(1e-3, closed, closed, np.array([m * G]), 0.0, False)
        np.testing.assert_allclose(bank.pressure_pa[0] - 1100.0, rise, rtol=0.03)


def _table(tmp_path, **override):
    p = np.array([0.0, 1000.0, 2000.0])
    f = np.array([0.0, 0.5])
    # bilinear functions are reproduced exactly by bilinear interpolation
    v = 1e-6 * (1 + 4e-3 * p[:, None] - 1 * f[None, :] + 1e-3 * p[:, None] * f[None, :])
    h = 1e-3 * (2 + 3e-3 * p[:, None] - f[None, :])
    arrays = {
        "pressure_pa": p,
        "load_n": f,
        "volume_m3": v,
        "height_m": h,
        "meta": np.array(json.dumps({"model": "test"})),
    }
    arrays.update(override)
    path = tmp_path / "char.npz"
    np.savez(path, **arrays)
    return path


def test_tabulated_is_exact_on_bilinear_data_and_clamps(tmp_path) -> None:
    c = TabulatedCharacteristic.from_file(_table(tmp_path))
    assert c.meta == {"model": "test"}
    p = np.array([250.0, 1500.0, 1999.0])
    f = np.array([0.1, 0.45, 0.25])
    np.testing.assert_allclose(
        c.volume_m3(p, f), 1e-6 * (1 + 4e-3 * p - 1 * f + 1e-3 * p * f), rtol=1e-12
    )
    np.testing.assert_allclose(c.height_m(p, f), 1e-3 * (2 + 3e-3 * p - f), rtol=1e-12)
    np.testing.assert_allclose(c.volume_slope_m3_pa(p, f), 1e-6 * (4e-3 + 1e-3 * f), rtol=1e-12)
    # load and low pressure clamped; above the last row linear along p (last interval's slope)
    pe = 5000.0 - 1.5 / 0.03**2  # 1.5 N beyond the last column: a pressure on the 30 mm patch
    np.testing.assert_allclose(
        c.volume_m3(5000.0, 2.0), 1e-6 * (1 + 4e-3 * pe - 0.5 + 1e-3 * pe * 0.5), rtol=1e-12
    )
    np.testing.assert_allclose(c.volume_slope_m3_pa(5000.0, 0.5), 1e-6 * (4e-3 + 0.5e-3))
    np.testing.assert_allclose(c.volume_m3(-100.0, -1.0), c.volume_m3(0.0, 0.0))


@pytest.mark.parametrize(
    ("override", "match"),
    [
        ({"volume_m3": np.ones((2, 2))}, "shape"),
        ({"pressure_pa": np.array([0.0, 2000.0, 1000.0])}, "strictly increasing"),
        ({"height_m": np.full((3, 2), np.nan)}, "NaN"),
        ({"volume_m3": -np.ones((3, 2))}, "> 0"),
        ({"meta": np.array("{not json")}, "meta"),
    ],
    ids=["shape", "order", "nan", "negative", "meta"],
)
def test_tabulated_rejects_bad_tables(tmp_path, override, match) -> None:
    with pytest.raises(InputError, match=match):
        TabulatedCharacteristic.from_file(_table(tmp_path, **override))


def test_tabulated_missing_array_and_missing_or_corrupt_file(tmp_path) -> None:
    path = tmp_path / "partial.npz"
    np.savez(path, pressure_pa=np.arange(3.0))
    with pytest.raises(InputError, match="lacks array"):
        TabulatedCharacteristic.from_file(path)
    with pytest.raises(InputError, match="does not exist"):
        TabulatedCharacteristic.from_file(tmp_path / "nope.npz")
    bad = tmp_path / "bad.npz"
    bad.write_bytes(b"not a zip file at all")
    with pytest.raises(InputError, match="not a readable"):
        TabulatedCharacteristic.from_file(bad)


def test_default_uses_the_packaged_table_when_present(tmp_path, monkeypatch) -> None:
    table = _table(tmp_path)
    monkeypatch.setattr(charmod, "packaged_table_path", lambda: table)
    assert isinstance(default_characteristic(), TabulatedCharacteristic)
    monkeypatch.setattr(charmod, "packaged_table_path", lambda: None)
    assert isinstance(default_characteristic(), AnalyticCharacteristic)


def test_bad_analytic_parameter_named() -> None:
    with pytest.raises(InputError, match="effective_area_m2"):
        AnalyticCharacteristic(effective_area_m2=-1.0)


def test_box_runs_on_a_tabulated_characteristic(tmp_path) -> None:
    """A table sampled from the analytic characteristic gives the same sealed increments."""
    from softpad.box import SimBox
    from softpad.sim import AnalyticWorld, SensorParams, get_object

    a = AnalyticCharacteristic()
    p = np.linspace(0.0, 4000.0, 81)
    f = np.linspace(0.0, 3.0, 61)
    pp, ff = np.meshgrid(p, f, indexing="ij")
    path = tmp_path / "table.npz"
    np.savez(
        path, pressure_pa=p, load_n=f, volume_m3=a.volume_m3(pp, ff), height_m=a.height_m(pp, ff)
    )
    tab = TabulatedCharacteristic.from_file(path)

    def increments(char: ModuleCharacteristic) -> np.ndarray:
        world = AnalyticWorld()
        box = SimBox(
            world, sensor=SensorParams.ideal(), characteristic=char, initial_pressure_pa=1100.0
        )
        ref = box.read().pressures_pa[:6].copy()
        world.place_object(get_object("object-4"))
        return box.read_many(3)[-1].pressures_pa[:6] - ref

    np.testing.assert_allclose(increments(tab), increments(a), rtol=0.02, atol=0.5)


def test_fast_path_matches_general_interpolation_on_the_packaged_table() -> None:
    """The gas solver's cached load-column path gives the bilinear values and slopes."""
    from softpad.sim import default_characteristic

    c = default_characteristic()
    assert isinstance(c, TabulatedCharacteristic)
    rng = np.random.default_rng(3)
    for k in range(100):
        p = rng.uniform(-200.0, 4500.0, 6)  # below, inside and above the table
        f = np.zeros(6) if k % 4 == 0 else rng.uniform(-0.5, 3.5, 6)
        v_fast, dv_fast = c.volume_and_slope(p, f)
        v_ref, dv_ref = c._interp(c.volume_m3_table, p, f)
        np.testing.assert_allclose(v_fast, v_ref, rtol=1e-12, atol=1e-18)
        np.testing.assert_allclose(dv_fast, dv_ref, rtol=1e-12, atol=1e-18)
        np.testing.assert_allclose(
            c.height_m(p, f), c._interp(c.height_m_table, p, f)[0], rtol=1e-12, atol=1e-18
        )
