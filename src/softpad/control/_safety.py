"""The verified safe state, and fault monitoring of every frame in every phase.

:func:`reach_safe_state` closes inflation, vents any channel above its limit or rising with its
inflation valve closed (stuck open), and keeps reading until every channel is valid, at or below
the maximum and not rising for ``quiet_s`` of box time; otherwise it names the channel it could
not make safe and what it tried.

:class:`FaultMonitor` is pure: fed every frame and the commanded valve states, it returns the
first fault it sees (sensor NaN, dropout or out of range, over-pressure, supply loss, a sealed
channel falling below its reference or rising steadily without a command). Its thresholds come
from the simulated box's noise and drift figures (docs/box-and-simulator.md, "Safety").
"""

from __future__ import annotations

import math
import re
from collections import deque
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from softpad.box import RATED_MAX_PRESSURE_PA, Box, ConnectionLost, PressureFrame, ValveCommand
from softpad.errors import (
    KPA_AS_PA,
    CheckedFields,
    Count,
    HardwareFault,
    NonNegative,
    Positive,
    check_range,
)

try:  # the steady-rise rates in compiled code (src/softpad/control/_fastmonitor.c; make ext)
    import softpad.control._fastmonitor as _fastmonitor
except ImportError:  # pragma: no cover - no C compiler: the NumPy reference alone
    _fastmonitor = None  # type: ignore[assignment]


@dataclass(frozen=True)
class DetectedFault:
    """A fault seen by the :class:`FaultMonitor`."""

    #: Box time of the frame that showed it, seconds.
    t_s: float
    #: 1-based channel, or None for a box-wide fault (supply).
    channel: int | None
    #: Short machine-readable cause: ``sensor_nan``, ``sensor_dropout``, ``sensor_range``,
    #: ``over_pressure``, ``supply_loss``, ``falling`` (leak or stuck-open deflation valve),
    #: ``rising`` (stuck-open inflation valve), ``no_response`` (a valve that does not act).
    cause: str
    #: One line for people.
    message: str

    def to_dict(self) -> dict[str, object]:
        """JSON-ready dict."""
        return {
            "t_s": round(self.t_s, 4),
            "channel": self.channel,
            "cause": self.cause,
            "message": self.message,
        }


class MonitoredFault(HardwareFault):
    """A :class:`HardwareFault` carrying the :class:`DetectedFault` that raised it."""

    def __init__(self, fault: DetectedFault) -> None:
        super().__init__(fault.message)
        self.fault = fault


@dataclass(frozen=True)
class FaultThresholds(CheckedFields, what="fault threshold"):
    """Thresholds of the :class:`FaultMonitor` (sources in docs/box-and-simulator.md)."""

    #: Hard maximum, pascals; a filtered reading above ``max - trip_margin_pa`` is a fault.
    max_pressure_pa: Positive = RATED_MAX_PRESSURE_PA
    #: Pascals below the maximum at which the monitor trips (50 Pa).
    trip_margin_pa: NonNegative = 50.0
    #: A reading below this is a sensor dropout (a module cannot be under vacuum), pascals.
    floor_pa: float = -500.0
    #: A reading at or above the sensor's full scale is out of range, pascals.
    sensor_max_pa: Positive = 10.0e3
    #: A filtered supply reading below this is a supply loss, pascals (half the 10 kPa supply).
    supply_min_pa: NonNegative = 5.0e3
    #: A sealed channel whose filtered reading drops this far below its reference is falling
    #: (leak, stuck-open deflation valve), pascals: 60 Pa is 5 sigma of the filtered noise
    #: plus drift (8 Pa / sqrt(10) and 3 Pa rms: 4 Pa; difference of two: 5.6 Pa) with room for
    #: the adjustment tolerance (30 Pa).
    fall_pa: Positive = 60.0
    #: A sealed channel rising faster than this over each of ``rise_windows`` consecutive
    #: windows of ``window_s`` is rising without a command, Pa/s (50 Pa/s: 5 sigma of the
    #: slope of a 10-sample mean over 0.5 s; a load step settles within one window).
    rise_pa_s: Positive = 50.0
    #: The same while an object may be placed on the pad (``loads_expected`` without the
    #: robot pressing), Pa/s: a load is a step that settles within a window; a stuck-open
    #: inflation valve fills a
    #: sealed module at 300-500 Pa/s for as long as the supply lasts (the simulated FEM
    #: module between 1.1 and 2.9 kPa), so three windows above 150 Pa/s are no load.
    rise_loaded_pa_s: Positive = 150.0
    #: Length of one rise window, seconds.
    window_s: Positive = 0.5
    #: Consecutive rising windows needed.
    rise_windows: Count = 3
    #: A sealed channel rising faster than ``rise_loaded_pa_s`` between each of
    #: ``steady_windows + 1`` consecutive levels ``steady_window_s`` apart (each the mean
    #: reading over one such window), the fastest of these rates at most ``steady_spread``
    #: times the slowest, rises steadily: a stuck-open inflation valve, whatever the phase
    #: (loads expected or not). A load (an object placed or dropped, settling, rocking) is a
    #: step that dominates one or two rates, not three even ones. Judged outside the robot's
    #: presses, over windows that may span them.
    steady_window_s: Positive = 0.25
    #: Consecutive rates of the steady-rise judgement.
    steady_windows: Count = 3
    #: The fastest of the steady rates over the slowest, at most.
    steady_spread: Positive = 1.25
    #: Running-average length of the monitored readings, samples.
    filter_length: Count = 10

    def __post_init__(self) -> None:
        super().__post_init__()
        # a maximum or a full scale under 100 Pa is kilopascals given as pascals
        for name in ("max_pressure_pa", "sensor_max_pa"):
            v = getattr(self, name)
            check_range(f"fault threshold {name}", v, 100.0, 1e6, "Pa", low_hint=KPA_AS_PA)
        if self.supply_min_pa != 0.0:  # 0: no supply sensor; under 100 Pa: kPa given as Pa
            check_range(
                "fault threshold supply_min_pa",
                self.supply_min_pa,
                100.0,
                1e6,
                "Pa",
                low_hint=KPA_AS_PA,
            )


