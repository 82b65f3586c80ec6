"""Initial inflation and adjustment of every module (thesis, Section 6.2.1.1), and the safe state.

Every module is brought to the same pressure p0 within t_adj, then the reference pressures are
saved as the mean of 10 reads. The controller is a per-channel bang-bang with hysteresis: a channel
starts correcting when the running average of 10 readings is off by more than t_adj, and stops
when a 3-sample average crosses p0 (one sample of lag, so the overshoot stays well below t_adj
even where the module is stiff and fills fast). The maximum pressure is never exceeded on purpose: any channel above it is vented.
"""

from __future__ import annotations

import math
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from softpad import thesis
from softpad.box import Box, PressureFrame, ValveCommand
from softpad.control._safety import DetectedFault, MonitoredFault
from softpad.errors import MS_AS_S, CheckedFields, HardwareFault, InputError, Positive, check_range
from softpad.sensing import RunningAverage, capture_reference

if TYPE_CHECKING:
    from softpad.control._safety import SafeStateResult

#: p0 of the thesis, Pa (:data:`softpad.thesis.P0_PA`).
DEFAULT_TARGET_PA = thesis.P0_PA
#: t_adj of the thesis, Pa (Section 6.3).
DEFAULT_TOLERANCE_PA = thesis.ADJUST_TOLERANCE_PA
#: Maximum pressure the software ever lets a module reach, Pa (modules are unusable above 2.8 kPa).
DEFAULT_MAX_PRESSURE_PA = thesis.MAX_PRESSURE_PA
#: Full scale of the box's pressure sensors, Pa: no limit can be checked above it.
SENSOR_FULL_SCALE_PA = 10.0e3

FrameHook = Callable[[PressureFrame], None]


