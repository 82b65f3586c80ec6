"""``softpad demo``: the project's main job on the simulated default."""

from __future__ import annotations

import argparse
import math
from pathlib import Path
from typing import Any


def register(sub: Any) -> None:
    p = sub.add_parser(
        "demo",
        help="run the main job: reproduce the thesis's Table 6.1 plans and write a report",
        description=(
            "Plan the grasps of the thesis's Table 6.1 objects from reference pressure "
            "increments, print them next to the thesis's values, and write a report folder "
            "with the table (Markdown, CSV) and a picture of every plan (like Fig. 6.10)."
        ),
    )
    p.add_argument("--out", default="report", help="report folder (default: report)")
    p.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    from softpad.layout import PadLayout
    from softpad.planning import TABLE_6_1, plan_grasps

    layout = PadLayout()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
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
    table = "\n".join(rows)
    print("Table 6.1 of the thesis, planned from reference increments:\n")
    print(table)
    (out / "table.md").write_text(table + "\n")
    (out / "table.csv").write_text("\n".join(csv_lines) + "\n")
    _plot_all(out / "plans.png", results, layout)
    print(f"\nreport written to {out}/ (table.md, table.csv, plans.png)")
    return 0


def _pi(theta: float) -> str:
    for num, text in ((0.0, "0"), (0.5, "pi/2"), (0.25, "pi/4"), (-0.25, "-pi/4")):
        if math.isclose(theta, num * math.pi, abs_tol=1e-9):
            return text
    return f"{theta:.3f}"


def _plot_all(path: Path, results: list[Any], layout: Any) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from softpad.planning import plot_plans

    n = len(results)
    cols = 4
    fig, axes = plt.subplots(
        math.ceil(n / cols), cols, figsize=(4.2 * cols, 2.6 * math.ceil(n / cols))
    )
    for ax, (case, plan) in zip(axes.flat, results, strict=False):
        plot_plans(case.delta_pa, [plan], layout, ax=ax, title=f"{case.name} ({case.weight_g:g} g)")
    for ax in list(axes.flat)[n:]:
        ax.axis("off")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
