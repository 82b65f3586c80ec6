"""Human-readable views of plans: a text table, an ASCII pad, and a matplotlib figure."""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from softpad.errors import InputError
from softpad.layout import GripperSpec, PadLayout
from softpad.planning._cases import PlanCase
from softpad.planning._records import GraspPlan

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.axes import Axes


def ascii_pad(
    delta_pa: ArrayLike, layout: PadLayout, plans: Sequence[GraspPlan] = (), cell: int = 9
) -> str:
    """Draw the pad as text: module numbers, increments in kPa, PCOM ``P`` and COG ``G``.

    ``*`` marks a PCOM and a COG that fall in the same character cell.
    """
    d = np.asarray(delta_pa, dtype=float)
    h = 4
    width, height = layout.cols * cell + 1, layout.rows * h + 1
    canvas = [[" "] * width for _ in range(height)]
    for r in range(layout.rows + 1):
        for x in range(width):
            canvas[r * h][x] = "-"
    for c in range(layout.cols + 1):
        for y in range(height):
            canvas[y][c * cell] = "+" if y % h == 0 else "|"
    for m in layout.modules:
        r, c = layout.row_col(m)
        label = f"{m} {d[m - 1] / 1e3:.3f}" if d[m - 1] else f"{m}"
        for i, ch in enumerate(label[: cell - 1]):
            canvas[r * h + 1][c * cell + 1 + i] = ch

    def mark(p: tuple[float, float], ch: str) -> None:
        x = min(round(p[0] * cell), width - 1)
        y = min(round((layout.rows - p[1]) * h), height - 1)
        canvas[y][x] = "*" if canvas[y][x] in "PG" and canvas[y][x] != ch else ch

    for plan in plans:
        mark(plan.pcom, "P")
        mark(plan.cog, "G")
    return "\n".join("".join(row).rstrip() for row in canvas)


def format_plans(
    delta_pa: ArrayLike, plans: Sequence[GraspPlan], layout: PadLayout, threshold_pa: float
) -> str:
    """The table ``softpad plan`` prints."""
    if not isinstance(layout, PadLayout):
        raise InputError(
            f"layout must be a PadLayout (parse_layout('2x3') for a name), got {layout!r}"
        )
    if np.size(delta_pa) != layout.n_modules:
        raise InputError(
            f"a {layout.name} pad needs {layout.n_modules} increments, got {np.size(delta_pa)}"
        )
    pad = ascii_pad(delta_pa, layout, plans)
    both = ", * = PCOM and centre of grasp in one character" if "*" in pad else ""
    lines = [
        f"SoftPad {layout.name}, pitch {layout.pitch_m * 1e3:g} mm, "
        f"object threshold t_o = {threshold_pa / 1e3:.3f} kPa",
        f"module number and increment (kPa), P = PCOM, G = centre of grasp{both}:",
        pad,
    ]
    if not plans:
        lines.append("no object detected (no module above t_o)")
    for i, p in enumerate(plans, 1):
        cx, cy = p.cog_m(layout)
        lines += [
            f"object {i}: modules {', '.join(map(str, p.modules))}",
            f"  PCOM   ({p.pcom[0]:.3f}, {p.pcom[1]:.3f}) module units",
            f"  COG    ({p.cog[0]:.3f}, {p.cog[1]:.3f}) module units = "
            f"({cx * 1e3:.1f}, {cy * 1e3:.1f}) mm",
            f"  theta  {math.degrees(p.theta):+.1f} deg ({p.theta:+.4f} rad), jaws close along it",
            f"  rule   {p.rule}" + (" (decided by a tie-break)" if p.tie_break else ""),
        ]
        if p.tentative:
            lines.append("  tried first: if it misses, the objects after it are grasped in turn")
        if p.reduced_modules != p.modules:
            lines.append(f"  kept   modules {', '.join(map(str, p.reduced_modules))}")
    return "\n".join(lines)


#: Font size of the pad pictures' labels, points (the figure's own size).
PAD_FONT_PT = 9.0


