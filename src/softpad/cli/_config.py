"""``softpad config check FILE``: validate an installation file and print the resolved values."""

from __future__ import annotations

import argparse
import sys
from typing import Any


def register(sub: Any) -> None:
    p = sub.add_parser(
        "config",
        help="installation file (TOML): check it and print the resolved values",
        description="Installation file utilities (see examples/site.toml, docs/hardware.md).",
    )
    csub = p.add_subparsers(dest="config_command", metavar="ACTION")
    c = csub.add_parser(
        "check",
        help="validate FILE and print every resolved value with its unit",
        description="Validate an installation file; a wrong value is named with its key (exit 2).",
    )
    c.add_argument("file", metavar="FILE.toml")
    c.add_argument("--json", action="store_true", help="print the resolved settings as JSON")
    c.set_defaults(handler=check)
    p.add_argument("--json", action="store_true", help=argparse.SUPPRESS)
    p.set_defaults(handler=_usage, _parser=p)


def _usage(args: argparse.Namespace) -> int:
    from softpad.cli.main import UsageError

    args._parser.print_help(sys.stderr)
    raise UsageError("an ACTION is required: check (see softpad config --help)")


def check(args: argparse.Namespace) -> int:
    from softpad.config import describe, load_installation

    inst = load_installation(args.file)
    if args.json:
        import dataclasses

        from softpad.cli._output import emit

        emit({"file": args.file, "installation": dataclasses.asdict(inst)})
        return 0
    for line in describe(inst):
        print(line)
    print("ok")
    return 0
