"""The daemon's fixed-rate schedule, period ring and GC control (softpad.box._schedule),
on a fake clock: what is counted, not how fast this machine is."""

from __future__ import annotations

import gc
import sys

import numpy as np
import pytest

from softpad.box import _schedule
from softpad.box._schedule import GcPauses, PeriodRing, TickSchedule, set_realtime_priority
from softpad.errors import InputError


class _Clock:
    """time.monotonic and time.sleep on a fake clock (sleep advances it)."""

    def __init__(self) -> None:
        self.t = 100.0
        self.slept: list[float] = []
        #: Added once to the next sleep: the machine stalled the sleeping thread this long.
        self.stall = 0.0

    def monotonic(self) -> float:
        return self.t

    def sleep(self, s: float) -> None:
        self.slept.append(s)
        self.t += s + self.stall
        self.stall = 0.0


@pytest.fixture
def clock(monkeypatch: pytest.MonkeyPatch) -> _Clock:
    c = _Clock()
    monkeypatch.setattr(_schedule.time, "monotonic", c.monotonic)
    monkeypatch.setattr(_schedule.time, "sleep", c.sleep)
    return c


def test_deadlines_are_absolute_and_late_ticks_are_dropped(clock: _Clock) -> None:
    s = TickSchedule(1000.0)
    t0 = clock.t
    assert s.wait() == 0 and clock.t == pytest.approx(t0 + 1e-3)
    clock.t += 0.4e-3  # the tick's work took 0.4 ms: the next wait is 0.6 ms, not 1 ms
    assert s.wait() == 0 and clock.t == pytest.approx(t0 + 2e-3)
    clock.t += 0.5e-3 + 1e-3  # late by half a period for tick 3: sampled late, not dropped
    assert s.wait() == 0 and clock.t == pytest.approx(t0 + 3.5e-3)
    assert s.wait() == 0 and clock.t == pytest.approx(t0 + 4e-3)  # back on the grid
    clock.t += 3.7e-3  # ticks 5..7 more than a period late: 2 dropped, tick 7 sampled late
    assert s.wait() == 2 and clock.t == pytest.approx(t0 + 7.7e-3)
    assert s.wait() == 0 and clock.t == pytest.approx(t0 + 8e-3)  # the grid never shifted


def test_a_tick_sampled_after_its_period_is_dropped(clock: _Clock) -> None:
    """A dropped tick is one whose sample was not taken within its period [t_k, t_k + 1 ms):
    a thread that wakes 9.05 ms late samples tick 2 at 11.05 ms, so ticks 2..10 (nine) are
    dropped, not only the eight the next wait skips."""
    s = TickSchedule(1000.0)
    t0 = clock.t
    assert s.wait() == 0 and s.due_s == pytest.approx(t0 + 1e-3)
    assert s.late(clock.t + 0.99e-3) == 0  # stamped 0.99 ms after its deadline: in its period
    assert s.late(clock.t + 1.0e-3) == 1  # its period is over: dropped though sampled
    clock.stall = 9.05e-3  # the next sleep wakes 9.05 ms after its deadline
    assert s.wait() == 0 and clock.t == pytest.approx(t0 + 11.05e-3)
    dropped = s.late(clock.t)
    assert dropped == 1  # tick 2, sampled 9.05 ms late
    dropped += s.wait()  # ticks 3..10 skipped; tick 11 (due 11 ms) sampled at 11.05 ms
    assert dropped == 9 and s.due_s == pytest.approx(t0 + 11e-3)
    assert s.late(clock.t) == 0
    assert s.wait() == 0 and clock.t == pytest.approx(t0 + 12e-3)  # on the grid again


def test_restart_starts_the_grid_at_now(clock: _Clock) -> None:
    s = TickSchedule(100.0)
    s.wait()
    clock.t += 5.0  # a pause that is not the schedule's fault (a lock-stepped simulator)
    s.restart()
    assert s.wait() == 0 and clock.slept[-1] == pytest.approx(0.01)


def test_the_ring_reports_percentiles_of_the_periods_it_kept() -> None:
    ring = PeriodRing(1e-3, size=1000)
    assert ring.summary()["period_p99_s"] is None
    t = 0.0
    for k in range(3000):  # the ring keeps the last 1000: periods of 1 ms and every 100th 3 ms
        t += 3e-3 if k % 100 == 0 else 1e-3
        ring.add(t)
    s = ring.summary()
    assert s["period_p50_s"] == pytest.approx(1e-3)
    assert s["period_max_s"] == pytest.approx(3e-3)
    assert s["period_error_max_s"] == pytest.approx(2e-3)
    assert s["period_p99_s"] == pytest.approx(np.percentile([1e-3] * 990 + [3e-3] * 10, 99))
    ring.restart()  # the next sample starts a new period: nothing spans the pause
    ring.add(t + 10.0)
    assert ring.summary()["period_max_s"] == pytest.approx(3e-3)


