"""Pictures of an experiment: a representative planned grasp of each object over the pad, like
the thesis's Fig. 6.10, beside every trial's outcome (success per object with its interval)."""

from __future__ import annotations

import math
from typing import Any

from softpad.layout import PadLayout
from softpad.trials._geometry import fingertip_rectangles_m, object_outlines_m
from softpad.trials._records import ExperimentResult, TrialResult


def draw_grasp(
    ax: Any,
    spec: Any,
    trial: TrialResult,
    layout: PadLayout,
    tip_thickness_m: float,
    tip_width_m: float,
    line_width_m: float,
) -> None:
    """Draw one trial on ``ax``: modules, object outline, planned fingertips (black), COG.

    Lengths on the axes are millimetres in the pad frame; the title gives the planned COG in
    millimetres and the direction of grasp in degrees, and this trial's outcome.
    """
    from matplotlib.patches import Polygon, Rectangle

    p = layout.pitch_m * 1e3
    side = p - line_width_m * 1e3
    for k in layout.modules:
        cx, cy = (c * p for c in layout.center(k))
        colour = "#f4a6c0" if k in trial.modules else "#f3d9e3"
        ax.add_patch(
            Rectangle(
                (cx - side / 2, cy - side / 2), side, side, facecolor=colour, edgecolor="none"
            )
        )
        ax.text(cx - side / 2 + 2, cy + side / 2 - 8, str(k), fontsize=8, color="#7a5060")
    x, y, yaw = trial.placement

    class _P:
        x_m, y_m, yaw_rad = x, y, yaw

    for poly in object_outlines_m(spec, _P):
        ax.add_patch(
            Polygon(
                poly * 1e3, closed=True, facecolor="#8fb3d9", edgecolor="#2b4c6f", alpha=0.6, lw=0.8
            )
        )
    if trial.cog is not None and trial.theta is not None:
        cog = (trial.cog[0] * layout.pitch_m, trial.cog[1] * layout.pitch_m)
        for rect in fingertip_rectangles_m(
            cog, trial.theta, trial.opening_m, tip_thickness_m, tip_width_m
        ):
            ax.add_patch(Polygon(rect * 1e3, closed=True, facecolor="black", edgecolor="black"))
        ax.plot([cog[0] * 1e3], [cog[1] * 1e3], marker="+", color="black", ms=6)
    verdict = "held" if trial.success else (trial.cause or "failed").replace("_", " ")
    plan = (
        "no plan"
        if trial.cog is None or trial.theta is None
        else f"COG ({trial.cog[0] * p:.0f}, {trial.cog[1] * p:.0f}) mm, "
        f"{math.degrees(trial.theta):.0f}°"
    )
    ax.set_title(f"{trial.object}: {plan}\ntrial {trial.trial + 1}: {verdict}", fontsize=8)
    _pad_axes(ax, layout)


def _pad_axes(ax: Any, layout: PadLayout) -> None:
    """Millimetre axes around the pad, with ticks and faint lines at every module boundary."""
    p = layout.pitch_m * 1e3
    ax.set_xlim(-20, layout.cols * p + 20)
    ax.set_ylim(-20, layout.rows * p + 20)
    ax.set_xticks([c * p for c in range(layout.cols + 1)])
    ax.set_yticks([r * p for r in range(layout.rows + 1)])
    ax.grid(True, color="0.6", lw=0.6)
    ax.set_axisbelow(False)
    ax.set_aspect("equal")
    ax.set_xlabel("x (mm)", fontsize=8)
    ax.set_ylabel("y (mm)", fontsize=8)
    ax.tick_params(labelsize=7)


