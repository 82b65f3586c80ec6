"""``softpad run`` and ``softpad box read``: output, JSON, plot, log, one-line errors."""

from __future__ import annotations

import json

import numpy as np
import pytest

from softpad.cli.main import main


def test_run_json_has_the_documented_keys(capsys, tmp_path) -> None:
    log = tmp_path / "run.mcap"
    assert (
        main(
            [
                "run",
                "--object",
                "object-4",
                "--hold-s",
                "1",
                "--json",
                "--record",
                str(log),
                "--box",
                "sim://?seed=3",
            ]
        )
        == 0
    )
    d = json.loads(capsys.readouterr().out)
    for key in ("objects", "contact_detected", "contact_delay_s", "finger_travel_m", "outcome"):
        assert key in d
    assert d["outcome"] == "held" and d["contact_detected"] is True
    assert set(d["objects"][0]) == {"modules", "pcom", "cog", "theta", "rule", "cog_m", "tentative"}
    # Table 6.1 plans (0.5, 1.2); the simulator predicts it within 0.1 module units
    # (tests/sim/test_table_6_1.py: COG_TOLERANCE)
    np.testing.assert_allclose(d["objects"][0]["cog"], [0.5, 1.2], atol=0.1)
    assert log.stat().st_size > 0


def test_run_prints_a_timeline_and_plots(capsys, tmp_path) -> None:
    png = tmp_path / "trace.png"
    assert main(["run", "--objects", "object-5", "--hold-s", "1", "--png", str(png)]) == 0
    out = capsys.readouterr().out
    for text in (
        "adjusted",
        "reference saved",
        "object detected on module(s) 1, 2, 3",
        "plan: modules 1,2,3",
        "contact detected",
        "outcome: held",
    ):
        assert text in out
    assert png.stat().st_size > 1000


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["run", "--object", "teapot"], "unknown object 'teapot'"),
        (["run", "--box", "serial://x:1"], "unknown box URL scheme 'serial'"),
        (["run", "--box", "sim://?speed=2"], "unknown sim:// option 'speed'"),
        (["run", "--record", "run.txt"], "--record must name a .mcap file"),
        (["box", "read", "--box", "sim://?rate_hz=-5"], "sample rate"),
        (["box", "read", "--count", "-1"], "--count must be >= 0"),
    ],
    ids=["object", "scheme", "option", "record", "rate", "count"],
)
def test_errors_are_one_line_and_exit_2(capsys, argv, message) -> None:
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert message in err and err.count("\n") == 1 and "Traceback" not in err


def test_a_hardware_fault_is_one_line_and_exit_3(capsys) -> None:
    argv = ["run", "--box", "sim://?seed=1&faults=leak:3:0.01", "--hold-s", "1", "--json"]
    assert main(argv) == 3
    captured = capsys.readouterr()
    assert "channel 3" in captured.err and captured.err.count("\n") == 1
    data = json.loads(captured.out)
    assert data["error"]["kind"] == "hardware" and "channel 3" in data["error"]["message"]
    assert data["error"]["events"] and data["error"]["frames"] > 0  # what was gathered before


