"""The scripting contract of the ``softpad`` command (issue 16): exit codes by outcome, JSON on
every path, output files checked before the work and written atomically, options that agree."""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest

from softpad.cli.main import build_parser, main
from softpad.errors import (
    EXIT_FAILED,
    EXIT_HARDWARE,
    EXIT_INPUT,
    EXIT_INTERNAL,
    EXIT_OK,
    HardwareFault,
    InputError,
    JobFailed,
    exit_code_for,
)

BANANA = "0,0.124,0.078,0.109,0,0"


def _json(capsys: pytest.CaptureFixture[str], *argv: str) -> tuple[int, dict, str]:
    code = main(list(argv))
    captured = capsys.readouterr()
    assert "Traceback" not in captured.err
    lines = captured.out.strip().splitlines()
    assert len(lines) == 1, captured.out  # one JSON object on stdout, nothing else
    data = json.loads(lines[0])
    assert data["schema_version"] >= 1
    return code, data, captured.err


def test_exit_code_of_each_exception_class() -> None:
    from softpad.box import ConnectionLost

    assert exit_code_for(InputError("x")) == EXIT_INPUT == 2
    assert exit_code_for(HardwareFault("x")) == EXIT_HARDWARE == 3
    assert exit_code_for(ConnectionLost("x")) == EXIT_HARDWARE
    assert exit_code_for(JobFailed("x")) == EXIT_FAILED == 1
    assert exit_code_for(KeyError("x")) == EXIT_INTERNAL == 4
    assert EXIT_OK == 0


def test_held_grasp_exits_0_with_json(capsys) -> None:
    code, data, _ = _json(capsys, "run", "--objects", "object-5", "--hold-s", "1", "--json")
    assert code == 0 and data["outcome"] == "held" and "error" not in data


def test_failed_grasp_exits_1_with_the_result_and_an_error(capsys) -> None:
    # object 1 on the 10/4 mounting: the fingertips miss the pad's sensitive area (seed run)
    argv = ["run", "--objects", "object-1", "--hold-s", "1", "--json"]
    code, data, _ = _json(capsys, *argv)
    assert code == 1
    assert data["outcome"] != "held"
    assert data["error"]["kind"] == "failed" and data["outcome"] in data["error"]["message"]


def test_bad_input_exits_2_with_json_naming_the_value(capsys) -> None:
    code, data, err = _json(capsys, "run", "--objects", "teapot", "--json")
    assert code == 2 and data["error"]["kind"] == "input"
    assert "teapot" in data["error"]["message"] and "teapot" in err


def test_usage_error_exits_2_with_json(capsys) -> None:
    code, data, _ = _json(capsys, "plan", "--delta", BANANA, "--bogus", "--json")
    assert code == 2 and "--bogus" in data["error"]["message"]


def test_link_fault_exits_3_with_json(capsys) -> None:
    import socket

    s = socket.create_server(("127.0.0.1", 0))
    port = s.getsockname()[1]
    s.close()
    code, data, _ = _json(
        capsys, "box", "inflate", "--box", f"zenoh://127.0.0.1:{port}?timeout_s=0.2", "--json"
    )
    assert code == 3 and data["error"]["kind"] == "hardware"


def test_internal_error_exits_4_naming_where_to_report(capsys, monkeypatch) -> None:
    import softpad.planning

    def broken(*args, **kwargs):
        raise ZeroDivisionError("boom")

    monkeypatch.setattr(softpad.planning, "plan_by_name", broken)
    code, data, err = _json(capsys, "plan", "--delta", BANANA, "--json")
    assert code == 4 and data["error"]["kind"] == "internal"
    assert "boom" in err and "report" in err and "--debug" in err
    assert main(["--debug", "plan", "--delta", BANANA]) == 4
    assert "Traceback" in capsys.readouterr().err  # only with --debug