@dataclass(frozen=True)
class InflationParams(CheckedFields, what="inflation"):
    """Parameters of the initial inflation and adjustment (Section 6.2.1.1)."""

    #: p0: pressure every module is brought to, pascals.
    target_pa: Positive = DEFAULT_TARGET_PA
    #: t_adj: allowed deviation from p0, pascals.
    tolerance_pa: Positive = DEFAULT_TOLERANCE_PA
    #: Safety limit; a channel above it is vented and the run fails, pascals (3.0 kPa).
    max_pressure_pa: Positive = DEFAULT_MAX_PRESSURE_PA
    #: Time allowed to reach p0 on every channel, seconds.
    timeout_s: Positive = 30.0
    #: Time every channel must stay within t_adj with its valves closed, seconds.
    settle_s: Positive = 0.5
    #: Reads averaged into the reference (10 in the thesis).
    reference_reads: int = thesis.REFERENCE_READS
    #: Running-average length used by the controller, samples.
    filter_length: int = thesis.FILTER_WINDOW
    #: A sealed channel losing pressure faster than this during the settle time leaks, Pa/s
    #: (50 Pa/s: 6 standard deviations of the rate measured over the 0.5 s settle time from two
    #: 10-sample means of the box sensor's 8 Pa noise, 7.2 Pa/s; 8.1 Pa/s over 200 simulated
    #: adjustments. At 25 Pa/s one adjustment in a hundred named a sound channel as leaking; a
    #: slower leak is caught by the fault monitor, 60 Pa under the reference). Judged times
    #: the measured noise's scale (:class:`SampleNoise`), like the other sealed-drift checks.
    max_drift_pa_s: Positive = 50.0
    #: Inflation needs the supply above the highest pressure the controller aims at
    #: (p0 + t_adj) by at least another t_adj, pascals (2 t_adj = 60 Pa above p0; the flow
    #: through the inflation orifice grows as sqrt(dp), so 60 Pa passes under a tenth of the
    #: flow from the nominal 10 kPa supply: too little to finish within the timeout). Judged
    #: on the supply reading averaged over ``filter_length`` samples (its 20 Pa noise).
    supply_margin_pa: Positive = 2 * DEFAULT_TOLERANCE_PA
    #: A channel inflating (deflating) for this long whose filtered pressure has not risen
    #: (fallen) by ``min_response_pa`` does not respond: stuck valve or leak, seconds (0.75 s:
    #: the slowest nominal inflation, an empty module of the FEM characteristic from the
    #: 10 kPa supply, gains 66 Pa in it, 88 Pa/s; near p0 it gains about 350 Pa). A sealed
    #: channel moving by ``min_response_pa`` within one such window is judged at once.
    response_s: Positive = 0.75
    #: The smallest change a working valve makes in ``response_s``, pascals (40 Pa, the valve
    #: check's ``min_change_pa``: 7 sigma of the difference of two 10-sample means of the
    #: sensor's 8 Pa noise and 3 Pa drift, 5.6 Pa).
    min_response_pa: Positive = 40.0
    #: An inflating channel filling at less than this fraction of the rate the other channels
    #: showed at the same pressure (their own inflations, :class:`FillRates`) leaks or has a
    #: stuck-open deflation valve (0.7: a stuck deflation valve leaves 0.73 of the fill at
    #: 200 Pa, 0.53 at 600 Pa, the outflow growing as sqrt(p); sound channels filling from
    #: ambient, 10 seeds at 100 Hz and 1 kHz with the nominal and a twice as noisy sensor,
    #: fill at 0.77 of their neighbours at the least), judged over ``fill_window_s`` once the
    #: rate is also ``fill_sigmas`` standard deviations of its noise below theirs.
    fill_ratio: Positive = 0.7
    #: Window of the fill rate, seconds.
    fill_window_s: Positive = 0.5
    #: Fill rates are judged from this pressure up, pascals: below it a module still unfolds
    #: from its collapsed shape (and the sensors' 20-40 Pa offsets shift it), sound channels
    #: filled at 0.16-1 of each other's rates below 100 Pa (the seeds above); a stuck
    #: deflation valve leaves 0.8 of the fill there anyway.
    fill_from_pa: Positive = 250.0
    #: Margin of the slow-fill judgement over the rate's noise, standard deviations.
    fill_sigmas: Positive = 6.0
    #: The safety trip acts on a reading this far below ``max_pressure_pa``, pascals (50 Pa:
    #: about six standard deviations of the sensor noise plus a few samples of the fastest
    #: rise), so that the true pressure never exceeds the maximum before the valves react.
    trip_margin_pa: float = 50.0

    @property
    def trip_pressure_pa(self) -> float:
        """Reading at which the safety trip vents a channel, pascals (maximum - margin)."""
        return self.max_pressure_pa - self.trip_margin_pa

    def __post_init__(self) -> None:
        super().__post_init__()
        for name, top in (("timeout_s", 600.0), ("settle_s", 60.0)):
            check_range(f"inflation {name}", getattr(self, name), 0.0, top, "s", MS_AS_S)
        if not (
            math.isfinite(self.trip_margin_pa) and 0 <= self.trip_margin_pa < self.max_pressure_pa
        ):
            raise InputError(
                f"trip margin must be in [0, {self.max_pressure_pa:g}) Pa, got {self.trip_margin_pa!r}"
            )
        lo, hi = thesis.P0_RANGE_PA
        if not lo <= self.target_pa <= hi:
            raise InputError(
                f"target pressure must be within the module's usable range "
                f"{lo / 1e3:g}..{hi / 1e3:g} kPa, got {self.target_pa!r} Pa "
                f"({self.target_pa / 1e3:g} kPa; pressures are in pascals)"
            )
        if self.max_pressure_pa >= SENSOR_FULL_SCALE_PA:
            raise InputError(
                f"maximum pressure must be below the sensor's full scale "
                f"{SENSOR_FULL_SCALE_PA / 1e3:g} kPa (the module's rating is "
                f"{thesis.MAX_PRESSURE_PA / 1e3:g} kPa), got {self.max_pressure_pa / 1e3:g} kPa"
            )
        if self.target_pa + self.tolerance_pa >= self.trip_pressure_pa:
            raise InputError(
                f"target pressure {self.target_pa / 1e3:g} kPa + tolerance must stay below the maximum "
                f"{self.max_pressure_pa / 1e3:g} kPa"
            )
        if not (isinstance(self.reference_reads, int) and self.reference_reads >= 1):
            raise InputError(
                f"reference reads must be an integer >= 1, got {self.reference_reads!r}"
            )


