"""The box daemon's fixed-rate schedule: absolute deadlines, period statistics, GC control.

The sampling thread of :class:`~softpad.box.BoxDaemon` reads the box, checks the limits and
runs the watchdog on ``t_k = t_0 + k / rate`` (absolute deadlines on the monotonic clock, so
a late tick never shifts the ones after it). Nothing in the schedule grows per tick: the
periods go into a preallocated ring, the figures (``softpad box stats``) are computed when
asked. The garbage collector is the one pause Python adds on its own, at any allocation of
any thread; :class:`GcPauses` freezes what exists at start-up (never scanned again), turns
the automatic collector off and lets the sampling thread collect right after a tick's work
(when the next deadline is furthest away), timing every collection, so the stats say how long
the longest one held the loop.

A tick is *dropped* when its sample was not taken within its period, ``[t_k, t_k + 1/rate)``:
either the loop reached it more than a period after its deadline (it is skipped, the schedule
stays on its grid), or its sample was stamped more than a period after the deadline (the
thread stalled between waking and sampling: the frame is kept but the tick counts as dropped,
:meth:`TickSchedule.late`). A tick sampled late by less shows as period error.
"""

from __future__ import annotations

import gc
import os
import sys
import threading
import time
from typing import Any

import numpy as np

#: Ticks of period history kept for the percentiles (a minute at 1 kHz).
RING_TICKS = 60_000
#: Young objects the sampling thread lets accumulate before it collects them (generation 0;
#: CPython collects automatically at 700).
GC_YOUNG_BATCH = 5_000
#: Python's thread switch interval while the daemon runs, seconds (default 5 ms): the most a
#: thread holding the GIL keeps the woken sampling thread waiting.
SWITCH_INTERVAL_S = 2e-4


class TickSchedule:
    """Absolute deadlines ``t0 + k * period`` on the monotonic clock.

    :meth:`wait` sleeps until the next deadline (the last ``spin_s`` of it busy-waiting, for
    sleep's wake-up latency) and returns how many ticks were dropped on the way (the loop
    was more than a period late for them); :meth:`late` tells whether the sample of the tick
    it returned for was taken after that tick's period (one more dropped tick).
    """

    def __init__(self, rate_hz: float, spin_s: float = 0.0) -> None:
        if not (rate_hz > 0 and np.isfinite(rate_hz)):
            raise ValueError(f"rate must be > 0 Hz, got {rate_hz!r}")
        self.period_s = 1.0 / float(rate_hz)
        self.spin_s = min(max(float(spin_s), 0.0), self.period_s / 2)
        self.restart()

    def restart(self) -> None:
        """Start the grid at now (after a pause that was not the schedule's fault)."""
        self._t0 = time.monotonic()
        self._k = 0
        #: Deadline of the tick :meth:`wait` last returned for, monotonic seconds.
        self.due_s = self._t0

    def wait(self) -> int:
        """Block until the next deadline; the number of ticks dropped to reach it."""
        self._k += 1
        period = self.period_s
        due = self._t0 + self._k * period
        now = time.monotonic()
        dropped = 0
        if now - due > period:
            dropped = int((now - due) / period)
            self._k += dropped
            due += dropped * period
        self.due_s = due
        wake = due - self.spin_s
        if now < wake:
            time.sleep(wake - now)
        while time.monotonic() < due:
            pass
        return dropped

    def late(self, sampled_s: float) -> int:
        """1 when a sample stamped at ``sampled_s`` (monotonic seconds) missed the period of
        the tick :meth:`wait` last returned for (the thread woke or ran more than a period
        late: that tick is dropped, though its frame exists), else 0."""
        return 1 if sampled_s - self.due_s >= self.period_s else 0


class PeriodRing:
    """The last :data:`RING_TICKS` sample times' periods in a preallocated ring (no
    allocation per tick) and their percentiles on demand."""

    def __init__(self, period_s: float, size: int = RING_TICKS) -> None:
        self.period_s = float(period_s)
        self._buf = np.zeros(size)
        self._n = 0
        self._last = -1.0

    def add(self, mono: float) -> None:
        """Record a sample taken at ``mono`` (monotonic seconds)."""
        last, self._last = self._last, mono
        if last >= 0.0:
            self._buf[self._n % self._buf.size] = mono - last
            self._n += 1

    def restart(self) -> None:
        """Forget the last sample time (the next period would span a pause, not a tick)."""
        self._last = -1.0

    def summary(self) -> dict[str, float | None]:
        """p50, p99 and max of the period and p99/max of ``|period - nominal|``, seconds."""
        iv = self._buf[: min(self._n, self._buf.size)].copy()
        if not iv.size:
            keys = ("mean", "p50", "p99", "max", "std", "error_p99", "error_max")
            return {f"period_{k}_s": None for k in keys}
        err = np.abs(iv - self.period_s)
        p50, p99 = np.percentile(iv, (50, 99))
        return {
            "period_mean_s": float(iv.mean()),
            "period_p50_s": float(p50),
            "period_p99_s": float(p99),
            "period_max_s": float(iv.max()),
            "period_std_s": float(iv.std()),
            "period_error_p99_s": float(np.percentile(err, 99)),
            "period_error_max_s": float(err.max()),
        }