class FaultMonitor:
    """Watch every frame for faults (pure: no I/O; fed frames and commanded valve states).

    Parameters
    ----------
    n_modules
        Channels 1..n_modules are watched.
    thresholds
        Fault thresholds.

    Notes
    -----
    A channel counts as *sealed* once its valves have been closed for a whole filter length;
    only sealed channels are judged for falling or rising. The falling check needs a reference
    (:meth:`set_reference`, the pressures saved after the adjustment): loads only ever raise a
    sealed module's pressure above it, so a drop below it means air is escaping.
    """

    def __init__(self, n_modules: int, thresholds: FaultThresholds | None = None) -> None:
        self.n = int(n_modules)
        self.th = thresholds or FaultThresholds()
        self.reference_pa: NDArray[np.float64] | None = None
        self._buf = _LastRows(self.th.filter_length, self.n)
        self._supply = _LastRows(self.th.filter_length, 1)
        self._sealed_frames = np.zeros(self.n, dtype=np.int64)
        self._valves_seen: tuple[ValveCommand, ...] | None = None
        self._sealed_now = np.zeros(self.n, dtype=bool)
        # the channels sealed for a whole filter length while that no longer changes (None:
        # counting; FaultMonitor._sealed)
        self._settled: NDArray[np.bool_] | None = None
        self._window_start: tuple[float, NDArray[np.float64]] | None = None
        self._rising = np.zeros(self.n, dtype=np.int64)
        # sealed (for a whole filter length) at the start of the current window and ever since
        self._sealed_window = np.zeros(self.n, dtype=bool)
        #: True while an object is being placed on the pad or the robot presses the pad or an
        #: object on it (wait_object, descend, close, lift): a sealed module then rises because
        #: of the load, so "rising" is judged against ``rise_loaded_pa_s`` instead.
        self.loads_expected = False
        self._steady = _SteadyRise(self.n, self.th.steady_window_s, self.th.steady_windows)
        #: True while the robot presses the pad or an object on it (descend, close, lift): the
        #: load may rise steadily for seconds, so "rising" is not judged at all (the range and
        #: over-pressure checks still are; these phases last a few seconds).
        self.robot_pressing = False

    def set_reference(self, reference_pa: Sequence[float] | NDArray[np.float64]) -> None:
        """Pressures the sealed modules must not fall below (the saved reference), pascals."""
        self.reference_pa = np.asarray(reference_pa, dtype=float)[: self.n].copy()

    def update(self, frame: PressureFrame, valves: Sequence[ValveCommand]) -> DetectedFault | None:
        """Judge one frame given the valve commands in force; the first fault found, or None."""
        p = frame.pressures_pa[: self.n]
        t = frame.t_s
        bad = self._check_raw(t, p)
        if bad is not None:
            return bad
        sealed = self._sealed(valves)
        self._buf.append(p)
        self._supply.append(float(frame.supply_pa))
        if self._buf.count < self.th.filter_length:
            return None
        length = self.th.filter_length  # np.mean's own sum and division, without its wrapper
        mean = np.add.reduce(self._buf.rows(), axis=0) / length
        supply = float(np.add.reduce(self._supply.rows()[:, 0])) / length
        th = self.th
        if not supply >= th.supply_min_pa:
            what = f"supply pressure {supply / 1e3:.2f} kPa is below {th.supply_min_pa / 1e3:g} kPa"
            return _fault(t, None, "supply_loss", what, "supply lost?")
        slopes = self._steady.update(t, p, sealed, rates=not self.robot_pressing)
        if slopes is not None:
            fault = self._check_steady(t, slopes)
            if fault is not None:
                return fault
        return self._check_trend(t, mean, sealed)

    def _sealed(self, valves: Sequence[ValveCommand]) -> NDArray[np.bool_]:
        """Count one more frame of every channel's valves closed (0 where not); the channels
        closed for a whole filter length. While the commands stay and every closed channel has
        been counted that far, the answer stays the same (the same array, never modified), and
        the counts are left as they are (they only matter as ``>= filter_length``)."""
        key = valves if isinstance(valves, tuple) else tuple(valves)
        if key != self._valves_seen:  # the commands change a few times a run
            self._valves_seen = key
            self._sealed_now = np.array([v is ValveCommand.CLOSED for v in valves[: self.n]])
            self._settled = None
        if self._settled is not None:
            return self._settled
        self._sealed_frames = np.where(self._sealed_now, self._sealed_frames + 1, 0)
        sealed = self._sealed_frames >= self.th.filter_length
        if np.array_equal(sealed, self._sealed_now):
            self._settled = sealed
        return sealed

    def _check_steady(
        self, t: float, rates: tuple[NDArray[np.float64], NDArray[np.float64]]
    ) -> DetectedFault | None:
        """A sealed channel rising steadily (``steady_*`` thresholds); ``rates``: between the
        windows' levels and within each window, Pa/s (NaN where not sealed throughout)."""
        th = self.th
        between, within = rates
        # no channel rising faster than the limit in every window: none is after the other
        # channels' fall is taken off either (_unbalanced only lowers a rate, or makes it NaN)
        fast = np.logical_and.reduce(between > th.rise_loaded_pa_s, axis=0)
        if not np.logical_or.reduce(fast):
            return None
        shown = between  # the message gives the channel's own rate (their mean, below)
        sealed = None
        if self.loads_expected:
            sealed = np.asarray(~np.isnan(between).any(axis=0), dtype=bool)
            between = _unbalanced(between, sealed)
        up = (between > th.rise_loaded_pa_s).all(axis=0)  # NaN: not sealed throughout
        if not up.any():  # the usual frame: no channel rising at all
            return None
        if sealed is not None:
            within = _unbalanced(within, sealed)
        up &= between.max(axis=0) <= th.steady_spread * between.min(axis=0)
        up &= (within > 0.5 * th.rise_loaded_pa_s).all(axis=0)
        if not up.any():
            return None
        shown = np.mean(shown, axis=0)
        k = int(np.argmax(up))
        span = th.steady_window_s * (th.steady_windows + 1)
        what = (
            f"rising {shown[k]:.0f} Pa/s with its inflation valve closed, steadily for {span:g} s"
        )
        return _fault(t, k, "rising", what, "inflation valve stuck open?")

    def _check_raw(self, t: float, p: NDArray[np.float64]) -> DetectedFault | None:
        th = self.th
        lo, hi = np.minimum.reduce(p), np.maximum.reduce(p)  # p.min(), p.max() unwrapped
        if th.floor_pa <= lo and hi <= th.max_pressure_pa - th.trip_margin_pa:
            return None  # NaN fails both comparisons, so the usual case is one pass
        for k in range(self.n):
            v = p[k]
            if not math.isfinite(v):
                return _fault(t, k, "sensor_nan", "pressure sensor gives no valid reading (NaN)")
            if v < th.floor_pa:
                what = f"pressure sensor reads {v / 1e3:.2f} kPa"
                return _fault(t, k, "sensor_dropout", what, "sensor dropout?")
            if v >= th.sensor_max_pa:
                what = f"pressure sensor at its full scale ({v / 1e3:.2f} kPa)"
                return _fault(t, k, "sensor_range", what)
            if v > th.max_pressure_pa - th.trip_margin_pa:
                what = (
                    f"pressure {v / 1e3:.3f} kPa tripped the safety limit "
                    f"{(th.max_pressure_pa - th.trip_margin_pa) / 1e3:.3f} kPa "
                    f"(maximum {th.max_pressure_pa / 1e3:.2f} kPa)"
                )
                return _fault(t, k, "over_pressure", what, "valve stuck open?")
        return None

    def _check_trend(
        self, t: float, mean: NDArray[np.float64], sealed: NDArray[np.bool_]
    ) -> DetectedFault | None:
        th = self.th
        ref = self.reference_pa
        if ref is not None:
            low = sealed & (mean < ref - th.fall_pa)
            if np.logical_or.reduce(low):  # low.any() without its wrapper (every frame)
                k = int(np.argmax(low))
                what = (
                    f"{mean[k] / 1e3:.3f} kPa with its valves closed, "
                    f"{(ref[k] - mean[k]):.0f} Pa below its reference"
                )
                return _fault(t, k, "falling", what, "leak or deflation valve stuck open?")
        self._sealed_window &= sealed
        if self._window_start is None or not np.logical_or.reduce(sealed) or self.robot_pressing:
            self._window_start = (t, mean.copy())
            self._sealed_window = sealed.copy()
            self._rising[:] = 0
            return None
        t0, m0 = self._window_start
        if t - t0 < th.window_s:
            return None
        slope = (mean - m0) / (t - t0)
        limit = th.rise_loaded_pa_s if self.loads_expected else th.rise_pa_s
        rise = _unbalanced(slope, self._sealed_window) if self.loads_expected else slope
        judged = self._sealed_window & (rise > limit)
        self._rising = np.where(judged, self._rising + 1, 0)
        self._window_start = (t, mean.copy())
        self._sealed_window = sealed.copy()
        up = self._rising >= th.rise_windows
        if up.any():
            k = int(np.argmax(up))
            what = f"rising {slope[k]:.0f} Pa/s with its inflation valve closed"
            return _fault(t, k, "rising", what, "inflation valve stuck open?")
        return None


