"""Pictures of an experiment: a representative planned grasp of each object over the pad, like
the thesis's Fig. 6.10, beside every trial's outcome (success per object with its interval)."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

from softpad.layout import PadLayout
from softpad.trials._geometry import fingertip_rectangles_m, object_outlines_m
from softpad.trials._records import ExperimentResult, TrialResult

#: Width the report's figures are printed at (a page, two columns), inches, and the smallest
#: font size they may then show, points: :func:`plot_grasps` sizes its labels to read there.
PAGE_WIDTH_IN = 7.0
SMALLEST_PRINTED_PT = 6.5
#: Colour of a module whose increment was above t_o.
_ABOVE_T_O = "#f4a6c0"


def draw_grasp(
    ax: Any,
    spec: Any,
    trial: TrialResult,
    layout: PadLayout,
    tip_thickness_m: float,
    tip_width_m: float,
    line_width_m: float,
    font_pt: float = 8.0,
) -> None:
    """Draw one trial on ``ax``: modules, object outline, planned fingertips (black), COG.

    Lengths on the axes are millimetres in the pad frame, the module grid drawn; the title
    gives the object and trial, the planned COG in millimetres and the direction of grasp in
    degrees, and this trial's outcome, each on its own line; every label ``font_pt`` points.
    """
    from matplotlib.patches import Polygon, Rectangle

    p = layout.pitch_m * 1e3
    side = p - line_width_m * 1e3
    for k in layout.modules:
        cx, cy = (c * p for c in layout.center(k))
        colour = _ABOVE_T_O if k in trial.modules else "#f3d9e3"
        ax.add_patch(
            Rectangle(
                (cx - side / 2, cy - side / 2), side, side, facecolor=colour, edgecolor="none"
            )
        )
        ax.text(
            cx - side / 2 + 2, cy + side / 2 - 2, str(k), fontsize=font_pt, color="#7a5060",
            va="top",
        )  # fmt: skip
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
    ax.set_title(f"{trial.object}, trial {trial.trial + 1}\n{plan}\n{verdict}", fontsize=font_pt)
    _pad_axes(ax, layout, font_pt)


def _pad_axes(ax: Any, layout: PadLayout, font_pt: float = 8.0) -> None:
    """Millimetre axes around the pad, with ticks and faint lines at every module boundary."""
    p = layout.pitch_m * 1e3
    ax.set_xlim(-20, layout.cols * p + 20)
    ax.set_ylim(-20, layout.rows * p + 20)
    ax.set_xticks([c * p for c in range(layout.cols + 1)])
    ax.set_yticks([r * p for r in range(layout.rows + 1)])
    ax.grid(True, color="0.6", lw=0.6)
    ax.set_axisbelow(False)
    ax.set_aspect("equal")
    ax.set_xlabel("x (mm)", fontsize=font_pt)
    ax.set_ylabel("y (mm)", fontsize=font_pt)
    ax.tick_params(labelsize=font_pt)


def plot_grasps(
    result: ExperimentResult,
    specs: dict[str, Any],
    path: str,
    layout: PadLayout | None = None,
    tip_thickness_m: float | None = None,
    tip_width_m: float | None = None,
    line_width_m: float | None = None,
    trial_index: int = 0,
) -> Any:
    """Save a figure with the planned grasp of trial ``trial_index`` of every object (Fig. 6.10)
    beside a bar chart of every object's successes over all its trials (Wilson intervals).

    Parameters
    ----------
    result
        The experiment.
    specs
        Catalogue objects by name.
    path
        Output image file; empty: the figure is returned open (pyplot's), not saved.
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

    Returns
    -------
    matplotlib.figure.Figure
        The figure (closed once saved). Every label is sized to print at
        :data:`SMALLEST_PRINTED_PT` or more when the figure is printed :data:`PAGE_WIDTH_IN` wide.
    """
    layout = layout or PadLayout()
    sizes = _sizes(layout, tip_thickness_m, tip_width_m, line_width_m)
    names = result.object_names
    fig, grid, cols, pt = _grasps_figure(len(names))
    for i, name in enumerate(names):
        ax = fig.add_subplot(grid[i // cols, i % cols])
        _grasp_panel(ax, result, name, specs[name], layout, sizes, trial_index, pt)
    success_chart(fig.add_subplot(grid[:, cols:]), result, pt)
    fig.suptitle(
        f"Planned grasp of trial {trial_index + 1} of each object (black: fingertips at the "
        "approach opening; pink: modules above t_o),\nand every trial's outcome (right)",
        fontsize=pt,
    )
    fig.tight_layout()
    if path:
        import matplotlib.pyplot as plt

        fig.savefig(path, dpi=150)
        plt.close(fig)
    return fig


def plot_grasp_columns(
    result: ExperimentResult,
    specs: dict[str, Any],
    folder: str | Path,
    layout: PadLayout | None = None,
    sizes_m: tuple[float | None, float | None, float | None] = (None, None, None),
    trial_index: int = 0,
) -> list[Path]:
    """:func:`plot_grasps` split into figures a paper's column wide (``COLUMN_WIDTH_IN``):
    ``folder/grasps-<object>.png``, trial ``trial_index`` of each object drawn by
    :func:`draw_grasp` with a legend of its marks, and ``folder/outcomes.png``, every
    object's trials held (:func:`success_chart`). Every label ``COLUMN_FONT_PT`` at the
    figure's own width. ``sizes_m``: fingertip thickness and width and line width, metres
    (None: the MuJoCo world's). Returns the paths."""
    from matplotlib.figure import Figure

    from softpad.planning import COLUMN_FONT_PT, COLUMN_WIDTH_IN

    layout = layout or PadLayout()
    sizes = _sizes(layout, *sizes_m)
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    paths = []
    for name in result.object_names:
        fig = Figure(figsize=(COLUMN_WIDTH_IN, 3.6), layout="constrained")
        ax = fig.add_subplot()
        _grasp_panel(ax, result, name, specs[name], layout, sizes, trial_index, COLUMN_FONT_PT)
        fig.legend(
            handles=_grasp_legend_handles(), loc="outside lower center", ncols=2,
            fontsize=COLUMN_FONT_PT, frameon=False,
        )  # fmt: skip
        paths.append(folder / f"grasps-{name}.png")
        fig.savefig(paths[-1], dpi=300)
    height = 0.9 + 0.22 * len(result.object_names)
    fig = Figure(figsize=(COLUMN_WIDTH_IN, height), layout="constrained")
    success_chart(fig.add_subplot(), result, COLUMN_FONT_PT)
    paths.append(folder / "outcomes.png")
    fig.savefig(paths[-1], dpi=300)
    return paths


def _grasp_legend_handles() -> list[Any]:
    """Legend entries of :func:`draw_grasp`'s marks."""
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    return [
        Patch(color="black", label="fingertips, approach opening"),
        Line2D([], [], ls="", marker="+", color="black", ms=6, label="planned COG"),
        Patch(facecolor="#8fb3d9", edgecolor="#2b4c6f", alpha=0.6, label="object"),
        Patch(color=_ABOVE_T_O, label="module above t_o"),
    ]


def _grasps_figure(n: int) -> tuple[Any, Any, int, float]:
    """The figure of :func:`plot_grasps` for ``n`` objects: the figure, its grid, the panels
    per row and the label size (pt) that prints readable a page wide."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    cols = min(4, n)
    rows = math.ceil(n / cols)
    width = 3.3 * cols + 4.6
    pt = SMALLEST_PRINTED_PT * width / PAGE_WIDTH_IN  # readable once printed a page wide
    fig = plt.figure(figsize=(width, 3.9 * rows + 1.0))
    return fig, fig.add_gridspec(rows, cols + 2), cols, pt


def _grasp_panel(
    ax: Any,
    result: ExperimentResult,
    name: str,
    spec: Any,
    layout: PadLayout,
    sizes: tuple[float, float, float],
    trial_index: int,
    font_pt: float = 8.0,
) -> None:
    """Trial ``trial_index`` of object ``name`` (its last when it has fewer) drawn by
    :func:`draw_grasp` with ``sizes`` (tip thickness, tip width, line width, metres); how many
    of all its trials held is the bar chart's."""
    trials = [t for t in result.trials if t.object == name]
    trial = trials[min(trial_index, len(trials) - 1)]
    draw_grasp(ax, spec, trial, layout, *sizes, font_pt=font_pt)


def wilson_interval(held: int, trials: int, confidence: float = 0.95) -> tuple[float, float]:
    """Wilson score interval of a success proportion (``scipy.stats.binomtest``'s; at 95 %
    the same bits written out, without importing scipy.stats)."""
    if confidence == 0.95 and trials >= 1:
        from softpad.trials._stats import wilson_bounds_95

        return wilson_bounds_95(int(held), int(trials))
    from scipy.stats import binomtest

    ci = binomtest(held, trials).proportion_ci(confidence_level=confidence, method="wilson")
    return float(ci.low), float(ci.high)


def success_chart(ax: Any, result: ExperimentResult, font_pt: float = 8.0) -> None:
    """Horizontal bars: each object's share of trials held, with its 95 % Wilson interval and
    the count (every trial of every object, not only the one drawn on the pad); labels
    ``font_pt`` points."""
    names = result.object_names
    for i, name in enumerate(names):
        outcomes = [t.success for t in result.trials if t.object == name]
        k, n = sum(outcomes), len(outcomes)
        lo, hi = wilson_interval(k, n)
        ax.barh(i, k / n, color="#7fb27f" if k == n else "#e0a060", height=0.6)
        ax.errorbar(k / n, i, xerr=[[k / n - lo], [hi - k / n]], color="k", capsize=3, lw=1)
        ax.text(1.03, i, f"{k}/{n}", va="center", fontsize=font_pt)
    ax.set_yticks(range(len(names)), names, fontsize=font_pt)
    ax.invert_yaxis()
    ax.set_xlim(0, 1.15)
    ax.set_xticks([0, 0.25, 0.5, 0.75, 1.0])
    ax.tick_params(axis="x", labelsize=font_pt)
    ax.set_xlabel("share of trials held (bar),\n95 % Wilson interval (line)", fontsize=font_pt)
    total = sum(t.success for t in result.trials)
    ax.set_title(f"every trial: {total}/{len(result.trials)} held", fontsize=font_pt)


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
