"""The demo's reference plans: the thesis planner on Table 6.1's reference increments (no
physics) as a Markdown table, a CSV file and one figure of every case."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any


def write_reference_plans(out: Path) -> None:
    """The planner on the thesis's Table 6.1 reference increments (no physics), written into
    the folder ``out`` as plans_reference.md, .csv and .png, and each case a column wide
    (3.5 in) into ``out/column/``.

    Parameters
    ----------
    out
        The report's folder.
    """
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


__all__ = ["write_reference_plans"]
