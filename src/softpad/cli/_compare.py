"""``softpad compare``: planner/detector pairs side by side on Experiment 2 over many seeds."""

from __future__ import annotations

import argparse
import json
import re
import sys
from typing import Any

from softpad.errors import InputError

_EPILOG = """examples:
  softpad compare --seeds 0-19 --json            the thesis pair against gripper-aware + cusum
  softpad compare --seeds 0-2 --objects object-1,cylinder --pair thesis:cusum
  softpad compare --seeds 0 --trials 1 --idle-hours 0.1 --png compare.png
"""


def register(sub: Any) -> None:
    p = sub.add_parser(
        "compare",
        help="compare planner/detector pairs on Experiment 2 over many seeds",
        description=(
            "Run Experiment 2 (MuJoCo trials) for each planner/detector pair over the given "
            "seeds and print per-pair and per-object success with 95 % Wilson intervals, "
            "failures by cause, detection delay and finger travel (median, p95) and the "
            "detector's false alarms per hour on an idle pad with noise and drift."
        ),
        epilog=_EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
        allow_abbrev=False,
    )
    p.add_argument("--seeds", default="0-9", metavar="A-B|A,B,...", help="seeds (default 0-9)")
    p.add_argument("--objects", metavar="NAME,...", help="catalogue names (default: all)")
    p.add_argument("--trials", type=int, default=5, help="trials per object and seed (default 5)")
    p.add_argument(
        "--pair",
        action="append",
        metavar="PLANNER:DETECTOR",
        help="a pair to run (repeatable; default thesis:thesis and gripper-aware:cusum)",
    )
    p.add_argument("--idle-hours", type=float, default=1.0, help="idle time for false alarms")
    p.add_argument("--workers", type=int, default=None, help="worker processes (default: all CPUs)")
    p.add_argument("--json", action="store_true", help="print the comparison as one JSON object")
    p.add_argument("--png", metavar="FILE.png", help="draw success and delay per pair")
    p.add_argument("--no-progress", action="store_true", help="no progress bar on stderr")
    p.set_defaults(handler=run)


def parse_seeds(text: str) -> list[int]:
    """``"0-9"`` or ``"0,3,5"`` (or both, comma-separated) as a list of seeds >= 0."""
    seeds: list[int] = []
    for part in str(text).split(","):
        m = re.fullmatch(r"\s*(\d+)\s*(?:-\s*(\d+)\s*)?", part)
        if not m:
            raise InputError(f"--seeds takes A-B or A,B,... with integers >= 0, got {text!r}")
        a, b = int(m.group(1)), int(m.group(2) or m.group(1))
        if b < a or b - a > 1000:
            raise InputError(f"--seeds range {part.strip()!r} must go up, at most 1000 seeds")
        seeds += range(a, b + 1)
    return seeds


def parse_pairs(pairs: list[str] | None) -> list[tuple[str, str]]:
    from softpad.planning import PLANNERS
    from softpad.sensing import CONTACT_DETECTORS
    from softpad.trials import DEFAULT_PAIRS

    if not pairs:
        return list(DEFAULT_PAIRS)
    out = []
    for text in pairs:
        planner, _, detector = text.partition(":")
        if planner not in PLANNERS or detector not in CONTACT_DETECTORS:
            raise InputError(
                f"--pair must be PLANNER:DETECTOR with PLANNER in {', '.join(PLANNERS)} and "
                f"DETECTOR in {', '.join(CONTACT_DETECTORS)}, got {text!r}"
            )
        out.append((planner, detector))
    return out


def run(args: argparse.Namespace) -> int:
    import math

    from softpad.cli._trials import check_counts, select_objects
    from softpad.trials import compare

    seeds, pairs = parse_seeds(args.seeds), parse_pairs(args.pair)
    specs = select_objects(args.objects)
    check_counts(args.trials, args.workers)
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
            on_trial=(lambda _: bar.update(1)) if bar else None,
        )
    finally:
        if bar is not None:
            bar.close()
    if args.png:
        _plot(d, args.png)
    print(json.dumps(d) if args.json else _table(d))
    return 0


def _bar(total: int, enabled: bool) -> Any:
    from softpad.cli._trials import progress_bar

    return progress_bar(total, enabled and sys.stderr.isatty(), desc="compare")


def _pct(x: float | None) -> str:
    return "-" if x is None else f"{100 * x:.1f} %"


def _table(d: dict[str, Any]) -> str:
    lines = [
        f"seeds {d['seeds'][0]}..{d['seeds'][-1]} ({len(d['seeds'])})",
        "| planner | detector | success | 95 % interval | delay median / p95 (ms) "
        "| travel median (mm) | false alarms/h | failures |",
        "|---|---|---:|---|---|---:|---:|---|",
    ]
    for c in d["combinations"]:
        lo, hi = c["success_interval"]
        dm, dp = c["delay_s_median"], c["delay_s_p95"]
        delay = "-" if dm is None else f"{1e3 * dm:.0f} / {1e3 * dp:.0f}"
        travel = (
            "-"
            if c["finger_travel_m_median"] is None
            else f"{1e3 * c['finger_travel_m_median']:.2f}"
        )
        lines.append(
            f"| {c['planner']} | {c['detector']} | {c['successes']}/{c['trials']} = "
            f"{_pct(c['success'])} | {_pct(lo)} .. {_pct(hi)} | {delay} | {travel} | "
            f"{c['false_alarms_per_hour']:g} | {c['failures'] or '-'} |"
        )
    return "\n".join(lines)


def _plot(d: dict[str, Any], path: str) -> None:
    import matplotlib.pyplot as plt

    combos = d["combinations"]
    names = [o["name"] for o in combos[0]["objects"]]
    fig, ax = plt.subplots(figsize=(9, 4))
    width = 0.8 / len(combos)
    for i, c in enumerate(combos):
        rates = [o["success"] for o in c["objects"]]
        xs = [k + i * width for k in range(len(names))]
        ax.bar(xs, rates, width, label=f"{c['planner']} + {c['detector']}")
    ax.set_xticks([k + 0.4 - width / 2 for k in range(len(names))], names, rotation=30)
    ax.set_ylabel("success rate")
    ax.set_ylim(0, 1.05)
    ax.legend(loc="lower left")
    ax.set_title(f"Experiment 2 over {len(d['seeds'])} seeds")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
