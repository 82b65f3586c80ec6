"""``softpad pad probe|map`` and ``softpad fem response``: JSON, errors, files."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from softpad import thesis
from softpad.sim import PadResponse, default_response, packaged_response_path


def test_probe_json_echoes_the_inputs_and_falls_from_centre_to_seam(cli) -> None:
    rises = []
    for at in ("0.5,0.5", "0.8333,0.5", "1,0.5"):
        code, out, _ = cli(
            "pad",
            "probe",
            "--at",
            at,
            "--force-n",
            "0.2",
            "--footprint-mm",
            "10,10",
            "--json",
        )
        assert code == 0
        data = json.loads(out)
        assert data["schema_version"] >= 1 and data["command"] == "pad probe"
        assert data["at"] == [float(v) for v in at.split(",")]
        assert data["force_n"] == 0.2 and data["footprint_mm"] == [10.0, 10.0]
        assert len(data["delta_kpa"]) == 6 and len(data["fem_delta_kpa"]) == 6
        # the simulated chambers share loads through the cast layer but not its compliance
        # coupling (dV_k/dp_l, l != k): the neighbours' rises differ by under 0.5 Pa
        np.testing.assert_allclose(data["delta_kpa"], data["fem_delta_kpa"], rtol=0.05, atol=5e-4)
        rises.append(data["delta_kpa"][3])  # module 4: bottom-left
    assert rises[0] > rises[1] > rises[2] > 0


def test_probe_text_lists_every_module(cli) -> None:
    code, out, _ = cli(
        "pad", "probe", "--at", "1.5,1.5", "--force-n", "0.1236", "--footprint-mm", "42,31"
    )
    assert code == 0
    rows = [line.split() for line in out.splitlines() if line.strip()[:1].isdigit()]
    assert [int(r[0]) for r in rows] == [1, 2, 3, 4, 5, 6]
    assert float(rows[1][1]) > thesis.OBJECT_THRESHOLD_PA / 1e3  # the 12.6 g brick is seen


def test_probe_reports_the_rise_per_newton_beside_the_rise(cli) -> None:
    """Issue 51: kPa/N (the figure README.md quotes) is printed, each column named in the
    header and explained in --help; it is the rise over the block's force."""
    argv = ("pad", "probe", "--at", "1.5,1.5", "--force-n", "0.2", "--footprint-mm", "10,10")
    code, out, _ = cli(*argv)
    assert code == 0
    header = next(line.split() for line in out.splitlines() if line.startswith("module"))
    assert header == ["module", "delta_kPa", "delta_kPa/N", "FEM_kPa", "FEM_kPa/N"]
    rows = [
        [float(v) for v in line.split()] for line in out.splitlines() if line.strip()[:1].isdigit()
    ]
    for _, rise, per_n, fem, fem_per_n in rows:
        assert per_n == pytest.approx(rise / 0.2, abs=1e-3)  # 3 decimals printed
        assert fem_per_n == pytest.approx(fem / 0.2, abs=1e-3)
    code, out, _ = cli(*argv, "--json")
    data = json.loads(out)
    np.testing.assert_allclose(
        data["delta_kpa_per_n"], np.array(data["delta_kpa"]) / 0.2, atol=1e-5
    )
    np.testing.assert_allclose(
        data["fem_delta_kpa_per_n"], np.array(data["fem_delta_kpa"]) / 0.2, atol=1e-5
    )
    code, out, _ = cli("pad", "probe", "--help")
    for column in header[1:]:
        assert f"  {column}  " in out  # each column explained


@pytest.mark.parametrize(
    ("argv", "names"),
    [
        (["--at", "4,1", "--force-n", "1", "--footprint-mm", "10,10"], "--at: 4 module units"),
        (["--at", "2.5,2.5", "--force-n", "1", "--footprint-mm", "10,10"], "off the 2x3 pad"),
        (["--at", "1", "--force-n", "1", "--footprint-mm", "10,10"], "--at"),
        (["--at", "1,1", "--force-n", "-1", "--footprint-mm", "10,10"], "--force-n"),
        (["--at", "1,1", "--force-n", "1", "--footprint-mm", "0,10"], "--footprint-mm"),
        (["--at", "1,1", "--force-n", "1", "--footprint-mm", "10,300"], "--footprint-mm"),
        (
            [
                "--at",
                "1,1",
                "--force-n",
                "1",
                "--footprint-mm",
                "10,10",
                "--box",
                "tcp://127.0.0.1:1",
            ],
            "--box",
        ),
    ],
)
def test_probe_bad_input_exits_2_naming_the_value(cli, argv, names) -> None:  # type: ignore[no-untyped-def]
    code, out, err = cli("pad", "probe", *argv)
    assert code == 2
    assert names in err and len(err.strip().splitlines()) == 1
    code, out, _ = cli("pad", "probe", *argv, "--json")
    assert code == 2 and "error" in json.loads(out)