def _unbalanced(slope: NDArray[np.float64], sealed: NDArray[np.bool_]) -> NDArray[np.float64]:
    """Each channel's rise, Pa/s (channels along the last axis, one window a row), less the net
    fall of the other sealed channels over the same window (while loads are expected): a load
    moving across the pad (an object rolling or sliding onto a module) raises one module as the
    modules it leaves fall, while gas from a stuck inflation valve raises one module without
    any other falling."""
    clean = np.where(np.isnan(slope), 0.0, slope)  # np.nan_to_num's values, less its cost
    if np.isinf(clean).any():
        clean = np.nan_to_num(slope)
    moved = np.where(sealed, clean, 0.0)
    return slope + np.minimum(moved.sum(axis=-1, keepdims=True) - moved, 0.0)


class _SteadyRise:
    """Rises of the channels sealed throughout the last ``count + 1`` windows of ``window_s``
    (pure bookkeeping of :class:`FaultMonitor`), from the mean raw reading of every half
    window: the rates between consecutive windows' levels, and within each window (its
    second half's level over its first's). A window's level averages a rocking object's
    4 Hz swing out instead of aliasing it into a trend; a load step, however large or slow to
    settle, raises the level of at most two windows, and leaves the windows without it flat
    inside."""

    def __init__(self, n: int, window_s: float, count: int) -> None:
        self.window_s = window_s
        self.count = count
        self._t = np.empty(64)  # frame times, oldest at _lo, the newest at _hi - 1
        self._sum = np.empty((64, n))  # running sums of the readings at those times
        self._lo = self._hi = 0
        self._total = np.zeros(n)
        self._sealed_from = np.full(n, np.inf)
        self._from_min = np.inf  # the earliest of _sealed_from
        self._sealed_seen: NDArray[np.bool_] | None = None  # the last frame's sealed channels
        self._t_seen = -np.inf  # and its time
        # the half-window edges back from the newest frame, seconds
        self._offsets = 0.5 * window_s * np.arange(2 * count + 3)
        #: The compiled rates (:func:`softpad.control._fastmonitor.rates`; None: not built,
        #: or too many windows for it: the NumPy reference).
        self._kernel = _fastmonitor.rates if _fastmonitor is not None and count < 30 else None

    def _append(self, t: float) -> None:
        if self._hi == len(self._t):  # full: move what is kept to the front, or grow
            keep = self._hi - self._lo
            if keep > len(self._t) // 2:
                self._t = np.concatenate([self._t, np.empty(len(self._t))])
                self._sum = np.concatenate([self._sum, np.empty_like(self._sum)])
            self._t[:keep] = self._t[self._lo : self._hi]
            self._sum[:keep] = self._sum[self._lo : self._hi]
            self._lo, self._hi = 0, keep
        self._t[self._hi] = t
        self._sum[self._hi] = self._total
        self._hi += 1

    def update(
        self, t: float, p: NDArray[np.float64], sealed: NDArray[np.bool_], rates: bool = True
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]] | None:
        """One frame's raw readings; the rates between windows (``count`` x n) and within
        them (``count + 1`` x n), newest first, Pa/s (NaN where a channel was not sealed
        throughout), or None before the whole span is in, when no channel was sealed
        throughout, or when ``rates`` is False (the frame only kept)."""
        if sealed is not self._sealed_seen or not t >= self._t_seen:
            # (the same array as the last frame's, never modified, and time going on: each
            # channel sealed since no later than that frame, the others not at all, as before)
            self._sealed_from = np.where(sealed, np.minimum(self._sealed_from, t), np.inf)
            self._sealed_seen, self._from_min = sealed, np.minimum.reduce(self._sealed_from)
        self._t_seen = t
        if self._hi == self._lo:
            self._append(t - 1e-9)
        self._total = self._total + p
        self._append(t)
        span = self.window_s * (self.count + 1)
        times = self._t
        while self._hi - self._lo > 1 and times[self._lo + 1] <= t - span:
            self._lo += 1
        if not rates or t - times[self._lo] < span:
            return None
        # ufunc reductions: the values of .min() and .all(), without their Python wrappers
        if self._from_min > t - span:
            return None  # no channel sealed throughout (see ``old`` below)
        kernel = self._kernel
        if kernel is not None:  # the rates below in one compiled call (the same bits)
            n = self._total.shape[0]
            between, within = np.empty((self.count, n)), np.empty((self.count + 1, n))
            done = kernel(
                times, self._sum, self._lo, self._hi, t, self._offsets, self._sealed_from,
                self.window_s, between, within,
            )  # fmt: skip
            if done >= 0:
                return (between, within) if done else None
        return self._rates(t)

    def _rates(self, t: float) -> tuple[NDArray[np.float64], NDArray[np.float64]] | None:
        """The rates of :meth:`update` at ``t`` (the reference of the compiled kernel)."""
        times = self._t
        half = 0.5 * self.window_s
        kept = times[self._lo : self._hi]
        edges = np.searchsorted(kept, t - self._offsets, side="right") - 1
        old = self._sealed_from > kept[edges[-1]]
        if np.logical_and.reduce(old):
            return None  # no channel sealed throughout: every rate would be NaN
        counts = (edges[:-1] - edges[1:]).astype(float)  # samples in each half window
        if np.minimum.reduce(counts) < 1.0:
            return None
        sums = self._sum[self._lo + edges]
        halves = (sums[:-1] - sums[1:]) / counts[:, None]
        levels = 0.5 * (halves[0::2] + halves[1::2])
        between = (levels[:-1] - levels[1:]) / self.window_s
        within = (halves[0::2] - halves[1::2]) / half
        if np.logical_or.reduce(old):
            between[:, old] = np.nan
            within[:, old] = np.nan
        return between, within


