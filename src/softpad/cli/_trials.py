"""``softpad trials``: grasp trials of the thesis's Experiment 2 in rigid-body physics."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable
from typing import Any

from softpad import thesis
from softpad.cli._args import Renamed, add_command, add_integer, int_ranges, name_list
from softpad.cli._output import emit, say
from softpad.cli._record import add_record_option
from softpad.cli._run import add_part_options
from softpad.errors import InputError

_EPILOG = """examples:
  softpad trials                                   all 11 objects x 5 trials (Table 6.1)
  softpad trials --objects banana,charger --trials 2 --seeds 7
  softpad trials --objects cylinder --trials 1 --seeds 0-2       three experiments, seeds 0, 1, 2
  softpad trials --objects cylinder --trials 1 --json

Each trial: a fresh MuJoCo world behind the simulated box; inflate to p0, save the reference,
place the object with a seeded random shift (3 mm standard deviation in x and y) and turn
(3 deg), plan from the pressure increments, open the jaws to the mounting's width, move over
the COG, descend at the approach speed until the pad senses the fingers (t_g), close, lift
10 cm, hold 15 s. Several seeds are pooled: per object trials, successes, a 95 % Wilson
interval and failures by cause, next to Table 6.1 (5/5 or 4/5) and the thesis's failures.
Failure causes: contact_not_detected, cog_outside_object, jaws_hit_object, object_outside_jaws,
slipped_during_hold, object_too_narrow, object_not_detected, box_fault; trial_error (the
trial raised: a bug; the other trials still run, the table counts it as failed, the JSON holds
its traceback and the command exits 4).
"""


_DESCRIPTION = """\
Run the closed loop (simulated box, thesis planner, contact detection, grasp, 15 s hold) on
the objects of Table 6.1 in a MuJoCo world, several trials each with random placement, and
print a Table 6.1-like table with the overall success rate next to the thesis's 94.5 %."""


def register(sub: Any) -> None:
    p = add_command(
        sub,
        "trials",
        "run grasp trials of the thesis's Experiment 2 (Table 6.1) on MuJoCo",
        _DESCRIPTION,
        _EPILOG,
    )
    add_trial_options(p)
    add_part_options(p)
    add_randomize_option(p)
    add_mounting_option(p, "each object's own: Table 6.1's per Section 6.3, an object set's")
    p.add_argument(
        "--scheduler",
        metavar="tcp://127.0.0.1:PORT|local",
        help="run every seed's trials as Dask tasks: on this running scheduler (loopback), or "
        "'local' for a Dask cluster of --workers processes on 127.0.0.1",
    )
    p.add_argument(
        "--hold-s", type=float, default=thesis.HOLD_S, help="hold time in s (default %(default)g)"
    )
    add_record_option(p, per_trial=True)
    p.add_argument(
        "--catalogue",
        metavar="FILE.toml",
        help="known objects (softpad learn) for --planner catalogue (without it no object is "
        "known and every one goes to the model-based planner)",
    )
    p.set_defaults(handler=run)


def add_randomize_option(p: Any) -> None:
    """``--randomize``: draw the simulator's uncertain inputs per trial (seeded)."""
    p.add_argument(
        "--randomize",
        action="store_true",
        help="draw every uncertain input of the simulated lab (pad and tip physics, grip force, "
        "seam, sample rate, noise, tubing, placement, unknown object sizes) from its sourced "
        "range per trial, seeded by the trial seed; --json carries the drawn values per trial "
        "(list: softpad.sim.UNCERTAIN_PARAMETERS, docs/trials.md)",
    )


def add_mounting_option(p: Any, default_text: str = "each object's own") -> None:
    """``--mounting``: the gripper's mounting, or ``auto`` (chosen from the pad's reading)."""
    p.add_argument(
        "--mounting",
        choices=("auto", "10/4", "6/2", "4/0"),
        default=None,
        help="gripper mounting (max/min width, cm) for every object; auto: chosen per trial "
        "from the pad's reading of the placed object (the smallest that opens beyond the "
        "object's estimated width along the planned grasp; no width oracle), as a lab runs "
        f"held-out objects (default: {default_text})",
    )


