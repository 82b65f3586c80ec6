"""``softpad log info|plot|export|recover`` on the regression recordings."""

from __future__ import annotations

import csv
import json
import shutil
from pathlib import Path

import pytest

from softpad.cli.main import main

DATA = Path(__file__).resolve().parents[1] / "data"


def test_log_info_json(capsys) -> None:
    assert main(["log", "info", str(DATA / "banana.mcap"), "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["objects"] == ["banana"] and d["outcome"] == "held" and d["complete"]
    assert d["channels"] == 6 and d["sample_rate_hz"] == pytest.approx(100.0)
    assert d["plans"][0]["modules"] == [2, 3, 4] and d["contact"]
    topics = {t["topic"]: t for t in d["topics"]}
    assert topics["/softpad/module_3/pressure"]["messages"] == d["frames"]
    assert topics["/softpad/module_3/pressure"]["type"] == "sensor_msgs/msg/FluidPressure"


def test_log_info_text(capsys) -> None:
    assert main(["log", "info", str(DATA / "object-1_object-4.mcap")]) == 0
    out = capsys.readouterr().out
    assert out.count("plan: modules") == 2 and "/softpad/valves" in out


def test_log_plot_writes_both_pictures(tmp_path, capsys) -> None:
    png, pad = tmp_path / "t.png", tmp_path / "pad.png"
    argv = ["log", "plot", str(DATA / "cylinder.mcap"), "--png", str(png), "--pad-png", str(pad)]
    assert main(argv) == 0
    assert png.stat().st_size > 10_000 and pad.stat().st_size > 5_000


def test_log_export_csv_has_frames_and_events(tmp_path, capsys) -> None:
    out = tmp_path / "run.csv"
    assert main(["log", "export", str(DATA / "banana.mcap"), "--out", str(out)]) == 0
    rows = list(csv.DictReader(out.open()))
    kinds = {r["event"] for r in rows if r["event"]}
    assert {"phase", "plan", "contact", "outcome"} <= kinds
    frames = [r for r in rows if not r["event"]]
    assert float(frames[-1]["p2_pa"]) > 500.0 and frames[0]["wall_ns"]


def test_log_export_refuses_other_formats(tmp_path, capsys) -> None:
    assert main(["log", "export", str(DATA / "banana.mcap"), "--out", str(tmp_path / "x.xls")]) == 2
    assert "--out must name a .csv or .parquet file" in capsys.readouterr().err


def test_log_recover_a_cut_file(tmp_path, capsys) -> None:
    cut = tmp_path / "cut.mcap"
    cut.write_bytes((DATA / "banana.mcap").read_bytes()[:120_000])
    assert main(["log", "info", str(cut), "--json"]) == 0
    captured = capsys.readouterr()
    d = json.loads(captured.out)
    assert not d["complete"] and 100 < d["frames"] and "cut short" in captured.err
    assert main(["log", "recover", str(cut)]) == 0
    assert "recovered" in capsys.readouterr().out
    fixed = tmp_path / "cut.recovered.mcap"
    assert main(["log", "info", str(fixed), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["frames"] == d["frames"]


def test_log_recover_refuses_an_empty_out(tmp_path, capsys) -> None:
    # found by the misuse campaign with a fresh seed (3801): '--out=' was dropped silently
    cut = tmp_path / "cut.mcap"
    cut.write_bytes((DATA / "banana.mcap").read_bytes()[:120_000])
    assert main(["log", "recover", str(cut), "--out="]) == 2
    assert "name is empty" in capsys.readouterr().err
    assert not (tmp_path / "cut.recovered.mcap").exists()


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["log", "info", "nowhere.mcap"], "does not exist"),
        (["log", "info", "README.md"], "not a readable MCAP file"),
    ],
    ids=["missing", "not-mcap"],
)
def test_log_errors(argv, message, capsys, monkeypatch) -> None:
    monkeypatch.chdir(Path(__file__).resolve().parents[2])
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert message in err and err.count("\n") == 1


def test_log_refuses_a_non_softpad_mcap(tmp_path, capsys) -> None:
    from mcap.writer import Writer

    other = tmp_path / "other.mcap"
    with open(other, "wb") as f:
        w = Writer(f)
        w.start()
        w.finish()
    assert main(["log", "info", str(other)]) == 2
    assert "not a SoftPad recording" in capsys.readouterr().err
    shutil.rmtree(tmp_path)
