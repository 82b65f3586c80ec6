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
        status = "" if self.met is None else ("  [met]" if self.met else "  [NOT MET]")
        tgt = f"  (target {self.target})" if self.target else ""
        return f"{self.name}: {self.value:.4g} {self.unit}{tgt}{status}  -- {self.detail}"


def median_time_s(fn: Callable[[], object], repeats: int, inner: int = 1) -> float:
    """Median over ``repeats`` of the mean wall time of ``inner`` calls of ``fn``, seconds."""
    samples = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        for _ in range(inner):
            fn()
        samples.append((time.perf_counter() - t0) / inner)
    return statistics.median(samples)
