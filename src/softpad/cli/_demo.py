"""``softpad demo``: the project's main job on the simulated default."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from softpad.cli._args import add_command
from softpad.cli._output import emit, say
from softpad.cli._paths import check_output_dir
from softpad.cli._record import add_record_option
from softpad.errors import InputError

_DESCRIPTION = """\
Run the thesis's Experiment 2 in simulation: the 11 objects of Table 6.1, 5 grasp trials
each, every trial the full closed loop (simulated box, planner, contact detection, grasp,
15 s hold) in a MuJoCo world, in parallel processes with a progress bar. Writes a report
folder: the table (Markdown, CSV, JSON), every planned grasp over the pad (like Fig. 6.10),
the pressure traces of one trial (like Fig. 6.8), and the planner's Table 6.1 plans from
reference increments."""


def register(sub: Any) -> None:
    from softpad.cli._trials import add_trial_options

    p = add_command(
        sub,
        "demo",
        "run the main job: the thesis's Experiment 2 (11 objects x 5 grasps) on MuJoCo",
        _DESCRIPTION,
    )  # --force comes with --record
    p.add_argument(
        "--out",
        default="report",
        help="report folder, absent or empty unless --force (default: report)",
    )
    add_trial_options(p, objects=False, one_seed=True)
    add_record_option(p, per_trial=True)
    p.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    from softpad.cli._trials import run_with_progress, trial_errors_exit
    from softpad.sim import get_object, object_names
    from softpad.trials import (
        check_counts,
        check_trial_recordings,
        errored_records,
        write_report,
    )

    check_counts(args.trials, args.workers)
    out = check_output_dir(args.out, "--out", force=args.force)
    try:
        out.mkdir(exist_ok=True)
    except OSError as exc:
        raise InputError(f"--out {args.out!r}: cannot create the folder: {exc.strerror}") from None
    specs = [get_object(n) for n in object_names()]
    check_trial_recordings(args.record, specs, args.trials, args.force)
    # the thesis's Fig. 6.8 shows an object on modules 1 and 4: object 4 lies there
    trace_object = "object-4" if any(s.name == "object-4" for s in specs) else specs[0].name
    # the planner on the thesis's reference increments (no physics; about 3 CPU s of figures)
    # drawn by a process of its own while the trials run, not before them, and the report's
    # column-wide figures there while this process draws the others (issue 50)
    with _beside() as side:
        plans = side.submit(_reference_plans, out)
        exp, trace = run_with_progress(
            specs,
            args.trials,
            not args.no_progress,
            desc="grasp trials",
            seed=args.seeds,
            workers=args.workers,
            trace_object=trace_object,
            record=args.record,
        )
        plans.result()
        say(exp.to_text(), args.json)
        paths = write_report(
            out,
            exp,
            {s.name: s for s in specs},
            trace,
            trace_title=f"{trace_object}, trial 1 (seed {args.seeds})",
            beside=side,  # the column-wide figures drawn there
        )
    names = ", ".join(p.name for p in paths if p.parent == out)
    say(
        f"\n{len(exp.trials)} trials in {exp.wall_time_s:.1f} s on {exp.workers} workers; "
        f"report written to {out}/ ({names}, plans_reference.md/.csv/.png; column/: each figure a column wide)",
        args.json,
    )
    if args.json:
        emit({"report": str(out), "files": [str(p) for p in paths], **exp.to_dict()})
    return trial_errors_exit(errored_records(exp.trials), "demo")


def _beside() -> Any:
    """An executor of one process for the work beside the trials: started (forked) before
    the trials' workers and before any thread, so that it shares no lock or import state
    with them; its errors come back through its futures."""
    from concurrent.futures import ProcessPoolExecutor

    return ProcessPoolExecutor(max_workers=1)


def _reference_plans(out: Path) -> None:
    """The planner on the thesis's Table 6.1 reference increments (no physics)."""
    from softpad.trials import write_reference_plans

    write_reference_plans(out)