def test_box_read_streams_frames(capsys) -> None:
    assert main(["box", "read", "--count", "3", "--box", "sim://?inflated_kpa=1.1&noise=0"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0].startswith("softpad box read: the simulated box sim://")  # which box first
    assert len(lines) == 5 and "ch8" in lines[1]
    assert lines[2].split()[1] == "1.1000"


def test_box_read_json(capsys) -> None:
    assert main(["box", "read", "--count", "2", "--json"]) == 0
    rows = [json.loads(line) for line in capsys.readouterr().out.splitlines()]
    assert [r["t_s"] for r in rows] == [0.01, 0.02] and len(rows[0]["pressures_kpa"]) == 8


def test_failed_run_still_saves_its_recording(capsys, tmp_path) -> None:
    from softpad.record import load_recording

    path = tmp_path / "fault.mcap"
    argv = [
        "run",
        "--box",
        "sim://?seed=1&faults=nan:4@6.5",
        "--hold-s",
        "1",
        "--record",
        str(path),
    ]
    assert main(argv) == 3  # a hardware fault
    assert "channel 4" in capsys.readouterr().err
    run = load_recording(path)
    assert run.complete and run.t_s[-1] >= 6.49 and run.events_of("fault")
    assert run.outcome == "fault"


@pytest.mark.parametrize(
    ("detector", "outcome"),
    [("thesis", "contact_not_detected"), ("cusum", "held"), ("adaptive", "held")],
)
def test_run_detector_by_name(cli, detector: str, outcome: str) -> None:
    """Object 1, seed 2, 100 Hz: a fingertip lands where the thesis's 10-sample average stays
    under t_g; the calibrated CUSUMs (chosen with --detector) see the touch."""
    code, out, _ = cli(
        "run", "--objects", "object-1", "--hold-s", "0", "--box", "sim://?seed=2",
        "--detector", detector, "--json",
    )  # fmt: skip
    assert code == (0 if outcome == "held" else 1)  # a grasp not held exits 1
    d = json.loads(out)
    assert d["outcome"] == outcome
    assert (d["contact_delay_s"] is not None) == (detector != "thesis")


def test_run_planner_by_name_moves_the_seam_grasp(cli) -> None:
    """Object 1's thesis grasp puts a fingertip on the 3|6 seam (docs/beat-the-thesis.md); the
    gripper-aware planner (--planner) moves it, and says so in the plan's rule."""
    runs = {}
    for planner in ("thesis", "gripper-aware"):
        code, out, _ = cli(
            "run", "--objects", "object-1", "--hold-s", "0", "--box", "sim://?seed=3",
            "--planner", planner, "--json",
        )  # fmt: skip
        assert code == 0
        runs[planner] = json.loads(out)["objects"][0]
    assert "+gripper" not in runs["thesis"]["rule"]
    assert runs["gripper-aware"]["rule"].endswith("+gripper")
    assert runs["gripper-aware"]["cog"] != runs["thesis"]["cog"]


def test_run_planner_keeps_the_seam_grasp_for_a_detector_that_senses_it(cli) -> None:
    """With --detector adaptive the planner is told the detector's sensing ratio (0.44 at
    100 Hz): a sole across the seam raises enough, and object 1's thesis grasp stays."""
    runs = {}
    for planner in ("thesis", "gripper-aware"):
        code, out, _ = cli(
            "run", "--objects", "object-1", "--hold-s", "0", "--box", "sim://?seed=3",
            "--planner", planner, "--detector", "adaptive", "--json",
        )  # fmt: skip
        assert code == 0
        runs[planner] = json.loads(out)["objects"][0]
    assert runs["gripper-aware"]["rule"] == runs["thesis"]["rule"]
    assert runs["gripper-aware"]["cog"] == runs["thesis"]["cog"]


def test_run_retries_a_grasp_that_landed_on_the_can(cli) -> None:
    """The can seen as a square of four modules: the gripper-aware plan closes along its
    length, the jaws land on it (stop ~50 mm above the pad base) and close on nothing; the
    loop retries the turned grasp and holds it. ``--max-attempts 1`` keeps the one grasp."""
    base = ["run", "--objects", "cylinder", "--hold-s", "0", "--box", "sim://?seed=1"]
    base += ["--planner", "gripper-aware", "--detector", "adaptive", "--json"]
    code, out, _ = cli(*base)
    assert code == 0
    (g,) = json.loads(out)["grasps"]
    assert g["attempts"] == 2 and g["outcome"] == "held"
    assert g["plan"]["rule"].endswith("+turned-after-miss+load-centred")
    assert g["stop_z_m"] < 0.017
    code, out, _ = cli(*base, "--max-attempts", "1")
    assert code == 1
    (g,) = json.loads(out)["grasps"]
    assert g["attempts"] == 1 and g["outcome"] == "missed" and g["stop_z_m"] > 0.017


def test_unknown_part_names_are_refused(cli) -> None:
    code, _, err = cli("run", "--planner", "magic")
    assert code == 2 and "invalid choice: 'magic'" in err


def test_the_timeline_says_whether_a_retry_followed_a_close() -> None:
    """A retry after the jaws closed on nothing and one at the landing (``closed`` False,
    the jaws not closed) read differently; an event without ``closed`` (a run recorded
    before it existed) reads as after a close."""
    from softpad.harness import retry_text as _retry_text

    event = dict(z_m=0.0291, cog=[1.33, 1.12], theta=1.5708, rule="n6+shifted-after-miss")
    after = _retry_text(event)
    assert after.startswith("the jaws closed on nothing after the fingers landed 29.1 mm")
    assert _retry_text({**event, "closed": True}) == after
    early = _retry_text({**event, "closed": False})
    assert "not closing" in early and "closed on nothing" not in early
    assert early.endswith("trying COG (1.33, 1.12) theta +1.571 rad [n6+shifted-after-miss]")


def test_drop_carried_is_an_option_of_run() -> None:
    """``--drop-carried`` (default) and ``--no-drop-carried`` reach the loop's parameters;
    the timeline names the modules that went up with the held object."""
    from softpad.cli._run import execution_params
    from softpad.cli.main import build_parser
    from softpad.harness import EVENT_TEXT as _EVENT_TEXT

    p = build_parser()
    assert execution_params(p.parse_args(["run"])).drop_carried is True
    assert execution_params(p.parse_args(["run", "--no-drop-carried"])).drop_carried is False
    (line,) = _EVENT_TEXT["carried"]({"modules": [4]})
    assert line.startswith("module(s) 4 unloaded during the hold")
