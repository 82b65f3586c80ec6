"""``softpad design``: rank pad designs for an object set (FEM response + simulated trials, Dask)."""

from __future__ import annotations

import argparse
import sys
from typing import Any

from softpad import thesis
from softpad.cli._args import add_command, int_ranges, name_list
from softpad.cli._output import emit, say
from softpad.cli._run import add_part_options
from softpad.cli._trials import add_mounting_option, add_randomize_option
from softpad.errors import InputError

_EPILOG = """examples:
  softpad design --example thesis-set --quick                  8 designs around the thesis's pad
  softpad design --example thesis-set --quick --json
  softpad design --objects my-set.toml --grid 2x3,3x4 --pitch-mm 35,45 --thickness-mm 1:2:0.5
  softpad design --example thesis-set --p0-kpa 0.6,1.1,2 --material neo-hookean,yeoh --png pareto.png
  softpad design --example thesis-set --quick --scheduler tcp://127.0.0.1:8786

Every design: the module's finite-element response at p0 (height, sealed-chamber rise per newton,
minimum detectable mass at the object threshold t_o), then the object set's grasp trials on the simulated
box over the analytic world with that response. The thesis's pad (2x3, 45 mm, 1.5 mm
neo-Hookean, the thesis's p0) is always the baseline row. Tasks run on Dask: a local cluster on
127.0.0.1 by default, or the scheduler given; finished tasks are cached (--cache), so a
sweep that was interrupted resumes.
"""

_DESCRIPTION = """\
Sweep pad designs (grid, pitch, layer thickness, material, p0) for an object set and rank
them by grasp success, minimum detectable mass, detection delay and module count."""


def _example_sets() -> list[str]:
    """The packaged object sets (``softpad.design.EXAMPLE_SETS``), read from the package's
    data so that building the parser imports neither the design layer nor the FEM."""
    from importlib import resources

    folder = resources.files("softpad").joinpath("data", "object_sets")
    return sorted(
        p.name.removesuffix(".toml") for p in folder.iterdir() if p.name.endswith(".toml")
    )


def register(sub: Any) -> None:
    p = add_command(
        sub,
        "design",
        "rank SoftPad designs for an object set (FEM + simulated trials, on Dask)",
        _DESCRIPTION,
        _EPILOG,
        force=True,
    )
    src = p.add_mutually_exclusive_group()
    src.add_argument(
        "--example", metavar="NAME", help="packaged object set: " + ", ".join(_example_sets())
    )
    src.add_argument("--objects", metavar="FILE.toml", help="object set file (docs/design.md)")
    p.add_argument(
        "--gripper", choices=("10/4", "6/2", "4/0"), help="one mounting for every object"
    )
    p.add_argument("--grid", metavar="RxC,...", help="grids, e.g. 2x3,3x4")
    p.add_argument(
        "--pitch-mm", metavar="V,...", help="module pitches in mm (list or start:stop:step)"
    )
    p.add_argument("--thickness-mm", metavar="V,...", help="layer thicknesses in mm")
    p.add_argument("--material", metavar="NAME,...", help="material presets (softpad fem --help)")
    p.add_argument("--p0-kpa", metavar="V,...", help="inflating pressures in kPa")
    p.add_argument(
        "--quick",
        action="store_true",
        help="the 8 quick designs unless variables are given, 1 trial, 2 s hold, coarser FEM mesh",
    )
    p.add_argument(
        "--trials", type=int, default=None, help="trials per object and seed (default 5; --quick 1)"
    )
    p.add_argument(
        "--seeds", default="0", metavar="SEEDS", help="experiment seeds: 0, 0-2 (default 0)"
    )
    p.add_argument(
        "--hold-s",
        type=float,
        default=None,
        help=f"hold time in s (default {thesis.HOLD_S:g}; --quick 2)",
    )
    add_randomize_option(p)
    add_mounting_option(p, "the object set's: each object's, or its one gripper")
    add_part_options(p)
    p.add_argument("--valves", choices=("thesis", "sized"), default="thesis",
                   help="the thesis's orifices, or orifices sized to each module's channel")  # fmt: skip
    p.add_argument(
        "--scheduler", metavar="tcp://127.0.0.1:PORT", help="a running Dask scheduler on loopback"
    )
    p.add_argument(
        "--workers", type=int, default=None, help="local cluster worker processes (default: CPUs)"
    )
    p.add_argument("--cache", metavar="DIR", help="result cache (default ~/.cache/softpad/design)")
    p.add_argument("--no-cache", action="store_true", help="compute everything, keep nothing")
    p.add_argument("--csv", metavar="FILE.csv", help="write the ranked table as CSV")
    p.add_argument("--parquet", metavar="FILE.parquet", help="write the ranked table as Parquet")
    p.add_argument("--png", metavar="FILE.png", help="write the Pareto plot")
    p.add_argument("--report", metavar="FILE.md", help="write the short Markdown report")
    p.add_argument("--no-progress", action="store_true", help="no progress bar on stderr")
    p.set_defaults(handler=run)


