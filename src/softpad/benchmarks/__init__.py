"""Benchmarks run by ``softpad bench`` / ``make bench``.

Each private module ``_<domain>.py`` defines ``run(quick: bool) -> list[BenchResult]``; speed
targets live here, never as wall-clock assertions in unit tests.
"""

from softpad.benchmarks._common import BenchResult, median_time_s

#: Benchmark modules in the order ``softpad bench`` runs them.
BENCH_MODULES = (
    "planning",
    "sim",
    "link",
    "board",
    "stall",
    "detectors",
    "fem",
    "trials",
    "safety",
    "design",
    "speed",
)

__all__ = ["BENCH_MODULES", "BenchResult", "median_time_s"]