def plot_plans(
    delta_pa: ArrayLike,
    plans: Sequence[GraspPlan],
    layout: PadLayout,
    gripper: GripperSpec | None = None,
    ax: Axes | None = None,
    title: str = "",
    vmax_kpa: float | None = None,
    legend: bool = True,
    colorbar: bool = True,
    font_pt: float = PAD_FONT_PT,
) -> Any:
    """Draw the pad, the increments as a heat map, PCOM, COG and the two fingertips (Fig. 6.10).

    Returns the matplotlib Axes. Both axes in millimetres of the pad frame (origin at the pad's
    bottom-left corner), the module grid drawn at every pitch and each module numbered; the
    fingertips are the jaws' two pads at the approach opening (the gripper's largest width),
    across the centre of grasp along theta, as the legend says. ``vmax_kpa`` fixes the top of
    the colour scale (several panels on one scale; default this panel's largest increment);
    ``legend`` and ``colorbar`` may be left to the caller (one for a whole figure);
    ``font_pt`` is the size of every label, points.
    """
    import matplotlib.pyplot as plt

    gripper = gripper or GripperSpec()
    d = np.asarray(delta_pa, dtype=float) / 1e3
    if ax is None:
        _, ax = plt.subplots(figsize=(1.6 * layout.cols + 1.4, 1.6 * layout.rows + 0.6))
    _draw_increments(ax, d, layout, vmax_kpa, colorbar, font_pt)
    for plan in plans:
        _draw_plan(ax, plan, layout, gripper)
    if plans and legend:  # outside the pad, so that it covers no module
        ax.legend(
            handles=plan_legend_handles(), loc="upper left", bbox_to_anchor=(1.0, 1.0),
            fontsize=font_pt, frameon=False, borderaxespad=0.2,
        )  # fmt: skip
    pitch_mm = layout.pitch_m * 1e3
    margin = 0.3 * pitch_mm
    ax.set_xlim(-margin, layout.cols * pitch_mm + margin)
    ax.set_ylim(-margin, layout.rows * pitch_mm + margin)
    ax.set_xticks(np.arange(layout.cols + 1) * pitch_mm)
    ax.set_yticks(np.arange(layout.rows + 1) * pitch_mm)
    ax.tick_params(labelsize=font_pt)
    ax.set_aspect("equal")
    ax.set_xlabel("x (mm)", fontsize=font_pt)
    ax.set_ylabel("y (mm)", fontsize=font_pt)
    if title:
        ax.set_title(title, fontsize=font_pt)
    return ax


#: Width of one column of a two-column paper, inches: the figures of
#: :func:`plot_plan_columns` are that wide.
COLUMN_WIDTH_IN = 3.5
#: Font size of every label of a column-wide figure, points (a paper's smallest is 6.5 pt).
COLUMN_FONT_PT = 7.0


def plot_plan_columns(
    cases: Sequence[tuple[PlanCase, GraspPlan]],
    folder: str | Path,
    layout: PadLayout,
    prefix: str = "plans_reference-",
    gripper: GripperSpec | None = None,
) -> list[Path]:
    """One figure :data:`COLUMN_WIDTH_IN` wide per case, to print in a paper's column: the
    pad in millimetres with the module grid (:func:`plot_plans`), the increments on one
    colour scale for all cases, a colour bar and the legend below; every label
    :data:`COLUMN_FONT_PT` at the figure's own width.

    Parameters
    ----------
    cases
        Each case (its ``name``, ``weight_g`` and ``delta_pa``, Pa) with its plan.
    folder
        Output folder (made if absent); each figure is ``folder/<prefix><name>.png``.
    layout
        The pad.
    prefix
        Start of each file name.
    gripper
        Fingertip sizes of the drawn jaws (default :class:`~softpad.layout.GripperSpec`).

    Returns
    -------
    list of pathlib.Path
        The figures written, in the order of ``cases``.
    """
    from matplotlib.figure import Figure

    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    vmax = max(float(np.max(case.delta_pa)) for case, _ in cases) / 1e3
    paths = []
    for case, plan in cases:
        fig = Figure(figsize=(COLUMN_WIDTH_IN, 2.7), layout="constrained")
        ax = fig.add_subplot()
        plot_plans(
            case.delta_pa, [plan], layout, gripper, ax=ax, vmax_kpa=vmax, legend=False,
            title=f"{case.name} ({case.weight_g:g} g), one scale for all objects",
            font_pt=COLUMN_FONT_PT,
        )  # fmt: skip
        fig.legend(
            handles=plan_legend_handles(one_line=True), loc="outside lower center", ncols=3,
            fontsize=COLUMN_FONT_PT, frameon=False,
        )  # fmt: skip
        paths.append(folder / f"{prefix}{case.name}.png")
        fig.savefig(paths[-1], dpi=300)
    return paths


