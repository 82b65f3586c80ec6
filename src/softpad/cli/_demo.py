"""``softpad demo``: the project's main job on the simulated default."""

from __future__ import annotations

import argparse
import math
from pathlib import Path
from typing import Any

from softpad.cli._args import add_command
from softpad.cli._output import emit, say
from softpad.cli._paths import check_output_dir
from softpad.cli._record import add_record_option, check_trial_recordings
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
    from softpad.cli._trials import check_counts, run_with_progress, trial_errors_exit
    from softpad.sim import get_object, object_names
    from softpad.trials import errored_records, write_report

    check_counts(args.trials, args.workers)
    out = check_output_dir(args.out, "--out", force=args.force)
    try:
        out.mkdir(exist_ok=True)
    except OSError as exc:
        raise InputError(f"--out {args.out!r}: cannot create the folder: {exc.strerror}") from None
    specs = [get_object(n) for n in object_names()]
    check_trial_recordings(args.record, specs, args.trials, args.force)
    # the planner on the thesis's reference increments first (instant), then the experiment
    _reference_plans(out)
    # the thesis's Fig. 6.8 shows an object on modules 1 and 4: object 4 lies there
    trace_object = "object-4" if any(s.name == "object-4" for s in specs) else specs[0].name
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
    say(exp.to_text(), args.json)
    paths = write_report(
        out,
        exp,
        {s.name: s for s in specs},
        trace,
        trace_title=f"{trace_object}, trial 1 (seed {args.seeds})",
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


def _reference_plans(out: Path) -> None:
    """The planner on the thesis's Table 6.1 reference increments (no physics)."""
    from softpad.layout import PadLayout
    from softpad.planning import TABLE_6_1, plan_grasps, plot_plan_columns

    layout = PadLayout()
    header = (
        "| object | weight (g) | modules | thesis (x, y, theta) | planned (x, y, theta) | rule |"
    )
    rows = [header, "|---|---|---|---|---|---|"]
    csv_lines = ["object,weight_g,modules,thesis_x,thesis_y,thesis_theta_rad,x,y,theta_rad,rule"]
    results = []
    for case in TABLE_6_1:
        (plan,) = plan_grasps(case.delta_pa, layout)
        results.append((case, plan))
        rows.append(
            f"| {case.name} | {case.weight_g:g} | {','.join(map(str, plan.modules))} | "
            f"({case.cog[0]:.2f}, {case.cog[1]:.2f}, {_pi(case.theta)}) | "
            f"({plan.cog[0]:.2f}, {plan.cog[1]:.2f}, {_pi(plan.theta)}) | {plan.rule} |"
        )
        csv_lines.append(
            f"{case.name},{case.weight_g},{' '.join(map(str, plan.modules))},{case.cog[0]},"
            f"{case.cog[1]},{case.theta:.9f},{plan.cog[0]:.6f},{plan.cog[1]:.6f},"
            f"{plan.theta:.9f},{plan.rule}"
        )
    (out / "plans_reference.md").write_text("\n".join(rows) + "\n")
    (out / "plans_reference.csv").write_text("\n".join(csv_lines) + "\n")
    _plot_all(out / "plans_reference.png", results, layout)
    plot_plan_columns(results, out / "column", layout)  # each case a column wide


def _pi(theta: float) -> str:
    for num, text in ((0.0, "0"), (0.5, "pi/2"), (0.25, "pi/4"), (-0.25, "-pi/4")):
        if math.isclose(theta, num * math.pi, abs_tol=1e-9):
            return text
    return f"{theta:.3f}"


def _plot_all(path: Path, results: list[Any], layout: Any) -> None:
    """Every reference case on one figure: one colour scale (the largest increment of all
    cases), one colour bar and one legend for all panels, axes in millimetres with the module
    grid; labels sized to read when the figure is printed a page wide (7 in)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    from softpad.planning import plan_legend_handles, plot_plans

    n = len(results)
    cols = 4
    rows = math.ceil(n / cols)
    vmax = max(float(np.max(case.delta_pa)) for case, _ in results) / 1e3
    width = 3.9 * cols
    pt = 6.5 * width / 7.0  # 6.5 pt once printed 7 in wide
    fig, axes = plt.subplots(rows, cols, figsize=(width, 3.0 * rows), squeeze=False)
    for ax, (case, plan) in zip(axes.flat, results, strict=False):
        plot_plans(
            case.delta_pa, [plan], layout, ax=ax, title=f"{case.name} ({case.weight_g:g} g)",
            vmax_kpa=vmax, legend=False, colorbar=False, font_pt=pt,
        )  # fmt: skip
    for ax in list(axes.flat)[n:]:
        ax.axis("off")
    fig.legend(handles=plan_legend_handles(), loc="lower right", fontsize=pt, frameon=False)
    fig.tight_layout(rect=(0, 0, 0.92, 1))
    image = axes.flat[0].images[0]
    bar = fig.colorbar(image, ax=axes.ravel().tolist(), fraction=0.02, pad=0.01)
    bar.set_label("pressure increment dP (kPa), one scale for all panels", fontsize=pt)
    bar.ax.tick_params(labelsize=pt)
    fig.savefig(path, dpi=110)
    plt.close(fig)
