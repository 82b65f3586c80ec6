"""The report folder of ``make demo``: table, grasp pictures, pressure traces."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from softpad.trials._records import THESIS_OVERALL_SUCCESS, ExperimentResult


def write_report(
    out: str | Path,
    result: ExperimentResult,
    specs: dict[str, Any],
    trace: Any | None = None,
    trace_title: str = "",
    tip_thickness_m: float | None = None,
    tip_width_m: float | None = None,
    line_width_m: float | None = None,
    beside: Any | None = None,
) -> list[Path]:
    """Write the experiment to ``out``: ``table.md``, ``table.csv``, ``results.json``,
    ``grasps.png`` (every planned grasp over the pad, like Fig. 6.10) and its column-wide
    figures in ``column/``, ``trace.png`` (pressure
    traces of one trial, like Fig. 6.8) and ``README.md`` (the summary); return the paths.
    Fingertip and line sizes (metres) default to the MuJoCo world's (see
    :func:`softpad.trials._plots.plot_grasps`). ``beside``: a
    :class:`concurrent.futures.ProcessPoolExecutor` that draws the column-wide figures while
    this process draws the others (the same files; ``softpad demo``'s second core)."""
    from softpad.trials._plots import plot_grasp_columns, plot_grasps

    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    sizes = (tip_thickness_m, tip_width_m, line_width_m)
    columns = (result, specs, out / "column")
    later = None if beside is None else beside.submit(plot_grasp_columns, *columns, sizes_m=sizes)
    paths = []
    md = result.to_markdown()
    (out / "table.md").write_text(md)
    (out / "table.csv").write_text(result.to_csv())
    (out / "results.json").write_text(json.dumps(result.to_dict(), indent=1) + "\n")
    paths += [out / "table.md", out / "table.csv", out / "results.json"]
    plot_grasps(
        result,
        specs,
        str(out / "grasps.png"),
        tip_thickness_m=tip_thickness_m,
        tip_width_m=tip_width_m,
        line_width_m=line_width_m,
    )
    paths.append(out / "grasps.png")
    if trace is not None:
        trace.plot(out / "trace.png", title=trace_title)
    column_paths = plot_grasp_columns(*columns, sizes_m=sizes) if later is None else later.result()
    paths += column_paths + ([out / "trace.png"] if trace is not None else [])
    (out / "README.md").write_text(_summary(result, md, trace is not None, trace_title))
    paths.append(out / "README.md")
    return paths


def _summary(result: ExperimentResult, table_md: str, has_trace: bool, trace_title: str) -> str:
    """The report's README.md: overall success, failures by cause, the table and the files."""
    n = len(result.trials)
    k = sum(t.success for t in result.trials)
    causes = result.failures_by_cause()
    lines = [
        "# SoftPad: Experiment 2 of the thesis (Table 6.1) in rigid-body simulation",
        "",
        f"{n} grasp trials ({len(result.object_names)} objects) on the simulated box with the "
        "MuJoCo world, seed "
        f"{result.seed}, {result.workers} worker processes, {result.wall_time_s:.1f} s wall time.",
        "",
        f"**Overall success: {k}/{n} = {100 * result.overall_success:.1f} %** "
        f"(thesis: 52/55 = {100 * THESIS_OVERALL_SUCCESS:.1f} %).",
        "",
        "Failures by cause: "
        + (", ".join(f"{c}: {v}" for c, v in sorted(causes.items())) or "none")
        + ".",
        "",
        table_md,
        "",
        "- `grasps.png`: the planned grasp of trial 1 of every object over the pad (black: the "
        "fingertips at the approach opening), like Fig. 6.10.",
        "- `column/`: the same figures split to print a paper's column wide (3.5 in): "
        "`grasps-OBJECT.png` and `outcomes.png`, and `plans_reference-OBJECT.png` from `softpad "
        "demo`.",
    ]
    if has_trace:
        lines.append(
            f"- `trace.png`: module pressures during one trial ({trace_title}), like Fig. 6.8."
        )
    lines += [
        "- `results.json`: every trial (placement, increments, plan, opening, contact delay, "
        "finger travel, outcome and cause).",
        "- `table.csv`: the table above.",
        "",
    ]
    return "\n".join(lines)
