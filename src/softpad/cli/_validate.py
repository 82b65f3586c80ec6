"""``softpad validate``: the simulator against every real observation of the thesis."""

from __future__ import annotations

import argparse
import sys
from typing import Any

from softpad.cli._args import add_command, int_ranges
from softpad.cli._output import emit, say
from softpad.cli._trials import add_mounting_option
from softpad.errors import InputError

_EPILOG = """examples:
  softpad validate                      the static rows (about a minute); trial rows not run
  softpad validate --seeds 0-9 --json   with Experiment 2 in MuJoCo: 10 x 55 thesis-pair trials
  softpad validate --placements 200     more placement draws for the static rows

Rows (docs/validation.md): Experiment 2 overall and per object (thesis pair), the failure
causes the thesis names (seam misses of object 5 and the charger, the cylinder's COG outside,
no jaw landings), Table 6.1's plans, Fig. 6.7's plans, the cylinder's modules, the minimum
detectable mass at 1.1 kPa, the 12.6 g Duplo piece against t_o and the idle noise (Fig. 6.8).
Every row has a role, counted apart: validation (a test the simulator could fail),
calibration (an object's unknown was chosen from that row), construction (true by how the
object was built or placed). A count agrees when the 95 % Wilson intervals of the thesis and
the prediction overlap and the prediction rests on at least ten times the thesis's trials
(undecided when they overlap on fewer); each count states the smallest rate difference its
test detects with 80 % power. A plan agrees when the modal plan over the draws is within
0.1 module and 10 degrees of the thesis's. The rest by the stated bound.
Exit 0 whatever the rows show (disagreements are results); 2 for bad input.
"""

_DESCRIPTION = """\
Check the simulator against the thesis's real observations (chapter 6): one row per
observation with the thesis's value, the prediction with its interval, and the agreement by
a stated test. Without --seeds only the cheap static rows run (analytic world, FEM response,
idle pad); with --seeds the Experiment 2 rows run the thesis pair in MuJoCo."""


def register(sub: Any) -> None:
    p = add_command(
        sub,
        "validate",
        "check the simulator against the thesis's real observations (chapter 6)",
        _DESCRIPTION,
        _EPILOG,
        json="print the observations as one JSON object",
    )
    p.add_argument(
        "--seeds",
        default=None,
        metavar="SEEDS",
        help="experiment seeds of the Experiment 2 rows: 7, 0-9 or 0-2,7 (default: not run)",
    )
    p.add_argument("--trials", type=int, default=5, help="trials per object per seed (default 5)")
    p.add_argument(
        "--placements",
        type=int,
        default=50,
        help="placement draws per object of the static rows (default %(default)s)",
    )
    p.add_argument(
        "--randomize",
        action="store_true",
        help="draw the uncertain parameters per trial from their ranges (seeded)",
    )
    add_mounting_option(p, "Table 6.1's per-object mounting, Section 6.3")
    p.add_argument("--workers", type=int, default=None, help="worker processes (default: all CPUs)")
    p.add_argument("--no-progress", action="store_true", help="no progress bar on stderr")
    p.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    from softpad.cli._trials import progress_bar
    from softpad.trials import check_counts, validate

    seeds = [] if args.seeds is None else int_ranges(args.seeds, "--seeds", lo=0, hi=2**32 - 1)
    if len(seeds) > 100:
        raise InputError(f"--seeds {args.seeds!r} names {len(seeds)} seeds; at most 100")
    check_counts(args.trials, args.workers)
    if not 2 <= args.placements <= 10_000:
        raise InputError(f"--placements must be from 2 to 10000, got {args.placements}")
    total = len(seeds) * 11 * args.trials
    bar = progress_bar(total, bool(seeds) and not args.no_progress and sys.stderr.isatty())
    try:
        result = validate(
            seeds,
            trials=args.trials,
            workers=args.workers,
            randomize=args.randomize,
            placements=args.placements,
            mounting=args.mounting,
            on_trial=(lambda r: bar.update(1)) if bar is not None else None,
        )
    finally:
        if bar is not None:
            bar.close()
    say(result.to_text(), args.json)
    if args.json:
        emit(result.to_dict())
    return 0
