"""Inflation matched to the approach: detection delay and finger force against p0 and speed.

For each inflation pressure p0 (the thesis's usable 0.5 to 2.8 kPa) and approach speed, the loop
runs on the simulated box (analytic world) and the ground truth gives the detection delay, the
fingertip travel into the pad and the force the fingers press on the pad at detection (the
modules' load then, less the object's resting load). :func:`recommend_p0` picks the p0 that
keeps both within stated bounds.
"""

from __future__ import annotations

import statistics
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from softpad import thesis
from softpad.box import SimBox
from softpad.control import ExecutionParams, InflationParams
from softpad.errors import InputError
from softpad.harness._run import run_simulated
from softpad.sensing import make_contact_detector


@dataclass(frozen=True)
class InflationPoint:
    """Medians over seeds at one (p0, approach speed); SI units."""

    p0_pa: float
    speed_m_s: float
    delay_s: float | None
    travel_m: float | None
    force_n: float | None
    held: int
    runs: int

    def to_dict(self) -> dict[str, Any]:
        return dict(vars(self))


class _ForceProbe:
    """Recorder reading the world's module loads before the descent and at the detection."""

    def __init__(self, box: SimBox) -> None:
        self.box, self.resting_n = box, 0.0
        self.force_n: float | None = None

    def frame(self, frame: Any, phase: str) -> None:
        pass

    def event(self, t_s: float, kind: str, **data: Any) -> None:
        if kind == "phase" and data.get("phase") == "descend":
            self.resting_n = float(self.box.world.module_loads_n().sum())
        elif kind == "contact":
            self.force_n = float(self.box.world.module_loads_n().sum()) - self.resting_n


def _median(values: list[float]) -> float | None:
    return statistics.median(values) if values else None


def inflation_point(
    p0_pa: float, speed_m_s: float, seeds: Sequence[int], detector: str, rate_hz: float, obj: str
) -> InflationPoint:
    """Run the loop at one (p0, speed) for every seed; medians of what the ground truth shows."""
    delays: list[float] = []
    travels: list[float] = []
    forces: list[float] = []
    held = 0
    params = ExecutionParams(
        inflation=InflationParams(target_pa=p0_pa), approach_speed_m_s=speed_m_s, hold_s=0.0
    )
    for seed in seeds:
        box = SimBox(seed=seed, sample_rate_hz=rate_hz)
        probe = _ForceProbe(box)
        with box:
            run = run_simulated(
                [obj],
                box,
                params,
                probe,
                contact_detector=make_contact_detector(
                    detector, box.sample_rate_hz, box.world.layout
                ),
            )
        held += run.outcome == "held"
        for v, out in ((run.contact_delay_s(), delays), (run.finger_travel_m(), travels)):
            if v is not None:
                out.append(float(v))
        if probe.force_n is not None:
            forces.append(probe.force_n)
    return InflationPoint(
        p0_pa, speed_m_s, _median(delays), _median(travels), _median(forces), held, len(seeds)
    )


def inflation_study(
    pressures_pa: Sequence[float] = (600.0, thesis.P0_PA, 1700.0, 2300.0),
    speeds_m_s: Sequence[float] = (0.02, 0.05, 0.1),
    seeds: Sequence[int] = (1, 2, 3),
    detector: str = "adaptive",
    rate_hz: float = 1000.0,
    obj: str = "object-5",
) -> list[InflationPoint]:
    """Every (p0, speed) point of the grid (p0 within the thesis's usable 0.5 to 2.8 kPa), with
    the best contact detector (the adaptive CUSUM) by default."""
    for p in pressures_pa:
        if not 500.0 <= p <= 2800.0:
            raise InputError(
                f"p0 must be within 0.5 to 2.8 kPa (thesis, Section 6.2.1.1), got {p / 1e3:g} kPa"
            )
    return [
        inflation_point(p, v, seeds, detector, rate_hz, obj)
        for v in speeds_m_s
        for p in pressures_pa
    ]


def recommend_p0(
    points: Sequence[InflationPoint], speed_m_s: float, max_delay_s: float, max_force_n: float
) -> InflationPoint | None:
    """The point at ``speed_m_s`` with the smallest finger force among those held every time,
    detected within ``max_delay_s`` and pressing at most ``max_force_n``; None if none is."""
    ok = [
        pt
        for pt in points
        if pt.speed_m_s == speed_m_s
        and pt.held == pt.runs
        and pt.delay_s is not None
        and pt.delay_s <= max_delay_s
        and pt.force_n is not None
        and pt.force_n <= max_force_n
    ]
    return min(ok, key=lambda pt: (pt.force_n, pt.p0_pa)) if ok else None
