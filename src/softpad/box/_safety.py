"""Box-side safety: a hard maximum pressure per channel, enforced under every back-end.

Every :class:`~softpad.box.Box` owns a :class:`SafetyGuard` (the base class calls it on every
frame read and every valve command), so the simulated box, a box served over ``zenoh://`` and the
box daemon on real hardware all run the same checks, whatever the client does:

* a channel whose reading, plus the rise expected before the next frame, exceeds the trip level
  ``max_pressure_pa - trip_margin_pa`` is *tripped*: its deflation valve is opened (inflation
  closed) at once;
* a channel whose reading is invalid (NaN, or outside the sensor's range: a broken wire reads
  its rail) is tripped too: the box cannot know its pressure, so it vents;
* while tripped, an ``inflate`` command on the channel raises :class:`SafetyTrip` (a
  :class:`~softpad.errors.HardwareFault`) and ``closed``/``deflate`` commands leave it venting;
  the trip is released once a valid reading is below ``release_pa``; the channel then keeps
  venting until the client commands it otherwise.
"""

from __future__ import annotations

import math
from collections import deque
from dataclasses import dataclass, field
from itertools import compress

import numpy as np
from numpy.typing import NDArray

from softpad import thesis
from softpad.errors import KPA_AS_PA, HardwareFault, InputError, check_range

#: The module's rated maximum pressure, Pa (seed, Section 6.3: modules are usable 0.5..2.8 kPa;
#: the thesis's box never takes them above 3 kPa).
RATED_MAX_PRESSURE_PA = thesis.MAX_PRESSURE_PA


class SafetyTrip(HardwareFault):
    """A command the box refuses because a channel is tripped (over-pressure or bad sensor)."""


@dataclass(frozen=True)
class SafetyLimits:
    """Limits the box enforces on every channel, whatever the client commands.

    Parameters
    ----------
    max_pressure_pa
        Hard maximum gauge pressure of a module, pascals (3 kPa, the module's rating).
    trip_margin_pa
        The trip acts on a reading this far below the maximum, pascals (50 Pa: about six
        standard deviations of the simulated sensor's 8 Pa white noise).
    release_pa
        A tripped channel is released once a valid reading is below this, pascals (2.5 kPa).
    sensor_min_pa, sensor_max_pa
        Range of the pressure sensor, pascals (-2..10 kPa); a reading at or beyond a rail is
        invalid (a broken wire reads its lower rail).
    rise_window
        Frames over which the guard estimates each channel's rise rate; the reading plus the
        rise expected over one sample period is compared with the trip level.
    """

    max_pressure_pa: float = RATED_MAX_PRESSURE_PA
    trip_margin_pa: float = 50.0
    release_pa: float = 2500.0
    sensor_min_pa: float = -2000.0
    sensor_max_pa: float = 10000.0
    rise_window: int = 10

    def __post_init__(self) -> None:
        for n in ("max_pressure_pa", "trip_margin_pa", "release_pa", "sensor_min_pa"):
            v = getattr(self, n)
            if not (isinstance(v, int | float) and math.isfinite(v)):
                raise InputError(f"safety {n} must be a finite number, got {v!r}")
        if not (isinstance(self.sensor_max_pa, int | float) and math.isfinite(self.sensor_max_pa)):
            raise InputError(f"safety sensor_max_pa must be finite, got {self.sensor_max_pa!r}")
        if not 0 < self.max_pressure_pa < self.sensor_max_pa:
            raise InputError(
                f"maximum pressure {self.max_pressure_pa / 1e3:g} kPa must be > 0 and below the "
                f"sensor's full scale {self.sensor_max_pa / 1e3:g} kPa"
            )
        if not 0 <= self.trip_margin_pa < self.max_pressure_pa:
            raise InputError(
                f"trip margin must be in [0, {self.max_pressure_pa:g}) Pa, got {self.trip_margin_pa!r}"
            )
        if not 0 < self.release_pa < self.trip_pa:
            raise InputError(
                f"release pressure {self.release_pa / 1e3:g} kPa must be > 0 and below the trip "
                f"level {self.trip_pa / 1e3:g} kPa"
            )
        for name in ("max_pressure_pa", "release_pa"):  # under 100 Pa: kPa given as Pa
            check_range(f"safety {name}", getattr(self, name), 100.0, 1e6, "Pa", low_hint=KPA_AS_PA)
        if not self.sensor_min_pa < 0:
            raise InputError(f"sensor lower rail must be < 0 Pa, got {self.sensor_min_pa!r}")
        if not (isinstance(self.rise_window, int) and self.rise_window >= 2):
            raise InputError(f"rise window must be an integer >= 2, got {self.rise_window!r}")

    @property
    def trip_pa(self) -> float:
        """Reading (plus expected rise) at which a channel is tripped, pascals."""
        return self.max_pressure_pa - self.trip_margin_pa