def add_trial_options(
    p: Any, seeds: str = "0", objects: bool = True, one_seed: bool = False
) -> None:
    """The options of the commands that run Experiment 2 (``trials``, ``compare``, ``demo``):
    ``--objects`` (unless not ``objects``), ``--trials``, ``--seeds`` (a range with default
    ``seeds``, or one value with ``one_seed``), ``--workers`` and ``--no-progress``."""
    if objects:
        p.add_argument(
            "--objects",
            metavar="NAME,...",
            help="comma-separated catalogue names (default: all of Table 6.1), or names of "
            "the --objects-file's objects",
        )
        p.add_argument(
            "--objects-file",
            metavar="FILE.toml",
            help="run the objects of this object set (the design format, docs/design.md: "
            "catalogue names or boxes and lying cylinders with mass, size, placement and "
            "mounting) instead of Table 6.1's",
        )
    p.add_argument("--trials", type=int, default=5, help="trials per object (default 5)")
    if one_seed:
        add_integer(p, "--seeds", "experiment seed, one value (default 0)", 0, 0, 2**32 - 1)
    else:
        help = f"experiment seeds: 7, 0-9 or 0-2,7 (default {seeds})"
        p.add_argument("--seeds", default=seeds, metavar="SEEDS", help=help)
    p.add_argument("--seed", action=Renamed, new="--seeds (e.g. --seeds 7 or --seeds 0-9)")
    p.add_argument("--workers", type=int, default=None, help="worker processes (default: all CPUs)")
    p.add_argument("--no-progress", action="store_true", help="no progress bar on stderr")


def select_objects(names_text: str | None, objects_file: str | None = None) -> list[Any]:
    """The objects named in ``names_text`` (comma-separated; all when None), of the catalogue
    or of ``objects_file`` (:func:`softpad.design.trial_objects`)."""
    from softpad.design import trial_objects

    names = None if names_text is None else name_list(names_text, "--objects")
    return trial_objects(names, objects_file)


def progress_bar(total: int, enabled: bool, desc: str = "trials") -> Any:
    """A tqdm bar on stderr, or None when disabled."""
    if not enabled:
        return None
    from tqdm import tqdm

    return tqdm(total=total, desc=desc, unit="trial", file=sys.stderr, dynamic_ncols=True)


def trial_errors_exit(errored: list[dict[str, Any]], prog: str) -> int:
    """Exit code of a command whose trials ran: 0, or the internal-error code with a message on
    stderr naming the trials that raised (:func:`softpad.trials.trial_errors_text`)."""
    from softpad.errors import EXIT_INTERNAL
    from softpad.trials import trial_errors_text

    text = trial_errors_text(errored, prog)
    if text is None:
        return 0
    print(text, file=sys.stderr)
    return EXIT_INTERNAL


def run_with_progress(
    specs: list[Any],
    trials: int,
    show: bool,
    desc: str = "trials",
    finished: list[dict[str, Any]] | None = None,
    **kwargs: Any,
) -> tuple[Any, Any]:
    """``run_experiment`` with a progress bar that names each finished trial's outcome;
    each finished trial's dict is appended to ``finished`` (kept when the run is interrupted)."""
    from softpad.trials import run_experiment

    bar = progress_bar(len(specs) * trials, show, desc=desc)
    tick = _ticker(bar, finished)

    try:
        return run_experiment(specs, trials=trials, on_trial=tick, **kwargs)
    finally:
        if bar is not None:
            bar.close()


def _ticker(bar: Any, finished: list[dict[str, Any]] | None) -> Callable[[Any], None]:
    """The ``on_trial`` hook: each finished trial's dict appended to ``finished`` (kept when
    the run is interrupted), its outcome shown on the progress bar."""

    def tick(result: Any) -> None:
        if finished is not None:
            finished.append(result.to_dict())
        if bar is not None:
            bar.set_postfix_str(f"{result.object}: {'held' if result.success else result.cause}")
            bar.update(1)

    return tick


def _show(args: argparse.Namespace) -> bool:
    """Whether to show a progress bar (asked for, and stderr a terminal)."""
    return not args.no_progress and sys.stderr.isatty()


def run(args: argparse.Namespace) -> int:
    from softpad.trials import check_campaign, check_counts, check_trial_recordings

    specs = select_objects(args.objects, args.objects_file)
    check_counts(args.trials, args.workers)
    seeds = int_ranges(args.seeds, "--seeds", lo=0, hi=2**32 - 1)
    check_campaign(seeds, args.seeds, args.hold_s, args.record)
    check_trial_recordings(args.record, specs, args.trials, args.force)
    check_catalogue_option(args.catalogue, [args.planner])

    finished: list[dict[str, Any]] = []
    args.partial = {"seeds": seeds, "completed_seeds": [], "finished_trials": finished}
    if getattr(args, "scheduler", None) is not None:
        return _run_on_dask(args, specs, seeds)
    return _pooled(args, _run_here(args, specs, seeds, finished), "workers")


