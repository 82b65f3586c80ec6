"""The zenoh link on loopback: frame latency and dropped frames at 1 kHz with three monitors.

The daemon (``softpad box serve --sim``, a 1 kHz simulated box) and each monitor run in their
own processes, as on a real installation. A monitor stamps every frame on arrival with the
same monotonic clock the daemon stamped it with when sampled (one machine), so the latency is
sample -> publish -> receive. Lost frames are gaps in the sequence numbers; dropped samples
are ticks the daemon's 1 kHz schedule missed (``softpad box stats``: a tick whose sample was
not taken within its period).

Beside them, in the same window and at the same priority, a bare loop on the same schedule
(no box, no link, no other thread: :data:`_FLOOR`) counts the ticks this machine drops on its
own: what no design of the daemon (a separate process, compiled code) could recover.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import time

import numpy as np

from softpad.benchmarks._common import BenchResult

#: Length of the full run (the issue's target: no dropped tick over a minute), seconds.
LOOP_SECONDS = 60.0
#: SCHED_FIFO priority of the daemon where allowed (docs/box.md's systemd unit uses the same).
RT_PRIORITY = 10

_MONITOR = r"""
import json, sys, time, threading
import zenoh
from softpad.box.wire import decode_frame, session_config, split_frame
port, duration = int(sys.argv[1]), float(sys.argv[2])
rows = []
def on(sample):
    now = time.monotonic()
    f = decode_frame(split_frame(sample.payload.to_bytes())[0])
    rows.append((f.seq, now - f.mono_s))
s = zenoh.open(session_config("client", connect=(f"tcp/127.0.0.1:{port}",)))
sub = s.declare_subscriber("softpad/box/frames", on)
time.sleep(duration)
sub.undeclare()
s.close()
print(json.dumps(rows))
"""


_FLOOR = r"""
import json, os, signal, sys, time
from softpad.box._schedule import TickSchedule
limit, priority = float(sys.argv[1]), int(sys.argv[2])
if priority:
    os.sched_setscheduler(0, os.SCHED_FIFO, os.sched_param(priority))
stop = []
signal.signal(signal.SIGTERM, lambda *_: stop.append(1))  # the window ends
s = TickSchedule(1000.0)
end = time.monotonic() + limit
dropped = sampled = 0
late = 0.0
while not stop and time.monotonic() < end:
    due = s.due_s + s.period_s  # the next deadline, before any tick is skipped
    dropped += s.wait()
    now = time.monotonic()
    missed = s.late(now)  # sampled, but after its period: dropped, not sampled
    dropped += missed
    sampled += 1 - missed
    late = max(late, now - due)
