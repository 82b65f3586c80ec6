"""Gripper-contact detection on the filtered pressure increments."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from softpad.sensing._filters import DEFAULT_FILTER_LENGTH, RunningAverage
from softpad.sensing._objects import DEFAULT_CONTACT_THRESHOLD_PA, check_threshold


class ContactDetector:
    """The thesis's contact detector (seed, Section 6.2.2).

    Contact is declared on the first frame where the running average (``window`` samples) of
    any module's increment over its reference exceeds ``threshold_pa`` (t_g). The filter starts
    primed with ``window`` zero increments (the reference itself), so one noise spike at the
    start cannot trigger it before the window has filled.

    Parameters
    ----------
    reference_pa
        Pressures of every channel just before the approach starts (object already on the pad),
        pascals. Increments are taken from these.
    threshold_pa
        t_g, 90 Pa by default.
    window
        Running-average length, 10 samples by default.
    """

    def __init__(
        self,
        reference_pa: ArrayLike,
        threshold_pa: float = DEFAULT_CONTACT_THRESHOLD_PA,
        window: int = DEFAULT_FILTER_LENGTH,
    ) -> None:
        self.reference_pa = np.asarray(reference_pa, dtype=float).copy()
        self.threshold_pa = check_threshold(threshold_pa, "contact threshold")
        self._filter = RunningAverage(window)
        for _ in range(window):
            self._filter.update(np.zeros_like(self.reference_pa))
        self.triggered_modules: tuple[int, ...] = ()

    def update(self, pressures_pa: ArrayLike) -> bool:
        """Feed one frame; return True once contact is detected (and from then on)."""
        if self.triggered_modules:
            return True
        filtered: NDArray[np.float64] = self._filter.update(
            np.asarray(pressures_pa, dtype=float) - self.reference_pa
        )
        hits = np.flatnonzero(filtered > self.threshold_pa)
        if hits.size:
            self.triggered_modules = tuple(int(k) + 1 for k in hits)
            return True
        return False
