"""The speed figures of the design issue, in one suite (``softpad bench --only design``).

* one 2 x 3 plan (the slowest Table 6.1 case) <= 20 us; one 64 x 64 plan <= 1 ms;
* the simulated box, 8 channels at 1 kHz, every valve open: >= 200x real time;
* Experiment 2 (11 objects x 5 MuJoCo trials) on 2 processes <= 30 s, with trials per second;
* a design sweep (the 8 quick designs x the Table 6.1 set x 2 seeds) on a local Dask cluster
  of 1 and of 2 workers: wall time, speed-up and scaling efficiency (nothing cached).
"""

from __future__ import annotations

import statistics
import tempfile
import time

from softpad.benchmarks._common import BenchResult, median_time_s
from softpad.benchmarks._planning import plan_2x3_figure, slowest_plan_s

PLAN_64X64_TARGET_S = 1e-3
SIM_TARGET = 200.0
EXPERIMENT_TARGET_S = 30.0


def run(quick: bool = False) -> list[BenchResult]:
    """Every figure of the suite."""
    return [*_plans(quick), _sim_valves_open(quick), _experiment(quick), *_sweep(quick)]


def _plans(quick: bool) -> list[BenchResult]:
    import numpy as np

    from softpad.layout import PadLayout
    from softpad.planning import TABLE_6_1, plan_grasps

    repeats, inner = (5, 200) if quick else (11, 1000)
    worst_name, worst = slowest_plan_s(TABLE_6_1, repeats, inner)
    big = PadLayout(64, 64)
    delta = np.zeros((64, 64))
    delta[10:20, 10:25] = 120.0  # three objects: a block, a bar, a strip
    delta[40:50, 30:33] = 80.0
    delta[5:8, 50:60] = 200.0
    flat = delta.ravel()
    t64 = median_time_s(lambda: plan_grasps(flat, big), repeats, 20 if quick else 50)
    return [
        plan_2x3_figure(
            f"plan 2x3, slowest Table 6.1 case ({worst_name})",
            worst,
            f"median of {repeats} x {inner} calls of plan_grasps per case",
        ),
        BenchResult(
            "plan 64x64 (3 objects, 4096 modules)",
            t64 * 1e3,
            "ms",
            target="<= 1 ms",
            met=t64 <= PLAN_64X64_TARGET_S,
            detail=f"median of {repeats} x {20 if quick else 50} calls of plan_grasps",
        ),
    ]


def _sim_valves_open(quick: bool) -> BenchResult:
    from softpad.box import open_box

    repeats, sim_s = (3, 2.0) if quick else (7, 5.0)
    factors = []
    for _ in range(repeats):
        with open_box("sim://?rate_hz=1000&inflated_kpa=0.5") as box:
            box.set_valves(["inflate"] * box.channels)
            box.read_many(100)
            n = round(sim_s * 1000)
            t0 = time.perf_counter()
            for _ in range(n):
                box.read()
            factors.append(sim_s / (time.perf_counter() - t0))
    f = statistics.median(factors)
    return BenchResult(
        "sim box, 8 channels at 1 kHz, every valve open",
        f,
        "x real time",
        target=">= 200x",
        met=f >= SIM_TARGET,
        detail=f"median of {repeats} runs of {sim_s:g} s simulated, box-side safety check on every frame",
    )


def _experiment(quick: bool) -> BenchResult:
    from softpad.sim import get_object, object_names
    from softpad.trials import run_experiment

    specs = [get_object(n) for n in object_names()]
    trials = 1 if quick else 5
    exp, _ = run_experiment(specs, trials=trials, seed=0, workers=2)
    n = len(exp.trials)
    rate = n / exp.wall_time_s
    label = f"Experiment 2, {len(specs)} objects x {trials} MuJoCo trials on 2 processes"
    target, met = ("<= 30 s", exp.wall_time_s <= EXPERIMENT_TARGET_S) if not quick else ("", None)
    return BenchResult(
        label,
        exp.wall_time_s,
        "s",
        target=target,
        met=met,
        detail=f"{rate:.2f} trials/s; {sum(t.success for t in exp.trials)}/{n} held",
    )


def _sweep(quick: bool) -> list[BenchResult]:
    from softpad.design import (
        QUICK_DESIGNS,
        ResultCache,
        TrialOptions,
        design_sweep,
        example_object_set,
    )

    objects = example_object_set("thesis-set")
    seeds = (0,) if quick else (0, 1)
    walls = {}
    for workers in (1, 2):
        with tempfile.TemporaryDirectory() as tmp:
            t0 = time.perf_counter()
            design_sweep(
                list(QUICK_DESIGNS),
                objects,
                TrialOptions(hold_s=2.0),
                seeds,
                quick=True,
                workers=workers,
                cache=ResultCache(tmp),
            )
            walls[workers] = time.perf_counter() - t0
    speedup = walls[1] / walls[2]
    what = f"{len(QUICK_DESIGNS)} designs x {len(objects.objects)} objects x {len(seeds)} seeds"
    return [
        BenchResult(
            f"design sweep, {what}, 1 Dask worker",
            walls[1],
            "s",
            detail="local cluster on 127.0.0.1 started included; FEM (8 cells) + trials (2 s hold), no cache",
        ),
        BenchResult(
            f"design sweep, {what}, 2 Dask workers",
            walls[2],
            "s",
            detail=f"speed-up {speedup:.2f}x, scaling efficiency {speedup / 2:.0%}",
        ),
    ]