@dataclass(frozen=True)
class AdjustmentResult:
    """Outcome of :func:`inflate_and_adjust`."""

    #: Saved reference pressure of every module (mean of the reference reads), pascals.
    reference_pa: NDArray[np.float64]
    #: Box time when every module was within tolerance, seconds.
    adjusted_at_s: float
    #: Box time when the reference was saved, seconds.
    reference_at_s: float
    #: The reads the reference averages (one row a read, one column a module), pascals: the
    #: empty pad's noise as the box shows it (None where not kept).
    reference_reads_pa: NDArray[np.float64] | None = None

    def to_dict(self) -> dict[str, object]:
        """JSON-ready dict (SI units)."""
        return {
            "reference_pa": [round(float(v), 2) for v in self.reference_pa],
            "adjusted_at_s": round(self.adjusted_at_s, 4),
            "reference_at_s": round(self.reference_at_s, 4),
        }


def check_frame(
    frame: PressureFrame,
    n_modules: int,
    max_pressure_pa: float,
    floor_pa: float = -500.0,
    trip_margin_pa: float = 0.0,
) -> NDArray[np.float64]:
    """Module pressures of a frame, or HardwareFault naming a bad channel.

    A NaN reading is a sensor fault; a reading below ``floor_pa`` (a module cannot be
    under vacuum) is a sensor dropout; a reading above ``max_pressure_pa - trip_margin_pa``
    is an over-pressure (the trip acts before the maximum itself is reached).
    """
    trip = max_pressure_pa - trip_margin_pa
    p = frame.pressures_pa[:n_modules]
    lo, hi = p.min(), p.max()  # NaN propagates: one pass decides the usual, healthy case
    if floor_pa <= lo and hi <= trip:
        return p
    bad = ~np.isfinite(p)
    if bad.any():
        ch = int(np.argmax(bad)) + 1
        raise HardwareFault(
            f"channel {ch}: pressure sensor gives no valid reading (NaN) at t = {frame.t_s:.2f} s"
        )
    low = p < floor_pa
    if low.any():
        ch = int(np.argmax(low)) + 1
        raise HardwareFault(
            f"channel {ch}: pressure sensor reads {p[ch - 1] / 1e3:.2f} kPa at t = {frame.t_s:.2f} s "
            "(sensor dropout?)"
        )
    high = p > trip
    if high.any():
        ch = int(np.argmax(high)) + 1
        raise HardwareFault(
            f"channel {ch}: pressure {p[ch - 1] / 1e3:.3f} kPa tripped the safety limit "
            f"{trip / 1e3:.3f} kPa (maximum {max_pressure_pa / 1e3:.2f} kPa) at "
            f"t = {frame.t_s:.2f} s (valve stuck open?)"
        )
    return p


def make_safe(
    box: Box,
    n_modules: int,
    max_pressure_pa: float,
    timeout_s: float = 30.0,
    on_frame: FrameHook | None = None,
    trip_margin_pa: float = 0.0,
) -> SafeStateResult:
    """Put the box in its verified safe state (see :func:`softpad.control.reach_safe_state`).

    Kept for callers of the earlier API; ``trip_margin_pa`` is unused (the safe state vents a
    channel 50 Pa below the maximum).
    """
    from softpad.control._safety import reach_safe_state

    return reach_safe_state(box, n_modules, max_pressure_pa, timeout_s=timeout_s, on_frame=on_frame)


