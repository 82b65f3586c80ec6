"""Files the commands write or read in bad shape: never clobbered, never a traceback, and what
was finished before Ctrl-C still printed (issue "A box that is safe to put on a network",
items 12-14)."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

DATA = Path(__file__).resolve().parents[1] / "data"


def softpad(*argv: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "softpad", *argv],
        capture_output=True,
        text=True,
        timeout=300,
        stdin=subprocess.DEVNULL,
    )


@pytest.mark.parametrize(
    "argv",
    [
        ["log", "plot", "REC", "--png", "OLD"],
        ["log", "plot", "REC", "--png", "new.png", "--pad-png", "OLD"],
        ["log", "export", "REC", "--csv", "OLD"],
    ],
)
def test_log_outputs_are_not_clobbered_without_force(tmp_path, argv):
    old = tmp_path / ("old.csv" if "--csv" in argv else "old.png")
    old.write_bytes(b"kept")
    argv = [str(DATA / "banana.mcap") if a == "REC" else a for a in argv]
    argv = [
        str(old) if a == "OLD" else (str(tmp_path / a) if a.endswith(".png") else a) for a in argv
    ]
    r = softpad(*argv)
    assert r.returncode == 2, r.stderr
    assert "exists; add --force" in r.stderr
    assert old.read_bytes() == b"kept"


def test_log_plot_refuses_a_picture_name_that_is_not_png(tmp_path):
    r = softpad("log", "plot", str(DATA / "banana.mcap"), "--png", str(tmp_path / "x.jpg"))
    assert r.returncode == 2
    assert ".png" in r.stderr
    assert not (tmp_path / "x.jpg").exists()


def _cut_before_first_frame(tmp_path: Path) -> Path:
    """The banana recording cut where it still reads as a recording but holds no frame."""
    from softpad.errors import InputError
    from softpad.record import load_recording

    src = (DATA / "banana.mcap").read_bytes()
    cut = tmp_path / "cut.mcap"
    for size in range(500, 40_000, 250):
        cut.write_bytes(src[:size])
        try:
            if len(load_recording(cut)) == 0:
                return cut
        except InputError:
            continue
    pytest.fail("no cut of the recording reads as one without frames")


def test_a_recording_cut_before_its_first_frame_is_input_not_a_crash(tmp_path):
    r = softpad("replay", str(_cut_before_first_frame(tmp_path)))
    assert r.returncode == 2, r.stderr
    assert "holds no frames" in r.stderr


def test_recover_of_a_complete_file_lists_each_topic_once(tmp_path):
    from mcap.reader import make_reader

    out = tmp_path / "again.mcap"
    r = softpad("log", "recover", str(DATA / "banana.mcap"), "--out", str(out))
    assert r.returncode == 0, r.stderr
    with open(out, "rb") as f:
        topics = [c.topic for c in make_reader(f).get_summary().channels.values()]
    assert topics, "no channel recovered"
    assert len(topics) == len(set(topics)), topics


def test_an_unwritable_folder_is_refused_before_the_work(tmp_path):
    # /proc refuses new files even to root, whom os.access lets through everywhere
    r = softpad("fem", "characteristic", "--out", "/proc/softpad-test.npz")
    assert r.returncode == 2
    assert "/proc" in r.stderr and "Traceback" not in r.stderr


def test_design_refuses_an_object_off_the_pad_before_any_work(tmp_path):
    f = tmp_path / "far.toml"
    f.write_text(
        'schema = "softpad-object-set/1"\nname = "far"\n[[object]]\nname = "far-brick"\n'
        'mass_g = 12.6\nshape = "box"\nsize_mm = [31, 31, 23]\n'
        'placement = { dx_mm = 1000000, dy_mm = 0, yaw_deg = 0 }\ngripper = "6/2"\n'
    )
    r = softpad("design", "--objects", str(f), "--quick", "--json")
    assert r.returncode == 2, r.stderr
    assert "off the 2x3 pad" in r.stderr
    assert json.loads(r.stdout)["error"]["kind"] == "input"


class _Finished:
    object, success, cause = "object-5", True, "held"

    def to_dict(self) -> dict:
        return {"object": self.object, "success": True}


def test_ctrl_c_during_trials_json_prints_what_was_finished(monkeypatch, capsys):
    import softpad.trials
    from softpad.cli.main import main

    def interrupted(specs, trials, *args, on_trial, **kwargs):
        on_trial(_Finished())
        raise KeyboardInterrupt

    monkeypatch.setattr(softpad.trials, "run_experiment", interrupted)
    monkeypatch.setattr(softpad.trials, "run_experiments", interrupted)
    assert main(["trials", "--objects", "object-5", "--trials", "3", "--json"]) == 130
    doc = json.loads(capsys.readouterr().out)
    assert doc["error"]["kind"] == "interrupted"
    assert doc["error"]["finished_trials"] == [{"object": "object-5", "success": True}]