def test_streaming_json_ends_with_the_error_line(capsys) -> None:
    code = main(
        ["box", "read", "--box", "zenoh://127.0.0.1:1?timeout_s=0.2", "--count", "2", "--json"]
    )
    lines = capsys.readouterr().out.strip().splitlines()
    assert code == 3 and json.loads(lines[-1])["error"]["kind"] == "hardware"
    code = main(["box", "read", "--count", "3", "--json"])
    lines = capsys.readouterr().out.strip().splitlines()
    assert code == 0 and len(lines) == 3
    assert all("pressures_kpa" in json.loads(line) for line in lines)


def test_help_documents_the_exit_codes(capsys) -> None:
    with pytest.raises(SystemExit):
        main(["--help"])
    out = capsys.readouterr().out
    for text in (
        "exit codes",
        "0  success",
        "1  the job ran",
        "2  bad input",
        "3  hardware",
        "4  internal",
    ):
        assert text in out
    doc = (Path(__file__).parents[2] / "docs" / "cli.md").read_text()
    assert "| 3 |" in doc and "--json" in doc


# --------------------------------------------------------------- no lost work
@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["run", "--record", "/nonexistent/dir/x.mcap"], "does not exist"),
        (["run", "--png", "/nonexistent/dir/x.png"], "does not exist"),
        (["run", "--record", "x.txt"], "must name a .mcap file"),
        (["plan", "--delta", BANANA, "--png", "DIR"], "must name a .png file"),
        (["fem", "characteristic", "--out", ""], "needs a file name"),
        (["fem", "characteristic", "--out", "c.txt"], "must name a .npz file"),
        (["fem", "sweep", "--csv", "same.csv", "--png", "/nonexistent/p.png"], "does not exist"),
        (["demo", "--out", "/proc/x"], "--out"),
    ],
)
def test_outputs_are_checked_before_any_work(capsys, monkeypatch, tmp_path, argv, message) -> None:
    import softpad.harness

    def never(*args, **kwargs):
        raise AssertionError("the work started before the output paths were checked")

    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(softpad.harness, "run_simulated", never)
    monkeypatch.setattr(softpad.harness, "run_objects", never)
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert message in err and err.count("\n") == 1


def test_an_existing_file_is_refused_without_force(capsys, monkeypatch, tmp_path) -> None:
    monkeypatch.chdir(tmp_path)
    Path("run.mcap").write_bytes(b"old")
    Path("run.png").write_bytes(b"old")
    argv = [
        "run",
        "--objects",
        "object-5",
        "--hold-s",
        "0",
        "--record",
        "run.mcap",
        "--png",
        "run.png",
    ]
    assert main(argv) == 2
    assert "add --force" in capsys.readouterr().err
    assert Path("run.mcap").read_bytes() == b"old"
    assert main([*argv, "--force"]) == 0
    from softpad.record import load_recording

    assert load_recording("run.mcap").complete
    assert Path("run.png").read_bytes()[:4] == b"\x89PNG"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["run.mcap", "run.png"]  # no temp file


def test_atomic_write_keeps_the_old_file_when_the_writer_fails(tmp_path) -> None:
    from softpad.cli._paths import atomic_path, write_text_atomic

    target = tmp_path / "table.csv"
    write_text_atomic(target, "old\n")
    with pytest.raises(RuntimeError), atomic_path(target) as tmp:
        tmp.write_text("half")
        raise RuntimeError("crash while writing")
    assert target.read_text() == "old\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["table.csv"]
    assert oct(target.stat().st_mode & 0o777) == oct(0o666 & ~_umask())


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def test_fem_characteristic_writes_to_the_working_folder_by_default() -> None:
    (action,) = [
        a for a in _subparser("fem", "characteristic")._actions if "--out" in a.option_strings
    ]
    assert action.default == "characteristic.npz"


# --------------------------------------------------------------- options that agree
def _subparser(*path: str):
    import argparse

    p = build_parser()
    for name in path:
        (sub,) = [a for a in p._actions if isinstance(a, argparse._SubParsersAction)]
        p = sub.choices[name]
    return p


def _all_parsers():
    import argparse

    todo = [("", build_parser())]
    while todo:
        name, p = todo.pop()
        yield name, p
        for a in p._actions:
            if isinstance(a, argparse._SubParsersAction):
                todo += [(f"{name} {n}".strip(), c) for n, c in a.choices.items()]


