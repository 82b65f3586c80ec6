"""Contact detectors side by side: detection delay on the simulated loop, false alarms idle.

Targets (issue "Beat the thesis's loop"): the best detector's median delay at most one third of
the thesis detector's at the same sample rate, with zero false alarms over 10 simulated hours
of an idle pad with sensor noise and drift.
"""

from __future__ import annotations

import statistics

from softpad.benchmarks._common import BenchResult


def _delays(detector: str, rate_hz: int, names: list[str], seeds: tuple[int, ...]) -> list[float]:
    from softpad.control import ExecutionParams
    from softpad.harness import run_simulated
    from softpad.sensing import make_contact_detector

    out = []
    for name in names:
        for seed in seeds:
            run = run_simulated(
                [name],
                f"sim://?seed={seed}&rate_hz={rate_hz}",
                ExecutionParams(hold_s=0.0),
                contact_detector=make_contact_detector(detector),
            )
            delay = run.contact_delay_s()
            if delay is not None:
                out.append(delay)
    return out


def run(quick: bool) -> list[BenchResult]:
    from softpad.sim import object_names
    from softpad.trials._compare import idle_false_alarms_per_hour

    names = list(object_names())[:3] if quick else list(object_names())
    seeds = (1,) if quick else (1, 2, 3)
    hours = 0.5 if quick else 10.0
    out = []
    for rate in (100, 1000):
        med = {d: statistics.median(_delays(d, rate, names, seeds)) for d in ("thesis", "cusum")}
        ratio = med["cusum"] / med["thesis"]
        out.append(
            BenchResult(
                f"contact delay at {rate} Hz, cusum / thesis (medians)",
                ratio,
                "x",
                target="<= 0.33",
                met=ratio <= 1 / 3 + 1e-9,
                detail=f"thesis {1e3 * med['thesis']:.0f} ms, cusum {1e3 * med['cusum']:.0f} ms; "
                f"{len(names)} objects x {len(seeds)} seeds, analytic world",
            )
        )
    for detector in ("thesis", "cusum"):
        alarms = idle_false_alarms_per_hour(detector, hours)
        out.append(
            BenchResult(
                f"false contact alarms, {detector} detector, idle pad with noise and drift",
                alarms,
                "per hour",
                target="0 per hour",
                met=alarms == 0,
                detail=f"{hours:g} h simulated at 100 Hz (seed 7), re-armed after each alarm",
            )
        )
    return out