def test_gc_is_collected_between_ticks_and_restored() -> None:
    enabled, switch = gc.isenabled(), sys.getswitchinterval()
    pauses = GcPauses()
    pauses.start()
    try:
        assert not gc.isenabled() and gc.get_freeze_count() > 0
        junk = [[] for _ in range(_schedule.GC_YOUNG_BATCH + 10)]  # young containers
        pauses.collect_if_due()
        assert pauses.count >= 1 and pauses.max_s > 0 and pauses.max_generation >= 0
        del junk
        d = pauses.to_dict()
        assert d["gc_collections"] == pauses.count and d["gc_pause_max_s"] >= 0
    finally:
        pauses.stop()
    assert gc.isenabled() == enabled and gc.get_freeze_count() == 0
    assert sys.getswitchinterval() == switch


@pytest.mark.parametrize("priority", [0, 100, -1, True, 1.5])
def test_real_time_priority_out_of_range_is_refused(priority) -> None:
    with pytest.raises(InputError, match="1 to 99"):
        set_realtime_priority(priority)


def test_the_served_simulator_draws_its_noise_between_ticks() -> None:
    """The daemon's between-ticks hook reaches the simulator through its layers; with it
    called after every read (as the sampling loop does), no read draws a noise block (about
    1.5 ms every 4096 frames, more than a tick's budget) and the frames are bitwise those
    of a box read without it."""
    from softpad.box import open_box, simulator_of
    from softpad.box._daemon import _between_ticks

    url = "sim://?rate_hz=1000&seed=3"
    plain, hooked = open_box(url), open_box(url)
    hook = _between_ticks(hooked)
    assert hook is not None and type(hooked) is not type(simulator_of(hooked))  # layered
    sensors = simulator_of(hooked).sensors  # type: ignore[union-attr]
    in_read = [0]
    draw = sensors._refill

    def counted() -> None:
        in_read[0] += 1
        draw()

    sensors._refill = counted  # type: ignore[method-assign]
    for box in (plain, hooked):  # blocks of 64 frames, not 4096: the same logic, quicker
        bank = simulator_of(box).sensors  # type: ignore[union-attr]
        bank.block = bank._i = 64
    n = 5 * 64 + 10
    a, b = [], []
    for k in range(n):
        for box in (plain, hooked):  # idle, inflating, sealed: the sensors' three paths
            if k in (100, 200):
                box.set_valve(1, "inflate" if k == 100 else "closed")
        a.append(plain.read())
        b.append(hooked.read())
        sensors._refill = draw  # type: ignore[method-assign]  # the hook's draws not counted
        hook()
        sensors._refill = counted  # type: ignore[method-assign]
    assert in_read[0] == 1  # only the first block, drawn before any hook call could
    for fa, fb in zip(a, b, strict=True):
        assert fa.t_s == fb.t_s and fa.supply_pa == fb.supply_pa
        np.testing.assert_array_equal(fa.pressures_pa, fb.pressures_pa)
    plain.close()
    hooked.close()


def test_the_link_bench_floor_counts_every_tick_of_its_window() -> None:
    """The bench's bare loop (the machine's floor beside the daemon) runs the schedule for its
    time limit and accounts for every tick of the window: sampled plus dropped is the number
    of periods elapsed; the bench turns its output into a figure beside the daemon's."""
    import json
    import os
    import subprocess

    from softpad.benchmarks._link import _FLOOR, _schedule_results

    env = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
    out = subprocess.run(
        [sys.executable, "-c", _FLOOR, "0.3", "0"],
        capture_output=True,
        text=True,
        timeout=120,
        env=env,
        check=True,
    )
    floor = json.loads(out.stdout)
    assert 299 <= floor["ticks"] <= 300 + 1000 * floor["late_max_s"] + 2
    assert 0 <= floor["dropped"] < floor["ticks"] and floor["late_max_s"] >= 0
    stats = {"frames": 1000, "dropped_samples": 2, "achieved_rate_hz": 998.0, "floor": floor}
    figures = {r.name.split(",")[0]: r for r in _schedule_results(stats, load=1.0)}
    assert figures["this machine's floor: a bare 1 kHz loop beside the daemon (same window and "
                   "priority"].value == floor["dropped"]  # fmt: skip