class _LastRows:
    """The last ``length`` rows appended, oldest first, as one contiguous array (each row
    written twice into a buffer of twice the length, so no copy is made to read them)."""

    def __init__(self, length: int, n: int) -> None:
        self._buf = np.zeros((2 * length, n))
        self._length = length
        self._next = 0
        #: Rows appended so far, at most ``length``.
        self.count = 0

    def append(self, row: NDArray[np.float64] | float) -> None:
        i = self._next
        self._buf[i] = row
        self._buf[i + self._length] = row
        self._next = (i + 1) % self._length
        self.count = min(self.count + 1, self._length)

    def rows(self) -> NDArray[np.float64]:
        """The rows appended, oldest first (a view: read it before the next append)."""
        start = self._next if self.count == self._length else 0
        return self._buf[start : start + self.count]


def _fault(t: float, k: int | None, kind: str, what: str, guess: str = "") -> DetectedFault:
    """The fault ``kind`` of channel index ``k`` (None: the supply) at ``t``, with the message
    ``"channel K: WHAT at t = T s (GUESS)"``."""
    where = "" if k is None else f"channel {k + 1}: "
    cause = f" ({guess})" if guess else ""
    channel = None if k is None else k + 1
    return DetectedFault(t, channel, kind, f"{where}{what} at t = {t:.2f} s{cause}")


