"""Where the box daemon's late ticks come from: a per-tick probe of its sampling thread.

    python docs/tick_probe.py daemon 60 10      # the daemon as 'box serve --sim' + 3 monitors
    python docs/tick_probe.py stripped 60 10    # the box, guard and frame encoding, one thread

(mode, seconds, SCHED_FIFO priority or 0; Linux). Around the sampler's sleep and around each
tick's work the probe reads the thread's ``/proc/self/task/TID/schedstat`` (CPU time, time
runnable on the run queue): time late that is neither is time blocked (the GIL, a lock, or a
timer that fired late because the virtual CPU was not running). Prints one JSON line: the
ticks the schedule skipped, by the cause that took most of the late time before each (the
daemon's own count, ``softpad box stats``, also has the ticks sampled after their period). docs/hardware.md ("The 1 kHz
schedule") quotes a run.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import threading
import time

import numpy as np

from softpad.box import _schedule

URL = "sim://?rate_hz=1000&inflated_kpa=1.1&object=banana"
#: Per tick: deadline, wake time, dropped, then (duration, cpu, run queue) of the sleep's
#: tail and of the work.
COLUMNS = 9


class Probe:
    """Patches :meth:`TickSchedule.wait` to record every tick (preallocated)."""

    def __init__(self, ticks: int) -> None:
        self.rec = np.zeros((ticks, COLUMNS))
        self.i = 0
        self.fd = -1
        self.prev: tuple[float, float, float] | None = None

    def schedstat(self) -> tuple[float, float]:
        cpu, queued = os.pread(self.fd, 64, 0).split()[:2]
        return int(cpu) * 1e-9, int(queued) * 1e-9

    def install(self) -> None:
        wait = _schedule.TickSchedule.wait
        probe = self

        def probed(schedule: _schedule.TickSchedule) -> int:
            if probe.fd < 0:
                tid = threading.get_native_id()
                probe.fd = os.open(f"/proc/self/task/{tid}/schedstat", os.O_RDONLY)
            t_in = time.monotonic()
            cpu0, q0 = probe.schedstat()
            i = probe.i
            if probe.prev is not None and 0 < i <= len(probe.rec):
                t, c, q = probe.prev
                probe.rec[i - 1, 6:9] = (t_in - t, cpu0 - c, q0 - q)
            dropped = wait(schedule)
            t = time.monotonic()
            cpu1, q1 = probe.schedstat()
            if i < len(probe.rec):
                probe.rec[i, 0:6] = (schedule.due_s, t, dropped, t - t_in, cpu1 - cpu0, q1 - q0)
            probe.prev = (t, cpu1, q1)
            probe.i = i + 1
            return dropped

        _schedule.TickSchedule.wait = probed  # type: ignore[method-assign]

    def causes(self) -> dict[str, int]:
        """Dropped ticks by the largest share of the late time before them (the first second,
        start-up, apart)."""
        r = self.rec[1 : max(self.i - 1, 1)]
        out = dict.fromkeys(
            (
                "start-up",
                "woke late, blocked",
                "woke late, run queue",
                "work, own CPU",
                "work, run queue",
                "work, blocked",
            ),
            0,
        )
        for k in np.nonzero(r[:, 2] > 0)[0]:
            if k < 1 or r[k, 0] - r[0, 0] < 1.0:
                out["start-up"] += int(r[k, 2])
                continue
            late, q = r[k - 1, 1] - r[k - 1, 0], r[k - 1, 5]
            work, wcpu, wq = r[k - 1, 6:9]
            share = {
                "woke late, blocked": late - q,
                "woke late, run queue": min(q, late),
                "work, own CPU": wcpu,
                "work, run queue": wq,
                "work, blocked": work - wcpu - wq,
            }
            out[max(share, key=share.__getitem__)] += int(r[k, 2])
        return out


def stripped(seconds: float, priority: int) -> None:
    from softpad.box import open_box
    from softpad.box._daemon import guard_box
    from softpad.box._link import encode_frame

    if priority:
        _schedule.set_realtime_priority(priority)
    box = guard_box(open_box(URL), 3000.0)
    gc = _schedule.GcPauses()
    gc.start()
    schedule = _schedule.TickSchedule(1000.0)
    end, seq = time.monotonic() + seconds, 0
    while time.monotonic() < end:
        schedule.wait()
        frame = box.read()
        seq += 1
        encode_frame(seq, time.monotonic(), frame)
        gc.collect_if_due()
    box.close()


def daemon(seconds: float, priority: int) -> None:
    import argparse

    from softpad.benchmarks._link import _MONITOR, _free_port
    from softpad.cli import _box

    port = _free_port()
    args = argparse.Namespace(
        rt_priority=priority or None,
        hardware=None,
        config=None,
        listen=[f"tcp/127.0.0.1:{port}"],
        port=None,
        sim=True,
        box=URL,
        rate_hz=None,
        watchdog_s=None,
        realtime=False,
    )
    d = _box._daemon_for(args).start()

    def ordinary() -> None:  # the monitors are not the daemon: the ordinary scheduler
        os.sched_setscheduler(0, os.SCHED_OTHER, os.sched_param(0))

    mons = [
        subprocess.Popen(
            [sys.executable, "-c", _MONITOR, str(port), str(seconds)],
            stdout=subprocess.PIPE,
            text=True,
            preexec_fn=ordinary,
        )
        for _ in range(3)
    ]
    for m in mons:
        m.communicate()
    d.close()


def main() -> None:
    mode, seconds = sys.argv[1], float(sys.argv[2])
    priority = int(sys.argv[3]) if len(sys.argv) > 3 else 0
    probe = Probe(int(seconds * 1000) + 5000)
    probe.install()
    load = os.getloadavg()[0]
    (daemon if mode == "daemon" else stripped)(seconds, priority)
    n = min(probe.i, len(probe.rec))
    print(
        json.dumps(
            {
                "mode": mode,
                "priority": priority,
                "load_at_start": load,
                "ticks": n,
                "dropped": int(probe.rec[:n, 2].sum()),
                "by_cause": probe.causes(),
            }
        )
    )


if __name__ == "__main__":
    main()