class GcPauses:
    """Control and time the garbage collector while the daemon runs.

    :meth:`start` moves every object alive now to the permanent generation
    (:func:`gc.freeze`: start-up's modules, the box, the session are never scanned again),
    turns the automatic collector off and times each collection through
    :data:`gc.callbacks`; :meth:`collect_if_due` (the sampling thread, after a tick) collects
    the youngest generation every :data:`GC_YOUNG_BATCH` new objects and an older one as often
    as CPython would (every tenth collection of the one below); :meth:`stop` restores it all.
    """

    def __init__(self) -> None:
        self.count = 0
        self.total_s = 0.0
        self.max_s = 0.0
        self.max_generation = -1
        self._t = 0.0
        self._was_enabled: bool | None = None
        self._switch: float | None = None
        self._older = gc.get_threshold()[1:]

    def start(self) -> None:
        self._was_enabled = gc.isenabled()
        self._switch = sys.getswitchinterval()
        gc.collect()
        gc.freeze()
        gc.disable()
        sys.setswitchinterval(SWITCH_INTERVAL_S)
        gc.callbacks.append(self._on_gc)

    def collect_if_due(self) -> None:
        """Collect what is due (called by the sampling thread between ticks)."""
        young, gen1, gen2 = gc.get_count()
        if young < GC_YOUNG_BATCH:
            return
        generation = 2 if gen2 >= self._older[1] else 1 if gen1 >= self._older[0] else 0
        gc.collect(generation)

    def stop(self) -> None:
        if self._on_gc in gc.callbacks:
            gc.callbacks.remove(self._on_gc)
        if self._was_enabled is not None:
            gc.unfreeze()
            if self._was_enabled:
                gc.enable()
            self._was_enabled = None
        if self._switch is not None:
            sys.setswitchinterval(self._switch)
            self._switch = None

    def _on_gc(self, phase: str, info: dict[str, Any]) -> None:
        if phase == "start":
            self._t = time.perf_counter()
            return
        pause = time.perf_counter() - self._t
        self.count += 1
        self.total_s += pause
        if pause > self.max_s:
            self.max_s = pause
            self.max_generation = int(info.get("generation", -1))

    def to_dict(self) -> dict[str, float | int]:
        return {
            "gc_collections": self.count,
            "gc_pause_total_s": round(self.total_s, 6),
            "gc_pause_max_s": round(self.max_s, 6),
            "gc_pause_max_generation": self.max_generation,
        }


class CpuClock:
    """CPU the daemon's process and its sampling thread used, as a share of one core."""

    def __init__(self) -> None:
        self._wall0 = time.monotonic()
        self._cpu0 = time.process_time()
        self._thread_cpu = 0.0
        self._thread_id: int | None = None

    def sampled_by_this_thread(self) -> None:
        """Called by the sampling thread: remember its CPU time (cheap, no allocation)."""
        self._thread_cpu = time.thread_time()
        self._thread_id = threading.get_ident()

    def to_dict(self) -> dict[str, float]:
        wall = max(time.monotonic() - self._wall0, 1e-9)
        return {
            "cpu_percent": round(100 * (time.process_time() - self._cpu0) / wall, 1),
            "sampler_cpu_percent": round(100 * self._thread_cpu / wall, 1),
            "load_average_1min": round(os.getloadavg()[0], 2) if hasattr(os, "getloadavg") else -1,
        }


def set_realtime_priority(priority: int) -> None:
    """Run the calling thread, and every thread it starts afterwards, under the kernel's
    fixed-priority real-time policy (``SCHED_FIFO``, 1..99): the sampling loop then wakes on
    time whatever else the machine runs. Call it before the daemon opens its session and
    starts its threads. Needs Linux and root or ``CAP_SYS_NICE`` (a systemd unit grants it
    with ``CPUSchedulingPolicy=fifo``; docs/box.md).

    Raises
    ------
    InputError
        The priority is out of range, or the system refuses the policy (the reason named).
    """
    from softpad.errors import InputError

    if isinstance(priority, bool) or not isinstance(priority, int) or not 1 <= priority <= 99:
        raise InputError(f"real-time priority must be an integer from 1 to 99, got {priority!r}")
    if not hasattr(os, "sched_setscheduler"):
        raise InputError("real-time priority needs Linux (os.sched_setscheduler)")
    try:
        os.sched_setscheduler(0, os.SCHED_FIFO, os.sched_param(priority))
    except PermissionError:
        raise InputError(
            f"real-time priority {priority} refused: needs root or CAP_SYS_NICE "
            "(systemd: CPUSchedulingPolicy=fifo)"
        ) from None
    except OSError as exc:
        raise InputError(f"real-time priority {priority} refused: {exc.strerror}") from None
