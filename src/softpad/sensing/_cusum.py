"""A sequential change detector for finger contact: one-sided CUSUM per module.

Page's CUSUM on each module's increment over the pre-descent reference::

    g_k = max(0, g_{k-1} + (dP_k - drift_pa)),      contact when g_k > threshold_pa

``drift_pa`` is the increment per sample the statistic forgives (about half the smallest step
worth detecting, above the noise); the threshold is calibrated on idle frames for a stated
false-alarm rate (:func:`calibrate_cusum_threshold`). Against the thesis's running average the
CUSUM accumulates evidence without the averaging window's lag: a step of height s is detected
after about ``threshold / (s - drift)`` samples.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from softpad.errors import InputError
from softpad.sensing._contact import ContactDetector, LatchingContactDetector
from softpad.sensing._objects import check_threshold

#: Noise allowance of the default CUSUM, Pa per sample: above the sensor's 8 Pa rms white noise
#: (softpad.sim.SensorParams) by almost four sigma.
DEFAULT_CUSUM_DRIFT_PA = 30.0
#: Decision threshold of the default CUSUM, Pa, from :func:`calibrate_cusum_threshold` on 10
#: simulated hours of idle pad at 100 Hz with noise and drift: largest idle statistic 23.5 Pa,
#: margin 2 on max(23.5, drift) (``softpad bench --only detectors`` re-measures it).
DEFAULT_CUSUM_THRESHOLD_PA = 60.0


class CusumContactDetector(LatchingContactDetector):
    """One-sided CUSUM per module (a :class:`~softpad.sensing.ContactDetector`).

    Parameters
    ----------
    drift_pa
        Noise allowance subtracted from every increment, pascals.
    threshold_pa
        Decision threshold on the accumulated statistic, pascals.
    """

    def __init__(
        self,
        drift_pa: float = DEFAULT_CUSUM_DRIFT_PA,
        threshold_pa: float = DEFAULT_CUSUM_THRESHOLD_PA,
    ) -> None:
        super().__init__()
        self.drift_pa = check_threshold(drift_pa, "CUSUM drift", positive=True)
        self.threshold_pa = check_threshold(threshold_pa, "CUSUM threshold", positive=True)
        self._g: NDArray[np.float64] = np.zeros(0)

    @property
    def statistic_pa(self) -> NDArray[np.float64]:
        """Current CUSUM statistic of every module, pascals."""
        return self._g.copy()

    def _restart(self, modules: int) -> None:
        self._g = np.zeros(modules)

    def _statistic(self, rise_pa: NDArray[np.float64]) -> NDArray[np.float64]:
        self._g = np.maximum(0.0, self._g + rise_pa - self.drift_pa)
        return self._g


def cusum_peak_pa(increments_pa: ArrayLike, drift_pa: float) -> float:
    """Largest CUSUM statistic over idle increments (rows = frames, columns = modules), Pa."""
    x = np.asarray(increments_pa, dtype=float)
    if x.ndim != 2 or x.shape[0] == 0:
        raise InputError(f"idle increments must have shape (frames, modules), got {x.shape}")
    g = np.zeros(x.shape[1])
    peak = 0.0
    for row in x - drift_pa:
        g = np.maximum(0.0, g + row)
        peak = max(peak, float(g.max()))
    return peak


def calibrate_cusum_threshold(
    increments_pa: ArrayLike, drift_pa: float = DEFAULT_CUSUM_DRIFT_PA, margin: float = 2.0
) -> float:
    """Threshold for no false alarm on idle data: ``margin`` times the largest idle statistic.

    Parameters
    ----------
    increments_pa
        Idle increments over a reference (no contact), shape (frames, modules), pascals.
    drift_pa
        The detector's noise allowance, pascals.
    margin
        Factor on the largest statistic seen (>= 1); the idle data should span at least the
        time over which the false-alarm rate is stated.
    """
    if not (math.isfinite(margin) and margin >= 1.0):
        raise InputError(f"calibration margin must be >= 1, got {margin!r}")
    return margin * max(cusum_peak_pa(increments_pa, drift_pa), drift_pa)


#: Contact detectors by name (``--detector``): a factory taking no argument each.
CONTACT_DETECTORS = ("thesis", "cusum")


def make_contact_detector(name: str) -> ContactDetector:
    """A contact detector by name: ``thesis`` (10-sample average above t_g) or ``cusum``."""
    from softpad.sensing._contact import ThesisContactDetector

    if name == "thesis":
        return ThesisContactDetector()
    if name == "cusum":
        return CusumContactDetector()
    raise InputError(
        f"unknown contact detector {name!r}; use one of {', '.join(CONTACT_DETECTORS)}"
    )