def test_map_writes_a_png_and_refuses_to_overwrite(cli, tmp_path: Path) -> None:
    png = tmp_path / "map.png"
    argv = [
        "pad",
        "map",
        "--force-n",
        "0.2",
        "--footprint-mm",
        "10,10",
        "--png",
        str(png),
        "--step-mm",
        "5",
    ]
    code, out, _ = cli(*argv, "--json")
    assert code == 0 and png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    data = json.loads(out)
    assert 0 < data["smallest_kpa"] < data["largest_kpa"]
    # the largest rise against the FEM's small-load law on the same block centres (5 %)
    pad = PadResponse()
    xs = np.arange(2.5e-3, 3 * 0.045, 5e-3)
    ys = np.arange(2.5e-3, 2 * 0.045, 5e-3)
    fem = max(
        pad.sealed_rise_pa(
            pad.rect_equivalent_loads((x, y), (0.01, 0.01), 0.2, 1100.0), 1100.0
        ).max()
        for x in xs
        for y in ys
    )
    assert data["largest_kpa"] == pytest.approx(fem / 1e3, rel=0.05)
    code, _, err = cli(*argv)
    assert code == 2 and "exists" in err


def test_map_needs_an_inflated_pad(cli, tmp_path: Path) -> None:
    code, _, err = cli(
        "pad",
        "map",
        "--force-n",
        "1",
        "--footprint-mm",
        "10,10",
        "--png",
        str(tmp_path / "m.png"),
        "--box",
        "sim://?inflated_kpa=0",
    )
    assert code == 2 and "inflate" in err


@pytest.mark.slow
def test_fem_response_regenerates_the_packaged_table(cli, tmp_path: Path) -> None:
    out = tmp_path / "r.npz"
    code, text, _ = cli(
        "fem", "response", "--out", str(out), "--no-convergence", "--no-progress", "--json"
    )
    assert code == 0 and json.loads(text)["path"] == str(out)
    from softpad.sim import ModuleResponse

    fresh = ModuleResponse.from_file(out)
    np.testing.assert_allclose(
        fresh.influence_m3_n, default_response().influence_m3_n, rtol=1e-6, atol=1e-15
    )
    np.testing.assert_allclose(
        fresh.compliance_m3_pa, default_response().compliance_m3_pa, rtol=1e-6
    )
    assert packaged_response_path() is not None


def test_sensitivity_reports_the_cast_pad_and_the_clamped_one(cli) -> None:
    """``pad sensitivity --json``: the line, corner and minimum detectable mass of the pad
    model asked for, equal to the library's figures; gain 1 (the default) on the cast pad is
    the FEM's own line sensitivity, below the thesis's 269 Pa/N."""
    from softpad.sim import pad_sensitivities

    figures = {}
    runs = (["--line-gain", "1"], ["--pad-model", "clamped", "--line-gain", "1"], [])
    for argv in runs:
        code, out, _ = cli("pad", "sensitivity", *argv, "--json")
        assert code == 0
        figures[" ".join(argv)] = json.loads(out)
    fem = figures["--line-gain 1"]
    assert fem["pad_model"] == "cast" and fem["line_gain"] == 1.0
    assert figures[""]["line_pa_n"] == fem["line_pa_n"]  # the default is the FEM alone
    code, out, _ = cli("pad", "sensitivity", "--line-gain", "5.95", "--json")
    figures["--line-gain 5.95"] = json.loads(out)
    lib = pad_sensitivities(PadResponse(line_gain=1.0))
    assert fem["line_pa_n"] == pytest.approx(lib["line_pa_n"], rel=1e-9)
    assert fem["line_pa_n"] < 269.0
    assert figures["--pad-model clamped --line-gain 1"]["pad_model"] == "clamped"
    top = figures["--line-gain 5.95"]  # the range's high end: the can seen, a 5 g Duplo face
    assert top["line_pa_n"] > 269.0
    assert top["min_detectable_mass_g"]["Duplo face 42x31 mm"] == pytest.approx(5.0, abs=0.01)


def test_sensitivity_text_names_the_figures(cli) -> None:
    code, out, _ = cli("pad", "sensitivity", "--line-gain", "1")
    assert code == 0
    assert "line sensitivity" in out and "corner sensitivity" in out
    assert "minimum detectable mass" in out
    code, _, err = cli("pad", "sensitivity", "--line-gain", "0.5")
    assert code == 2 and "--line-gain" in err