#: A module cannot be under vacuum: a reading below this is a failed sensor, pascals.
_FLOOR_PA = FaultThresholds().floor_pa


@dataclass(frozen=True)
class SafeStateResult:
    """Outcome of :func:`reach_safe_state`."""

    #: True when every channel read valid, at or below the maximum and not rising for the
    #: quiet time, with every inflation valve commanded closed.
    verified: bool
    #: Last filtered pressure of every module, pascals (NaN where the sensor gave none).
    pressures_pa: NDArray[np.float64]
    #: The channel that could not be made safe (None when verified, or when the box could
    #: not be reached: see ``reason``).
    channel_unsafe: int | None
    #: What was done, in order (one line each).
    tried: tuple[str, ...]
    #: Box time when the watch ended, seconds.
    t_s: float
    #: Why it is not verified ("" when verified).
    reason: str = ""

    def to_dict(self) -> dict[str, object]:
        """JSON-ready dict (SI units; None where a sensor gave no valid reading)."""
        return {
            "verified": self.verified,
            "pressures_pa": [
                None if not math.isfinite(v) else round(float(v), 1) for v in self.pressures_pa
            ],
            "channel_unsafe": self.channel_unsafe,
            "tried": list(self.tried),
            "t_s": round(self.t_s, 4),
            "reason": self.reason,
        }