def _designs(args: argparse.Namespace) -> list[Any]:
    """The designs the options span (the quick set when none is given with --quick)."""
    from softpad.design import designs_from_text

    materials = None if args.material is None else name_list(args.material, "--material")
    given = (args.grid, args.pitch_mm, args.thickness_mm, materials, args.p0_kpa)
    return designs_from_text(*given, quick=args.quick)


def _outputs(args: argparse.Namespace) -> dict[str, Any]:
    """Output files, checked before any work."""
    from softpad.cli._paths import check_output

    return {
        "csv": check_output(args.csv, "--csv", force=args.force, suffix=".csv"),
        "parquet": check_output(args.parquet, "--parquet", force=args.force, suffix=".parquet"),
        "png": check_output(args.png, "--png", force=args.force, suffix=".png"),
        "report": check_output(args.report, "--report", force=args.force, suffix=".md"),
    }


def run(args: argparse.Namespace) -> int:
    from softpad.cli._paths import write_text_atomic
    from softpad.design import ResultCache, cache_folder, cached_line, design_sweep, write_sweep

    designs, object_set, options, seeds = _sweep_inputs(args)
    outputs = _outputs(args)
    cache = ResultCache(None if args.no_cache else cache_folder(args.cache))
    bar = _bar(not args.no_progress and sys.stderr.isatty())
    try:
        result = design_sweep(
            designs, object_set, options, seeds, quick=args.quick, scheduler=args.scheduler,
            workers=args.workers, cache=cache, progress=bar,
        )  # fmt: skip
    finally:
        if bar is not None:
            bar.close()
    write_sweep(result, outputs, write_text_atomic)
    if result.meta["cached"]:  # first: what was not computed now, where it came from
        result.meta["cache_dir"] = str(cache.root)
        say(cached_line(result.meta["cached"], result.meta["computed"], cache.root), args.json)
    say(result.to_text(), args.json)
    say(
        f"({result.meta['computed']} tasks computed, {result.meta['cached']} cached, "
        f"{result.meta['wall_time_s']:.1f} s)",
        args.json,
    )
    if args.json:
        emit(result.to_dict())
    return 0


def _sweep_inputs(args: argparse.Namespace) -> tuple[list[Any], Any, Any, list[int]]:
    """The sweep's designs, object set, trial options and seeds, checked before any work."""
    from softpad.design import check_scheduler_address, choose_object_set, sweep_trial_options

    object_set = choose_object_set(args.objects, args.example, args.gripper, args.mounting)
    designs = _designs(args)
    object_set.check_on_pads(designs)
    seeds = int_ranges(args.seeds, "--seeds", lo=0, hi=2**32 - 1)
    if len(seeds) > 100:
        raise InputError(f"--seeds names {len(seeds)} seeds; at most 100")
    options = sweep_trial_options(
        args.trials, args.hold_s, args.quick, args.planner, args.detector, args.randomize,
        args.mounting, args.valves,
    )  # fmt: skip
    if args.scheduler is not None:
        check_scheduler_address(args.scheduler)
    if args.workers is not None and not 1 <= args.workers <= 256:
        raise InputError(f"--workers must be from 1 to 256, got {args.workers}")
    return designs, object_set, options, seeds


class _Bar:
    """A tqdm bar fed by the sweep's ``progress(done, total, what)`` hook."""

    def __init__(self) -> None:
        self.bar: Any = None

    def __call__(self, done: int, total: int, what: str) -> None:
        from tqdm import tqdm

        if self.bar is None:
            self.bar = tqdm(
                total=total,
                desc="design tasks",
                unit="task",
                file=sys.stderr,
                dynamic_ncols=True,
                initial=done - 1,
            )
        self.bar.set_postfix_str(what[:40])
        self.bar.update(1)

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()


def _bar(enabled: bool) -> _Bar | None:
    return _Bar() if enabled else None
