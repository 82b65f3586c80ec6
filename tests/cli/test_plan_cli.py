"""``softpad plan`` end to end: outputs, input formats and bad input."""

from __future__ import annotations

import io
import json
import math
import subprocess
import sys
from pathlib import Path

import pytest

BANANA = "0,0.124,0.078,0.109,0,0"


def test_json_has_exactly_the_documented_keys(cli) -> None:
    code, out, _ = cli("plan", "--delta", BANANA, "--json")
    assert code == 0
    data = json.loads(out)
    assert list(data) == ["schema_version", "objects"]
    (obj,) = data["objects"]
    assert list(obj) == ["modules", "pcom", "cog", "theta", "rule", "cog_m", "tentative"]
    assert obj["modules"] == [2, 3, 4]
    assert obj["cog"] == [1.0, 1.0]
    assert obj["theta"] == -math.pi / 4
    assert obj["cog_m"] == pytest.approx([0.045, 0.045])


def test_pitch_scales_cog_in_metres(cli) -> None:
    _, out, _ = cli("plan", "--delta", BANANA, "--pitch-mm", "30", "--json")
    assert json.loads(out)["objects"][0]["cog_m"] == pytest.approx([0.03, 0.03])


def test_threshold_flag_changes_detection(cli) -> None:
    _, out, _ = cli("plan", "--delta", BANANA, "--threshold-kpa", "0.1", "--json")
    assert [o["modules"] for o in json.loads(out)["objects"]] == [[2, 4]]


def test_pressures_with_reference_equal_delta(cli) -> None:
    _, a, _ = cli("plan", "--delta", BANANA, "--json")
    _, b, _ = cli(
        "plan",
        "--pressures",
        "1.1,1.224,1.178,1.209,1.1,1.1",
        "--reference",
        "1.1,1.1,1.1,1.1,1.1,1.1",
        "--json",
    )
    pa, pb = json.loads(a)["objects"][0], json.loads(b)["objects"][0]
    assert pa["modules"] == pb["modules"] and pa["rule"] == pb["rule"]
    assert pa["cog"] == pytest.approx(pb["cog"], abs=1e-9)


@pytest.mark.parametrize(
    "content",
    [
        '{"delta_kpa": [0, 0.124, 0.078, 0.109, 0, 0]}',
        "module,delta_kpa\n1,0\n2,0.124\n3,0.078\n4,0.109\n5,0\n6,0\n",
        "0,0.124,0.078,0.109,0,0\n",
        "module,pressure_kpa,reference_kpa\n1,1.1,1.1\n2,1.224,1.1\n3,1.178,1.1\n"
        "4,1.209,1.1\n5,1.1,1.1\n6,1.1,1.1\n",
    ],
    ids=["json", "csv-delta", "csv-one-line", "csv-pressures"],
)
def test_frame_files(tmp_path: Path, cli, content: str) -> None:
    f = tmp_path / "frame.txt"
    f.write_text(content)
    code, out, _ = cli("plan", "--frame", str(f), "--json")
    assert code == 0
    assert json.loads(out)["objects"][0]["modules"] == [2, 3, 4]


def test_frame_from_stdin(monkeypatch: pytest.MonkeyPatch, cli) -> None:
    monkeypatch.setattr(sys, "stdin", io.StringIO('{"delta_kpa": [0,0,0.062,0,0,0.062]}'))
    _, out, _ = cli("plan", "--frame", "-", "--json")
    assert json.loads(out)["objects"][0]["cog"] == [2.5, 1.0]


def test_table_output_is_readable(cli) -> None:
    code, out, _ = cli("plan", "--delta", BANANA)
    assert code == 0
    assert "modules 2, 3, 4" in out and "-45.0 deg" in out and "n3-diagonal-corner" in out


def test_plot_is_written(tmp_path: Path, cli) -> None:
    png = tmp_path / "plan.png"
    code, _, _ = cli("plan", "--delta", BANANA, "--png", str(png))
    assert code == 0
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["--delta", "0,0.1,0.1"], "needs 6 increments"),
        (["--delta", "0,abc,0,0,0,0"], "item 2 'abc' is not a number"),
        (["--delta", "0,nan,0,0,0,0"], "must be finite"),
        (["--delta", "0,inf,0,0,0,0"], "must be finite"),
        (["--delta", BANANA, "--layout", "2by3"], "ROWSxCOLS"),
        (["--delta", BANANA, "--threshold-kpa", "-0.1"], ">= 0.001 kPa"),
        (["--delta", BANANA, "--pitch-mm", "0"], ">= 1 mm"),
        (["--pressures", BANANA], "needs --reference"),
        (["--pressures", BANANA, "--reference", "1,1"], "6 pressures and 6 reference"),
        (["--frame", "/nonexistent/frame.csv"], "cannot read frame file"),
    ],
    ids=[
        "wrong-count",
        "not-a-number",
        "nan",
        "inf",
        "bad-layout",
        "negative-threshold",
        "zero-pitch",
        "missing-reference",
        "reference-count",
        "missing-file",
    ],
)
def test_bad_input_is_one_line_and_exit_2(cli, argv: list[str], message: str) -> None:
    code, _, err = cli("plan", *argv)
    assert code == 2
    assert message in err
    assert "Traceback" not in err
    assert len(err.strip().splitlines()) == 1
    assert err.startswith("softpad plan: error:")


@pytest.mark.parametrize(
    ("content", "message"),
    [
        ("{not json", "not valid JSON"),
        ('{"delta": [1]}', "needs key delta_kpa"),
        ("module,weight\n1,2\n", "header must name delta_kpa"),
        ("", "is empty"),
    ],
    ids=["bad-json", "bad-key", "bad-header", "empty"],
)
def test_corrupt_frame_files(tmp_path: Path, cli, content: str, message: str) -> None:
    f = tmp_path / "frame"
    f.write_text(content)
    code, _, err = cli("plan", "--frame", str(f))
    assert code == 2 and message in err


def test_argparse_range_errors_exit_2_without_traceback() -> None:
    proc = subprocess.run(
        [
            sys.executable,
            "-m",
            "softpad",
            "plan",
            "--delta",
            BANANA,
            "--threshold-kpa",
            "-1",
        ],
        capture_output=True,
        text=True,
    )
    assert proc.returncode == 2
    assert "--threshold-kpa must be >= 0.001 kPa, got -1 kPa" in proc.stderr
    assert "Traceback" not in proc.stderr


@pytest.mark.parametrize("text", ["0\r0", '0,"1\r', "a,b\r\n1,2\r3"], ids=["cr", "quote", "mixed"])
def test_frame_files_with_carriage_returns_get_one_line_errors(cli, tmp_path, text: str) -> None:
    """A lone carriage return ends a line as a newline does; a broken quote is bad CSV; either
    way exit 2 with the file named (found by tests/cli/test_fuzz.py)."""
    path = tmp_path / "frame.csv"
    path.write_bytes(text.encode())
    code, _, err = cli("plan", "--frame", str(path))
    assert code == 2 and "frame" in err and err.count("\n") == 1