def reach_safe_state(
    box: Box,
    n_modules: int,
    max_pressure_pa: float = RATED_MAX_PRESSURE_PA,
    *,
    vent: Sequence[int] = (),
    quiet_s: float = 2.0,
    timeout_s: float = 30.0,
    rise_pa_s: float = 50.0,
    on_frame: Callable[[PressureFrame], None] | None = None,
) -> SafeStateResult:
    """Bring the box to a verified safe state: inflation closed, nothing over the maximum or rising.

    Closes every inflation valve (channels in ``vent``, and any the box has tripped, are vented
    instead), then reads frames: a channel reading above ``max_pressure_pa`` minus 50 Pa or
    rising faster than ``rise_pa_s`` over 0.5 s with its inflation valve closed (stuck open) is
    vented. Returns verified once every module reads valid, at or below the maximum and has not
    risen more than ``rise_pa_s * 0.5 s`` over the last ``quiet_s``; after ``timeout_s`` of box
    time without that, returns unverified naming the worst channel.
    """
    tried: list[str] = []
    last = np.full(n_modules, np.nan)
    t = 0.0
    if box.closed:
        return SafeStateResult(False, last, None, (), t, "the box is closed")
    try:
        venting = _close_inflation(box, n_modules, vent, tried)
        window: deque[tuple[float, NDArray[np.float64]]] = deque()
        filt: deque[NDArray[np.float64]] = deque(maxlen=10)
        t_start: float | None = None
        while True:
            frame = box.read()
            if on_frame is not None:
                on_frame(frame)
            t = frame.t_s
            t_start = t if t_start is None else t_start
            p = frame.pressures_pa[:n_modules].astype(float)
            filt.append(p)
            last = np.mean(filt, axis=0)
            window.append((t, last))
            while window and t - window[0][0] > quiet_s:
                window.popleft()
            new = _channels_to_vent(box, last, window, venting, max_pressure_pa, rise_pa_s)
            for k, why in new:
                box.set_valve(k + 1, ValveCommand.DEFLATE)
                venting[k] = True
                tried.append(f"vented channel {k + 1} ({why}) at t = {t:.2f} s")
            ok, worst, reason = _judge(last, window, len(filt), max_pressure_pa, rise_pa_s, quiet_s)
            if ok and t - t_start >= quiet_s:
                tried.append(f"verified at t = {t:.2f} s")
                return SafeStateResult(True, last, None, tuple(tried), t)
            if t - t_start >= timeout_s:
                return SafeStateResult(False, last, worst, tuple(tried), t, reason)
    except ConnectionLost as exc:
        return SafeStateResult(False, last, None, tuple(tried), t, f"box unreachable: {exc}")
    except HardwareFault as exc:  # a refused command or a back-end fault while venting
        return SafeStateResult(False, last, None, tuple(tried), t, str(exc))


def _close_inflation(
    box: Box, n_modules: int, vent: Sequence[int], tried: list[str]
) -> NDArray[np.bool_]:
    venting = np.zeros(n_modules, dtype=bool)
    for ch in range(1, box.channels + 1):
        if ch <= n_modules and (ch in vent or box.safety.tripped[ch - 1]):
            box.set_valve(ch, ValveCommand.DEFLATE)
            venting[ch - 1] = True
        else:
            box.set_valve(ch, ValveCommand.CLOSED)
    tried.append("closed every inflation valve")
    if venting.any():
        chans = ", ".join(str(int(k) + 1) for k in np.flatnonzero(venting))
        tried.append(f"vented channel {chans} (suspect or tripped)")
    return venting


