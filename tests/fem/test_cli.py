"""``softpad fem ...`` end to end on coarse meshes: JSON contract, outputs, bad input."""

from __future__ import annotations

import json

import numpy as np
import pytest


def test_sweep_json_has_exactly_the_documented_keys(cli) -> None:
    code, out, _ = cli(
        "fem", "sweep", "--model", "yeoh", "--mesh", "coarse", "--points", "3",
        "--max-pressure-kpa", "1", "--json",
    )  # fmt: skip
    assert code == 0
    payload = json.loads(out)
    assert list(payload) == ["schema_version", "model", "pressure_kpa", "height_mm"]
    assert payload["model"] == "yeoh"
    assert payload["pressure_kpa"] == [0.0, 0.5, 1.0]
    assert payload["height_mm"][0] == 0.0 and 8.0 < payload["height_mm"][2] < 10.0


def test_param_overrides_the_preset(cli) -> None:
    argv = [
        "fem",
        "sweep",
        "--mesh",
        "coarse",
        "--points",
        "2",
        "--max-pressure-kpa",
        "1",
        "--json",
    ]
    _, stiff, _ = cli(*argv)
    code, soft, _ = cli(*argv, "--param", "mu=30000")
    assert code == 0
    assert json.loads(soft)["height_mm"][1] > json.loads(stiff)["height_mm"][1] + 0.5


def test_sweep_writes_csv_png_vtu(tmp_path, cli) -> None:
    code, out, _ = cli(
        "fem", "sweep", "--mesh", "coarse", "--points", "3", "--max-pressure-kpa", "0.6",
        "--thickness-mm", "2", "--csv", str(tmp_path / "h.csv"), "--png", str(tmp_path / "h.png"),
        "--vtu", str(tmp_path / "m.vtu"),
    )  # fmt: skip
    assert code == 0 and "height_mm" in out
    for name in ("h.csv", "h.png", "m.vtu"):
        assert (tmp_path / name).stat().st_size > 0


def test_characteristic_writes_a_loadable_table(tmp_path, cli) -> None:
    from softpad.fem import ModuleCharacteristic

    out_path = tmp_path / "c.npz"
    code, out, _ = cli(
        "fem", "characteristic", "--mesh", "coarse", "--pressures-kpa", "0,1",
        "--loads-n", "0,0.2", "--out", str(out_path),
    )  # fmt: skip
    assert code == 0 and "2 pressures x 2 loads" in out
    table = ModuleCharacteristic.from_npz(out_path)
    np.testing.assert_allclose(table.pressure_pa, [0.0, 1000.0])


def test_fit_from_a_csv(tmp_path, cli) -> None:
    data = tmp_path / "m.csv"
    data.write_text("pressure_kpa,height_mm\n0.5,5.0\n1.0,6.6\n")
    code, out, _ = cli(
        "fem", "fit", "--data", str(data), "--model", "neo-hookean", "--mesh", "coarse",
        "--max-evals", "4", "--json",
    )  # fmt: skip
    assert code == 0
    info = json.loads(out)
    assert info["rmse_mm"] <= info["initial_rmse_mm"]


@pytest.mark.parametrize(
    ("argv", "key"),
    [
        (["design", "--values-mm", "1.5,2", "--models", "neo-hookean"], "height_mm"),
        (
            ["stiffness", "--pressures-kpa", "0.5,1.5", "--forces-n", "0.2,0.8"],
            "stiffness_n_per_mm",
        ),
        (["sensitivity", "--pressures-kpa", "0.5,2"], "side_mm"),
        (["chamber", "--masses-g", "6,12.6"], "min_detectable_mass_g"),
    ],
    ids=["design", "stiffness", "sensitivity", "chamber"],
)
def test_study_commands_write_json_csv_png(tmp_path, cli, argv: list[str], key: str) -> None:
    csv, png = tmp_path / "r.csv", tmp_path / "r.png"
    code, out, _ = cli(
        "fem", *argv, "--mesh", "coarse", "--json", "--csv", str(csv), "--png", str(png)
    )
    assert code == 0
    assert key in json.loads(out)
    assert csv.stat().st_size > 0 and png.stat().st_size > 0


def test_compare_ranks_models_from_a_csv(tmp_path, cli) -> None:
    data = tmp_path / "m.csv"
    data.write_text("pressure_kpa,height_mm\n0.5,6.1\n1.0,8.0\n2.0,11.2\n")
    code, out, _ = cli(
        "fem", "compare", "--data", str(data), "--models", "yeoh,neo-hookean",
        "--mesh", "coarse",
    )  # fmt: skip
    assert code == 0
    lines = out.strip().splitlines()
    assert lines[1].split()[1] == "neo-hookean" and lines[2].split()[1] == "yeoh"


@pytest.mark.parametrize(
    ("argv", "fragment"),
    [
        (["fem", "sweep", "--thickness-mm", "0"], "got 0 mm"),
        (["fem", "sweep", "--thickness-mm", "-1.5"], "-1.5"),
        (["fem", "sweep", "--width-mm", "nan"], "nan"),
        (["fem", "sweep", "--model", "rubber"], "'rubber'"),
        (["fem", "sweep", "--max-pressure-kpa", "50"], "<= 10 kPa"),
        (["fem", "chamber", "--masses-g", "6,abc"], "'abc'"),
        (["fem", "chamber", "--footprint-mm", "42by31"], "'42by31'"),
        (["fem", "stiffness", "--forces-n", "0.2,-1"], "'-1'"),
        (["fem", "design", "--models", "neo-hookean,foam"], "'foam'"),
        (["fem", "fit", "--data", "/nonexistent/m.csv"], "does not exist"),
        (["fem", "sweep", "--param", "mu=-5000"], "-5000 Pa <= 0"),
        (["fem", "sweep", "--model", "yeoh", "--param", "c1=-1"], "not convex"),
        (["fem", "sweep", "--param", "alpha1=2"], "'alpha1'"),
        (["fem", "sweep", "--param", "mu"], "NAME=VALUE"),
    ],
    ids=[
        "zero-thickness",
        "negative-thickness",
        "nan-width",
        "unknown-model",
        "pressure-too-high",
        "bad-mass",
        "bad-footprint",
        "negative-force",
        "unknown-design-model",
        "missing-data",
        "non-convex-mu",
        "non-convex-yeoh",
        "unknown-parameter",
        "param-without-value",
    ],
)
def test_bad_input_is_one_line_and_exit_2(cli, argv: list[str], fragment: str) -> None:
    code, _, err = cli(*argv)
    assert code == 2
    assert fragment in err
    assert len(err.strip().splitlines()) == 1
    assert "Traceback" not in err
