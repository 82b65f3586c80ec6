"""The finite-element response of a design's module at p0."""

from __future__ import annotations

import pytest

from softpad.design import FemResponse, fem_response
from softpad.design._response import GRAVITY_M_S2

pytestmark = pytest.mark.fem


@pytest.fixture(scope="module")
def thesis_response() -> FemResponse:
    return fem_response(0.045, 0.0015, "neo-hookean", 1100.0)


def test_height_and_volume_match_the_fem_docs(thesis_response: FemResponse) -> None:
    # docs/fem.md (default mesh): 8.26 mm and 7.72 mL at 1.1 kPa, 3.71 mL/kPa
    r = thesis_response
    assert r.height_m * 1e3 == pytest.approx(8.26, abs=0.02)
    assert r.volume_m3 * 1e6 == pytest.approx(7.72, abs=0.05)
    assert r.compliance_m3_pa * 1e9 == pytest.approx(3.71, abs=0.05)


def test_small_load_slope_matches_the_sealed_equilibrium_solve(
    thesis_response: FemResponse,
) -> None:
    """The linearised rise (one tangent solve) against softpad.fem's sealed-chamber study,
    which solves the nonlinear sealed equilibrium for a 6 g brick: within 3 %."""
    from softpad.fem import LoadPatch, sealed_chamber_study

    study = sealed_chamber_study(
        initial_pressure_pa=1100.0,
        masses_kg=(0.006,),
        footprint=LoadPatch("rectangle", 0.042, 0.031),
    )
    solved_rise_pa = float(study.delta_pressure_pa[0])
    linear_rise_pa = thesis_response.rise_pa_n * 0.006 * GRAVITY_M_S2
    assert linear_rise_pa == pytest.approx(solved_rise_pa, rel=0.03)
    assert thesis_response.min_detectable_mass_kg == pytest.approx(
        study.min_detectable_mass_kg(50.0), rel=1e-6
    )


def test_fitted_characteristic_reproduces_the_sealed_rise(thesis_response: FemResponse) -> None:
    """The simulator's characteristic, fitted at p0, rises per newton as the FEM (1 %)."""
    from softpad.fem import DEFAULT_DEAD_VOLUME_M3
    from softpad.sim import sealed_sensitivity_pa_n

    ch = thesis_response.characteristic()
    sim_rise = sealed_sensitivity_pa_n(ch, 1100.0, tubing_volume_m3=DEFAULT_DEAD_VOLUME_M3)
    assert sim_rise == pytest.approx(thesis_response.rise_pa_n, rel=0.01)
    assert float(ch.height_m(1100.0, 0.0)) == pytest.approx(thesis_response.height_m, rel=1e-9)


def test_sensitivity_map_peaks_at_the_centre(thesis_response: FemResponse) -> None:
    r = thesis_response
    centre = next(
        v for (x, y), v in zip(r.map_xy_m, r.map_rise_pa_n, strict=True) if x == 0 and y == 0
    )
    edge = [
        v
        for (x, y), v in zip(r.map_xy_m, r.map_rise_pa_n, strict=True)
        if max(x, y) >= 0.0225 - 1e-9
    ]
    assert centre == pytest.approx(max(r.map_rise_pa_n))
    assert max(edge) == pytest.approx(0.0, abs=1e-6 * centre)  # clamped edges feel nothing
    assert 0.2 < r.sensitive_fraction < 0.8


def test_thinner_layer_is_taller_and_more_compliant() -> None:
    thin = fem_response(0.045, 0.001, "neo-hookean", 1100.0, cells_in_plane=8)
    thick = fem_response(0.045, 0.0025, "neo-hookean", 1100.0, cells_in_plane=8)
    assert thin.height_m > thick.height_m
    assert thin.compliance_m3_pa > thick.compliance_m3_pa


def test_round_trip_through_the_cache_format(thesis_response: FemResponse) -> None:
    import json

    again = FemResponse.from_dict(json.loads(json.dumps(thesis_response.to_dict())))
    assert again == thesis_response