def _channels_to_vent(
    box: Box,
    p: NDArray[np.float64],
    window: deque[tuple[float, NDArray[np.float64]]],
    venting: NDArray[np.bool_],
    max_pressure_pa: float,
    rise_pa_s: float,
) -> list[tuple[int, str]]:
    out = []
    t1, p1 = window[-1]
    # rise over the last half second (the window's part that is at least that old)
    older = [(t0, p0) for t0, p0 in window if t1 - t0 >= 0.5]
    slope = (p1 - older[-1][1]) / (t1 - older[-1][0]) if older else np.zeros_like(p1)
    for k in np.flatnonzero(~venting):
        if not math.isfinite(p[k]) or p[k] < _FLOOR_PA:
            out.append((int(k), "no valid reading"))
        elif p[k] > max_pressure_pa - 50.0:
            out.append((int(k), f"{p[k] / 1e3:.3f} kPa, over the limit"))
        elif slope[k] > rise_pa_s:
            out.append((int(k), f"rising {slope[k]:.0f} Pa/s with inflation closed"))
        elif box.safety.tripped[k]:
            out.append((int(k), "tripped by the box"))
    return out


def _judge(
    p: NDArray[np.float64],
    window: deque[tuple[float, NDArray[np.float64]]],
    n_filtered: int,
    max_pressure_pa: float,
    rise_pa_s: float,
    quiet_s: float,
) -> tuple[bool, int | None, str]:
    invalid = ~np.isfinite(p) | (np.nan_to_num(p) < _FLOOR_PA)
    if invalid.any():
        k = int(np.argmax(invalid))
        return False, k + 1, f"channel {k + 1}: no valid reading, its pressure cannot be verified"
    over = p > max_pressure_pa
    if over.any():
        k = int(np.argmax(p))
        return False, k + 1, f"channel {k + 1}: {p[k] / 1e3:.3f} kPa is above the maximum"
    rise = p - np.min([w for _, w in window], axis=0)
    tol = rise_pa_s * 0.5
    if (rise > tol).any() or n_filtered < 10:
        k = int(np.argmax(rise))
        return False, k + 1, f"channel {k + 1}: still rising ({rise[k]:.0f} Pa in {quiet_s:g} s)"
    return True, None, ""


_CHANNEL = re.compile(r"channel (\d+)")


def describe_fault(exc: HardwareFault, t_s: float) -> DetectedFault:
    """The :class:`DetectedFault` behind ``exc`` (parsed from its message when not monitored)."""
    if isinstance(exc, MonitoredFault):
        return exc.fault
    m = _CHANNEL.search(str(exc))
    cause = type(exc).__name__
    if isinstance(exc, ConnectionLost):
        cause = "link_lost"
    elif "could not reach" in str(exc):
        cause = "adjust_failed"
    elif "leak" in str(exc):
        cause = "falling"
    elif "supply" in str(exc):
        cause = "supply_loss"
    elif str(exc).startswith("robot"):
        cause = "robot"
    return DetectedFault(t_s, int(m.group(1)) if m else None, cause, str(exc))


