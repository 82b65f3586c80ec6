"""``softpad bench``: run the benchmarks and print the measured figures."""

from __future__ import annotations

import argparse
import importlib
import json
from typing import Any

from softpad.errors import InputError


def register(sub: Any) -> None:
    from softpad.benchmarks import BENCH_MODULES

    p = sub.add_parser(
        "bench",
        help="measure speed and detection figures (medians)",
        description="Run the benchmarks: " + ", ".join(BENCH_MODULES) + ". Figures are medians.",
    )
    p.add_argument(
        "--only", metavar="NAMES", help="comma-separated subset of: " + ", ".join(BENCH_MODULES)
    )
    p.add_argument("--quick", action="store_true", help="fewer repeats (a smoke run)")
    p.add_argument("--json", action="store_true", help="print the results as JSON")
    p.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    from softpad.benchmarks import BENCH_MODULES

    names = list(BENCH_MODULES)
    if args.only:
        names = [s.strip() for s in args.only.split(",") if s.strip()]
        unknown = [n for n in names if n not in BENCH_MODULES]
        if unknown:
            raise InputError(
                f"unknown benchmark {unknown[0]!r}; choose from {', '.join(BENCH_MODULES)}"
            )
    out = []
    for name in names:
        module = importlib.import_module(f"softpad.benchmarks._{name}")
        if not args.json:
            print(f"== {name}", flush=True)
        for r in module.run(quick=args.quick):
            out.append({"suite": name, **r.__dict__})
            if not args.json:
                print("  " + r.line(), flush=True)
    if args.json:
        print(json.dumps(out, indent=1))
    return 0
