"""``softpad pad probe|map`` and ``softpad fem response``: JSON, errors, files."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from softpad import thesis
from softpad.sim import default_response, packaged_response_path


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
        np.testing.assert_allclose(data["delta_kpa"], data["fem_delta_kpa"], rtol=0.05, atol=1e-6)
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
    assert 0 < data["smallest_kpa"] < data["largest_kpa"] < 0.2
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