def check_catalogue_option(path: str | None, planners: list[str]) -> None:
    """``--catalogue``: read (a bad file is named before any trial) and only beside the
    ``catalogue`` planner, which is the one that uses it (InputError otherwise)."""
    if path is None:
        return
    if "catalogue" not in planners:
        raise InputError(
            f"--catalogue is for --planner catalogue (the planner here: {', '.join(planners)})"
        )
    from softpad.planning import load_catalogue

    load_catalogue(path)


def _pooled(args: argparse.Namespace, experiments: list[Any], workers: str) -> int:
    """Print the seeds' experiments pooled (``--json``: as one object); the exit code."""
    from softpad.trials import ExperimentResult, errored_records

    pooled = ExperimentResult.pooled(experiments)
    say(pooled.to_text(), args.json)
    say(
        f"({len(pooled.trials)} trials in {pooled.wall_time_s:.1f} s on {pooled.workers} "
        f"{workers})",
        args.json,
    )
    if args.json:
        emit(pooled.to_dict())
    return trial_errors_exit(errored_records(pooled.trials), "trials")


def _run_here(
    args: argparse.Namespace, specs: list[Any], seeds: list[int], finished: list[dict[str, Any]]
) -> list[Any]:
    """Every seed's experiment on this machine's worker processes, all seeds' trials queued
    at once (the workers live across the seeds); ``args.partial`` follows the finished seeds."""
    done: list[Any] = []

    def seed_done(exp: Any) -> None:
        done.append(exp)
        args.partial["completed_seeds"] = sorted(e.seed for e in done)
        if len(seeds) > 1:
            say(f"seed {exp.seed}: {exp.overall()['successes']}/{len(exp.trials)} held", args.json)

    if args.record is not None:  # one seed (checked by run); recordings named per trial
        exp, _ = run_with_progress(
            specs,
            args.trials,
            _show(args),
            finished=finished,
            seed=seeds[0],
            workers=args.workers,
            config=_config(args),
            record=args.record,
        )
        seed_done(exp)
        return done
    return run_seeds_with_progress(
        specs,
        args.trials,
        seeds,
        _show(args),
        finished,
        workers=args.workers,
        config=_config(args),
        on_seed=seed_done,
    )


def run_seeds_with_progress(
    specs: list[Any],
    trials: int,
    seeds: list[int],
    show: bool,
    finished: list[dict[str, Any]] | None = None,
    **kwargs: Any,
) -> list[Any]:
    """``run_experiments`` (every seed's trials queued at once on the same workers) with the
    progress bar of :func:`run_with_progress` over all the seeds' trials."""
    from softpad.trials import run_experiments

    bar = progress_bar(len(specs) * trials * len(seeds), show)
    try:
        return run_experiments(specs, trials, seeds, on_trial=_ticker(bar, finished), **kwargs)
    finally:
        if bar is not None:
            bar.close()


def _config(args: argparse.Namespace) -> Any:
    """The trials' configuration: hold time, planner and contact detector from the options."""
    from softpad.trials import TrialConfig, trial_execution_params

    execution = trial_execution_params(hold_s=args.hold_s)
    return TrialConfig(
        execution,
        planner=args.planner,
        detector=args.detector,
        randomize=args.randomize,
        mounting=args.mounting,
        catalogue=getattr(args, "catalogue", None),
    )


def _run_on_dask(args: argparse.Namespace, specs: list[Any], seeds: list[int]) -> int:
    """``--scheduler``: every seed's trials as Dask tasks (softpad.design's client), pooled."""
    from softpad.design import check_scheduler_address, run_experiment_on_dask

    if args.record:
        raise InputError("--record is not available with --scheduler (trials run on Dask workers)")
    address = None if args.scheduler == "local" else check_scheduler_address(args.scheduler)
    total = len(specs) * args.trials * len(seeds)
    bar = progress_bar(total, not args.no_progress and sys.stderr.isatty())
    try:
        exps = run_experiment_on_dask(
            specs,
            args.trials,
            seeds,
            _config(args),
            scheduler=address,
            workers=args.workers,
            on_trial=(lambda r: bar.update(1)) if bar is not None else None,
        )
    finally:
        if bar is not None:
            bar.close()
    args.partial["completed_seeds"] = [e.seed for e in exps]
    if len(seeds) > 1:
        for exp in exps:
            say(f"seed {exp.seed}: {exp.overall()['successes']}/{len(exp.trials)} held", args.json)
    return _pooled(args, exps, "Dask workers")
