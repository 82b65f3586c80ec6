"""Shared helpers of the benchmarks."""

from __future__ import annotations

import statistics
import time
from collections.abc import Callable
from dataclasses import dataclass


@dataclass(frozen=True)
class BenchResult:
    """One measured figure."""

    #: What was measured.
    name: str
    #: The figure (median where timed).
    value: float
    #: Its unit.
    unit: str
    #: The target, as text (e.g. ``"<= 50 us"``), or empty.
    target: str = ""
    #: Whether the target is met (None when there is no target).
    met: bool | None = None
    #: How it was measured (repeats, sizes, machine-relevant facts).
    detail: str = ""

    def line(self) -> str:
        """One printed line: the figure, its target and whether it is met, how it was measured
        (a figure without a target says so)."""
        if self.met is None:
            status = f"target {self.target}" if self.target and self.target != "-" else "no target"
        else:
            status = f"target {self.target}: {'met' if self.met else 'NOT MET'}"
        return f"{self.name}: {self.value:.4g} {self.unit}  [{status}]  -- {self.detail}"


def median_time_s(fn: Callable[[], object], repeats: int, inner: int = 1) -> float:
    """Median over ``repeats`` of the mean wall time of ``inner`` calls of ``fn``, seconds."""
    samples = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        for _ in range(inner):
            fn()
        samples.append((time.perf_counter() - t0) / inner)
    return statistics.median(samples)
