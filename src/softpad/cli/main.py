"""Entry point of the ``softpad`` command.

Sub-commands are registered by private modules (``_plan``, ``_box``, ...), each with a
``register(subparsers)`` function; heavy libraries are imported only inside the handlers.
Every exception becomes a one-line message and the exit code of its class
(:func:`softpad.errors.exit_code_for`); with ``--json`` stdout carries one JSON object
``{"schema_version": ..., "error": {"kind", "message", ...}}`` instead.
"""

from __future__ import annotations

import argparse
import importlib
import os
import sys
import traceback
from collections.abc import Sequence
from typing import Any, NoReturn

from softpad import __version__
from softpad.cli._args import UsageError, plain_float, plain_int
from softpad.cli._installation import add_config_options, apply_installation
from softpad.cli._signals import Terminated, exit_code_of_interrupt, sigterm_stops
from softpad.errors import (
    EXIT_INPUT,
    SoftPadError,
    exit_code_for,
)

#: Modules that register sub-commands, in the order they appear in ``softpad --help``.
_COMMAND_MODULES = (
    "_plan",
    "_run",
    "_box",
    "_config",
    "_trials",
    "_compare",
    "_learn",
    "_validate",
    "_calibrate",
    "_results",
    "_fem",
    "_design",
    "_pad",
    "_demo",
    "_replay",
    "_log",
    "_bench",
    "_ros",
    "_ros2",
    "_completion",
)

EXIT_USAGE = EXIT_INPUT

#: Where internal errors (bugs) are reported.
REPORT_URL = "the SoftPad issue tracker (issues new), with the command line and softpad --version"

EXIT_CODES_HELP = """exit codes (the same for every command):
  0  success: every grasp held, every study done (for trials, demo, fem: the study ran;
     its failed grasps are results)
  1  the job ran but failed (a grasp not held in 'run'; a model that did not converge)
  2  bad input: usage, values, files (nothing was started)
  3  hardware or link fault (the box was put in a safe state)
  4  internal error: a bug; the message says where to report it (--debug shows the traceback)
  130, 143  stopped by Ctrl-C (SIGINT) or SIGTERM, after the same clean-up

--json (every command): stdout carries one JSON object with "schema_version" and the result,
or {"schema_version": 1, "error": {"kind", "message", ...what was gathered before}}; streaming
commands (box read) print one object per line, the last one the error if any. Human text goes
to stderr.
"""


class _Parser(argparse.ArgumentParser):
    """ArgumentParser without prefix abbreviations whose usage errors raise :class:`UsageError`."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        kwargs["allow_abbrev"] = False
        super().__init__(*args, **kwargs)
        # type=int and type=float take plain ASCII numbers only (not 1_0, ٣ or １)
        self.register("type", int, plain_int)
        self.register("type", float, plain_float)

    def _get_values(self, action: argparse.Action, arg_strings: list[str]) -> Any:
        # argparse drops a value "--" (--flag=--) and hands [] on instead of a string
        if arg_strings == ["--"] and action.option_strings and action.nargs is None:
            value = self._get_value(action, "--")
            self._check_value(action, value)
            return value
        return super()._get_values(action, arg_strings)

    def error(self, message: str) -> NoReturn:
        raise UsageError(f"{message} (see {self.prog} --help)")


_registered: dict[str, dict[str, Any]] = {}  # module: {its command: its help line}


def build_parser(argv: Sequence[str] | None = None) -> argparse.ArgumentParser:
    """The ``softpad`` parser with every sub-command registered; for ``argv``, only the command
    it names gets its options and the others their names and help lines (once one build has
    read them): 2-6 ms instead of 15-20 (issue 50); ``--help`` and every message stay."""
    parser = _Parser(
        prog="softpad",
        description=(
            "SoftPad: soft sensorized pneumatic surfaces for grasping with rigid grippers. "
            "Plans grasps from module pressure increments, runs the closed loop on a simulated "
            "pneumatic box, and models a module with finite elements."
        ),
        epilog=EXIT_CODES_HELP,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    parser.add_argument("--version", action="version", version=f"softpad {__version__}")
    parser.add_argument(
        "--debug", action="store_true", help="show the traceback of internal errors"
    )
    parser.add_argument("--json", action="store_true", help=argparse.SUPPRESS)
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    word = next((w for w in argv or () if w not in ("-h", "--help", "--version", "--json")), "")
    command = None if argv is None or word.startswith("-") else word  # None: argparse's reading
    for module in _COMMAND_MODULES:
        known = _registered.get(module)
        if command is not None and known is not None and command not in known:
            for name, help in known.items():  # placeholders, never parsed with
                sub.add_parser(name, help=help, add_help=False)
            continue
        start = len(sub._choices_actions)
        importlib.import_module(f"softpad.cli.{module}").register(sub)
        known = _registered[module] = {a.dest: a.help for a in sub._choices_actions[start:]}
        for name in known:
            add_config_options(sub.choices[name])
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Run the ``softpad`` command line ``argv``; return its exit code."""
    argv = list(sys.argv[1:] if argv is None else argv)
    debug = "--debug" in argv or os.environ.get("SOFTPAD_DEBUG") == "1"
    argv = [a for a in argv if a != "--debug"]
    json_mode = "--json" in argv
    name = next((a for a in argv if not a.startswith("-")), "")
    args: argparse.Namespace | None = None
    try:
        parser = build_parser(argv)
        apply_installation(parser, argv)
        args = parser.parse_args(argv)
        name = args.command or ""
        if not getattr(args, "handler", None):
            parser.print_help(sys.stderr if json_mode else sys.stdout)
            if json_mode:
                raise UsageError("a COMMAND is required (see softpad --help)")
            return EXIT_USAGE
        with sigterm_stops():
            return int(args.handler(args) or 0)
    except KeyboardInterrupt as exc:  # Ctrl-C: 130; SIGTERM: 143 (docs/cli.md)
        stopped = "terminated" if isinstance(exc, Terminated) else "interrupted"
        print(f"softpad {name}: {stopped}", file=sys.stderr)
        if json_mode:  # what was finished before Ctrl-C, as the one JSON object on stdout
            from softpad.cli._output import emit, error_object

            emit(
                error_object(
                    "interrupted", f"{stopped} by a signal", getattr(args, "partial", None)
                )
            )
        return exit_code_of_interrupt(exc)
    except BrokenPipeError:
        return 0
    except Exception as exc:  # every error: one line, the exit code of its class
        return _report(exc, name, json_mode, debug, args)


def _report(exc: BaseException, name: str, json_mode: bool, debug: bool, args: Any) -> int:
    from softpad.cli._output import emit, error_object

    code = exit_code_for(exc)
    prog = f"softpad {name}".strip()
    if isinstance(exc, SoftPadError):
        kind, message = exc.kind, str(exc)
    elif isinstance(exc, OSError) and exc.filename is not None:  # a file that cannot be used
        code, kind = EXIT_INPUT, "input"
        message = f"cannot use file {exc.filename!r}: {exc.strerror or exc}"
    else:
        kind = "internal"
        message = (
            f"internal error: {type(exc).__name__}: {exc}. This is a bug; please report it to "
            f"{REPORT_URL}" + ("" if debug else " (rerun with --debug for the traceback)")
        )
    if debug:
        traceback.print_exception(exc, file=sys.stderr)
    print(f"{prog}: error: {message}", file=sys.stderr)
    if json_mode:
        partial = getattr(exc, "partial", None) or getattr(args, "partial", None)
        emit(error_object(kind, message, partial))
    return code


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