print(json.dumps({"ticks": sampled + dropped, "dropped": dropped, "late_max_s": late}))
"""


def _serve_command(port: int, duration_s: float) -> list[str]:
    """The command line of the served simulated box the link benchmark measures."""
    return [
        sys.executable,
        "-m",
        "softpad.cli.main",
        "box",
        "serve",
        "--sim",
        "--box",
        "sim://?rate_hz=1000&inflated_kpa=1.1&object=banana",
        "--listen",
        f"tcp/127.0.0.1:{port}",
        "--duration-s",
        str(duration_s),
        *(["--rt-priority", str(RT_PRIORITY)] if _fifo_priority() else []),
    ]


def _measure(duration_s: float) -> tuple[np.ndarray, int, int, dict]:
    from softpad.box import open_box

    sys.path.insert(0, "")
    port = _free_port()
    serve = subprocess.Popen(
        _serve_command(port, duration_s + 300),
        stdout=subprocess.PIPE,
        stderr=subprocess.DEVNULL,
        text=True,
    )
    try:
        serve.stdout.readline()  # type: ignore[union-attr]  # "serving ..."
        before = _sampling_stats(port)  # the window starts with the daemon sampling
        floor = subprocess.Popen(  # the machine's own stalls over the same window
            [sys.executable, "-c", _FLOOR, str(duration_s + 300), str(_fifo_priority())],
            stdout=subprocess.PIPE,
            text=True,
        )
        mons = [
            subprocess.Popen(
                [sys.executable, "-c", _MONITOR, str(port), str(duration_s)],
                stdout=subprocess.PIPE,
                text=True,
            )
            for _ in range(3)
        ]
        results = [json.loads(m.communicate(timeout=duration_s + 60)[0]) for m in mons]
        with open_box(f"zenoh://127.0.0.1:{port}?timeout_s=30") as box:
            stats = box.request("stats")  # type: ignore[attr-defined]
        floor.terminate()
        for key in ("dropped_samples", "frames"):  # within the monitors' window
            stats[key] -= before[key]
        stats["floor"] = json.loads(floor.communicate(timeout=60)[0])
    finally:
        serve.terminate()
        serve.wait(timeout=10)
    lat: list[float] = []
    lost, got = 0, 0
    for rows in results:
        if not rows:
            continue
        seq = np.array([r[0] for r in rows])
        lat.extend(r[1] for r in rows[100:])  # skip the subscription's first frames
        lost += int(np.sum(np.maximum(np.diff(seq) - 1, 0)))
        got += len(rows)
    return np.asarray(lat), lost, got, stats


def _sampling_stats(port: int, deadline_s: float = 120.0) -> dict:
    """The daemon's stats once it has sampled for a second (a busy machine may take long to
    start the simulator: waits up to ``deadline_s``)."""
    from softpad.box import open_box

    end = time.monotonic() + deadline_s
    with open_box(f"zenoh://127.0.0.1:{port}?timeout_s=30") as box:
        while True:
            stats = box.request("stats")  # type: ignore[attr-defined]
            if stats["frames"] >= 1000 or time.monotonic() > end:
                return stats
            time.sleep(0.2)


def _fifo_priority() -> int:
    """:data:`RT_PRIORITY` where this process may use SCHED_FIFO (root or CAP_SYS_NICE on
    Linux; the daemon then runs at it, as its systemd unit does: docs/hardware.md), else 0."""
    return RT_PRIORITY if _fifo_allowed() else 0


def _fifo_allowed() -> bool:
    """Whether this process may use SCHED_FIFO (tried in a forked child)."""
    if not hasattr(os, "sched_setscheduler"):
        return False
    try:
        pid = os.fork()
    except OSError:
        return False
    if pid == 0:  # try it in a child, never in the benchmark's own process
        try:
            os.sched_setscheduler(0, os.SCHED_FIFO, os.sched_param(RT_PRIORITY))
            os._exit(0)
        except OSError:
            os._exit(1)
    return os.waitpid(pid, 0)[1] == 0


def _free_port() -> int:
    import socket

    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def run(quick: bool) -> list[BenchResult]:
    """Latency p50/p99 (fraction of the 1 ms period), lost frames, the daemon's schedule:
    dropped ticks, period error p99, its CPU."""
    duration = 3.0 if quick else LOOP_SECONDS
    load = os.getloadavg()[0]
    lat, lost, got, stats = _measure(duration)
    detail = f"3 monitor processes x {duration:g} s, {got} frames received, load {load:.1f}"
    return [*_link_results(lat, lost, got, detail), *_schedule_results(stats, load)]


def _link_results(lat: np.ndarray, lost: int, got: int, detail: str) -> list[BenchResult]:
    """Latency p50 and p99 (``lat``, seconds, as fractions of the 1 ms period) and frames
    lost."""
    period = 1e-3
    p50, p99 = (float(np.percentile(lat, q)) / period for q in (50, 99)) if lat.size else (0, 0)
    return [
        BenchResult(
            "zenoh link, sample -> receive latency p50, fraction of the 1 ms period",
            p50,
            "periods",
            target="< 1",
            met=p50 < 1 and got > 0,
            detail=detail,
        ),
        BenchResult(
            "zenoh link, sample -> receive latency p99, fraction of the 1 ms period",
            p99,
            "periods",
            detail=detail,
        ),
        BenchResult(
            "zenoh link, frames lost between daemon and 3 monitors (sequence gaps)",
            float(lost),
            "frames",
            target="0",
            met=lost == 0 and got > 0,
            detail=detail,
        ),
    ]


def _schedule_results(stats: dict, load: float) -> list[BenchResult]:
    """The daemon's dropped ticks, period error p99 and CPU, from its ``stats``."""
    err_ms = (stats.get("period_error_p99_s") or 0.0) * 1e3
    ms = {k: (stats.get(f"period_{k}_s") or 0.0) * 1e3 for k in ("p50", "p99", "max")}
    loop = (
        f"{stats['frames']} frames in the measured window, period p50/p99/max "
        f"{ms['p50']:.3f}/{ms['p99']:.3f}/{ms['max']:.3f} ms, longest gc "
        f"{stats.get('gc_pause_max_s', 0) * 1e3:.2f} ms, load {load:.1f} at the start, "
        f"SCHED_FIFO {stats.get('realtime_priority') or 'off'}"
    )
    floor = stats.get("floor") or {}
    return [
        BenchResult(
            "box daemon at 1 kHz (sim box, 3 monitors), ticks dropped by the schedule",
            float(stats["dropped_samples"]),
            "ticks",
            target="0",
            met=stats["dropped_samples"] == 0 and stats["frames"] > 0,
            detail=f"achieved {stats['achieved_rate_hz']:.0f} Hz; {loop}",
        ),
        BenchResult(
            "box daemon at 1 kHz, period error p99 (|period - 1 ms|)",
            err_ms,
            "ms",
            target="< 0.2 ms",
            met=err_ms < 0.2 and stats["frames"] > 0,
            detail=loop,
        ),
        BenchResult(
            "this machine's floor: a bare 1 kHz loop beside the daemon (same window and "
            "priority, no box, no link), ticks dropped",
            float(floor.get("dropped", float("nan"))),
            "ticks",
            detail=f"of {floor.get('ticks', 0)} ticks; latest wake-up "
            f"{floor.get('late_max_s', float('nan')) * 1e3:.2f} ms after its deadline; the "
            "daemon cannot drop fewer than the machine stalls",
        ),
        BenchResult(
            "box daemon at 1 kHz, CPU of the daemon process (sampling thread)",
            float(stats.get("cpu_percent", float("nan"))),
            "% of a core",
            detail=f"sampling thread {stats.get('sampler_cpu_percent', float('nan'))} %",
        ),
    ]
