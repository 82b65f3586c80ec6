"""The FEM module response (softpad/data/module_response.npz) and how the pad reads it."""

from __future__ import annotations

import numpy as np
import pytest

from softpad import thesis
from softpad.errors import InputError
from softpad.fem import DEFAULT_WALL_WIDTH_M
from softpad.layout import PadLayout
from softpad.sim import ModuleResponse, PadResponse, default_response
from softpad.sim._response import operating_pressure, rect_points

R = default_response()


def test_packaged_response_covers_the_usable_range_with_a_converged_mesh() -> None:
    assert R.pressure_pa[0] <= thesis.P0_RANGE_PA[0] and R.pressure_pa[-1] >= thesis.P0_RANGE_PA[1]
    assert R.chamber_side_m == pytest.approx(thesis.CHAMBER_SIDE_M)
    conv = R.meta["convergence"]
    # the default 12 x 12 x 2 mesh against 24 x 24 x 4: every probe within 2 %
    assert conv["largest_difference"] < 0.02
    assert set(conv["probes"]) >= {"10x10 mm at the centre", "10x10 mm, 15 mm off"}


@pytest.mark.parametrize("pressure_pa", [500.0, 1100.0, 1777.0, 2800.0])
def test_influence_is_symmetric_largest_at_the_centre_and_zero_at_the_clamp(
    pressure_pa: float,
) -> None:
    r = np.linspace(0.0, 0.0225, 46)
    along = R.influence(np.column_stack([r, np.zeros_like(r)]), pressure_pa)
    assert np.all(np.diff(along) <= 1e-15)  # falls monotonically from the centre
    assert along[-1] == pytest.approx(0.0, abs=1e-12)
    pts = np.array([[0.004, 0.011], [-0.004, 0.011], [0.011, -0.004], [-0.011, -0.004]])
    v = R.influence(pts, pressure_pa)
    np.testing.assert_allclose(v, v[0], rtol=1e-8)  # x <-> y: to the solver tolerance
    assert R.influence([(0.03, 0.0)], pressure_pa)[0] == 0.0


def test_reference_patch_sampling_matches_the_fems_consistent_load() -> None:
    """The sampled mean over the 30 mm patch against the FEM's own load vector: 3 %."""
    for i, p in enumerate(R.pressure_pa):
        assert R.reference_influence(p) == pytest.approx(R.reference_influence_m3_n[i], rel=0.03)


def test_response_falls_off_as_the_fem_says() -> None:
    """Relative response of a 10 mm block (issue 10: about 0.67 at 13.6 mm, 0.44 at 17.2 mm,
    0.18 at 20.2 mm for a point); a 10 mm block averages over +-5 mm, so within 0.08."""
    p = thesis.P0_PA
    c = R.mean_influence((0, 0), (0.01, 0.01), p)
    got = [R.mean_influence((d, 0), (0.01, 0.01), p) / c for d in (0.0136, 0.0172, 0.0202)]
    np.testing.assert_allclose(got, [0.67, 0.44, 0.18], atol=0.08)


def test_pad_locates_points_in_module_order() -> None:
    pad = PadResponse()
    centres = PadLayout().centers * PadLayout().pitch_m
    np.testing.assert_allclose(pad.module_centers_m(), centres)
    idx, local = pad.locate(centres + 1e-3)
    np.testing.assert_array_equal(idx, np.arange(6))
    np.testing.assert_allclose(local, 1e-3)
    idx, _ = pad.locate([(-0.001, 0.02), (0.2, 0.02)])
    np.testing.assert_array_equal(idx, -1)
    # the cast pad's grid wall (1 mm on its 46 mm pitch, scaled to 45 mm); the clamped
    # modules meet at their edges (thesis.SEAM_WIDTH_M)
    assert pad.seam_width_m == pytest.approx(DEFAULT_WALL_WIDTH_M * 45 / 46)
    assert PadResponse(pad_model="clamped").seam_width_m == pytest.approx(thesis.SEAM_WIDTH_M)


def test_equivalent_load_of_the_reference_patch_is_the_load_itself() -> None:
    """The clamped pad: a load on the characteristic's central patch is its own equivalent
    load, on its own module only."""
    pad = PadResponse(pad_model="clamped")
    c = pad.module_centers_m()[4]
    for p in (500.0, 1100.0, 2800.0):
        eq = pad.rect_equivalent_loads(c, R.reference_patch_m, 1.0, p)
        np.testing.assert_allclose(eq, np.eye(6)[4], atol=1e-9)