def _response_fault(valves: int, change_pa: float) -> tuple[str, str]:
    """The cause (:class:`DetectedFault` kinds) and description of a channel's wrong answer to
    its valves (1 inflating, -1 deflating, 0 sealed)."""
    if valves > 0:
        return "no_response", "does not rise while inflating (leak, stuck deflation valve?)"
    if valves < 0:
        return "no_response", "does not fall while deflating (inflation valve stuck open?)"
    if change_pa > 0:
        return "rising", "rising with its valves closed (inflation valve stuck open?)"
    return "falling", "loses pressure with its valves closed (leak or deflation valve stuck open?)"


class SampleNoise:
    """The white noise of one pressure sample as the box shows it, Pa: from the first
    differences of sealed channels' readings (robust: 1.4826 x the median absolute
    difference / sqrt 2, over the last ``size`` differences); the nominal sensor's until
    ``min_count`` are in. A real box measures its own noise this way; the controller's
    sealed-drift thresholds grow with it, so a noisier sensor is judged more slowly, not
    named faulty."""

    def __init__(
        self, nominal_pa: float = thesis.SENSOR_NOISE_STD_PA, size: int = 256, min_count: int = 32
    ) -> None:
        self.nominal_pa = nominal_pa
        self.min_count = min_count
        self._diffs: deque[float] = deque(maxlen=size)
        self._last: NDArray[np.float64] | None = None

    def update(self, raw: NDArray[np.float64], sealed: NDArray[np.bool_]) -> None:
        """One frame's readings and which channels were sealed since the previous frame."""
        if self._last is not None and sealed.any():
            self._diffs.extend(np.abs(raw[sealed] - self._last[sealed]).tolist())
        self._last = raw.copy()

    @property
    def sigma_pa(self) -> float:
        if len(self._diffs) < self.min_count:
            return self.nominal_pa
        return 1.4826 * float(np.median(self._diffs)) / math.sqrt(2.0)

    def scale(self) -> float:
        """How many times noisier than the nominal sensor the box is (at least 1)."""
        return max(1.0, self.sigma_pa / self.nominal_pa)


class FillRates:
    """How fast each channel filled at each pressure, and the channel filling far slower now
    than the other channels did at the same pressure (a leak or a stuck-open deflation valve
    while it fills: it still rises, so no response window finds it, until it is sealed at p0).

    Only what the controller sees: the filtered readings of channels inflating for a whole
    window with a filter clean of older samples. Every such window gives its channel's rate
    and mean pressure; the rate is kept per channel in ``bin_pa`` pressure bins. A channel is
    judged against the median of the other channels' rates in its bin (at least two of them),
    so that a lagging channel is compared at its own pressure, where the fill is slower.
    """

    def __init__(
        self,
        n: int,
        window_s: float,
        from_pa: float = 0.0,
        bin_pa: float = 50.0,
        top_pa: float = 1e4,
    ) -> None:
        self.window_s = window_s
        self.from_pa = from_pa
        self.bin_pa = bin_pa
        self._rates = np.full((n, int(top_pa / bin_pa) + 1), np.nan)
        self._hist: deque[tuple[float, NDArray[np.float64]]] = deque()
        self._clean_from = np.full(n, np.inf)

    def update(
        self, t: float, filtered: NDArray[np.float64], clean: NDArray[np.bool_]
    ) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]] | None:
        """One frame: ``clean`` marks the channels inflating with a filter holding only
        samples since their command. Returns (rate, expected rate, window mean pressure) of
        every channel, Pa/s and Pa, NaN where not judged; None before a whole window."""
        self._clean_from = np.where(clean, np.minimum(self._clean_from, t), np.inf)
        self._hist.append((t, filtered.copy()))
        while len(self._hist) > 1 and t - self._hist[1][0] >= self.window_s:
            self._hist.popleft()
        t0, f0 = self._hist[0]
        if t - t0 < self.window_s:
            return None
        judged = (self._clean_from <= t0) & (filtered + f0 >= 2.0 * self.from_pa)
        rate = np.where(judged, (filtered - f0) / (t - t0), np.nan)
        mid = np.where(judged, 0.5 * (filtered + f0), np.nan)
        last = self._rates.shape[1] - 1
        bins = np.clip(np.nan_to_num(mid / self.bin_pa), 0, last).astype(np.int64)
        k = np.flatnonzero(judged)
        self._rates[k, bins[k]] = rate[k]
        expected = np.full_like(rate, np.nan)
        for i in k.tolist():
            expected[i] = _median_of_others(self._rates[:, bins[i]].tolist(), i)
        return rate, expected, mid


