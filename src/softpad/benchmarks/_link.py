"""The zenoh link on loopback: frame latency and dropped frames at 1 kHz with three monitors.

The daemon (``softpad box serve --sim``, a 1 kHz simulated box) and each monitor run in their
own processes, as on a real installation. A monitor stamps every frame on arrival with the
same monotonic clock the daemon stamped it with when sampled (one machine), so the latency is
sample -> publish -> receive. Lost frames are gaps in the sequence numbers; dropped samples
are ticks the daemon's 1 kHz schedule missed (``softpad box stats``).
"""

from __future__ import annotations

import json
import subprocess
import sys
import time

import numpy as np

from softpad.benchmarks._common import BenchResult

_MONITOR = r"""
import json, sys, time, threading
import zenoh
from softpad.box._auth import split_frame
from softpad.box._link import decode_frame, session_config
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


def _measure(duration_s: float) -> tuple[np.ndarray, int, int, dict]:
    from softpad.box import open_box

    sys.path.insert(0, "")
    port = _free_port()
    serve = subprocess.Popen(
        [
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
            str(duration_s + 6),
        ],
        stdout=subprocess.PIPE,
        stderr=subprocess.DEVNULL,
        text=True,
    )
    try:
        serve.stdout.readline()  # type: ignore[union-attr]  # "serving ..."
        time.sleep(0.5)
        mons = [
            subprocess.Popen(
                [sys.executable, "-c", _MONITOR, str(port), str(duration_s)],
                stdout=subprocess.PIPE,
                text=True,
            )
            for _ in range(3)
        ]
        results = [json.loads(m.communicate(timeout=duration_s + 30)[0]) for m in mons]
        with open_box(f"zenoh://127.0.0.1:{port}") as box:
            stats = box.request("stats")  # type: ignore[attr-defined]
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


def _free_port() -> int:
    import socket

    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def run(quick: bool) -> list[BenchResult]:
    """Latency p50/p99 (fraction of the 1 ms period), lost frames, dropped samples."""
    duration = 3.0 if quick else 10.0
    lat, lost, got, stats = _measure(duration)
    period = 1e-3
    p50, p99 = (float(np.percentile(lat, q)) / period for q in (50, 99)) if lat.size else (0, 0)
    detail = f"3 monitor processes x {duration:g} s, {got} frames received"
    return [
        BenchResult(
            "zenoh link, sample -> receive latency p50, fraction of the 1 ms period",
            p50,
            "periods",
            target="< 1",
            met=p50 < 1,
            detail=detail,
        ),
        BenchResult(
            "zenoh link, sample -> receive latency p99, fraction of the 1 ms period",
            p99,
            "periods",
            target="-",
            met=None,
            detail=detail,
        ),
        BenchResult(
            "zenoh link, frames lost between daemon and 3 monitors (sequence gaps)",
            float(lost),
            "frames",
            target="0",
            met=lost == 0,
            detail=detail,
        ),
        BenchResult(
            "box daemon at 1 kHz (sim box), samples dropped by the schedule / achieved rate",
            float(stats["dropped_samples"]),
            "samples",
            target="0",
            met=stats["dropped_samples"] == 0,
            detail=(
                f"achieved {stats['achieved_rate_hz']:.0f} Hz, jitter (std) "
                f"{(stats['jitter_std_s'] or 0) * 1e3:.3f} ms over {stats['frames']} frames"
            ),
        ),
    ]