class RunSafety:
    """Safety of one run of the loop: the fault monitor of every frame and the safe state.

    Parameters
    ----------
    box
        The run's box.
    n_modules
        Modules on the pad (channels 1..n).
    max_pressure_pa, trip_margin_pa
        The run's maximum and trip margin (from the inflation parameters), pascals.
    """

    def __init__(
        self, box: Box, n_modules: int, max_pressure_pa: float, trip_margin_pa: float
    ) -> None:
        self.box = box
        self.n = n_modules
        self.max_pressure_pa = max_pressure_pa
        self.monitor = FaultMonitor(
            n_modules,
            FaultThresholds(
                max_pressure_pa=max_pressure_pa,
                trip_margin_pa=trip_margin_pa,
                # a box without a supply sensor reports 0 Pa: no supply-loss judgement
                supply_min_pa=FaultThresholds.supply_min_pa if box.supply_sensor else 0.0,
            ),
        )
        self.faults: list[DetectedFault] = []
        self.safe_state: SafeStateResult | None = None
        #: Box time of the last frame watched, seconds.
        self.last_t = 0.0

    def watch(self, frame: PressureFrame) -> NDArray[np.float64]:
        """Judge one frame; return the module pressures or raise :class:`MonitoredFault`."""
        self.last_t = frame.t_s
        fault = self.monitor.update(frame, self.box.valves)
        if fault is not None:
            raise MonitoredFault(fault)
        return frame.pressures_pa[: self.n]

    def check_valves(self, read: Callable[[], NDArray[np.float64]], verify_s: float = 2.0) -> None:
        """Run :func:`check_valves` through ``read``; the falling check is suspended during the
        pulses and its reference moved to the pressures they leave. Then every channel is
        watched sealed for ``verify_s`` (2 s: a fault that starts during the pulses shows
        within the 2 s the campaign allows): falling 60 Pa below the new reference (leak,
        stuck deflation valve: the monitor) or rising as far above it (stuck inflation valve)
        is a fault; a valve that stuck during the check is not missed."""
        self.monitor.reference_pa = None
        check_valves(self.box, self.n, read, clock=lambda: self.last_t)
        th = self.monitor.th
        rows = [read() for _ in range(th.filter_length)]
        reference = np.mean(rows, axis=0)
        self.monitor.set_reference(reference)
        filt: deque[NDArray[np.float64]] = deque(rows, maxlen=th.filter_length)
        t_end = self.last_t + verify_s
        while self.last_t < t_end:
            filt.append(read())
            rise = np.mean(filt, axis=0) - reference
            up = rise > th.fall_pa
            if up.any():
                k = int(np.argmax(up))
                what = f"rising {rise[k]:.0f} Pa above its reference after the valve check"
                raise MonitoredFault(
                    _fault(self.last_t, k, "rising", what, "inflation valve stuck open?")
                )

    def fail(
        self, exc: HardwareFault, t_s: float, on_frame: Callable[[PressureFrame], None]
    ) -> DetectedFault:
        """Record the fault behind ``exc``, reach the verified safe state, attach both to ``exc``."""
        fault = describe_fault(exc, t_s)
        self.faults.append(fault)
        suspect = [fault.channel] if fault.channel is not None else []
        self.safe_state = reach_safe_state(
            self.box, self.n, self.max_pressure_pa, vent=suspect, on_frame=on_frame
        )
        exc.faults = tuple(self.faults)  # type: ignore[attr-defined]
        exc.safe_state = self.safe_state  # type: ignore[attr-defined]
        return fault


def check_valves(
    box: Box,
    n_modules: int,
    read: Callable[[], NDArray[np.float64]],
    pulse_s: float = 0.5,
    min_change_pa: float = 40.0,
    clock: Callable[[], float] = lambda: math.nan,
) -> None:
    """Pulse every module's deflation then inflation valve and check the pressure answers.

    Deflates every module for ``pulse_s``, then inflates for ``pulse_s``, then closes; a module
    whose filtered pressure does not fall (then rise) by ``min_change_pa`` has a valve that does
    not open (stuck closed, or no supply) and raises :class:`MonitoredFault`. A load moving on
    the pad during a pulse can hide a working valve's answer (a can rolling off a module as the
    check inflated it took 200 Pa off its 220 Pa rise), so a module that did not answer is
    pulsed once more at once, alone, with the same valve; only a valve that fails twice is a
    fault, named ``pulse_s`` after its first failure. ``read`` reads one frame (the caller's,
    so that every frame passes its monitor) and returns the module pressures; ``clock`` gives
    the box time of the last frame (for the fault's time stamp).
    """
    for cmd, sign, what in (
        (ValveCommand.DEFLATE, -1.0, "deflation"),
        (ValveCommand.INFLATE, 1.0, "inflation"),
    ):
        channels = list(range(1, n_modules + 1))
        for _ in range(2):
            change = _pulse(box, channels, cmd, read, pulse_s)
            dead = sign * change < min_change_pa
            channels, change = [c for c, d in zip(channels, dead, strict=True) if d], change[dead]
            if not channels:
                break
        else:
            raise MonitoredFault(
                DetectedFault(
                    clock(),
                    channels[0],
                    "no_response",
                    f"channel {channels[0]}: {what} valve does not act (pressure changed "
                    f"{change[0]:+.0f} Pa in a {pulse_s:g} s pulse, twice; stuck closed?)",
                )
            )


def _pulse(
    box: Box,
    channels: list[int],
    cmd: ValveCommand,
    read: Callable[[], NDArray[np.float64]],
    pulse_s: float,
) -> NDArray[np.float64]:
    """Open ``cmd``'s valve of ``channels`` for ``pulse_s`` and close it: the change of each
    one's pressure (5-frame means before and after), Pa."""
    idx = np.asarray(channels) - 1
    before = np.mean([read() for _ in range(5)], axis=0)[idx]
    for ch in channels:
        box.set_valve(ch, cmd)
    for _ in range(max(1, round(pulse_s * box.sample_rate_hz) - 5)):
        read()
    for ch in channels:
        box.set_valve(ch, ValveCommand.CLOSED)
    after = np.mean([read() for _ in range(5)], axis=0)[idx]
    return np.asarray(after - before, dtype=float)