def _median_of_others(column: list[float], i: int) -> float:
    """The median of the finite values of ``column`` but its ``i``-th, NaN when fewer than
    two: np.median's value (the middle one, or the mean of the middle two, ``(a + b) / 2``)
    on plain floats (a few channels: a NumPy call per channel cost more than the sort)."""
    others = sorted(v for j, v in enumerate(column) if j != i and math.isfinite(v))
    n = len(others)
    if n < 2:
        return math.nan
    half = n // 2
    return others[half] if n % 2 else (others[half - 1] + others[half]) / 2


class InflationController:
    """Initial inflation and adjustment as a state machine stepped with every frame.

    ``adjust`` (a per-channel bang-bang with hysteresis towards p0) -> ``settle`` (every
    channel sealed within t_adj for ``settle_s``; a channel losing pressure leaks) ->
    ``reference`` (every valve closed; the mean of ``reference_reads`` frames is the
    reference) -> ``done``. :meth:`step` takes one frame and returns the valve commands to
    apply now (1-based channel, command); a fault raises :class:`HardwareFault` naming the
    channel. Every frame is also checked for faults whatever the state: sensor, over-pressure,
    supply, and a channel that does not answer its valves (:meth:`_check_response`).

    Parameters
    ----------
    n_modules
        Modules on the pad (channels 1..n_modules).
    params
        Inflation parameters (thesis defaults).
    """

    def __init__(self, n_modules: int, params: InflationParams | None = None) -> None:
        self.n = int(n_modules)
        self.params = params or InflationParams()
        p = self.params
        self.state = "adjust"
        self._filt = RunningAverage(p.filter_length)
        self._fast = RunningAverage(3)  # short filter for stopping: 1 sample of lag
        self._supply = RunningAverage(p.filter_length)
        self._valves = np.zeros(self.n, dtype=np.int8)  # 0 closed, 1 inflating, -1 deflating
        self._since = np.zeros(self.n, dtype=np.int64)  # frames since each channel's change
        self._since_t = np.zeros(self.n)  # box time of each channel's last change
        self._seen_after = np.full(self.n, -np.inf)  # frames up to here predate the change
        self._from = np.full(self.n, np.nan)  # filtered pressure once the change shows
        self._starts = np.zeros(self.n, dtype=np.int64)  # corrections started per channel
        self.noise = SampleNoise()
        self.fill = FillRates(self.n, p.fill_window_s, p.fill_from_pa)
        self._t0: float | None = None
        self._settled: tuple[float, NDArray[np.float64]] | None = None
        self._reads: list[NDArray[np.float64]] = []
        #: Box time when every module was within tolerance (end of ``settle``), seconds.
        self.adjusted_at_s: float | None = None
        #: The outcome once ``state`` is ``done``.
        self.result: AdjustmentResult | None = None

    def step(self, frame: PressureFrame) -> list[tuple[int, ValveCommand]]:
        """Advance with one frame; the valve commands to apply now."""
        p = self.params
        self._t0 = frame.t_s if self._t0 is None else self._t0
        raw = check_frame(frame, self.n, p.max_pressure_pa, trip_margin_pa=p.trip_margin_pa)
        if self.state == "reference":
            return self._reference(frame, raw)
        if self.state == "done":
            return []
        self.noise.update(raw, (self._valves == 0) & (self._since >= 1))
        filtered = self._filt.update(raw)
        fast = self._fast.update(raw)
        supply = float(self._supply.update(np.array([frame.supply_pa]))[0])
        self._since += frame.t_s > self._seen_after
        if not self._filt.full:
            return []
        self._check_response(frame.t_s, filtered, fast, supply)
        self._check_fill(frame.t_s, filtered)
        commands = self._bang_bang(frame.t_s, filtered, fast)
        if commands:
            self._settled = None
            self.state = "adjust"
            return commands
        return self._settle(frame.t_s, filtered)

    def _bang_bang(
        self, t: float, filtered: NDArray[np.float64], fast: NDArray[np.float64]
    ) -> list[tuple[int, ValveCommand]]:
        """Start a correction once the long filter holds no sample from before the channel's
        last change and it is off by more than t_adj; stop when the short filter crosses p0.

        A sealed channel that drifted t_adj from its baseline within ``response_s`` (over
        40 Pa/s: the settle check's leak rate is 50 Pa/s) is not corrected but named: at
        1 kHz the correction would otherwise restart before the drift reaches
        ``min_response_pa``, and a stuck valve would cycle until the timeout."""
        p = self.params
        err, err_fast, v = filtered - p.target_pa, fast - p.target_pa, self._valves
        start = (v == 0) & (self._since > p.filter_length) & (np.abs(err) > p.tolerance_pa)
        stop = ((v == 1) & (err_fast >= 0)) | ((v == -1) & (err_fast <= 0))
        out = []
        for k in np.flatnonzero(stop):
            out.append(self._set(int(k), 0))
        for k in np.flatnonzero(start):
            moved = float(fast[k] - self._from[k])  # NaN (no baseline yet) compares False
            # the noise scale (a median) only where the nominal tolerance is already exceeded
            if (
                abs(moved) >= p.tolerance_pa
                and t - self._since_t[k] < p.response_s
                and abs(moved) >= p.tolerance_pa * self.noise.scale()
            ):
                cause, what = _response_fault(0, moved)
                message = (
                    f"channel {k + 1}: {what} ({moved:+.0f} Pa in "
                    f"{t - self._since_t[k]:.2f} s) at t = {t:.2f} s"
                )
                raise MonitoredFault(DetectedFault(t, int(k) + 1, cause, message))
            out.append(self._set(int(k), 1 if err[k] < 0 else -1))
            self._starts[k] += 1
        return out

    def command_seen_after(self, channel: int, t_s: float | None) -> None:
        """The box applied the last command of ``channel`` (1-based) after its frame at box
        time ``t_s`` (:attr:`softpad.box.Box.command_seen_after_s`): frames up to then, still
        on their way, neither count towards the command's filter nor start its windows."""
        if t_s is None or not math.isfinite(t_s):
            return
        k = channel - 1
        self._seen_after[k] = t_s
        self._since_t[k] = max(self._since_t[k], t_s)

    def _set(self, k: int, state: int) -> tuple[int, ValveCommand]:
        self._valves[k] = state
        self._since[k] = 0
        self._from[k] = np.nan
        cmd = ValveCommand.INFLATE if state > 0 else ValveCommand.DEFLATE
        return k + 1, cmd if state else ValveCommand.CLOSED

    def _settle(self, t: float, filtered: NDArray[np.float64]) -> list[tuple[int, ValveCommand]]:
        """Every channel sealed, its filter clean of older samples and within t_adj for
        ``settle_s``: a channel losing more than ``max_drift_pa_s`` (times the measured noise's
        scale, :class:`SampleNoise`) leaks; else the reference."""
        p = self.params
        calm = (
            not self._valves.any()
            and self._since.min() > p.filter_length
            and bool((np.abs(filtered - p.target_pa) <= p.tolerance_pa).all())
        )
        if not calm:
            self._settled = None
            self.state = "adjust"
            self._check_timeout(t, filtered)
            return []
        if self._settled is None:
            self._settled, self.state = (t, filtered.copy()), "settle"
            return []
        t_set, p_set = self._settled
        if t - t_set < p.settle_s:
            return []
        rate = (filtered - p_set) / (t - t_set)
        limit = p.max_drift_pa_s * self.noise.scale()  # on a noisier box, by as much more
        leaking = rate < -limit
        if leaking.any():
            k = int(np.argmax(leaking))
            raise HardwareFault(
                f"channel {k + 1}: loses {-rate[k] / 1e3:.3f} kPa/s with its valves closed "
                f"(leak; limit {limit / 1e3:.3f} kPa/s)"
            )
        self.adjusted_at_s, self.state = t, "reference"
        return [(ch, ValveCommand.CLOSED) for ch in range(1, self.n + 1)]

    def _reference(
        self, frame: PressureFrame, raw: NDArray[np.float64]
    ) -> list[tuple[int, ValveCommand]]:
        self._reads.append(raw)
        if len(self._reads) >= self.params.reference_reads:
            assert self.adjusted_at_s is not None
            ref = capture_reference(self._reads)
            reads = np.array(self._reads)
            self.result = AdjustmentResult(ref, self.adjusted_at_s, frame.t_s, reads)
            self.state = "done"
        return []

    def _check_response(
        self,
        t: float,
        filtered: NDArray[np.float64],
        fast: NDArray[np.float64],
        supply: float,
    ) -> None:
        """Every channel must answer its valves, judged from a baseline taken once its filter
        holds only samples after its last command (the long filter for a moving channel, the
        3-sample one for a sealed channel, whose bang-bang may restart within a filter length):

        * at once: a sealed channel moving ``min_response_pa`` from its baseline, an inflating
          (deflating) channel falling (rising) as much: stuck valve or leak;
        * after each ``response_s`` window: an inflating (deflating) channel that has not risen
          (fallen) ``min_response_pa``; the next window starts there.

        An inflating channel needs the supply ``supply_margin_pa`` above p0."""
        p, v = self.params, self._valves
        if supply < p.target_pa + p.supply_margin_pa and (v == 1).any():
            k = int(np.argmax(v == 1))
            raise HardwareFault(
                f"channel {k + 1}: supply pressure {supply / 1e3:.2f} kPa is too low to "
                f"inflate to {p.target_pa / 1e3:.2f} kPa (supply lost?)"
            )
        sealed = v == 0
        level = np.where(sealed, fast, filtered)
        clear = np.isnan(self._from) & (self._since >= np.where(sealed, 3, p.filter_length))
        self._from[clear] = level[clear]
        self._since_t[clear] = t
        started = ~np.isnan(self._from)
        change = level - self._from
        wrong = started & np.where(
            sealed, np.abs(change) >= p.min_response_pa, change * v <= -p.min_response_pa
        )
        if wrong.any():  # on a noisier box than the nominal sensor, by as much more
            limit = p.min_response_pa * self.noise.scale()
            wrong &= np.where(sealed, np.abs(change) >= limit, change * v <= -limit)
        window = started & (t - self._since_t >= p.response_s)
        dead = window & ~sealed & (change * v < p.min_response_pa)
        bad = wrong | dead
        if bad.any():
            k = int(np.argmax(bad))
            cause, what = _response_fault(int(v[k]), float(change[k]))
            message = (
                f"channel {k + 1}: {what} ({change[k]:+.0f} Pa in "
                f"{t - self._since_t[k]:.2f} s) at t = {t:.2f} s"
            )
            raise MonitoredFault(DetectedFault(t, k + 1, cause, message))
        self._from[window] = level[window]  # the next window starts here
        self._since_t[window] = t

    def _check_fill(self, t: float, filtered: NDArray[np.float64]) -> None:
        """An inflating channel filling at under ``fill_ratio`` of the other channels' rate at
        its pressure, and ``fill_sigmas`` standard deviations of the rate's noise below it
        (the noise as measured: :class:`SampleNoise`), leaks or has a stuck deflation valve."""
        p = self.params
        clean = (self._valves == 1) & (self._since >= p.filter_length)
        got = self.fill.update(t, filtered, clean)
        if got is None:
            return
        rate, expected, mid = got
        slow = rate < p.fill_ratio * expected  # NaN (not judged) compares False
        if not slow.any():
            return
        sigma = math.sqrt(2.0 / p.filter_length) * self.noise.sigma_pa / p.fill_window_s
        slow &= expected - rate > p.fill_sigmas * sigma
        if slow.any():
            k = int(np.argmax(slow))
            message = (
                f"channel {k + 1}: fills at {rate[k]:.0f} Pa/s at {mid[k] / 1e3:.2f} kPa where "
                f"the other channels filled at {expected[k]:.0f} Pa/s at t = {t:.2f} s "
                "(leak, stuck deflation valve?)"
            )
            raise MonitoredFault(DetectedFault(t, k + 1, "no_response", message))

    def _check_timeout(self, t: float, filtered: NDArray[np.float64]) -> None:
        p = self.params
        assert self._t0 is not None
        if t - self._t0 <= p.timeout_s:
            return
        # the culprit: off tolerance, else still correcting, else corrected most often
        off = np.flatnonzero(np.abs(filtered - p.target_pa) > p.tolerance_pa)
        if off.size == 0:
            off = np.flatnonzero(self._valves)
        if off.size == 0:
            off = np.flatnonzero(self._starts == self._starts.max())
        which = ", ".join(str(int(c) + 1) for c in off)
        now = ", ".join(f"{v / 1e3:.2f}" for v in filtered)
        raise HardwareFault(
            f"channel {which}: could not reach {p.target_pa / 1e3:.2f} +/- "
            f"{p.tolerance_pa / 1e3:.2f} kPa within {p.timeout_s:g} s (now {now} kPa; leak, low "
            "supply or stuck valve?)"
        )


