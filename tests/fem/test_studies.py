"""Studies reproduce the thesis's qualitative findings (coarse meshes, few load steps)."""

from __future__ import annotations

import json

import numpy as np
import pytest

from softpad.errors import InputError
from softpad.fem import (
    ATMOSPHERIC_PRESSURE_PA,
    CHARACTERISTIC_PATH,
    MODEL_NAMES,
    MeshOptions,
    ModuleCharacteristic,
    ModuleSetup,
    design_sweep,
    inflation_sweep,
    load_characteristic,
    module_characteristic,
    sealed_chamber_study,
    sensitive_area_study,
    stiffness_study,
)

COARSE = MeshOptions(6, 1)


@pytest.fixture(scope="module")
def heights_at_1kpa() -> dict[str, float]:
    out = {}
    for name in MODEL_NAMES:
        result = inflation_sweep(ModuleSetup(name, mesh=COARSE), [0.0, 500.0, 1000.0])
        out[name] = result.height_at(1000.0)
    return out


def test_yeoh_deforms_more_than_neo_hookean(heights_at_1kpa: dict[str, float]) -> None:
    assert heights_at_1kpa["yeoh"] > 1.05 * heights_at_1kpa["neo-hookean"]


@pytest.mark.parametrize("name", ["ogden-1", "ogden-2"], ids=["ogden-1", "ogden-2"])
def test_both_ogden_sets_largely_overestimate(heights_at_1kpa: dict[str, float], name: str) -> None:
    assert heights_at_1kpa[name] > 1.3 * heights_at_1kpa["neo-hookean"]


@pytest.mark.parametrize("name", ["mooney-rivlin", "varga"], ids=["mooney-rivlin", "varga"])
def test_mooney_rivlin_and_varga_follow_neo_hookean(
    heights_at_1kpa: dict[str, float], name: str
) -> None:
    """Same initial shear modulus (42 kPa); the thesis found a similar trend."""
    np.testing.assert_allclose(heights_at_1kpa[name], heights_at_1kpa["neo-hookean"], rtol=0.02)


def test_inflation_result_outputs(tmp_path) -> None:
    calls: list[tuple[int, int]] = []
    result = inflation_sweep(
        ModuleSetup("neo-hookean", mesh=MeshOptions(3, 1)),
        [0.0, 400.0, 800.0],
        progress=lambda done, total: calls.append((done, total)),
    )
    assert calls == [(1, 3), (2, 3), (3, 3)]
    payload = result.to_json_dict()
    assert list(payload) == ["model", "pressure_kpa", "height_mm"]
    assert payload["pressure_kpa"] == [0.0, 0.4, 0.8]
    assert payload["height_mm"][0] == 0.0
    assert np.all(np.diff(result.height_m) > 0) and np.all(np.diff(result.volume_m3) > 0)
    path = result.to_csv(tmp_path / "h.csv")
    assert path.read_text().splitlines()[0] == "pressure_kpa,height_mm,volume_ml"


@pytest.mark.parametrize(
    ("parameter", "values", "sign"),
    [("thickness", [0.001, 0.002], -1), ("width", [0.040, 0.050], 1)],
    ids=["thicker-deforms-less", "wider-deforms-more"],
)
def test_design_trends(parameter: str, values: list[float], sign: int) -> None:
    result = design_sweep(parameter, values, setups=[ModuleSetup("neo-hookean", mesh=COARSE)])
    assert sign * (result.height_m[0, 1] - result.height_m[0, 0]) > 0.1e-3


@pytest.fixture(scope="module")
def stiffness():
    return stiffness_study(
        ModuleSetup("neo-hookean", mesh=COARSE),
        [500.0, 1400.0, 2800.0],
        forces_n=(0.2, 0.8),
        radius_m=0.01,
    )


def test_stiffness_rises_with_pressure_for_a_light_load(stiffness) -> None:
    k = stiffness.stiffness_n_per_m[:, 0]
    assert np.all(np.diff(k) > 0)
    assert not np.any(stiffness.touches_base[:, 0])


def test_heavy_load_at_low_pressure_touches_the_base_and_stiffens(stiffness) -> None:
    """Thesis Fig. 6.3c: where the layer meets the lower one the stiffness is higher."""
    k = stiffness.stiffness_n_per_m[:, 1]
    assert stiffness.touches_base[0, 1]
    assert not stiffness.touches_base[2, 1]
    assert k[0] > k[1]


def test_stiffness_decreases_with_force_at_high_pressure(stiffness) -> None:
    k = stiffness.stiffness_n_per_m[2]
    assert k[1] < k[0]


def test_sensitive_area_definition() -> None:
    """Half-maximum area of dw/dp on the top face: plausible size, shrinking with the fraction."""
    setup = ModuleSetup("neo-hookean", mesh=COARSE)
    half = sensitive_area_study(setup, [1000.0], fraction=0.5)
    most = sensitive_area_study(setup, [1000.0], fraction=0.9)
    assert 0.015 < half.side_m[0] < 0.045
    assert most.area_m2[0] < half.area_m2[0]
    assert half.centre_response_m3_per_n[0] > 0


@pytest.fixture(scope="module")
def chamber():
    return sealed_chamber_study(
        ModuleSetup("neo-hookean", mesh=COARSE), 1100.0, masses_kg=(0.006, 0.0126, 0.05)
    )


