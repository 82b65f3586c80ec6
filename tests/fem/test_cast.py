"""The cast pad (one upper layer over every chamber): its limits, symmetry, reciprocity, mesh
convergence and the packaged table."""

from __future__ import annotations

import numpy as np
import pytest

from softpad.errors import InputError
from softpad.fem import (
    DEFAULT_CAST_MESH,
    CastPadGeometry,
    CastPadModel,
    CastPadResponse,
    MeshOptions,
    ModuleGeometry,
    ModuleModel,
    cast_convergence,
    cast_pad_response,
    cast_sensitivities,
)

COARSE = MeshOptions(3, 1)


@pytest.fixture(scope="module")
def coarse_table() -> CastPadResponse:
    return cast_pad_response(mesh=COARSE, pressures_pa=[1100.0])


@pytest.mark.parametrize(
    "kwargs",
    [
        {"rows": 0},
        {"cols": 2.5},
        {"wall_width_m": 0.0},
        {"wall_width_m": 0.03},
        {"foundation_pa_per_m": -1.0},
        {"thickness_m": 0.04},
    ],
    ids=["no-rows", "fractional-cols", "no-wall", "wall-wider-than-half", "negative-k", "thick"],
)
def test_bad_geometry_is_refused(kwargs: dict[str, float]) -> None:
    with pytest.raises(InputError):
        CastPadGeometry(**kwargs)  # type: ignore[arg-type]


def test_single_chamber_limit_is_the_clamped_module() -> None:
    """One chamber with a thin border (0.1 mm) is the clamped 45 mm module of Section 7.2:
    the same centre height and chamber compliance at 1.1 kPa (independent meshes and
    boundary conditions of the same FElupe element) within 1.5 %."""
    pad = CastPadGeometry(rows=1, cols=1, wall_width_m=1e-4)
    cast = CastPadModel(pad=pad, mesh=MeshOptions(6, 1))
    cast.solve(1100.0)
    _, c_cast = cast.chamber_sensitivity()
    module = ModuleModel(
        geometry=ModuleGeometry(0.045, 0.0015), mesh=MeshOptions(6, 1, grading=0.5), contact=False
    )
    module.solve(1100.0)
    _, c_module = module.pressure_sensitivity(with_compliance=True)
    np.testing.assert_allclose(cast.height_m, module.height_m, rtol=0.015)
    np.testing.assert_allclose(cast.volume_m3(), module.volume_m3(), rtol=0.015)
    np.testing.assert_allclose(c_cast[0, 0], c_module, rtol=0.015)


def test_compliance_matrix_is_symmetric_and_diagonally_dominant(
    coarse_table: CastPadResponse,
) -> None:
    """Reciprocity: dV_k/dp_l = dV_l/dp_k (solved separately for each chamber); a
    neighbour's share is a few per cent of a chamber's own compliance and of opposite sign
    (pressing one membrane up pulls the shared edge from the other)."""
    c = coarse_table.compliance_m3_pa[0]
    np.testing.assert_allclose(c, c.T, rtol=1e-6, atol=1e-9 * np.abs(c).max())
    diag = np.diag(c)
    off = c - np.diag(diag)
    assert (diag > 0).all()
    assert np.abs(off).max() < 0.05 * diag.min()
    assert c[0, 1] < 0


def test_mirror_symmetry_of_the_pad(coarse_table: CastPadResponse) -> None:
    """Module 1's response at a point equals module 3's at the point mirrored about the pad's
    middle column, and module 4's mirrored about the middle line."""
    t = coarse_table
    lx, ly = t.x_axis_m[-1], t.y_axis_m[-1]
    rng = np.random.default_rng(3)
    pts = rng.uniform([0.0, 0.0], [lx, ly], size=(50, 2))
    s = t.influence(pts, 1100.0)
    sx = t.influence(np.column_stack([lx - pts[:, 0], pts[:, 1]]), 1100.0)
    sy = t.influence(np.column_stack([pts[:, 0], ly - pts[:, 1]]), 1100.0)
    scale = np.abs(s).max()
    np.testing.assert_allclose(s[:, 0], sx[:, 2], atol=1e-9 * scale)
    np.testing.assert_allclose(s[:, 0], sy[:, 3], atol=1e-9 * scale)


def test_a_load_on_the_line_squeezes_both_chambers(coarse_table: CastPadResponse) -> None:
    """The shared layer: a load astride the line between modules 1 and 2 raises both
    equally (symmetry), a load at the corner of four raises all four, and a load on a
    module's centre barely reaches its neighbours (< 3 %)."""
    probes = cast_sensitivities(coarse_table)["probes"]
    line = probes["10x10 mm on the line 1|2"]["rise_pa_n"]
    np.testing.assert_allclose(line[0], line[1], rtol=0.02)
    assert line[0] > 10.0
    corner = probes["10x10 mm at the corner 1|2|4|5"]["rise_pa_n"]
    assert min(corner[k] for k in (0, 1, 3, 4)) > 0.0
    centre = probes["10x10 mm weight, module 1's centre"]["rise_pa_n"]
    assert max(abs(v) for v in centre[1:]) < 0.03 * centre[0]


