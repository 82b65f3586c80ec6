"""A stall of the daemon's Python side against the over-pressure guard, in wall-clock time.

The hardware box runs as on the board: :class:`~softpad.box.HardwareBox` reads a fake IIO tree
and drives fake GPIO lines (:class:`~softpad.box.FileValveLines`, a file one byte per line),
served by a :class:`~softpad.box.BoxDaemon`. The physics is the project's simulated box in
another process (:data:`_PLANT`), paced to the wall clock: it reads the valve lines, steps the
chambers' gas model (seed 1; channel 1's inflation valve stuck open, the worst case: nothing
the daemon commands stops the inflow) and writes each chamber's true pressure into the IIO
files as counts (1 Pa per count), recording the peak true pressure. It runs under
``SCHED_FIFO`` where allowed (physics is never late); its longest gap between two updates of
the sensor files is reported (``plant_max_gap_s``): a gap is time the guard could not see.

When channel 1's reading comes within :data:`STALL_BEFORE_TRIP_PA` of the trip level, this
process holds the interpreter lock for the stall (a C call through :class:`ctypes.PyDLL`, which
never releases it): every Python thread of the daemon stops (its sampling loop and guard, the
zenoh callbacks' Python side), as in a long collection or a flood of queries. The compiled guard
(:mod:`softpad.box._fastguard`, off the lock) keeps running; without it, nothing vents until the
stall ends.
"""

from __future__ import annotations

import ctypes
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

from softpad.benchmarks._common import BenchResult

#: The ceiling of the true pressure during a stall (issue 49), pascals.
CEILING_PA = 3100.0
#: The stall starts when channel 1 reads this far below the trip level, pascals.
STALL_BEFORE_TRIP_PA = 30.0
#: Channel 1's pressure at the start, pascals (near the trip level: the run is short).
START_PA = 2500.0

_PLANT = r"""
import json, os, signal, sys, time
from softpad.box import SimBox, ValveCommand
from softpad.box._sim_faults import Fault
root, gpio, start_pa = sys.argv[1], sys.argv[2], float(sys.argv[3])
try:  # physics is never late: the plant runs ahead of the daemon where the system allows
    os.sched_setscheduler(0, os.SCHED_FIFO, os.sched_param(20))
except (OSError, AttributeError):
    pass
sim = SimBox(channels=8, sample_rate_hz=1000.0, seed=1, initial_pressure_pa=start_pa)
sim.inject_fault(Fault.parse("stuck:1:inflate"))
n = sim.world.layout.n_modules
files = [os.open(f"{root}/iio:device0/in_voltage{k}_raw", os.O_WRONLY) for k in range(n)]
gfd = os.open(gpio, os.O_RDONLY)
stop = []
signal.signal(signal.SIGTERM, lambda *_: stop.append(1))
peak, steps, rise, last_lines = 0.0, 0, [], b""
for k in range(n):
    os.pwrite(files[k], b"%9d\n" % int(round(sim.true_pressures_pa[k])), 0)
print("ready", flush=True)
sys.stdin.readline()  # the daemon is up: the physics starts now
t0 = before = time.monotonic()
gap = 0.0
while not stop:
    now = time.monotonic()
    gap, before = max(gap, now - before), now
    lines = os.pread(gfd, 2 * n, 0)
    if lines != last_lines:  # normally-closed valves: a line active is a valve open
        for k in range(n):
            cmd = "inflate" if lines[2 * k] else ("deflate" if lines[2 * k + 1] else "closed")
            sim._apply_valve(k + 1, ValveCommand.parse(cmd))
        last_lines = lines
    due = int((time.monotonic() - t0) * 1000.0)
    while steps < due:  # the chambers keep the wall clock's time
        sim._read()
        steps += 1
        p = sim.true_pressures_pa
        peak = max(peak, float(p[0]))
        if len(rise) < 500:
            rise.append(float(p[0]))
    p = sim.true_pressures_pa
    for k in range(n):
        os.pwrite(files[k], b"%9d\n" % int(round(p[k])), 0)
    time.sleep(0.0002)
rates = [(rise[i + 100] - rise[i]) * 10.0 for i in range(0, min(len(rise) - 100, 400), 100)]
print(json.dumps({"peak_pa": peak, "rise_pa_s": max(rates) if rates else None, "steps": steps,
                  "plant_max_gap_s": gap}))
"""


