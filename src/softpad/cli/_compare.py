"""``softpad compare``: planner/detector pairs side by side on Experiment 2 over many seeds."""

from __future__ import annotations

import argparse
import sys
from typing import Any

from softpad.cli._args import add_command, int_ranges
from softpad.errors import InputError

_EPILOG = """examples:
  softpad compare --seeds 0-19 --json            the thesis pair against gripper-aware + adaptive
  softpad compare --seeds 0-2 --objects object-1,cylinder --pair thesis:cusum
  softpad compare --seeds 0 --objects-file src/softpad/data/object_sets/ycb-dev.toml --json
  softpad compare --seeds 0 --trials 1 --idle-hours 0.1 --png compare.png
  softpad compare --merge a.json --merge b.json --png both.png   pairs run apart, one table
"""


_DESCRIPTION = """\
Run Experiment 2 (MuJoCo trials) for each planner/detector pair over the given seeds and
print per-pair and per-object success with 95 % Wilson intervals, failures by cause,
detection delay and finger travel (median, p95) and the detector's false alarms per hour on
an idle pad with noise and drift."""


def register(sub: Any) -> None:
    from softpad.cli._trials import add_mounting_option, add_randomize_option, add_trial_options
    from softpad.planning import available_planners
    from softpad.sensing import available_contact_detectors

    p = add_command(
        sub,
        "compare",
        "compare planner/detector pairs on Experiment 2 over many seeds",
        _DESCRIPTION,
        _EPILOG,
        json="print the comparison as one JSON object",
    )
    add_trial_options(p, seeds="0-9")
    add_randomize_option(p)
    add_mounting_option(p, "each object's own: Table 6.1's per Section 6.3, an object set's")
    p.add_argument(
        "--pair",
        action="append",
        metavar="PLANNER:DETECTOR",
        help="a pair to run (repeatable; default thesis:thesis and gripper-aware:adaptive); "
        f"PLANNER from {', '.join(available_planners())}, DETECTOR from "
        f"{', '.join(available_contact_detectors())}",
    )
    p.add_argument("--idle-hours", type=float, default=1.0, help="idle time for false alarms")
    p.add_argument(
        "--catalogue",
        metavar="FILE.toml",
        help="known objects (softpad learn) for the catalogue planner's pairs",
    )
    p.add_argument("--png", metavar="FILE.png", help="draw success and delay per pair")
    p.add_argument("--force", action="store_true", help="overwrite an existing --png file")
    p.add_argument(
        "--merge",
        action="append",
        metavar="FILE.json",
        help="run nothing: print (and draw) the pairs of saved 'compare --json' outputs of the "
        "same seeds and objects as one comparison (repeatable)",
    )
    p.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    import math

    from softpad.cli._paths import check_output
    from softpad.cli._trials import select_objects
    from softpad.trials import TrialConfig, check_counts, compare, parse_pairs

    check_output(args.png, "--png", force=args.force, suffix=".png")  # before hours of trials
    if args.merge:
        return _show(_merged(args), args)
    seeds, pairs = int_ranges(args.seeds, "--seeds", lo=0, hi=2**32 - 1), parse_pairs(args.pair)
    specs = select_objects(args.objects, args.objects_file)
    check_counts(args.trials, args.workers)
    if args.catalogue:
        from softpad.planning import load_catalogue

        load_catalogue(args.catalogue)  # a bad file is named before any trial
    if not (math.isfinite(args.idle_hours) and 0 < args.idle_hours <= 100):
        raise InputError(f"--idle-hours must be in (0, 100] h, got {args.idle_hours!r}")
    bar = _bar(len(specs) * args.trials * len(seeds) * len(pairs), not args.no_progress)
    try:
        d = compare(
            specs,
            seeds,
            pairs,
            trials=args.trials,
            workers=args.workers,
            idle_hours=args.idle_hours,
            config=TrialConfig(
                randomize=args.randomize, catalogue=args.catalogue, mounting=args.mounting
            ),
            on_trial=(lambda _: bar.update(1)) if bar else None,
        )
    finally:
        if bar is not None:
            bar.close()
    return _show(d, args)


def _merged(args: argparse.Namespace) -> dict[str, Any]:
    """The comparisons of the ``--merge`` files as one."""
    from softpad.trials import read_comparisons

    if args.pair:
        raise InputError("--merge runs no pair: leave out --pair (each file names its own)")
    return read_comparisons(args.merge)


def _show(d: dict[str, Any], args: argparse.Namespace) -> int:
    """Draw, then print the comparison as JSON or as a table."""
    from softpad.trials import comparison_table, plot_comparison

    if args.png:
        plot_comparison(d).savefig(args.png, dpi=120)
    if args.json:
        from softpad.cli._output import emit

        emit(d)
    else:
        print(comparison_table(d))
    from softpad.cli._trials import trial_errors_exit

    return trial_errors_exit(
        [t for c in d["combinations"] for t in c.get("errored", [])], "compare"
    )


def _bar(total: int, enabled: bool) -> Any:
    from softpad.cli._trials import progress_bar

    return progress_bar(total, enabled and sys.stderr.isatty(), desc="compare")