def test_file_round_trip(coarse_table: CastPadResponse, tmp_path) -> None:  # type: ignore[no-untyped-def]
    path = coarse_table.to_npz(tmp_path / "cast.npz")
    back = CastPadResponse.from_file(path)
    np.testing.assert_array_equal(back.influence_m3_n, coarse_table.influence_m3_n)
    assert back.meta == coarse_table.meta
    assert back.shape == (2, 3)


def test_unreadable_file_is_an_input_error(tmp_path) -> None:  # type: ignore[no-untyped-def]
    bad = tmp_path / "bad.npz"
    bad.write_text("not a table")
    with pytest.raises(InputError, match="not a readable"):
        CastPadResponse.from_file(bad)
    with pytest.raises(InputError, match="does not exist"):
        CastPadResponse.from_file(tmp_path / "missing.npz")


@pytest.mark.slow
def test_mesh_convergence_of_the_probes() -> None:
    """The probes' rises on the shipped mesh against a finer one (12 cells centre-to-wall, 3
    through): within 3 % for the module centre and the line; the corner, a small rise on a
    steep slope, within 10 %."""
    conv = cast_convergence(DEFAULT_CAST_MESH, MeshOptions(12, 3))
    for name, v in conv["probes"].items():
        tol = 0.10 if "corner" in name else 0.03
        assert abs(v["difference"]) < tol, (name, v)


@pytest.mark.slow
def test_packaged_table_is_what_the_generator_writes() -> None:
    """softpad/data/cast_pad_response.npz at 1.1 kPa equals a fresh solve with its settings."""
    from softpad.sim import default_cast_response

    shipped = default_cast_response()
    assert shipped is not None
    fresh = cast_pad_response(mesh=DEFAULT_CAST_MESH, pressures_pa=[1100.0])
    i = int(np.flatnonzero(shipped.pressure_pa == 1100.0)[0])
    np.testing.assert_allclose(
        shipped.influence_m3_n[i], fresh.influence_m3_n[0], rtol=1e-5, atol=1e-15
    )


def test_cli_writes_a_readable_table(cli, tmp_path) -> None:  # type: ignore[no-untyped-def]
    """``softpad fem cast-response`` on the coarse mesh at one pressure: the table it writes
    reads back, and its JSON carries the probes' figures of that table."""
    out = tmp_path / "cast.npz"
    argv = ["fem", "cast-response", "--mesh", "coarse", "--pressures-kpa", "1.1", "--out"]
    code, text, _ = cli(*argv, str(out), "--json")
    assert code == 0
    import json

    data = json.loads(text)
    table = CastPadResponse.from_file(out)
    assert table.shape == (2, 3) and data["meta"]["wall_width_m"] == 1e-3
    want = cast_sensitivities(table)["probes"]
    got = data["sensitivities"]["probes"]
    for name, v in want.items():
        assert got[name]["min_rise_pa_n"] == pytest.approx(v["min_rise_pa_n"], rel=1e-12)
    code, _, err = cli(*argv, str(out))
    assert code == 2 and "exists" in err
    code, _, err = cli(*argv[:-2], "9", "--out", str(tmp_path / "y.npz"))
    assert code == 2 and "--pressures-kpa: 9 kPa" in err
    code, _, err = cli(*argv[:-1], str(tmp_path / "x.npz"), "--wall-mm", "0")
    assert code == 2 and "--wall-mm" in err


def test_a_yielding_wall_foundation_tends_to_the_rigid_walls(coarse_table: CastPadResponse) -> None:
    """Walls on a Winkler foundation: a stiff one (1e12 Pa/m) is the rigid walls (1 %); a soft
    one (25 MPa/m) lets a load on the line squeeze both chambers more and one at the centre
    less (the chambers grow more compliant)."""
    probes = {}
    for k in (1e12, 2.5e7):
        table = cast_pad_response(
            pad=CastPadGeometry(foundation_pa_per_m=k), mesh=COARSE, pressures_pa=[1100.0]
        )
        probes[k] = cast_sensitivities(table)["probes"]
    rigid = cast_sensitivities(coarse_table)["probes"]
    line, centre = "10x10 mm on the line 1|2", "10x10 mm weight, module 1's centre"
    for name in (line, centre):
        assert probes[1e12][name]["min_rise_pa_n"] == pytest.approx(
            rigid[name]["min_rise_pa_n"], rel=0.01
        )
    assert probes[2.5e7][line]["min_rise_pa_n"] > 1.5 * rigid[line]["min_rise_pa_n"]
    assert probes[2.5e7][centre]["min_rise_pa_n"] < rigid[centre]["min_rise_pa_n"]