def test_every_parser_refuses_abbreviations_and_offers_json() -> None:
    for name, p in _all_parsers():
        assert p.allow_abbrev is False, name
        options = {s for a in p._actions for s in a.option_strings}
        assert "--json" in options, name
        assert "--plot" not in options or name in ("run", "plan"), name  # only the renamed stub


@pytest.mark.parametrize(
    ("group", "names"),
    [
        ("box", "read, monitor, stats, serve or inflate"),
        ("config", "check"),
        (
            "fem",
            "sweep, design, stiffness, sensitivity, chamber, fit, compare, characteristic, response or cast-response",
        ),
        ("log", "info, plot, export or recover"),
        ("pad", "probe, map or sensitivity"),
        ("ros", "node, env or urdf"),
        ("sim", "arm-node"),
    ],
    ids=lambda v: v.split(",")[0],
)
def test_a_group_without_its_command_is_a_usage_error_naming_them(capsys, group, names) -> None:
    assert main([group, "--json"]) == 2
    captured = capsys.readouterr()
    assert f"is required: {names} (see softpad {group} --help)" in captured.err.splitlines()[-1]
    assert json.loads(captured.out)["error"]["kind"] == "input"


def test_abbreviated_options_are_usage_errors(capsys) -> None:
    assert main(["fem", "compare", "--data", "x.csv", "--model", "yeoh"]) == 2
    assert "--model" in capsys.readouterr().err


def test_renamed_options_name_the_new_spelling(capsys) -> None:
    assert main(["run", "--plot", "x.png"]) == 2
    assert "--png" in capsys.readouterr().err
    assert main(["trials", "--seed", "3"]) == 2
    assert "--seeds" in capsys.readouterr().err


@pytest.mark.parametrize(
    ("text", "values"),
    [("7", [7]), ("0-3", [0, 1, 2, 3]), ("0-2,7", [0, 1, 2, 7]), ("2,2,1", [2, 1])],
)
def test_seed_ranges(text, values) -> None:
    from softpad.cli._args import int_ranges

    assert int_ranges(text, "--seeds") == values


@pytest.mark.parametrize("text", ["-1", "3-1", "a", "", "1-", "0-99999"])
def test_bad_seed_ranges_name_the_item(text) -> None:
    from softpad.cli._args import int_ranges

    with pytest.raises(InputError, match="--seeds"):
        int_ranges(text, "--seeds")


def test_shell_completion_is_generated_from_the_parser(capsys, tmp_path) -> None:
    import shutil
    import subprocess

    assert main(["completion", "bash"]) == 0
    script = capsys.readouterr().out
    assert "complete -o filenames -F _softpad softpad" in script
    assert main(["completion", "zsh"]) == 0
    assert capsys.readouterr().out.startswith("#compdef softpad")
    if shutil.which("bash") is None:
        pytest.skip("no bash")
    (tmp_path / "c.sh").write_text(script)
    probe = (
        f"source {tmp_path / 'c.sh'}; COMP_WORDS=(softpad fem cha); COMP_CWORD=2; _softpad; "
        'echo "${COMPREPLY[@]}"; COMP_WORDS=(softpad run --p0); COMP_CWORD=2; _softpad; '
        'echo "${COMPREPLY[@]}"'
    )
    out = subprocess.run(["bash", "-c", probe], capture_output=True, text=True, check=True).stdout
    assert out.split("\n")[:2] == ["chamber characteristic", "--p0-kpa"]


