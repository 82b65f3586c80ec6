"""Planner speed: one plan on the 2 x 3 pad, in process (target <= 20 us, issue 15)."""

from __future__ import annotations

from softpad.benchmarks._common import BenchResult, median_time_s

TARGET_S = 20e-6


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
                target="<= 20 us",
                met=t <= TARGET_S,
                detail=f"median of {repeats} x {inner} calls of plan_grasps",
            )
        )
    # every reference case (Table 6.1, Fig. 6.7, one per rule): the slowest rule's median
    from softpad.planning import FIG_6_7, RULE_CASES

    worst_name, worst = "", 0.0
    for case in TABLE_6_1 + FIG_6_7 + RULE_CASES:

        def plan_case(d: tuple[float, ...] = case.delta_pa) -> object:
            return plan_grasps(d, layout)

        t = median_time_s(plan_case, 5 if quick else 11, 200)
        if t > worst:
            worst_name, worst = case.name, t
    results.append(
        BenchResult(
            f"plan 2x3, slowest of {len(TABLE_6_1 + FIG_6_7 + RULE_CASES)} reference cases ({worst_name})",
            worst * 1e6,
            "us",
            target="<= 20 us",
            met=worst <= TARGET_S,
            detail="median per case of 11 x 200 calls; the largest median",
        )
    )
    return results