def inflate_and_adjust(
    box: Box,
    n_modules: int,
    params: InflationParams | None = None,
    on_frame: FrameHook | None = None,
    on_adjusted: Callable[[float], None] | None = None,
    safe_state: bool = True,
) -> AdjustmentResult:
    """Bring modules 1..n_modules to p0 within t_adj and save the reference (Section 6.2.1.1):
    an :class:`InflationController` stepped with every frame read.

    Parameters
    ----------
    box
        An open box; module k is channel k.
    n_modules
        Modules on the pad.
    params
        Inflation parameters (thesis defaults).
    on_frame
        Called with every frame read (logging hook).
    on_adjusted
        Called with the box time when every module is within tolerance, before the
        reference reads.
    safe_state
        On a fault, reach the verified safe state before raising (its result is attached to
        the exception as ``safe_state``); False leaves that to the caller.

    Raises
    ------
    HardwareFault
        When a channel cannot reach p0 in ``timeout_s``, does not answer its valves (leak,
        stuck valve, no supply), exceeds the maximum, leaks, or its sensor fails; the message
        names the channel. The box is put in the safe state first.
    """
    params = params or InflationParams()
    if not 1 <= n_modules <= box.channels:
        raise InputError(f"a box with {box.channels} channels cannot drive {n_modules} modules")
    ctl = InflationController(n_modules, params)
    try:
        while ctl.result is None:
            frame = box.read()
            if on_frame is not None:
                on_frame(frame)
            was = ctl.state
            for ch, cmd in ctl.step(frame):
                box.set_valve(ch, cmd)
                ctl.command_seen_after(ch, box.command_seen_after_s)
            if ctl.state == "reference" and was != "reference" and on_adjusted is not None:
                assert ctl.adjusted_at_s is not None
                on_adjusted(ctl.adjusted_at_s)
        return ctl.result
    except HardwareFault as exc:
        if safe_state and not hasattr(exc, "safe_state"):
            exc.safe_state = make_safe(  # type: ignore[attr-defined]
                box, n_modules, params.max_pressure_pa, on_frame=on_frame
            )
        raise