def test_sealed_chamber_satisfies_the_isothermal_gas_law(chamber) -> None:
    pa, vd = ATMOSPHERIC_PRESSURE_PA, chamber.dead_volume_m3
    before = (pa + chamber.initial_pressure_pa) * (chamber.initial_volume_m3 + vd)
    after = (pa + chamber.pressure_pa) * (chamber.volume_m3 + vd)
    np.testing.assert_allclose(after, before, rtol=1e-8)


def test_brick_raises_the_pressure_above_the_thesis_threshold(chamber) -> None:
    """Thesis: the 12.6 g Duplo brick (42 x 31 mm) gives a rise above t_o = 0.05 kPa."""
    assert chamber.delta_pressure_pa[1] > 50.0
    assert np.all(np.diff(chamber.delta_pressure_pa) > 0)


def test_small_load_slope_matches_the_sealed_solve(chamber) -> None:
    np.testing.assert_allclose(
        chamber.delta_pressure_pa[0], chamber.rise_per_kg_pa * 0.006, rtol=0.03
    )


def test_minimum_detectable_mass_is_grams(chamber) -> None:
    """Thesis: about 6 g at 1.1 kPa; the model gives the same order with t_o = 50 Pa."""
    m = chamber.min_detectable_mass_kg(50.0)
    assert 0.003 < m < 0.02
    np.testing.assert_allclose(chamber.min_detectable_mass_kg(100.0), 2 * m, rtol=1e-12)
    with pytest.raises(InputError, match="-1"):
        chamber.min_detectable_mass_kg(-1.0)


def test_tiny_characteristic_table_and_round_trip(tmp_path) -> None:
    table = module_characteristic(
        ModuleSetup(mesh=MeshOptions(4, 1)), pressures_pa=[0.0, 1000.0], loads_n=[0.0, 0.3]
    )
    assert table.volume_m3.shape == (2, 2) and table.height_m.shape == (2, 2)
    gap = table.meta["gap_volume_m3"]
    assert gap == 0.2e-6
    np.testing.assert_allclose(table.volume_m3[0], gap, atol=1e-9)
    assert table.volume_m3[1, 0] > table.volume_m3[1, 1] > gap
    assert table.height_m[1, 0] > table.height_m[1, 1]
    path = table.to_npz(tmp_path / "c.npz")
    back = ModuleCharacteristic.from_npz(path)
    np.testing.assert_array_equal(back.volume_m3, table.volume_m3)
    assert back.meta["source"] == "softpad fem characteristic"
    np.testing.assert_allclose(back.volume_at(1000.0, 0.3), table.volume_m3[1, 1])
    np.testing.assert_allclose(
        back.volume_at(500.0, 0.0), 0.5 * (table.volume_m3[1, 0] + gap), rtol=1e-12
    )


def test_corrupt_characteristic_file_is_an_input_error(tmp_path) -> None:
    bad = tmp_path / "bad.npz"
    bad.write_bytes(b"not a zip")
    with pytest.raises(InputError, match=r"bad\.npz"):
        ModuleCharacteristic.from_npz(bad)
    with pytest.raises(InputError, match="does not exist"):
        ModuleCharacteristic.from_npz(tmp_path / "missing.npz")


def test_shipped_characteristic_file() -> None:
    """The file the simulator reads: layout, ranges, physics, size."""
    assert CHARACTERISTIC_PATH.stat().st_size < 200_000
    with np.load(CHARACTERISTIC_PATH, allow_pickle=False) as data:
        assert set(data.files) == {"pressure_pa", "load_n", "volume_m3", "height_m", "meta"}
        meta = json.loads(str(data["meta"]))
    for key in ("model", "thickness_m", "width_m", "load_patch", "source", "version"):
        assert key in meta
    table = load_characteristic()
    p, f = table.pressure_pa, table.load_n
    # to 5 kPa and 6 N: a gripper pressing an object into a sealed module stays in the FEM data
    assert p[0] == 0.0 and p[-1] == 5000.0 and f[0] == 0.0 and f[-1] >= 6.0
    assert table.volume_m3.shape == (p.size, f.size)
    # volume grows with pressure and shrinks with load; once the layer is pressed flat on the
    # base, micron-sized pockets beside the patch change by a few uL, hence 0.01 mL tolerance
    assert np.all(np.diff(table.volume_m3[:, 0]) > 0)
    assert np.all(np.diff(table.volume_m3, axis=1) < 1e-8)
    inflated = table.pressure_pa >= 1000.0
    light = table.load_n <= 0.5
    assert np.all(np.diff(table.volume_m3[np.ix_(inflated, light)], axis=1) < 0)
    # issue 5 scale: ~8 mL under the layer and ~8.3 mm at 1.1 kPa, ~3.8 mL per kPa
    np.testing.assert_allclose(table.height_at(1100.0), 8.3e-3, rtol=0.05)
    np.testing.assert_allclose(table.volume_at(1100.0), 8.0e-6, rtol=0.1)
    # strictly positive volumes (residual gap), as the simulator's sealed-gas model needs
    assert table.volume_m3.min() >= meta["gap_volume_m3"] > 0


@pytest.mark.slow
@pytest.mark.parametrize("name", MODEL_NAMES, ids=MODEL_NAMES)
def test_every_preset_converges_from_0_to_3_kpa(name: str) -> None:
    """Issue 5: with the thesis's forms every model inflates monotonically to 3 kPa."""
    result = inflation_sweep(
        ModuleSetup(name, mesh=MeshOptions(4, 1)), [0.0, 1000.0, 2000.0, 3000.0]
    )
    assert np.all(np.diff(result.height_m) > 0)
    assert np.all(np.diff(result.volume_m3) > 0)
