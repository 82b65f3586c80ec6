"""``softpad config check FILE``: validate an installation file and print the resolved values."""

from __future__ import annotations

import argparse
from typing import Any

from softpad.cli._args import add_command, add_group


def register(sub: Any) -> None:
    csub = add_group(
        sub,
        "config",
        "installation file (TOML): check it and print the resolved values",
        "Installation file utilities (see examples/site.toml, docs/hardware.md).",
        "examples:\n  softpad config check examples/site.toml      every resolved value with its unit\n"
        "  softpad run --config examples/site.toml       the file's values as the defaults\n",
    )
    c = add_command(
        csub,
        "check",
        "validate FILE and print every resolved value with its unit",
        "Validate an installation file: every wrong value is named with its key, and every "
        "unreadable or wrong password file, certificate or key (exit 2); weak security "
        "settings are warned about on stderr.",
        json="print the resolved settings as JSON",
    )
    c.add_argument("file", metavar="FILE.toml")
    c.set_defaults(handler=check)


def check(args: argparse.Namespace) -> int:
    import sys

    from softpad.config import check_installation_file, describe

    inst, warnings = check_installation_file(args.file)  # every error of the file at once
    if args.json:
        import dataclasses

        from softpad.cli._output import emit

        emit({"file": args.file, "installation": dataclasses.asdict(inst), "warnings": warnings})
        return 0
    for w in warnings:
        print(f"softpad config: warning: {w}", file=sys.stderr)
    for line in describe(inst):
        print(line)
    print("ok")
    return 0
