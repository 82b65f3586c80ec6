"""The end-of-run valve check (softpad.control.check_valves) on a box whose pressures follow
the valves exactly: a working valve answers even when a load leaves its module mid-pulse, a
dead one is named."""

from __future__ import annotations

import numpy as np
import pytest

from softpad.box import ValveCommand
from softpad.control import MonitoredFault, check_valves

#: Pressure rate of a module while its valve is open, Pa/s (a 0.5 s pulse: 200 Pa, 150 Pa).
INFLATE_PA_S, DEFLATE_PA_S = 400.0, -300.0


class _Box:
    """Six modules at 1.1 kPa, 100 frames/s; ``dead`` (channel, command) valves do nothing;
    ``unload`` {frame: (channel, Pa)} takes a load off a module at that frame."""

    sample_rate_hz = 100.0

    def __init__(self, dead=(), unload=None) -> None:  # type: ignore[no-untyped-def]
        self.p = np.full(6, 1100.0)
        self.valves = [ValveCommand.CLOSED] * 6
        self.dead, self.unload = set(dead), dict(unload or {})
        self.frame = 0
        self.commands: list[tuple[int, ValveCommand]] = []

    def set_valve(self, ch: int, cmd: ValveCommand) -> None:
        self.valves[ch - 1] = cmd
        if cmd is not ValveCommand.CLOSED:
            self.commands.append((ch, cmd))

    def read(self) -> np.ndarray:
        self.frame += 1
        for k, cmd in enumerate(self.valves):
            rate = {ValveCommand.INFLATE: INFLATE_PA_S, ValveCommand.DEFLATE: DEFLATE_PA_S}
            if (k + 1, cmd) not in self.dead:
                self.p[k] += rate.get(cmd, 0.0) / self.sample_rate_hz
        if self.frame in self.unload:
            ch, pa = self.unload[self.frame]
            self.p[ch - 1] -= pa
        return self.p.copy()


def _pulses(box: _Box, cmd: ValveCommand) -> dict[int, int]:
    return {ch: sum(1 for c, k in box.commands if c == ch and k is cmd) for ch in range(1, 7)}


def test_every_valve_answering_is_pulsed_once() -> None:
    box = _Box()
    check_valves(box, 6, box.read)  # type: ignore[arg-type]
    assert set(_pulses(box, ValveCommand.DEFLATE).values()) == {1}
    assert set(_pulses(box, ValveCommand.INFLATE).values()) == {1}


def test_a_load_leaving_a_module_mid_pulse_is_not_a_dead_valve() -> None:
    """A can rolling off module 1 during the inflation pulse takes 300 Pa off its 200 Pa rise:
    the module is pulsed again, alone, answers, and no fault is raised (the check before
    retried nothing and named channel 1's inflation valve)."""
    box = _Box(unload={80: (1, 300.0)})  # frames 61-110 inflate
    check_valves(box, 6, box.read)  # type: ignore[arg-type]
    assert _pulses(box, ValveCommand.INFLATE) == {1: 2, 2: 1, 3: 1, 4: 1, 5: 1, 6: 1}


@pytest.mark.parametrize(
    ("channel", "cmd", "what"),
    [(4, ValveCommand.INFLATE, "inflation"), (2, ValveCommand.DEFLATE, "deflation")],
)
def test_a_dead_valve_fails_twice_and_is_named(channel, cmd, what) -> None:
    box = _Box(dead={(channel, cmd)})
    with pytest.raises(MonitoredFault) as err:
        check_valves(box, 6, box.read, clock=lambda: box.frame / box.sample_rate_hz)  # type: ignore[arg-type]
    fault = err.value.fault
    assert (fault.channel, fault.cause) == (channel, "no_response")
    assert f"channel {channel}: {what} valve does not act" in str(err.value)
    assert "twice" in str(err.value)
    assert _pulses(box, cmd)[channel] == 2
    assert sum(_pulses(box, cmd).values()) == 7  # the others once
    # named one pulse after its first failure: 2 pulses (+ 1 before for the inflation valve)
    pulses = 2 if cmd is ValveCommand.DEFLATE else 3
    assert fault.t_s == pytest.approx(pulses * 0.55, abs=0.02)
