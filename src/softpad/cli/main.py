"""Entry point of the ``softpad`` command.

Sub-commands are registered by private modules (``_plan``, ``_box``, ...), each with a
``register(subparsers)`` function; heavy libraries are imported only inside the handlers.
Every :class:`~softpad.errors.SoftPadError` becomes a one-line message and exit code 2.
"""

from __future__ import annotations

import argparse
import importlib
import sys
from collections.abc import Sequence
from typing import NoReturn

from softpad import __version__
from softpad.errors import SoftPadError

#: Modules that register sub-commands, in the order they appear in ``softpad --help``.
_COMMAND_MODULES = (
    "_plan",
    "_run",
    "_box",
    "_config",
    "_trials",
    "_compare",
    "_fem",
    "_demo",
    "_replay",
    "_log",
    "_bench",
)

EXIT_USAGE = 2


class _Parser(argparse.ArgumentParser):
    """ArgumentParser whose usage errors are one line (the value and what is allowed)."""

    def error(self, message: str) -> NoReturn:
        self.exit(EXIT_USAGE, f"{self.prog}: error: {message} (see {self.prog} --help)\n")


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(
        prog="softpad",
        description=(
            "SoftPad: soft sensorized pneumatic surfaces for grasping with rigid grippers. "
            "Plans grasps from module pressure increments, runs the closed loop on a simulated "
            "pneumatic box, and models a module with finite elements."
        ),
    )
    parser.add_argument("--version", action="version", version=f"softpad {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    for name in _COMMAND_MODULES:
        module = importlib.import_module(f"softpad.cli.{name}")
        module.register(sub)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    if not getattr(args, "handler", None):
        parser.print_help()
        return EXIT_USAGE
    try:
        return int(args.handler(args) or 0)
    except SoftPadError as exc:
        print(f"softpad {args.command}: error: {exc}", file=sys.stderr)
        return EXIT_USAGE
    except KeyboardInterrupt:
        print(f"softpad {args.command}: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:
        return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
