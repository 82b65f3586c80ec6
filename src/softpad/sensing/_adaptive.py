"""A CUSUM contact detector whose allowance follows how much each module moves on its own.

An object resting on the soft pad can rock its modules for seconds (in the MuJoCo world tall
objects swing modules by 40 to 120 Pa at about 4 Hz before the fingers arrive), while a module
with nothing on it shows only the sensor's noise. One threshold for both is either slow on the
quiet modules or fires on the rocking ones. This detector gives every module its own allowance:
the fixed allowance plus an *envelope*, the largest recent size of that module's own rise::

    e_k   = P_k - b_{k-1},         b_k = b_{k-1} + (P_k - b_{k-1}) / (baseline_time_s f)
    s_k   = mean of e over the last smoothing_s
    env_k = max(E0 exp(-(k-L-H)+ / (envelope_time_s f)), max |s_j| for k-L-H < j <= k-L)
    g_k   = max(0, g_{k-1} + s_k - drift_pa - env_k)

with L = envelope_lag_s f and H = envelope_hold_s f. The envelope is the largest size of the
module's rise over the last ``envelope_hold_s`` (longer than a rocking period, so it does not
sag between two crests), read ``envelope_lag_s`` late, so a fingertip's own rise (tens of ms)
cannot raise the allowance that should detect it. Until the window has seen the module, a
starting envelope E0 = ``initial_envelope_pa`` (a module may be rocking when the descent
starts) stands in; then it fades with ``envelope_time_s``. The slow
baseline (1 s) follows an idle pad's drift and leak and not a rocking object. Thresholds are
calibrated on idle recordings for a stated false-alarm rate with the same peaks-over-threshold
fit as the plain CUSUM (:func:`calibrate_adaptive`); the loaded pad is covered by the envelope.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from softpad.errors import CheckedFields, InputError, NonNegative, Positive
from softpad.sensing._contact import LatchingContactDetector
from softpad.sensing._cusum import CusumLimit, _checked, excursion_peaks, fit_limit


@dataclass(frozen=True)
class AdaptiveParams(CheckedFields, what="adaptive CUSUM"):
    """Time constants and the starting envelope of :class:`AdaptiveCusumDetector`."""

    #: Time constant of the baseline, s: follows an idle pad's drift (2 s correlation), leak
    #: and temperature, not a 4 Hz rocking.
    baseline_time_s: Positive = 1.0
    #: Moving-average length of the rise, s (at least one sample): 4 ms halves the white
    #: noise at 1 kHz and costs 2 ms of a fingertip's ramp.
    smoothing_s: Positive = 4e-3
    #: Envelope at the start of the descent, Pa: the largest rocking swing seen on loaded pads
    #: before the touch (120 Pa on object 6 in MuJoCo) is reached by envelope plus allowance.
    initial_envelope_pa: NonNegative = 80.0
    #: Fading time of the starting envelope once the window has filled, s.
    envelope_time_s: Positive = 0.25
    #: Length of the window the envelope is the largest rise in, s: more than one period of
    #: the rocking (4 Hz in MuJoCo; 0.3 s covers down to 3.3 Hz).
    envelope_hold_s: Positive = 0.3
    #: Delay of the envelope behind the rise, s: longer than a fingertip's detection.
    envelope_lag_s: Positive = 0.05


class AdaptiveCusumDetector(LatchingContactDetector):
    """One-sided CUSUM per module with an allowance raised by the module's own recent motion.

    Parameters
    ----------
    limit
        Fixed allowance and threshold, pascals.
    sample_rate_hz
        Frames per second of the box.
    params
        Time constants and starting envelope.
    """

    def __init__(
        self, limit: CusumLimit, sample_rate_hz: float, params: AdaptiveParams | None = None
    ) -> None:
        super().__init__()
        if not (math.isfinite(sample_rate_hz) and sample_rate_hz > 0):
            raise InputError(f"sample rate must be a number of Hz > 0, got {sample_rate_hz!r}")
        self.limit, self.params = _checked(limit, "adaptive "), params or AdaptiveParams()
        p, f = self.params, sample_rate_hz
        self._rate = f
        self._gain = 1.0 / max(1.0, p.baseline_time_s * f)
        self._smooth = max(1, round(p.smoothing_s * f))
        self._lag = max(1, round(p.envelope_lag_s * f))
        self._hold = max(1, round(p.envelope_hold_s * f))
        self._window = np.arange(self._hold)  # offsets of the hold window from the oldest |s|
        self._decay = math.exp(-1.0 / max(1.0, p.envelope_time_s * f))
        self._restart(0)

    @property
    def statistic_pa(self) -> NDArray[np.float64]:
        """Current per-module statistic, pascals."""
        return self._g.copy()

    @property
    def floor_key(self) -> tuple[object, ...]:
        return ("adaptive", self.limit, self.params, self._rate)

    @property
    def envelope_pa(self) -> NDArray[np.float64]:
        """Current per-module envelope (the allowance above the fixed one), pascals."""
        return self._env.copy()

    def _restart(self, modules: int) -> None:
        self._g, self._baseline, self._sum = np.zeros((3, modules))
        self._start = self.params.initial_envelope_pa
        self._env = np.full(modules, self._start)
        self._rises = np.zeros((self._smooth, modules))
        self._past = np.zeros((self._lag + self._hold, modules))  # |s|, oldest read first
        self._k = 0

    def step(self, rise_pa: NDArray[np.float64]) -> NDArray[np.float64]:
        """Advance by one frame's rise over the reference; the per-module statistic."""
        e = rise_pa - self._baseline
        self._baseline += self._gain * e
        i, n = self._k % self._smooth, self._past.shape[0]
        self._sum += e - self._rises[i]
        self._rises[i] = e
        s = self._sum / self._smooth
        self._past[self._k % n] = np.abs(s)
        self._k += 1
        window = (self._k + self._window) % n  # the hold window, lag frames back
        if self._k > n:  # the window has seen the module: the starting envelope fades
            self._start *= self._decay
        self._env = np.maximum(self._start, self._past[window].max(axis=0))
        self._g = np.maximum(0.0, self._g + s - self.limit.drift_pa - self._env)
        return self._g

    def _exceeds(self, rise_pa: NDArray[np.float64]) -> NDArray[np.bool_]:
        return self.step(rise_pa) > self.limit.threshold_pa


