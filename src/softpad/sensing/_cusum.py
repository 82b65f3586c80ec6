"""A sequential change detector for finger contact: one-sided CUSUM on a tracking baseline.

Page's CUSUM on each module's rise over a baseline that follows the idle pad, optionally also on
the sum of the rises of every pair of modules (two fingertips landing on two modules at once:
twice the signal for sqrt(2) times the noise)::

    e_k  = P_k - b_{k-1},     b_k = b_{k-1} + (P_k - b_{k-1}) / (baseline_time_s * f)
    g_k  = max(0, g_{k-1} + e_k - drift_pa)                      per module
    gp_k = max(0, gp_{k-1} + e_i,k + e_j,k - pair_drift_pa)       per pair (i, j)

Contact is declared when any ``g`` exceeds ``threshold_pa`` (or any ``gp`` its threshold).
The baseline starts at the pre-descent reference and follows the slow changes of an idle pad
(sensor drift, room temperature, a small leak) with the time constant ``baseline_time_s``,
far longer than a fingertip's rise. Thresholds are calibrated on recordings without contact
for a stated false-alarm rate (:func:`calibrate_cusum`, :func:`fit_limit`): the peaks of the
statistic's excursions have an exponential tail (Siegmund's approximation for a random walk
with negative drift), fitted over a high level (peaks over threshold); the threshold is the
level that tail crosses once per stated period. More samples or more statistics mean more
excursions, so thresholds depend on the sample rate and the pad's size
(:meth:`CusumCalibration.limits_for`). The shipped calibrations (:data:`CUSUM_CALIBRATIONS`)
cover an idle pad and a pad loaded by an object before the fingers touch it; the pairs are off
by default (modules under one object rock together).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from softpad.errors import InputError
from softpad.sensing._contact import LatchingContactDetector
from softpad.sensing._objects import check_threshold

#: Time constant of the baseline that follows an idle pad, seconds: long against a fingertip's
#: rise (tens of ms), short against the pad's thermal and leak changes (minutes); the sensor
#: drift (2 s correlation time) is mostly followed.
DEFAULT_BASELINE_TIME_S = 0.1
#: Allowances of the per-module and per-pair statistics, Pa per sample: about 4 times the white
#: noise of one module (8 Pa rms, softpad.sim.SensorParams) and of a pair's sum (11 Pa); over
#: the rocking of a loaded pad (see CUSUM_CALIBRATIONS), 30 Pa gives the shortest median delay
#: on the simulated loop among 16..30 Pa with the thresholds calibrated.
DEFAULT_DRIFTS_PA = (30.0, 40.0)


@dataclass(frozen=True)
class CusumLimit:
    """Allowance and threshold of one family of CUSUM statistics (single modules or pairs).

    Attributes
    ----------
    drift_pa
        Rise per sample the statistic forgives, pascals.
    threshold_pa
        Decision threshold on the statistic, pascals.
    tail_pa
        Scale of the exponential tail of idle excursion peaks, pascals (0: not calibrated):
        the threshold for the same false-alarm rate rises by ``tail_pa`` per factor e more
        excursions (more samples per hour, more statistics).
    """

    drift_pa: float
    threshold_pa: float
    tail_pa: float = 0.0

    def raised(self, factor: float) -> CusumLimit:
        """The limit for ``factor`` times as many excursions an hour (never lowered)."""
        extra = self.tail_pa * math.log(max(1.0, factor))
        return CusumLimit(self.drift_pa, self.threshold_pa + extra, self.tail_pa)


def _pairs(modules: int) -> int:
    return modules * (modules - 1) // 2


@dataclass(frozen=True)
class CusumCalibration:
    """The CUSUM's limits calibrated on an idle recording of one pad at one sample rate.

    Attributes
    ----------
    sample_rate_hz
        Frames per second of the recording.
    modules
        Modules of the recorded pad.
    single, pair
        Limits of the per-module and per-pair statistics; each is crossed once per
        ``2 * hours_per_alarm`` hours by its tail, so the detector's false alarms are at most
        one per ``hours_per_alarm`` hours; no idle peak of the recording reached them. ``pair``
        None: modules alone.
    hours_per_alarm
        Stated mean time between false alarms of an idle pad, hours.
    idle_hours
        Length of the idle recording, hours.
    """

    sample_rate_hz: float
    modules: int
    single: CusumLimit
    pair: CusumLimit | None
    hours_per_alarm: float
    idle_hours: float

    def limits_for(
        self, sample_rate_hz: float, modules: int
    ) -> tuple[CusumLimit, CusumLimit | None]:
        """Single and pair limits for another rate and pad size (thresholds raised for more
        samples and statistics, never lowered)."""
        rate = sample_rate_hz / self.sample_rate_hz
        single = self.single.raised(rate * modules / self.modules)
        if self.pair is None:
            return single, None
        pair = self.pair.raised(rate * _pairs(modules) / max(1, _pairs(self.modules)))
        return single, pair


#: Calibrations of the default CUSUM (modules alone, allowance 30 Pa, baseline time 0.1 s), for
#: at most one false alarm per 1000 h; each threshold is the larger of two fits:
#: * an idle 2 x 3 pad inflated to p0 with sensor noise (8 Pa rms), sensor drift and the slow
#:   disturbances on, 10 simulated hours (``sim://?inflated_kpa=1.1&disturbances=1&seed=7``;
#:   ``softpad bench --only detectors`` re-measures it);
#: * a loaded pad before the fingers touch it: the approach and descent frames of 102 MuJoCo
#:   trials at 100 Hz (11 objects x 5 trials x experiment seeds 100 and 101, up to the first
#:   fingertip touch; 264 s), where an object resting on the soft modules rocks them together
#:   at about 4 Hz by up to 40 Pa: 60.6 Pa (tail 4.09 Pa from the 50 highest of 97
#:   excursions), carried to 1 kHz as 60.6 + 4.09 ln 10 = 70.0 Pa. The loaded pad sets both
#:   thresholds and the allowance: at 16, 20 and 24 Pa the fits give 185, 119 and 83 Pa, and
#:   the pair statistics (modules under one object rock in phase) are off by default.
CUSUM_CALIBRATIONS: tuple[CusumCalibration, ...] = (
    CusumCalibration(100.0, 6, CusumLimit(30.0, 60.6, 4.09), None, 1000.0, 10.0),
    CusumCalibration(1000.0, 6, CusumLimit(30.0, 70.0, 4.09), None, 1000.0, 10.0),
)


class CusumContactDetector(LatchingContactDetector):
    """One-sided CUSUM per module and per pair of modules on a tracking baseline.

    Parameters
    ----------
    single
        Allowance and threshold of the per-module statistics.
    pair
        Allowance and threshold of the per-pair statistics; None: modules alone.
    baseline_samples
        Time constant of the baseline in samples (``baseline_time_s`` times the sample
        rate); 0 keeps the baseline at the reference (Page's CUSUM on the increment).

    :func:`cusum_for_rate` builds the calibrated detector for a box's sample rate.
    """

    def __init__(
        self, single: CusumLimit, pair: CusumLimit | None = None, baseline_samples: float = 0.0
    ) -> None:
        super().__init__()
        self.single = _checked(single, "")
        self.pair = None if pair is None else _checked(pair, "pair ")
        if not (
            math.isfinite(baseline_samples) and (baseline_samples == 0 or baseline_samples >= 1)
        ):
            raise InputError(
                f"CUSUM baseline time must be 0 or at least one sample, got {baseline_samples!r}"
            )
        self._gain = 1.0 / baseline_samples if baseline_samples else 0.0
        self._g = self._gp = self._baseline = np.zeros(0)
        self._i = self._j = np.zeros(0, dtype=int)

    @property
    def statistic_pa(self) -> NDArray[np.float64]:
        """Current per-module CUSUM statistic, pascals."""
        return self._g.copy()

    @property
    def floor_key(self) -> tuple[object, ...]:
        return ("cusum", self.single, self._gain)

    def floor_probe(self) -> CusumContactDetector:
        """The per-module statistics alone (a step of one module; the pairs couple modules)."""
        return CusumContactDetector(self.single, None, 1.0 / self._gain if self._gain else 0.0)

    def _restart(self, modules: int) -> None:
        self._g = np.zeros(modules)
        self._baseline = np.zeros(modules)  # rises are taken over the reference
        self._i, self._j = np.triu_indices(modules, k=1)
        self._gp = np.zeros(self._i.size)

    def _exceeds(self, rise_pa: NDArray[np.float64]) -> NDArray[np.bool_]:
        e = rise_pa - self._baseline
        self._baseline += self._gain * e
        self._g = np.maximum(0.0, self._g + e - self.single.drift_pa)
        hit = self._g > self.single.threshold_pa
        if self.pair is not None:
            self._gp = np.maximum(0.0, self._gp + e[self._i] + e[self._j] - self.pair.drift_pa)
            hit |= self._pair_modules(self._gp > self.pair.threshold_pa)
        return hit

    def _pair_modules(self, fired: NDArray[np.bool_]) -> NDArray[np.bool_]:
        """Modules named by the pairs that fired: those of them rising on their own (their
        statistic above zero), else the two of the strongest pair."""
        named = np.zeros(self._g.size, dtype=bool)
        if fired.any():
            named[self._i[fired]] = named[self._j[fired]] = True
            named &= self._g > 0.0
            if not named.any():
                k = int(np.argmax(self._gp))
                named[self._i[k]] = named[self._j[k]] = True
        return named


def _checked(limit: CusumLimit, what: str) -> CusumLimit:
    check_threshold(limit.drift_pa, f"CUSUM {what}drift", positive=True)
    check_threshold(limit.threshold_pa, f"CUSUM {what}threshold", positive=True)
    return limit


def cusum_for_rate(
    sample_rate_hz: float, modules: int = 6, baseline_time_s: float = DEFAULT_BASELINE_TIME_S
) -> CusumContactDetector:
    """The calibrated CUSUM for a pad of ``modules`` modules on a box sampling at
    ``sample_rate_hz``: the calibration of the fastest tabulated rate not above it (the
    slowest for slower boxes), its thresholds raised for more samples and statistics."""
    if not (math.isfinite(sample_rate_hz) and sample_rate_hz > 0):
        raise InputError(f"sample rate must be a number of Hz > 0, got {sample_rate_hz!r}")
    below = [c for c in CUSUM_CALIBRATIONS if c.sample_rate_hz <= sample_rate_hz]
    cal = max(below, key=lambda c: c.sample_rate_hz) if below else CUSUM_CALIBRATIONS[0]
    single, pair = cal.limits_for(sample_rate_hz, modules)
    return CusumContactDetector(single, pair, max(1.0, baseline_time_s * sample_rate_hz))


def cusum_statistics(
    increments_pa: ArrayLike,
    drifts_pa: tuple[float, float],
    baseline_samples: float,
    state: _IdleState | None = None,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Per-module and per-pair statistics after every frame (rows) of idle increments, never
    latching: the detector's recursion in closed form (the baseline as a linear filter, the
    CUSUM as Lindley's ``S_k - min(0, min_j S_j)`` of the partial sums). ``state`` carries
    the baseline and statistics from one block of frames to the next."""
    x = np.asarray(increments_pa, dtype=float)
    if x.ndim != 2 or x.shape[0] == 0 or not np.isfinite(x).all():
        raise InputError(f"increments must be finite, shape (frames, modules), got {x.shape}")
    from scipy.signal import lfilter  # here: planning and sensing load without SciPy

    st = state or _IdleState(x.shape[1])
    a = 1.0 / baseline_samples if baseline_samples else 0.0
    b, _ = lfilter([a], [1.0, a - 1.0], x, axis=0, zi=(1.0 - a) * st.baseline[None, :])
    e = x - np.vstack([st.baseline[None, :], b[:-1]])
    i, j = np.triu_indices(x.shape[1], k=1)
    g = _lindley(e - drifts_pa[0], st.single)
    gp = _lindley(e[:, i] + e[:, j] - drifts_pa[1], st.pair)
    st.baseline, st.single, st.pair = b[-1].copy(), g[-1].copy(), gp[-1].copy()
    return g, gp


class _IdleState:
    def __init__(self, modules: int) -> None:
        self.baseline = np.zeros(modules)
        self.single = np.zeros(modules)
        self.pair = np.zeros(_pairs(modules))


def _lindley(z: NDArray[np.float64], start: NDArray[np.float64]) -> NDArray[np.float64]:
    s = start + np.cumsum(z, axis=0)
    out: NDArray[np.float64] = s - np.minimum.accumulate(np.minimum(s, 0.0), axis=0)
    return out


def excursion_peaks(statistic_pa: ArrayLike) -> NDArray[np.float64]:
    """Peak of every excursion of CUSUM statistics above zero (columns pooled), pascals."""
    g = np.asarray(statistic_pa, dtype=float)
    peaks = [np.zeros(0)]
    for col in g.T:
        edges = np.flatnonzero(np.diff(np.r_[0, (col > 0).astype(np.int8), 0]))
        if edges.size:
            peaks.append(np.maximum.reduceat(col, edges[0::2]))
    return np.concatenate(peaks)


def fit_limit(
    peaks_pa: ArrayLike, drift_pa: float, hours: float, hours_per_alarm: float, fit: int = 200
) -> CusumLimit:
    """The limit whose threshold the exponential tail of idle excursion peaks crosses once
    per ``hours_per_alarm`` (the ``fit`` highest peaks give the tail's scale over the level
    they exceed: maximum likelihood), and at least the highest peak seen."""
    peaks = np.sort(np.asarray(peaks_pa, dtype=float))
    if peaks.size <= fit:
        raise InputError(
            f"the idle recording has {peaks.size} excursions of the statistic; the tail fit "
            f"needs more than {fit}: record longer"
        )
    level = float(peaks[-fit - 1])
    tail = float(np.mean(peaks[-fit:] - level))
    threshold = level + tail * math.log(max(1.0, fit / hours * hours_per_alarm))
    return CusumLimit(drift_pa, max(threshold, float(peaks[-1])), tail)


def calibrate_cusum(
    idle_increments_pa: ArrayLike,
    sample_rate_hz: float,
    drifts_pa: tuple[float, float] = DEFAULT_DRIFTS_PA,
    baseline_time_s: float = DEFAULT_BASELINE_TIME_S,
    hours_per_alarm: float = 1000.0,
    block: int = 1 << 20,
) -> CusumCalibration:
    """Calibrate the thresholds on an idle recording for one false alarm per ``hours_per_alarm``.

    Parameters
    ----------
    idle_increments_pa
        Increments of an idle pad over its reference, shape (frames, modules), pascals.
    sample_rate_hz
        Frames per second of the recording.
    drifts_pa
        Allowances of the per-module and the per-pair statistics, pascals per sample.
    baseline_time_s
        The baseline's time constant, seconds.
    hours_per_alarm
        Stated mean time between false alarms (each family gets half the rate), hours.
    block
        Frames processed at once (memory).
    """
    if not (math.isfinite(hours_per_alarm) and hours_per_alarm > 0):
        raise InputError(f"hours per false alarm must be > 0, got {hours_per_alarm!r}")
    if not (math.isfinite(sample_rate_hz) and sample_rate_hz > 0):
        raise InputError(f"sample rate must be a number of Hz > 0, got {sample_rate_hz!r}")
    x = np.asarray(idle_increments_pa)
    if x.ndim != 2 or x.shape[0] == 0:
        raise InputError(f"idle increments must have shape (frames, modules), got {x.shape}")
    hours = x.shape[0] / sample_rate_hz / 3600.0
    samples = max(1.0, baseline_time_s * sample_rate_hz)
    state, peaks, pair_peaks = _IdleState(x.shape[1]), [], []
    for start in range(0, x.shape[0], block):  # an excursion across two blocks counts twice
        g, gp = cusum_statistics(x[start : start + block], drifts_pa, samples, state)
        peaks.append(excursion_peaks(g))
        pair_peaks.append(excursion_peaks(gp))
    single = fit_limit(np.concatenate(peaks), drifts_pa[0], hours, 2 * hours_per_alarm)
    pair = fit_limit(np.concatenate(pair_peaks), drifts_pa[1], hours, 2 * hours_per_alarm)
    return CusumCalibration(
        sample_rate_hz, x.shape[1], single, pair, hours_per_alarm, round(hours, 6)
    )