def _site(root: Path) -> Any:
    from softpad.config import parse_installation

    dev = root / "iio:device0"
    dev.mkdir(parents=True)
    for k in range(6):
        (dev / f"in_voltage{k}_raw").write_text(f"{0:9d}\n")
    chans = [
        {"gpiochip": "/dev/gpiochip0", "inflate_line": 2 * k, "deflate_line": 2 * k + 1,
         "iio_device": 0, "iio_channel": k}
        for k in range(6)
    ]  # fmt: skip
    box = {
        "channel": chans,
        "iio_root": str(root),
        "sample_rate_hz": 1000.0,
        "inflate_valves": "normally_closed",
        "deflate_valves": "normally_closed",
    }
    return parse_installation({"box": box}).box


def stalled_peak(stall_s: float, compiled: bool = True, port: int | None = None) -> dict[str, Any]:
    """Peak true pressure of channel 1 (stuck-open inflation valve) when the daemon's Python
    side stops for ``stall_s`` seconds as it nears the trip level; ``compiled``: with the
    compiled guard (else the daemon's Python guard only)."""
    from softpad.box import BoxDaemon, FileValveLines, HardwareBox

    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp)
        settings = _site(root)
        gpio = root / "gpio"
        lines = FileValveLines(
            gpio,
            ((w.gpiochip, o) for w in settings.channels for o in (w.inflate_line, w.deflate_line)),
        )
        plant = subprocess.Popen(
            [sys.executable, "-c", _PLANT, str(root), str(gpio), str(START_PA)],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            text=True,
        )
        try:
            assert plant.stdout is not None and plant.stdout.readline().strip() == "ready"
            box = HardwareBox(settings, lines=lines)
            if not compiled:
                box.start_guard = None  # type: ignore[assignment,method-assign]
            port = port or _free_port()
            daemon = BoxDaemon(box, (f"tcp/127.0.0.1:{port}",))
            with daemon:
                guarded = box.guard_stats() is not None
                assert plant.stdin is not None
                plant.stdin.write("go\n")
                plant.stdin.flush()
                _wait_near_trip(daemon, box)
                t0 = time.monotonic()
                ctypes.PyDLL(None).usleep(int(stall_s * 1e6))  # holds the GIL throughout
                held_s = time.monotonic() - t0
                time.sleep(1.0)  # the daemon's own guard catches up
                stats = box.guard_stats()
        finally:
            plant.terminate()
            out, _ = plant.communicate(timeout=30)
        result = json.loads(out.strip().splitlines()[-1])
    return {**result, "stall_s": held_s, "compiled_guard": guarded, "guard": stats}


def _wait_near_trip(daemon: Any, box: Any) -> None:
    level = daemon.trip_pa - STALL_BEFORE_TRIP_PA
    end = time.monotonic() + 60.0
    while time.monotonic() < end:
        last = daemon._last
        if last is not None and last.pressures_pa[0] >= level:
            return
        time.sleep(0.0005)
    raise RuntimeError(f"channel 1 never reached {level:.0f} Pa")


def _free_port() -> int:
    import socket

    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def run(quick: bool) -> list[BenchResult]:
    out = []
    for stall in (0.1, 0.5):
        for compiled in (True, False):
            r = stalled_peak(stall, compiled)
            who = "compiled guard" if r["compiled_guard"] else "Python guard only"
            out.append(
                BenchResult(
                    f"stall {stall * 1e3:.0f} ms, {who}: peak true pressure",
                    r["peak_pa"] / 1e3,
                    "kPa",
                    f"<= {CEILING_PA / 1e3:g} kPa",
                    r["peak_pa"] <= CEILING_PA,
                    f"GIL held {r['stall_s'] * 1e3:.0f} ms from {STALL_BEFORE_TRIP_PA:g} Pa "
                    f"below the trip (plant's longest gap {r['plant_max_gap_s'] * 1e3:.1f} ms); "
                    f"stuck-open inflation valve, rise {r['rise_pa_s']:.0f} Pa/s; "
                    "wall-clock plant (simulated chambers), fake GPIO and IIO",
                )
            )
    return out
