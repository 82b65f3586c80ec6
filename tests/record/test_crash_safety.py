"""``kill -9`` of a recording run leaves a readable file that lacks at most one flush period
(100 ms) and one frame."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

from softpad.record import FLUSH_PERIOD_S, load_recording, recover

# The child records a long run and, after every frame, stores the wall-clock stamp (log_time)
# of the last message it handed to the writer in a side file (pwrite survives kill -9):
# that is what was recorded before the kill, against which the file's content is measured.
_CHILD = """
import os, struct, sys
from softpad.box import open_box
from softpad.control import ExecutionParams
from softpad.harness import run_simulated
from softpad.record import McapRecorder
box = open_box("sim://?seed=1&realtime=1")  # real-time pace: the 100 ms flush decides
fd = os.open(sys.argv[2], os.O_WRONLY | os.O_CREAT)
rec = McapRecorder(sys.argv[1], {"objects": ["banana"]})
class Probe:
    def frame(self, frame, phase):
        rec.frame(frame, phase)
        os.pwrite(fd, struct.pack("<q", rec.last_log_ns), 0)
    def event(self, t_s, kind, **data):
        rec.event(t_s, kind, **data)
run_simulated(["banana"], box, ExecutionParams(hold_s=3600.0), Probe())
"""


def test_kill_9_loses_at_most_one_flush_period(tmp_path: Path) -> None:
    path, side = tmp_path / "crash.mcap", tmp_path / "last_ns"
    child = subprocess.Popen([sys.executable, "-c", _CHILD, str(path), str(side)])
    try:
        deadline = time.monotonic() + 120.0
        while not (path.exists() and side.exists() and side.stat().st_size == 8):
            assert child.poll() is None, "the recording run ended early"
            assert time.monotonic() < deadline, "the recording run did not start"
            time.sleep(0.05)
        time.sleep(1.5)  # 150 frames: several flush periods
        os.kill(child.pid, signal.SIGKILL)
    finally:
        child.kill()
        child.wait(timeout=30)
    assert child.returncode == -signal.SIGKILL
    last_recorded_ns = int.from_bytes(side.read_bytes()[:8], "little", signed=True)
    run = load_recording(path)  # read up to the last complete chunk
    assert not run.complete and len(run) > 50
    lost_s = (last_recorded_ns - int(run.wall_ns[-1])) * 1e-9
    print(f"kill -9: {lost_s * 1e3:.1f} ms of recording lost")  # shown by pytest -s
    # a flush is due with the first frame after the period ran out: one flush period, plus one
    # frame interval of the 100 Hz box (the frame arriving late), plus 5 ms for the messages
    # of the frame being written
    assert lost_s <= FLUSH_PERIOD_S + 0.010 + 0.005, lost_s
    # after recovery ROS tooling opens it as any complete file
    fixed = recover(path)
    from rosbags.highlevel import AnyReader

    with AnyReader([fixed]) as reader:
        counts = {c.topic: c.msgcount for c in reader.connections}
    assert counts["/softpad/supply/pressure"] == len(run)  # a frame's last message ends it
    assert counts["/softpad/module_1/pressure"] in (len(run), len(run) + 1)
    assert load_recording(fixed).complete