def _cause(v: float, rise: float, invalid: bool, lim: SafetyLimits) -> str:
    """Why a channel reading ``v`` (rising ``rise`` a frame) trips, for the trip history."""
    if invalid:
        return f"reading {v / 1e3:.3f} kPa is not valid"
    if v > lim.trip_pa:
        return f"{v / 1e3:.3f} kPa over the trip level {lim.trip_pa / 1e3:.3f} kPa"
    return (
        f"{v / 1e3:.3f} kPa rising {rise / 1e3:.3f} kPa a frame: the trip level "
        f"{lim.trip_pa / 1e3:.3f} kPa within a frame"
    )


@dataclass
class SafetyGuard:
    """State of the box-side safety of ``channels`` channels (pure: no I/O).

    :meth:`check` takes every frame's readings and returns the channels that must be vented
    now; :meth:`allows_inflate` tells whether an inflate command may pass. ``trips`` keeps
    (t_s, channel, cause) of every trip for diagnostics.
    """

    channels: int
    limits: SafetyLimits = field(default_factory=SafetyLimits)
    tripped: NDArray[np.bool_] = field(init=False)
    trips: list[tuple[float, int, str]] = field(init=False, default_factory=list)
    _history: deque[list[float] | NDArray[np.float64]] = field(init=False)
    _times: deque[float] = field(init=False)
    _lows: deque[float] = field(init=False)
    _any_tripped: bool = field(init=False, default=False)
    _trip_pa: float = field(init=False, default=0.0)
    _release_pa: float = field(init=False, default=0.0)
    _min_pa: float = field(init=False, default=0.0)
    _max_pa: float = field(init=False, default=0.0)
    _free: list[bool] = field(init=False)
    _held: list[bool] = field(init=False)

    def __post_init__(self) -> None:
        self.tripped = np.zeros(self.channels, dtype=bool)
        window = self.limits.rise_window
        self._history, self._times, self._lows = (deque(maxlen=window) for _ in range(3))
        lim = self.limits  # its levels read on every frame: plain attributes, not properties
        self._trip_pa, self._release_pa = lim.trip_pa, lim.release_pa
        self._min_pa, self._max_pa = lim.sensor_min_pa, lim.sensor_max_pa
        self._free, self._held = [True] * self.channels, [False] * self.channels
        self._any_tripped = False  # in the instance's dict (the compiled frame reads it there)

    def check(self, t_s: float, pressures_pa: NDArray[np.float64]) -> list[int]:
        """Update with one frame; return the 1-based channels newly tripped (to vent now)."""
        times = self._times
        if times and t_s == times[-1]:
            return []  # the same frame seen again (a wrapper sharing this guard)
        values = np.asarray(pressures_pa, dtype=float).tolist()
        if len(values) != self.channels:
            values = values[: self.channels]
        ordered = sorted(values)  # lowest and highest at once (cheaper than min and max)
        finite = math.isfinite(sum(values))
        return self._update(t_s, values, values, ordered[0], ordered[-1], finite)

    def check_span(
        self, t_s: float, row: NDArray[np.float64], low: float, high: float
    ) -> list[int]:
        """:meth:`check` of a frame whose readings ``row`` (one per channel, never modified
        afterwards) have the lowest and highest value ``low`` and ``high`` (NaN when a reading
        is NaN), computed by the caller: the same decisions, without sorting the readings (the
        simulated box knows them for a whole block of frames at once)."""
        times = self._times
        if times and t_s == times[-1]:
            return []
        if self._any_tripped or not (low > self._min_pa and high < self._max_pa):
            finite = math.isfinite(low) and math.isfinite(high)
            return self._update(t_s, row, None, low, high, finite)
        # _update's hot path, inline (the simulated box's every frame): every reading within
        # the sensor's range (so finite: the rails are) and no channel tripped
        self._history.append(row)
        lows = self._lows
        lows.append(low)
        times.append(t_s)
        rise = (high - lows[0]) / (len(times) - 1) if t_s > times[0] else 0.0
        if not rise <= 0.0:  # a NaN rise (a NaN low in the window) fails the test below
            high += rise
        if high <= self._trip_pa:
            return []
        return self._check_arrays(t_s, row.tolist(), self.limits)

    def _update(
        self,
        t_s: float,
        row: NDArray[np.float64] | list[float],
        values: list[float] | None,
        low: float,
        top: float,
        finite: bool,
    ) -> list[int]:
        """Add a frame to the window and decide (``values``: ``row`` as floats, None: not yet
        converted; ``finite``: every reading finite)."""
        self._history.append(row)  # the deques drop their oldest beyond rise_window
        # a frame with a NaN has no order: its low is NaN, which fails the rise bound below
        # (the exact test decides) while it is the window's oldest
        lows, times = self._lows, self._times
        lows.append(low if finite else math.nan)
        times.append(t_s)
        # The hot path (every frame of every box): every reading finite and within the
        # sensor's range, no tripped channel below the release level, and even the highest
        # reading of an untripped channel plus a bound on the largest rise of the window,
        # (highest now - lowest then) / (frames - 1), below the trip level: nothing trips or
        # is released. Plain floats: on 8 values several times faster than NumPy calls.
        # Otherwise the exact per-channel test decides.
        if self._any_tripped:
            if values is None:
                values = list(row) if isinstance(row, list) else row.tolist()
            if min(compress(values, self._held)) < self._release_pa:
                return self._check_arrays(t_s, values, self.limits)
            high = max(compress(values, self._free), default=-math.inf)
        else:
            high = top
        if finite and low > self._min_pa and top < self._max_pa:
            # one frame in the window: t_s is its oldest time too, no rise
            rise = (high - lows[0]) / (len(times) - 1) if t_s > times[0] else 0.0
            if not rise <= 0.0:  # a NaN rise (a NaN low in the window) fails the test below
                high += rise
            if high <= self._trip_pa:
                return []
        if values is None:
            values = list(row) if isinstance(row, list) else row.tolist()
        return self._check_arrays(t_s, values, self.limits)

    def _check_arrays(self, t_s: float, values: list[float], lim: SafetyLimits) -> list[int]:
        """The full per-channel test: trips, releases, invalid readings (plain floats: a loop
        over a few channels is several times faster than NumPy calls; the tripped states
        read as a list, written back only where one changes)."""
        first, n = self._history[0], len(self._history)
        if not isinstance(first, list):  # a row given to check_span
            first = first.tolist()
        span = self._times[-1] - self._times[0]
        per_frame = 1.0 / (n - 1) if n >= 2 and span > 0 else 0.0
        tripped, held, new = self.tripped, self.tripped.tolist(), []
        low, top, trip_pa, release_pa = self._min_pa, self._max_pa, self._trip_pa, self._release_pa
        for k, v in enumerate(values):
            invalid = not math.isfinite(v) or v <= low or v >= top
            rise = (v - first[k]) * per_frame  # the window's mean rise per frame
            rise = rise if math.isfinite(rise) and rise > 0.0 else 0.0  # NaN: invalid, not rising
            if held[k] and v < release_pa and not invalid:
                tripped[k] = held[k] = False  # released (a NaN reading is never below)
            if (invalid or v + rise > trip_pa) and not held[k]:
                tripped[k] = held[k] = True
                new.append(k + 1)
                self.trips.append((t_s, k + 1, _cause(v, rise, invalid, lim)))
        if held != self._held:
            self._any_tripped = True in held
            self._held = held
            self._free = [not x for x in held]
        return new

    def allows_inflate(self, channel: int) -> bool:
        """Whether an inflate command on ``channel`` (1-based) may pass."""
        return not bool(self.tripped[channel - 1])

    def refuse_inflate(self, channel: int) -> SafetyTrip:
        """The error raised for a refused inflate command on ``channel``."""
        cause = next((c for _, ch, c in reversed(self.trips) if ch == channel), "tripped")
        return SafetyTrip(
            f"channel {channel}: inflate refused by the box's safety limit (maximum "
            f"{self.limits.max_pressure_pa / 1e3:g} kPa): {cause}; venting until below "
            f"{self.limits.release_pa / 1e3:g} kPa"
        )
