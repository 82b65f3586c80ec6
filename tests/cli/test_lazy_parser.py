"""``main`` builds only the command it runs (issue 50): every command's help, the list of
commands and the unknown-command message are those of the full parser, and a part registered
after a first build is offered by the next one."""

from __future__ import annotations

import argparse
import importlib

import pytest

from softpad.cli._args import UsageError
from softpad.cli._installation import leaf_parsers
from softpad.cli.main import build_parser, main
from softpad.planning import PLANNER_REGISTRY, ThesisPlanner, register_planner

cli_main = importlib.import_module("softpad.cli.main")


def _commands(parser: argparse.ArgumentParser) -> dict[str, argparse.ArgumentParser]:
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    return dict(sub.choices)


def _helps(parser: argparse.ArgumentParser) -> dict[str, str]:
    """The ``--help`` of ``parser`` and of every command under it, by prog."""
    out = {parser.prog: parser.format_help()}
    for command in _commands(parser).values():
        out.update({p.prog: p.format_help() for p in leaf_parsers(command)})
        out[command.prog] = command.format_help()
    return out


def test_each_commands_help_is_that_of_the_full_parser() -> None:
    full = build_parser()
    names = list(_commands(full))
    assert len(names) >= 20 and "run" in names and "sim" in names
    for name in names:
        lazy = build_parser([name])
        assert lazy.format_help() == full.format_help()  # softpad --help
        expected = {p.prog: p.format_help() for p in leaf_parsers(_commands(full)[name])}
        expected[f"softpad {name}"] = _commands(full)[name].format_help()
        got = _helps(lazy)
        assert {k: got[k] for k in expected} == expected, name


def _run(argv: list[str], capsys: pytest.CaptureFixture[str]) -> tuple[object, str, str]:
    try:
        code: object = main(argv)
    except SystemExit as exc:  # --help, --version
        code = exc.code
    out = capsys.readouterr()
    return code, out.out, out.err


@pytest.mark.parametrize(
    "argv",
    [[], ["--json"], ["--help"], ["--version"], ["nope"], ["--json", "nope"], ["run", "--help"],
     ["box", "read", "--help"], ["box"], ["run", "--p0-kpa", "9"], ["plan", "--nope"]],
)  # fmt: skip
def test_output_and_exit_code_are_those_of_the_full_parser(
    argv: list[str], capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    lazy = _run(argv, capsys)
    full = cli_main.build_parser
    monkeypatch.setattr(cli_main, "build_parser", lambda argv=None: full())  # all in full
    assert _run(argv, capsys) == lazy
    assert lazy[0] != 0 or "--help" in argv or "--version" in argv


def test_a_planner_registered_after_a_first_build_is_offered(
    capsys: pytest.CaptureFixture[str],
) -> None:
    assert _run(["run", "--help"], capsys)[0] == 0
    assert "test-late-planner" not in capsys.readouterr().out
    register_planner("test-late-planner", lambda context: ThesisPlanner(context.params), "late")
    try:
        code, out, _ = _run(["run", "--help"], capsys)
        assert code == 0 and "test-late-planner: late" in " ".join(out.split())
        args = build_parser(["run"]).parse_args(["run", "--planner", "test-late-planner"])
        assert args.planner == "test-late-planner"
    finally:
        PLANNER_REGISTRY.unregister("test-late-planner")
    with pytest.raises(UsageError, match="test-late-planner"):
        build_parser(["run"]).parse_args(["run", "--planner", "test-late-planner"])


@pytest.mark.parametrize(
    ("argv", "filled"),
    [
        ([], set()),
        (["run", "--json"], {"run"}),
        (["--json", "-h", "box", "read"], {"box"}),
        (["--", "run"], None),  # argparse's own reading: the full parser
        (["--config", "x.toml", "run"], None),
        (["--json=1", "run"], None),
    ],
)
def test_the_command_is_read_only_where_argparse_reads_it_so(
    argv: list[str], filled: set[str] | None
) -> None:
    """Only the command argparse will parse with has its options (placeholders: no -h)."""
    commands = _commands(build_parser()).keys()
    built = {n: p for n, p in _commands(build_parser(argv)).items() if p.add_help}
    assert set(built) == (set(commands) if filled is None else filled)
