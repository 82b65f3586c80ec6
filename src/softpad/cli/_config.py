"""``softpad config check FILE``: validate an installation file and print the resolved values."""

from __future__ import annotations

import argparse
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
    c.set_defaults(handler=check)
    p.set_defaults(handler=_usage, _parser=p)


def _usage(args: argparse.Namespace) -> int:
    args._parser.print_help()
    return 2


def check(args: argparse.Namespace) -> int:
    from softpad.config import describe, load_installation

    for line in describe(load_installation(args.file)):
        print(line)
    print("ok")
    return 0