@pytest.mark.parametrize("pressure_pa", [500.0, 1100.0, 2800.0])
def test_cast_equivalent_loads_raise_the_chamber_as_the_cast_fem(pressure_pa: float) -> None:
    """The cast pad: the equivalent load on the clamped characteristic's patch raises a sealed
    chamber (at its small-load slope) as much as the load does on the cast FEM's chamber
    alone (1e-4: the patch sampled in the pad's and the model's frames), and a central load passes under 0.5 % to the neighbours."""
    pad = PadResponse(line_gain=1.0)
    c = pad.module_centers_m()[4]
    eq = pad.rect_equivalent_loads(c, R.reference_patch_m, 1.0, pressure_pa)
    slope_cl = R.sealed_rise_per_newton(pressure_pa) * R.reference_influence(pressure_pa)
    cast = pad.cast
    assert cast is not None
    pts = rect_points(c * cast.pitch_m / PadLayout().pitch_m, R.reference_patch_m * 46 / 45)
    s = cast.influence(pts, pressure_pa)[:, 4].mean()
    gas = (
        cast.volumes(pressure_pa)[4] + thesis.CHAMBER_GAP_VOLUME_M3 + thesis.TUBING_VOLUME_M3
    ) / (101325.0 + pressure_pa)
    rise_cast = s / (cast.compliance(pressure_pa)[4, 4] + gas)
    assert eq[4] * slope_cl == pytest.approx(rise_cast, rel=1e-4)
    assert np.abs(np.delete(eq, 4)).max() < 5e-3 * eq[4]


def test_a_pad_of_another_pitch_scales_the_response() -> None:
    pad = PadResponse(PadLayout(3, 3, 0.030))
    assert pad.chamber_side_m == pytest.approx(0.030)
    c = pad.module_centers_m()[4]
    assert pad.pad_model == "clamped"  # no cast response for 3 x 3
    clamped = PadResponse(pad_model="clamped")
    big = clamped.rect_equivalent_loads(clamped.module_centers_m()[4], (0.015, 0.015), 1.0, 1100.0)
    small = pad.rect_equivalent_loads(c, (0.010, 0.010), 1.0, 1100.0)
    assert small[4] == pytest.approx(big[4], rel=1e-2)


def test_rect_points_cover_the_rectangle() -> None:
    pts = rect_points((0.01, 0.02), (0.004, 0.002), np.pi / 2, 0.5e-3)
    assert len(pts) == 8 * 4
    np.testing.assert_allclose(pts.mean(axis=0), (0.01, 0.02), atol=1e-12)
    np.testing.assert_allclose(np.ptp(pts, axis=0), (0.0015, 0.0035), atol=1e-12)


def test_operating_pressure_is_rounded_and_clamped() -> None:
    assert operating_pressure(1123.0, R) == 1100.0
    assert operating_pressure(0.0, R) == R.pressure_pa[0]
    assert operating_pressure(9e3, R) == R.pressure_pa[-1]


def test_round_trip_and_bad_files(tmp_path) -> None:
    path = R.to_npz(tmp_path / "r.npz")
    back = ModuleResponse.from_file(path)
    np.testing.assert_array_equal(back.influence_m3_n, R.influence_m3_n)
    assert back.meta == R.meta
    with pytest.raises(InputError, match="does not exist"):
        ModuleResponse.from_file(tmp_path / "none.npz")
    np.savez(tmp_path / "partial.npz", pressure_pa=np.ones(2))
    with pytest.raises(InputError, match="lacks array"):
        ModuleResponse.from_file(tmp_path / "partial.npz")
    with pytest.raises(InputError, match="influence_m3_n"):
        ModuleResponse(
            R.pressure_pa,
            R.axis_m,
            R.influence_m3_n[:, :2],
            R.volume_m3,
            R.compliance_m3_pa,
            R.reference_influence_m3_n,
            R.reference_patch_m,
        )


@pytest.mark.parametrize("seam_mm", [0.0, 3.0], ids=["chambers-meet", "3mm-walls"])
def test_a_seam_of_its_own_stretches_the_cast_map_onto_the_chambers(seam_mm: float) -> None:
    """With a seam width of its own the cast map's chamber edges fall on this pad's: module 5's
    centre reads the map's centre, its chamber edge the map's edge (bonded: under 5 % of the
    centre), and half way the map's half way."""
    pad = PadResponse(seam_width_m=seam_mm * 1e-3, line_gain=1.0)
    plain = PadResponse(line_gain=1.0)
    assert pad.chamber_side_m == pytest.approx(0.045 - seam_mm * 1e-3)
    c = pad.module_centers_m()[4]
    h, hp = 0.5 * pad.chamber_side_m, 0.5 * plain.chamber_side_m
    for frac in (0.0, 0.5):
        got = pad.influences([c + np.array([frac * h, 0.0])], 1100.0)[0, 4]
        want = plain.influences([c + np.array([frac * hp, 0.0])], 1100.0)[0, 4]
        assert got == pytest.approx(want, rel=1e-9)
    edge = pad.influences([c + np.array([h, 0.0])], 1100.0)[0, 4]
    # (with no seam the edge is the line, where the map's two chamber edges meet: +- a trace)
    assert abs(edge) < 0.05 * pad.influences([c], 1100.0)[0, 4]
