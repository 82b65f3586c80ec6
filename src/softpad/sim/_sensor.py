"""Pressure-sensor model: offset, white noise, slow drift, quantisation, range.

Defaults are chosen so that traces look like the thesis's Fig. 6.8 ("data look noisy mostly
because of the pressure sensors performance") while the thesis thresholds keep their meaning
(docs/box-and-simulator.md gives the numbers):

* white noise 8 Pa rms per sample and a slow drift (first-order Gauss-Markov, 3 Pa rms,
  2 s correlation time): the mean of 10 reads has about 4 Pa rms, so an increment of a 12.6 g
  brick (86 Pa sealed) is far above t_o = 50 Pa and the 6 g minimum detectable mass (41 Pa)
  stands out by about 5 sigma of a single sample;
* the 10-sample running average has about 4 Pa rms, so t_g = 90 Pa is about 20 sigma away:
  no false contact in hours of idle noise;
* quantisation 2.44 Pa (a 12-bit converter over a 10 kPa span), a per-channel zero offset of
  20 Pa rms (drawn once per box; the reference removes it) and a range of -2..10 kPa.

Noise is drawn in blocks (vectorised), deterministically from the box's seed.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from softpad import thesis
from softpad.errors import (
    CheckedFields,
    InputError,
    NonNegative,
    Positive,
    check_count,
    check_range,
)

MS_AS_S = "milliseconds given as seconds?"


@dataclass(frozen=True)
class SensorParams(CheckedFields, what="sensor"):
    """Parameters of the channel pressure sensors and of the supply sensor."""

    #: Standard deviation of the white noise of one sample, pascals.
    noise_std_pa: NonNegative = thesis.SENSOR_NOISE_STD_PA
    #: Stationary standard deviation of the slow drift, pascals.
    drift_std_pa: NonNegative = thesis.SENSOR_DRIFT_STD_PA
    #: Correlation time of the drift, seconds.
    drift_time_s: Positive = 2.0
    #: Resolution of the converter, pascals (0: none).
    quantization_pa: NonNegative = thesis.SENSOR_QUANTIZATION_PA
    #: Standard deviation of the per-channel zero offset, pascals.
    offset_std_pa: NonNegative = 20.0
    #: Readings saturate at these values, pascals.
    range_min_pa: float = -2.0e3
    #: Readings saturate at these values, pascals.
    range_max_pa: float = 10.0e3
    #: White noise of the supply-pressure sensor, pascals.
    supply_noise_std_pa: NonNegative = 20.0

    def __post_init__(self) -> None:
        super().__post_init__()
        if not self.range_min_pa < self.range_max_pa:
            raise InputError("sensor range_min_pa must be below range_max_pa")
        # the fast drift's correlation time (slow thermal zero shifts are a layer of their own):
        # beyond ten minutes it is milliseconds given as seconds
        check_range("sensor drift_time_s", self.drift_time_s, 0.0, 600.0, "s", MS_AS_S)

    @classmethod
    def ideal(cls) -> SensorParams:
        """A noise-free, offset-free, unquantised sensor (for tests of the physics)."""
        return cls(0.0, 0.0, 1.0, 0.0, 0.0, -1e6, 1e6, 0.0)


#: Ramps of at least this many readings get their rows' lowest and highest values computed at
#: once (:attr:`SensorBank.span`); a shorter one costs more in the reductions than it saves.
SPAN_ROWS = 8


#: An unchanged box's readings are computed this many samples at a time at first, then twice
#: as many each time they are used up (a box often changes again within a few samples: the
#: rest of a 4096-sample block, with its rows' spans, cost about 1 ms).
STILL_ROWS = 32


#: A sensor bank whose noise block lasts less than this (simulated seconds) filters the drift
#: with scipy's lfilter; longer blocks (100 Hz: 41 s) use :func:`drift_recursion`.
LFILTER_BELOW_S = 10.0


def drift_recursion(
    innov: NDArray[np.float64], d0: NDArray[np.float64], a: float
) -> NDArray[np.float64]:
    """``d[k] = a d[k-1] + innov[k]`` down the rows from ``d[-1] = d0``, in plain floats
    column by column: bit for bit what ``lfilter([1], [1, -a], innov, axis=0, zi=a d0)``
    computes (``x + a y``, one product and one sum a sample), without importing SciPy."""
    cols = []
    for col, d in zip(innov.T.tolist(), d0.tolist(), strict=True):
        out: list[float] = []
        add = out.append
        for e in col:
            d = a * d + e
            add(d)
        cols.append(out)
    return np.array(cols, dtype=float).T.reshape(innov.shape)


def _row_spans(block: NDArray[np.float64]) -> tuple[list[float], list[float]]:
    """Lowest and highest value of every row of ``block`` (NaN where a row has a NaN)."""
    return np.minimum.reduce(block, axis=1).tolist(), np.maximum.reduce(block, axis=1).tolist()


class SensorBank:
    """Noisy readings of every channel; noise drawn in blocks from a seeded generator.

    Parameters
    ----------
    n_channels
        Number of channels.
    dt_s
        Sample period, seconds.
    params
        Sensor parameters.
    rng
        Random generator (the box's, seeded).
    block
        Samples drawn per block.
    """

    def __init__(
        self,
        n_channels: int,
        dt_s: float,
        params: SensorParams,
        rng: np.random.Generator,
        block: int = 4096,
    ) -> None:
        check_count("sensor bank n_channels", n_channels, 1, 1024)
        if not (isinstance(dt_s, int | float) and math.isfinite(dt_s) and dt_s > 0):
            raise InputError(f"sensor bank sample period dt_s must be > 0 seconds, got {dt_s!r}")
        self.params = params
        self.n = n_channels
        self.rng = rng
        self.block = block
        self.offset_pa = (
            rng.normal(0.0, params.offset_std_pa, n_channels)
            if params.offset_std_pa
            else np.zeros(n_channels)
        )
        self._a = math.exp(-dt_s / params.drift_time_s)
        self._drift_innov = params.drift_std_pa * math.sqrt(1 - self._a**2)
        self._drift = (
            rng.normal(0.0, params.drift_std_pa, n_channels)
            if params.drift_std_pa
            else np.zeros(n_channels)
        )
        # the drift's recursion over a block of rows: scipy's lfilter (a C loop, 0.2 ms a
        # block) where blocks come fast, else plain floats (about 3 ms a block of 4096 x 8)
        # that spare the process importing scipy.signal (0.7 CPU s); the same bits (tested)
        self._lfilter = bool(params.drift_std_pa) and dt_s * block < LFILTER_BELOW_S
        if self._lfilter:  # imported here, not in the first sample: a box daemon
            import scipy.signal  # noqa: F401  samples under its lock (seconds on a busy host)
        self._q = params.quantization_pa
        self._lo, self._hi = params.range_min_pa, params.range_max_pa
        self._inv_q = 1.0 / self._q if self._q else 0.0
        self._i = block
        self._noise = np.zeros((block, n_channels))
        self._supply_noise: list[float] = [0.0] * block  # plain floats: read one per sample
        self._same = 0
        self._static: NDArray[np.float64] | None = None
        self._static_lo: list[float] = []
        self._static_hi: list[float] = []
        self._ramp_lo: list[float] | None = None
        self._ramp_hi: list[float] = []
        #: The last reading with its lowest and highest value (NaN when one is NaN), where
        #: they were computed for its whole block at once (a still box, a ramp of at least
        #: SPAN_ROWS readings); None otherwise. The box's guard takes them (no sorting).
        self.span: tuple[NDArray[np.float64], float, float] | None = None
        self._static_start = 0
        self._ramp: NDArray[np.float64] | None = None
        self._ramp_key = -1
        self._ramp_start = 0
        self._ramp_next = -1
        self._ramp_end = -1  # first sample index after the current ramp (-1: no ramp)

    def _refill(self) -> None:
        p, n, b = self.params, self.n, self.block
        noise = self.rng.normal(0.0, p.noise_std_pa, (b, n)) if p.noise_std_pa else np.zeros((b, n))
        if p.drift_std_pa:
            # first-order Gauss-Markov drift d[k] = a d[k-1] + e[k], one row per sample: the
            # same recursion as a Python loop over the rows (bitwise, tested), run by lfilter
            innov = self.rng.normal(0.0, self._drift_innov, (b, n))
            a = self._a
            if self._lfilter:
                from scipy.signal import lfilter

                zi = (a * self._drift)[None, :]
                drift = lfilter([1.0], [1.0, -a], innov, axis=0, zi=zi)[0]
            else:
                drift = drift_recursion(innov, self._drift, a)
            self._drift = drift[-1].copy()
            noise += drift
        self._noise = noise + self.offset_pa
        self._supply_noise = (
            self.rng.normal(0.0, p.supply_noise_std_pa, b) if p.supply_noise_std_pa else np.zeros(b)
        ).tolist()
        self._i = 0

    def refill_if_due(self) -> bool:
        """Draw the next noise block now if the current one is used up (True when it did).

        The same draws in the same order as the next :meth:`sample` would make (nothing else
        draws from the generator between samples), only earlier: a box daemon calls it
        between ticks, so the block's draw (about 1.5 ms for 8 channels, every 4096 frames)
        does not delay a sample.
        """
        if self._i < self.block:
            return False
        self._refill()
        self._static = None
        self._ramp = None
        self._ramp_end = -1
        return True

    def sample(
        self, true_pa: NDArray[np.float64], supply_pa: float, changed: bool = True
    ) -> tuple[NDArray[np.float64], float]:
        """One reading of every channel and of the supply, pascals.

        ``changed=False`` promises that ``true_pa`` equals the previous call's: after two such
        calls the readings of the next samples are computed at once (:data:`STILL_ROWS`, then
        twice as many each time, to the end of the noise block: the hot path of an idle box).
        The returned array must not be modified (copy it first).
        """
        if self._i >= self.block:
            self._refill()
            self._static = None
        i = self._i
        self._i = i + 1
        self._ramp = None
        self._ramp_end = -1
        if changed:
            self._same = 0
            self._static = None
        else:
            self._same += 1
            if self._static is None and self._same >= 2:
                self._still_rows(true_pa, i, STILL_ROWS)
            if self._static is not None:
                j = i - self._static_start
                if j >= self._static.shape[0]:  # the rows computed so far used: twice as many
                    self._still_rows(true_pa, i, 2 * self._static.shape[0])
                    j = 0
                row = self._static[j]
                self.span = (row, self._static_lo[j], self._static_hi[j])
                return row, supply_pa + self._supply_noise[i]
        self.span = None
        return self._quantise(true_pa + self._noise[i]), supply_pa + self._supply_noise[i]

    def _still_rows(self, true_pa: NDArray[np.float64], i: int, rows: int) -> None:
        """The readings of an unchanged box from sample ``i`` on, ``rows`` of them (to the
        end of the noise block at most), with each row's lowest and highest: each row the
        same as a sample computed alone, however many are computed at once."""
        self._static = self._quantise(true_pa + self._noise[i : i + rows])
        self._static.flags.writeable = False
        self._static_start = i
        self._static_lo, self._static_hi = _row_spans(self._static)

    def sample_path(
        self, path: NDArray[np.float64], row: int, key: int, supply_pa: float
    ) -> tuple[NDArray[np.float64], float]:
        """One reading while the true pressures follow ``path`` (one row per sample; this
        sample is row ``row``).

        Readings along the path are computed for its remaining rows at once (up to the end
        of the noise block), as long as ``key`` (which identifies the path) stays the same
        and the calls are consecutive. The returned array must not be modified (copy it).
        """
        hit = self.next_on_ramp(key, supply_pa)
        if hit is not None:
            return hit
        if self._i >= self.block:
            self._refill()
        i = self._i
        self._i = i + 1
        self._same = 0
        self._static = None
        k = min(path.shape[0] - row, self.block - i)
        ramp = self._quantise(path[row : row + k] + self._noise[i : i + k])
        ramp.flags.writeable = False
        self._ramp, self._ramp_key, self._ramp_start = ramp, key, i
        self._ramp_end = i + k
        self._ramp_next = i + 1
        reading = ramp[0]
        if k >= SPAN_ROWS:
            self._ramp_lo, self._ramp_hi = _row_spans(ramp)
            self.span = (reading, self._ramp_lo[0], self._ramp_hi[0])
        else:  # too short a ramp to pay for the reductions
            self._ramp_lo, self.span = None, None
        return reading, supply_pa + self._supply_noise[i]

    def next_on_ramp(self, key: int, supply_pa: float) -> tuple[NDArray[np.float64], float] | None:
        """The next reading of the ramp computed by :meth:`sample_path` for ``key``, or None
        when that path does not cover it (then call :meth:`sample_path`, which recomputes).
        Lets the box skip computing the true pressures while a ramp lasts."""
        i = self._i
        # _ramp_end <= block, and -1 when there is no ramp
        if i != self._ramp_next or key != self._ramp_key or i >= self._ramp_end:
            return None
        self._i = self._ramp_next = i + 1
        self._same = 0
        ramp = self._ramp
        assert ramp is not None
        j = i - self._ramp_start
        row = ramp[j]
        lo = self._ramp_lo
        self.span = None if lo is None else (row, lo[j], self._ramp_hi[j])
        return row, supply_pa + self._supply_noise[i]

    def _quantise(self, x: NDArray[np.float64]) -> NDArray[np.float64]:
        # np.rint is what np.round(.., 0) computes (half to even), and maximum/minimum clip
        # like np.clip (NaN stays NaN), without those functions' Python-level wrappers
        if self._q:
            x = x * self._inv_q
            np.rint(x, out=x)
            x *= self._q
        np.maximum(x, self._lo, out=x)
        np.minimum(x, self._hi, out=x)
        return x
