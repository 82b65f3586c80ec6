"""The fault monitor's shortcuts (the sealed channels kept while nothing changes, the
sealed-since times kept, the steady-rise test's early exit) change no decision: the monitor
against one with every shortcut undone, frame by frame, on random runs with faults."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import pytest
from numpy.typing import NDArray

from softpad.box import PressureFrame, ValveCommand
from softpad.control import FaultMonitor
from softpad.control._safety import DetectedFault, _fault, _unbalanced

C, INF, D = ValveCommand.CLOSED, ValveCommand.INFLATE, ValveCommand.DEFLATE


class _Reference(FaultMonitor):
    """Every frame counted, every sealed-since time recomputed, and the steady-rise test
    without its early exit (the monitor's code before its shortcuts)."""

    def _sealed(self, valves: Sequence[ValveCommand]) -> NDArray[np.bool_]:
        self._settled = None
        self._steady._sealed_seen = None
        return super()._sealed(valves)

    def _check_steady(
        self, t: float, rates: tuple[NDArray[np.float64], NDArray[np.float64]]
    ) -> DetectedFault | None:
        th = self.th
        between, within = rates
        shown, sealed = between, None
        if self.loads_expected:
            sealed = np.asarray(~np.isnan(between).any(axis=0), dtype=bool)
            between = _unbalanced(between, sealed)
        up = (between > th.rise_loaded_pa_s).all(axis=0)
        if not up.any():
            return None
        if sealed is not None:
            within = _unbalanced(within, sealed)
        up &= between.max(axis=0) <= th.steady_spread * between.min(axis=0)
        up &= (within > 0.5 * th.rise_loaded_pa_s).all(axis=0)
        if not up.any():
            return None
        k = int(np.argmax(up))
        span = th.steady_window_s * (th.steady_windows + 1)
        what = f"rising {np.mean(shown, axis=0)[k]:.0f} Pa/s with its inflation valve closed, "
        what += f"steadily for {span:g} s"
        return _fault(t, k, "rising", what, "inflation valve stuck open?")


def _run(seed: int, monitor: FaultMonitor, frames: int = 2500) -> list[object]:
    """Random valve commands, phases (loads expected, the robot pressing), load steps,
    leaks, stuck valves and now and then a bad reading, 100 Hz; every frame's answer."""
    rng = np.random.default_rng(seed)
    monitor.set_reference(np.full(6, 1100.0))
    p, rate = np.full(8, 1150.0), np.zeros(8)
    valves = (C,) * 8
    out: list[object] = []
    for k in range(frames):
        if rng.random() < 0.004:  # a command: some channels open a while
            valves = tuple(rng.choice([C, C, C, INF, D], 8))
        if rng.random() < 0.003:
            monitor.loads_expected = not monitor.loads_expected
        if rng.random() < 0.003:
            monitor.robot_pressing = not monitor.robot_pressing
        if rng.random() < 0.004:  # a leak, a stuck valve (steady rise) or a load step
            ch = rng.integers(6)
            rate[ch] = rng.choice([-80.0, 0.0, 180.0, 250.0, 400.0])
            p[ch] += rng.choice([0.0, 60.0, 150.0])
        p = np.clip(p + rate * 0.01, 0.0, 2800.0)
        reading = p + rng.normal(0.0, 8.0, 8)
        if rng.random() < 0.0005:
            reading[rng.integers(6)] = rng.choice([np.nan, -900.0])
        fault = monitor.update(PressureFrame(0.01 * (k + 1), reading, 10e3), valves)
        out.append(None if fault is None else fault.to_dict())
        if fault is not None and rng.random() < 0.5:  # found: the run would vent it
            rate[:] = 0.0
    return out


@pytest.mark.parametrize("seed", range(6))
def test_the_shortcuts_change_no_decision(seed: int) -> None:
    want = _run(seed, _Reference(6))
    got = _run(seed, FaultMonitor(6))
    assert got == want
    causes = {f["cause"] for f in want if isinstance(f, dict)}
    assert "rising" in causes  # the steady and trend tests decided something
