"""Initial inflation and adjustment of every module (seed, Section 6.2.1.1), and the safe state.

Every module is brought to the same pressure p0 within t_adj, then the reference pressures are
saved as the mean of 10 reads. The controller is a per-channel bang-bang with hysteresis: a channel
starts correcting when the running average of 10 readings is off by more than t_adj, and stops
when a 3-sample average crosses p0 (one sample of lag, so the overshoot stays well below t_adj
even where the module is stiff and fills fast). The maximum pressure is never exceeded on purpose: any channel above it is vented.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from softpad import thesis
from softpad.box import Box, PressureFrame, ValveCommand
from softpad.errors import CheckedFields, HardwareFault, InputError, Positive

if TYPE_CHECKING:
    from softpad.control._safety import SafeStateResult
from softpad.sensing import RunningAverage, capture_reference

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
    #: slower leak is caught by the fault monitor, 60 Pa under the reference).
    max_drift_pa_s: Positive = 50.0
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


def inflate_and_adjust(
    box: Box,
    n_modules: int,
    params: InflationParams | None = None,
    on_frame: FrameHook | None = None,
    on_adjusted: Callable[[float], None] | None = None,
    safe_state: bool = True,
) -> AdjustmentResult:
    """Bring modules 1..n_modules to p0 within t_adj and save the reference (Section 6.2.1.1).

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
        When a channel cannot reach p0 in ``timeout_s`` (leak, supply too low, stuck valve),
        exceeds the maximum, leaks, or its sensor fails; the message names the channel. The box
        is put in the safe state first.
    """
    params = params or InflationParams()
    if not 1 <= n_modules <= box.channels:
        raise InputError(f"a box with {box.channels} channels cannot drive {n_modules} modules")
    target, tol = params.target_pa, params.tolerance_pa
    filt = RunningAverage(params.filter_length)
    fast = RunningAverage(3)  # short filter for stopping: 1 sample of lag, small overshoot
    state = np.zeros(n_modules, dtype=np.int8)  # 0 closed, 1 inflating, -1 deflating
    since = np.zeros(n_modules, dtype=np.int64)  # frames since each channel's last change
    starts = np.zeros(n_modules, dtype=np.int64)  # corrections started per channel
    settled_since: float | None = None
    settle_start_p: NDArray[np.float64] | None = None
    t0: float | None = None

    def apply(k: int, s: int) -> None:
        if state[k] != s:
            cmd = (
                ValveCommand.INFLATE
                if s > 0
                else ValveCommand.DEFLATE
                if s < 0
                else ValveCommand.CLOSED
            )
            box.set_valve(k + 1, cmd)
            state[k] = s
            since[k] = 0

    try:
        while True:
            frame = box.read()
            if on_frame is not None:
                on_frame(frame)
            t0 = frame.t_s if t0 is None else t0
            p_raw = check_frame(
                frame, n_modules, params.max_pressure_pa, trip_margin_pa=params.trip_margin_pa
            )
            p = filt.update(p_raw)
            p_fast = fast.update(p_raw)
            since += 1
            if not filt.full:
                continue
            err = p - target
            err_fast = p_fast - target
            # start only once the long filter holds no sample from before the last change;
            # stop when the short filter crosses p0 (decided for all channels at once)
            start = (state == 0) & (since > params.filter_length) & (np.abs(err) > tol)
            stop = ((state == 1) & (err_fast >= 0)) | ((state == -1) & (err_fast <= 0))
            if start.any() or stop.any():
                for ks in np.flatnonzero(stop):
                    apply(int(ks), 0)
                for kb in np.flatnonzero(start):
                    apply(int(kb), 1 if err[kb] < 0 else -1)
                    starts[kb] += 1
            inflating = state == 1
            if inflating.any() and frame.t_s - t0 > 1.0 and frame.supply_pa < target + 2 * tol:
                k = int(np.argmax(inflating))
                raise HardwareFault(
                    f"channel {k + 1}: supply pressure {frame.supply_pa / 1e3:.2f} kPa is too low to "
                    f"inflate to {target / 1e3:.2f} kPa (supply lost?)"
                )
            # judge sealed channels only once the filter holds no sample from before a change
            if (
                not state.any()
                and since.min() > params.filter_length
                and (np.abs(err) <= tol).all()
            ):
                if settled_since is None:
                    settled_since, settle_start_p = frame.t_s, p.copy()
                elif frame.t_s - settled_since >= params.settle_s:
                    assert settle_start_p is not None
                    rate = (p - settle_start_p) / (frame.t_s - settled_since)
                    leaking = rate < -params.max_drift_pa_s
                    if leaking.any():
                        k = int(np.argmax(leaking))
                        raise HardwareFault(
                            f"channel {k + 1}: loses {-rate[k] / 1e3:.3f} kPa/s with its valves closed (leak)"
                        )
                    break
            else:
                settled_since = None
            if frame.t_s - t0 > params.timeout_s:
                # the culprit: off tolerance, else still correcting, else corrected most often
                off = np.flatnonzero(np.abs(err) > tol)
                if off.size == 0:
                    off = np.flatnonzero(state)
                if off.size == 0:
                    off = np.flatnonzero(starts == starts.max())
                which = ", ".join(str(int(c) + 1) for c in off)
                raise HardwareFault(
                    f"channel {which}: could not reach {target / 1e3:.2f} +/- {tol / 1e3:.2f} kPa within "
                    f"{params.timeout_s:g} s (now {', '.join(f'{v / 1e3:.2f}' for v in p)} kPa; leak, low "
                    "supply or stuck valve?)"
                )
        adjusted_at = frame.t_s
        box.close_valves()
        if on_adjusted is not None:
            on_adjusted(adjusted_at)
        reads = []
        for _ in range(params.reference_reads):
            frame = box.read()
            if on_frame is not None:
                on_frame(frame)
            reads.append(
                check_frame(
                    frame, n_modules, params.max_pressure_pa, trip_margin_pa=params.trip_margin_pa
                )
            )
        return AdjustmentResult(capture_reference(reads), adjusted_at, frame.t_s)
    except HardwareFault as exc:
        if safe_state and not hasattr(exc, "safe_state"):
            exc.safe_state = make_safe(  # type: ignore[attr-defined]
                box, n_modules, params.max_pressure_pa, on_frame=on_frame
            )
        raise