def calibrate_adaptive(
    idle_increments_pa: ArrayLike,
    sample_rate_hz: float,
    drift_pa: float,
    hours_per_alarm: float = 1000.0,
    params: AdaptiveParams | None = None,
    fit: int = 200,
) -> CusumLimit:
    """The threshold of the adaptive CUSUM for one false alarm per ``hours_per_alarm`` on an
    idle pad: peaks over threshold of its statistic's excursions over the recording
    (``(frames, modules)`` increments over the reference, Pa), as :func:`fit_limit`."""
    x = np.asarray(idle_increments_pa, dtype=float)
    if x.ndim != 2 or x.shape[0] == 0 or not np.isfinite(x).all():
        raise InputError(f"idle increments must be finite, shape (frames, modules), got {x.shape}")
    det = AdaptiveCusumDetector(CusumLimit(drift_pa, 1.0), sample_rate_hz, params)
    det.reset(np.zeros(x.shape[1]))
    g = np.empty_like(x)
    for k, row in enumerate(x):
        g[k] = det.step(row)
    hours = x.shape[0] / sample_rate_hz / 3600.0
    return fit_limit(excursion_peaks(g), drift_pa, hours, hours_per_alarm, fit)


#: Shipped limits of the adaptive CUSUM by sample rate (Hz): allowance and threshold for one
#: false alarm per 1000 h of an idle pad, fitted by :func:`calibrate_adaptive` on
#: ``sim://?inflated_kpa=1.1&disturbances=1&seed=7`` (2 idle hours at 100 Hz, 0.5 h at
#: 1 kHz; allowance 15 and 5 Pa, the smallest giving the fit its 200 excursions). Checked
#: without refit on loaded pads: no alarm before the first fingertip touch in the descents of
#: 174 MuJoCo trials at 100 Hz (experiment seeds 100-103) and 84 at 1 kHz (100-101), where
#: the plain CUSUM's thresholds needed 60-300 Pa.
ADAPTIVE_CALIBRATIONS: dict[float, CusumLimit] = {
    100.0: CusumLimit(15.0, 23.1, 1.94),
    1000.0: CusumLimit(5.0, 17.8, 1.33),
}


def adaptive_for_rate(sample_rate_hz: float, modules: int = 6) -> AdaptiveCusumDetector:
    """The calibrated adaptive CUSUM for a box sampling at ``sample_rate_hz``: the limits of
    the fastest calibrated rate not above it (the slowest for slower boxes), the threshold
    raised by the tail for more samples and modules than calibrated (6)."""
    if not (math.isfinite(sample_rate_hz) and sample_rate_hz > 0):
        raise InputError(f"sample rate must be a number of Hz > 0, got {sample_rate_hz!r}")
    below = [r for r in ADAPTIVE_CALIBRATIONS if r <= sample_rate_hz]
    rate = max(below) if below else min(ADAPTIVE_CALIBRATIONS)
    limit = ADAPTIVE_CALIBRATIONS[rate].raised(sample_rate_hz / rate * modules / 6)
    return AdaptiveCusumDetector(limit, sample_rate_hz)