# --------------------------------------------------------------- thesis parameters, units
def test_run_passes_the_thesis_parameters_in_si(monkeypatch, capsys) -> None:
    import softpad.harness

    seen = {}

    def capture(names, box, params, *rest):
        seen["params"] = params
        raise InputError("stop here")

    monkeypatch.setattr(softpad.harness, "run_objects", capture)
    argv = ["run", "--p0-kpa", "1.5", "--object-threshold-kpa", "0.07"]
    argv += ["--contact-threshold-kpa", "0.12", "--window", "5", "--approach-speed-mps", "0.02"]
    assert main(argv) == 2
    p = seen["params"]
    assert p.inflation.target_pa == pytest.approx(1500.0)
    assert p.planner.object_threshold_pa == pytest.approx(70.0)
    assert p.contact_threshold_pa == pytest.approx(120.0)
    assert p.filter_length == 5 and p.approach_speed_m_s == pytest.approx(0.02)


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["run", "--p0-kpa", "1100"], "--p0-kpa must be <= 2.8 kPa, got 1100"),
        (["run", "--p0-kpa", "0.2"], "--p0-kpa must be >= 0.5 kPa"),
        (["run", "--window", "0"], "--window must be from 1 to 200, got 0"),
        (["run", "--contact-threshold-kpa", "90"], "got 90 kPa"),
        (["run", "--approach-speed-mps", "5"], "got 5 m/s"),
        (["plan", "--delta", "0,124,78,109,3,2"], "were pascals given as kPa?"),
        (
            [
                "plan",
                "--pressures",
                "1200,1.1,1.1,1.1,1.1,1.1",
                "--reference",
                "1.1,1.1,1.1,1.1,1.1,1.1",
            ],
            "1200 kPa, outside the sensor range",
        ),
        (
            [
                "plan",
                "--pressures=-5,1.1,1.1,1.1,1.1,1.1",
                "--reference",
                "1.1,1.1,1.1,1.1,1.1,1.1",
            ],
            "-5 kPa, outside the sensor range",
        ),
        (["fem", "sweep", "--points", "1000000000"], "--points must be from 2 to 200"),
        (["fem", "chamber", "--footprint-mm", "1000x1000"], "wider than the module"),
        (["fem", "stiffness", "--radius-mm", "100"], "below half the module width"),
        (["bench", "--only", ""], "--only needs"),
        (["bench", "--only", ","], "--only needs"),
        (["trials", "--objects", "banana,banana"], "'banana' is named twice"),
        (["trials", "--seeds=-1"], "--seeds: '-1'"),
        (["run", "--box", "zenoh://[::1:5757"], "malformed box URL"),
        (["run", "--box", "sim://?seed=-1", "--hold-s", "0"], "seed must be >= 0"),
    ],
)
def test_implausible_values_are_refused_naming_them(capsys, argv, message) -> None:
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert message in err and err.count("\n") == 1 and "Traceback" not in err


def test_api_rejects_unit_mixups() -> None:
    from softpad.planning import PlannerParams, plan_grasps

    with pytest.raises(InputError, match="pascals given as kPa"):
        plan_grasps([0, 124e3, 78e3, 109e3, 0, 0])
    with pytest.raises(InputError, match="kPa given as pascals"):
        plan_grasps([0, 0.124, 0.078, 0.109, 0, 0])  # kPa-sized values planned nothing before
    with pytest.raises(InputError, match="kPa given as pascals"):
        PlannerParams(object_threshold_pa=0.05)
    with pytest.raises(InputError, match="theta"):
        PlannerParams(default_theta=float("nan"))
    (plan,) = plan_grasps([0, 124, 78, 109, 0, 0], layout="2x3")
    assert plan.modules == (2, 3, 4)
    with pytest.raises(InputError, match="layout"):
        plan_grasps([0, 124, 78, 109, 0, 0], layout=23)  # type: ignore[arg-type]


def test_run_simulated_with_no_object_is_refused() -> None:
    from softpad.harness import run_simulated

    with pytest.raises(InputError, match="no object"):
        run_simulated([])


@pytest.mark.parametrize("content", [b"\x89PNG\r\n\x1a\n\x00\xff\xfe", b"PK\x03\x04\xff\xfe\x00"])
def test_binary_files_are_input_errors(capsys, tmp_path, content) -> None:
    path = tmp_path / "garbage.bin"
    path.write_bytes(content)
    for argv in (
        ["plan", "--frame", str(path)],
        ["fem", "fit", "--data", str(path)],
        ["fem", "compare", "--data", str(path)],
    ):
        assert main(argv) == 2, argv
        assert "garbage.bin" in capsys.readouterr().err