def plan_legend_handles(one_line: bool = False) -> list[Any]:
    """Legend entries of :func:`plot_plans`' marks: PCOM, COG and the fingertips (their label
    on ``one_line`` or two)."""
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    return [
        Line2D([], [], ls="", marker="o", color="tab:blue", ms=6, label="PCOM"),
        Line2D([], [], ls="", marker="x", color="k", ms=8, mew=2, label="COG"),
        Patch(color="k", label="fingertips," + (" " if one_line else "\n") + "jaws open"),
    ]


def _draw_increments(
    ax: Any,
    d_kpa: NDArray[np.float64],
    layout: PadLayout,
    vmax_kpa: float | None = None,
    colorbar: bool = True,
    font_pt: float = PAD_FONT_PT,
) -> None:
    """Heat map of the increments (kPa) over the modules, module numbers and the module grid
    (millimetres)."""
    d = d_kpa
    grid = np.zeros((layout.rows, layout.cols))
    for m in layout.modules:
        r, c = layout.row_col(m)
        grid[layout.rows - 1 - r, c] = d[m - 1]
    vmax = vmax_kpa if vmax_kpa is not None else max(float(np.max(np.abs(d))), 1e-6)
    p = layout.pitch_m * 1e3
    im = ax.imshow(
        grid,
        origin="lower",
        extent=(0, layout.cols * p, 0, layout.rows * p),
        cmap="RdPu",
        vmin=0,
        vmax=vmax,
    )
    if colorbar:
        bar = ax.figure.colorbar(im, ax=ax, fraction=0.04, pad=0.02)
        bar.set_label("dP (kPa)", fontsize=font_pt)
        bar.ax.tick_params(labelsize=font_pt)
    for m in layout.modules:
        x, y = layout.center(m)
        ax.text((x - 0.45) * p, (y + 0.28) * p, str(m), fontsize=font_pt, color="0.3")
    for k in range(layout.cols + 1):
        ax.axvline(k * p, color="0.5", lw=1.2)
    for k in range(layout.rows + 1):
        ax.axhline(k * p, color="0.5", lw=1.2)


def _draw_plan(ax: Any, plan: GraspPlan, layout: PadLayout, gripper: GripperSpec) -> None:
    """PCOM, COG and the two fingertips of ``plan``, millimetres."""
    from matplotlib.patches import Rectangle

    mm = layout.pitch_m * 1e3  # per module unit
    thick, width = gripper.tip_thickness_m * 1e3, gripper.tip_width_m * 1e3
    ax.plot(plan.pcom[0] * mm, plan.pcom[1] * mm, "o", color="tab:blue", ms=6, label="PCOM")
    ax.plot(plan.cog[0] * mm, plan.cog[1] * mm, "x", color="k", ms=8, mew=2, label="COG")
    for tx, ty in gripper.fingertip_centres(plan.cog_m(layout), plan.theta):
        rect = Rectangle(
            (tx * 1e3 - thick / 2, ty * 1e3 - width / 2),
            thick,
            width,
            angle=math.degrees(plan.theta),
            rotation_point="center",
            color="k",
        )
        ax.add_patch(rect)
