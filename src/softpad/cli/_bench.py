"""``softpad bench``: run the benchmarks and print the measured figures."""

from __future__ import annotations

import argparse
import importlib
from typing import Any

from softpad.cli._args import add_command, name_list
from softpad.cli._output import emit
from softpad.errors import InputError


def register(sub: Any) -> None:
    from softpad.benchmarks import BENCH_MODULES

    p = add_command(
        sub,
        "bench",
        "measure speed and detection figures (medians)",
        "Run the benchmarks: " + ", ".join(BENCH_MODULES) + ". Figures are medians.",
    )
    p.add_argument(
        "--only", metavar="NAMES", help="comma-separated subset of: " + ", ".join(BENCH_MODULES)
    )
    p.add_argument("--quick", action="store_true", help="fewer repeats (a smoke run)")
    p.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    from softpad.benchmarks import BENCH_MODULES

    names = list(BENCH_MODULES)
    if args.only is not None:
        names = name_list(args.only, "--only")
        unknown = [n for n in names if n not in BENCH_MODULES]
        if unknown:
            raise InputError(
                f"unknown benchmark {unknown[0]!r}; choose from {', '.join(BENCH_MODULES)}"
            )
    out: list[dict[str, Any]] = []
    args.partial = {"results": out}
    for name in names:
        module = importlib.import_module(f"softpad.benchmarks._{name}")
        if not args.json:
            print(f"== {name}", flush=True)
        for r in module.run(quick=args.quick):
            out.append({"suite": name, **r.__dict__})
            if not args.json:
                print("  " + r.line(), flush=True)
    if args.json:
        emit({"results": out})
    return 0
