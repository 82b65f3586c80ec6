"""Plug a different contact detector into a simulated grasp.

A detector written here, not in the library: contact when a module rises above its lowest
(3-sample averaged) value since the descent began. Nothing else changes: the same box, robot,
planner and execution.
(The library's own alternative is ``softpad.sensing.CusumContactDetector``.)

Run: .venv/bin/python examples/custom_contact_detector.py
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from softpad.control import ExecutionParams
from softpad.harness import run_simulated


class PeakRiseDetector:
    """Contact when any module rises ``threshold_pa`` above its lowest value since the reset
    (a ``softpad.sensing.ContactDetector``): the pad's slow sag under the object is followed,
    the fingers' press is not.

    Parameters
    ----------
    threshold_pa
        Rise over the running minimum that declares contact, pascals.
    window
        Samples averaged before comparing (noise), samples.
    """

    def __init__(self, threshold_pa: float = 60.0, window: int = 3) -> None:
        self.threshold_pa, self.window = threshold_pa, window
        self._low = np.zeros(0)
        self._recent: list[np.ndarray] = []
        self._triggered: tuple[int, ...] = ()

    @property
    def triggered_modules(self) -> tuple[int, ...]:
        return self._triggered

    def reset(self, reference_pa: ArrayLike) -> None:
        self._low = np.asarray(reference_pa, dtype=float).copy()
        self._recent = []
        self._triggered = ()

    def update(self, pressures_pa: ArrayLike) -> bool:
        if self._triggered:
            return True
        self._recent = [*self._recent[-(self.window - 1) :], np.asarray(pressures_pa, float)]
        mean = np.mean(self._recent, axis=0)
        self._low = np.minimum(self._low, mean)
        hits = np.flatnonzero(mean - self._low > self.threshold_pa)
        self._triggered = tuple(int(k) + 1 for k in hits)
        return bool(hits.size)


def main() -> dict[str, float | str | None]:
    params = ExecutionParams(hold_s=1.0)
    runs = {}
    for name, detector in (("thesis", None), ("peak-rise", PeakRiseDetector())):
        run = run_simulated(["object-5"], "sim://?seed=3", params, contact_detector=detector)
        delay = run.contact_delay_s()
        runs[name] = run
        print(
            f"{name:7s} outcome {run.outcome}, contact {1e3 * (delay or float('nan')):.0f} ms after touch"
        )
    return {
        "outcome": runs["peak-rise"].outcome,
        "thesis_delay_s": runs["thesis"].contact_delay_s(),
        "custom_delay_s": runs["peak-rise"].contact_delay_s(),
    }


if __name__ == "__main__":
    main()
