"""Planner speed: one plan on the 2 x 3 pad, in process (target <= 50 us)."""

from __future__ import annotations

from softpad.benchmarks._common import BenchResult, median_time_s

TARGET_S = 50e-6


def run(quick: bool = False) -> list[BenchResult]:
    from softpad.layout import PadLayout
    from softpad.planning import TABLE_6_1, plan_grasps

    layout = PadLayout()
    results = []
    repeats, inner = (7, 200) if quick else (21, 1000)
    for name in ("banana", "limes", "cylinder"):
        case = next(c for c in TABLE_6_1 if c.name == name)
        delta = case.delta_pa

        def one_plan(d: tuple[float, ...] = delta) -> object:
            return plan_grasps(d, layout)

        t = median_time_s(one_plan, repeats, inner)
        results.append(
            BenchResult(
                f"plan 2x3 ({name}, rule {plan_grasps(delta, layout)[0].rule})",
                t * 1e6,
                "us",
                target="<= 50 us",
                met=t <= TARGET_S,
                detail=f"median of {repeats} x {inner} calls of plan_grasps",
            )
        )
    return results