def plot_grasps(
    result: ExperimentResult,
    specs: dict[str, Any],
    path: str,
    layout: PadLayout | None = None,
    tip_thickness_m: float | None = None,
    tip_width_m: float | None = None,
    line_width_m: float | None = None,
    trial_index: int = 0,
) -> None:
    """Save a figure with the planned grasp of trial ``trial_index`` of every object (Fig. 6.10)
    beside a bar chart of every object's successes over all its trials (Wilson intervals).

    Parameters
    ----------
    result
        The experiment.
    specs
        Catalogue objects by name.
    path
        Output image file.
    layout
        Pad geometry.
    tip_thickness_m, tip_width_m
        Fingertip size (closing direction, across), metres; by default the MuJoCo gripper's
        (:class:`softpad.sim.MujocoGripper`, 4 x 16 mm).
    line_width_m
        Width of the non-sensitive lines drawn between modules, metres; by default the MuJoCo
        pad's (pitch less the dome's side, 5 mm).
    trial_index
        Which trial of each object to draw.
    """
    layout = layout or PadLayout()
    tip_thickness_m, tip_width_m, line_width_m = _sizes(
        layout, tip_thickness_m, tip_width_m, line_width_m
    )
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    names = result.object_names
    n = len(names)
    cols = min(4, n)
    rows = math.ceil(n / cols)
    fig = plt.figure(figsize=(3.3 * cols + 4.6, 3.0 * rows + 0.6))
    grid = fig.add_gridspec(rows, cols + 2)
    sizes = (tip_thickness_m, tip_width_m, line_width_m)
    for i, name in enumerate(names):
        ax = fig.add_subplot(grid[i // cols, i % cols])
        _grasp_panel(ax, result, name, specs[name], layout, sizes, trial_index)
    success_chart(fig.add_subplot(grid[:, cols:]), result)
    fig.suptitle(
        f"Planned grasp of trial {trial_index + 1} of each object (black: fingertips at the "
        "approach opening; pink: modules above t_o), and every trial's outcome (right)",
        fontsize=10,
    )
    fig.tight_layout()
    fig.savefig(path, dpi=150)
    plt.close(fig)


def _grasp_panel(
    ax: Any,
    result: ExperimentResult,
    name: str,
    spec: Any,
    layout: PadLayout,
    sizes: tuple[float, float, float],
    trial_index: int,
) -> None:
    """Trial ``trial_index`` of object ``name`` (its last when it has fewer) drawn by
    :func:`draw_grasp` with ``sizes`` (tip thickness, tip width, line width, metres), the
    title ending with how many of all its trials held."""
    trials = [t for t in result.trials if t.object == name]
    trial = trials[min(trial_index, len(trials) - 1)]
    draw_grasp(ax, spec, trial, layout, *sizes)
    held = sum(t.success for t in trials)
    ax.set_title(f"{ax.get_title()} ({held}/{len(trials)} held in all)", fontsize=8)


def wilson_interval(held: int, trials: int, confidence: float = 0.95) -> tuple[float, float]:
    """Wilson score interval of a success proportion (``scipy.stats.binomtest``)."""
    from scipy.stats import binomtest

    ci = binomtest(held, trials).proportion_ci(confidence_level=confidence, method="wilson")
    return float(ci.low), float(ci.high)


def success_chart(ax: Any, result: ExperimentResult) -> None:
    """Horizontal bars: each object's share of trials held, with its 95 % Wilson interval and
    the count (every trial of every object, not only the one drawn on the pad)."""
    names = result.object_names
    for i, name in enumerate(names):
        outcomes = [t.success for t in result.trials if t.object == name]
        k, n = sum(outcomes), len(outcomes)
        lo, hi = wilson_interval(k, n)
        ax.barh(i, k / n, color="#7fb27f" if k == n else "#e0a060", height=0.6)
        ax.errorbar(k / n, i, xerr=[[k / n - lo], [hi - k / n]], color="k", capsize=3, lw=1)
        ax.text(1.03, i, f"{k}/{n}", va="center", fontsize=8)
    ax.set_yticks(range(len(names)), names, fontsize=8)
    ax.invert_yaxis()
    ax.set_xlim(0, 1.15)
    ax.set_xticks([0, 0.25, 0.5, 0.75, 1.0])
    ax.tick_params(axis="x", labelsize=8)
    ax.set_xlabel("share of trials held (bar), 95 % Wilson interval (line)", fontsize=8)
    total = sum(t.success for t in result.trials)
    ax.set_title(f"every trial: {total}/{len(result.trials)} held", fontsize=9)


def _sizes(
    layout: PadLayout,
    tip_thickness_m: float | None,
    tip_width_m: float | None,
    line_width_m: float | None,
) -> tuple[float, float, float]:
    """Fingertip thickness and width and line width, metres; the MuJoCo world's by default."""
    from softpad.sim import MujocoGripper, PadPhysics

    return (
        tip_thickness_m or MujocoGripper().tip_thickness_m,
        tip_width_m or MujocoGripper().tip_width_m,
        line_width_m or layout.pitch_m - PadPhysics().sensitive_side_m,
    )
