"""Plug a different contact detector into a simulated grasp.

A two-sided CUSUM on the summed increment of every module replaces the thesis's running
average; nothing else changes: the same box, robot, planner and execution.

Run: .venv/bin/python examples/custom_contact_detector.py
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from softpad.control import ExecutionParams
from softpad.harness import run_simulated


class CusumContactDetector:
    """One-sided CUSUM on the largest module increment (a ``softpad.sensing.ContactDetector``).

    Parameters
    ----------
    drift_pa
        Increment per sample that the statistic forgives (noise allowance), pascals.
    threshold_pa
        Value of the accumulated statistic that declares contact, pascals.
    """

    def __init__(self, drift_pa: float = 20.0, threshold_pa: float = 150.0) -> None:
        self.drift_pa, self.threshold_pa = drift_pa, threshold_pa
        self._reference = np.zeros(0)
        self._g = np.zeros(0)
        self._triggered: tuple[int, ...] = ()

    @property
    def triggered_modules(self) -> tuple[int, ...]:
        return self._triggered

    def reset(self, reference_pa: ArrayLike) -> None:
        self._reference = np.asarray(reference_pa, dtype=float).copy()
        self._g = np.zeros_like(self._reference)
        self._triggered = ()

    def update(self, pressures_pa: ArrayLike) -> bool:
        if self._triggered:
            return True
        rise = np.asarray(pressures_pa, dtype=float) - self._reference
        self._g = np.maximum(0.0, self._g + rise - self.drift_pa)
        hits = np.flatnonzero(self._g > self.threshold_pa)
        self._triggered = tuple(int(k) + 1 for k in hits)
        return bool(hits.size)


def main() -> dict[str, float | str | None]:
    params = ExecutionParams(hold_s=1.0)
    runs = {}
    for name, detector in (("thesis", None), ("cusum", CusumContactDetector())):
        run = run_simulated(["banana"], "sim://?seed=3", params, contact_detector=detector)
        delay = run.contact_delay_s()
        runs[name] = run
        print(
            f"{name:7s} outcome {run.outcome}, contact {1e3 * (delay or float('nan')):.0f} ms after touch"
        )
    return {
        "outcome": runs["cusum"].outcome,
        "thesis_delay_s": runs["thesis"].contact_delay_s(),
        "cusum_delay_s": runs["cusum"].contact_delay_s(),
    }


if __name__ == "__main__":
    main()
