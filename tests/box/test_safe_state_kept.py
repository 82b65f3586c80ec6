"""A safe state nothing undoes (issue 35, items 7 and 9).

A channel the safe state vented may have a stuck inflation valve: closing the box, releasing
control or a lost link must leave it venting, never seal it again (before: 9 of 13 runs
re-sealed and reached 6.2-6.5 kPa; through the daemon the guard cycled 2.2-2.96 kPa). The
simulated ``disconnect`` refuses valve commands and its physics and own guard go on.
"""

from __future__ import annotations

import time

import pytest

from softpad.box import Box, ConnectionLost, SimBox, ValveCommand, open_box, simulator_of
from softpad.box._daemon import BoxDaemon
from softpad.box._sim import Fault
from softpad.control import reach_safe_state

#: The module's rated maximum, Pa, and the campaign's stated margin of the true pressure over
#: it (sensor offset and noise plus one frame of the fastest rise), Pa.
MAX_PA, MARGIN_PA = 3000.0, 100.0


def _stuck_box(rate_hz: float = 100.0) -> Box:
    box = open_box(f"sim://?rate_hz={rate_hz:g}&inflated_kpa=1.1&seed=3&faults=stuck:2:inflate")
    assert simulator_of(box) is not None
    return box


def test_closing_the_box_keeps_a_vented_stuck_channel_venting() -> None:
    box = _stuck_box()
    res = reach_safe_state(box, 6, vent=[2])
    assert res.verified, res
    assert box.valves[1] is ValveCommand.DEFLATE
    box.close()
    assert box.valves[1] is ValveCommand.DEFLATE  # not sealed again
    peak = 0.0
    for _ in range(3000):  # 30 s of the box's physics after the close
        box._read()
        peak = max(peak, float(box.true_pressures_pa.max()))
    assert peak <= MAX_PA, peak


def test_close_inflation_closes_only_inflation() -> None:
    with SimBox() as box:
        box.set_valves(["inflate", "deflate", "closed"] + ["inflate"] * 5)
        box.close_inflation()
        assert box.valves[:3] == (ValveCommand.CLOSED, ValveCommand.DEFLATE, ValveCommand.CLOSED)
        assert set(box.valves[3:]) == {ValveCommand.CLOSED}


def _daemon_loop(daemon: BoxDaemon, seconds: float) -> tuple[float, list[ValveCommand]]:
    """The daemon's sampling and safety step, run in-process: (peak true Pa, the changes of
    channel 2's valves)."""
    box = daemon.box
    assert simulator_of(box) is not None
    peak, changes = 0.0, [box.valves[1]]
    for _ in range(round(seconds * box.sample_rate_hz)):
        frame = box.read()
        daemon._safety(frame, time.monotonic())
        peak = max(peak, float(box.true_pressures_pa.max()))
        if box.valves[1] is not changes[-1]:
            changes.append(box.valves[1])
    return peak, changes


def test_daemon_release_keeps_a_vented_channel_venting() -> None:
    daemon = BoxDaemon(_stuck_box())
    daemon.box.set_valve(2, "deflate")  # the client's safe state vented channel 2
    daemon._safe_state("hold")  # what a release (or a watchdog trip) does
    peak, changes = _daemon_loop(daemon, 30.0)
    assert changes == [ValveCommand.DEFLATE], changes  # never re-sealed
    assert peak <= MAX_PA


def test_daemon_guard_leaves_a_channel_it_vented_venting() -> None:
    daemon = BoxDaemon(_stuck_box())  # no client: the stuck valve fills channel 2
    peak, changes = _daemon_loop(daemon, 30.0)
    # vented once (by the box's guard or the daemon's), never sealed again: no cycling
    assert changes == [ValveCommand.CLOSED, ValveCommand.DEFLATE], changes
    assert peak <= MAX_PA + MARGIN_PA


@pytest.mark.parametrize("rate_hz", [100.0, 1000.0], ids=["100Hz", "1kHz"])
def test_disconnect_refuses_commands_and_the_physics_goes_on(rate_hz: float) -> None:
    box = _stuck_box(rate_hz)
    box.inject_fault(Fault("disconnect", None, 0.5))
    with pytest.raises(ConnectionLost):
        for _ in range(round(rate_hz)):
            box.read()
    before = box.true_pressures_pa[1]
    valves = box.valves
    with pytest.raises(ConnectionLost):
        box.set_valve(2, "deflate")
    assert box.valves == valves and not box._def[1]  # the command did not get through
    peak = 0.0
    for _ in range(round(20.0 * rate_hz)):  # reads fail, the box's clock and physics go on
        with pytest.raises(ConnectionLost):
            box.read()
        peak = max(peak, float(box.true_pressures_pa.max()))
    assert box.true_pressures_pa[1] != before
    # the box's own guard vented the stuck channel at its trip level
    assert box._def[1] and peak <= MAX_PA + MARGIN_PA
