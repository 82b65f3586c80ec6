"""Run only by tests/test_session_signals.py, in a pytest of its own started ignoring SIGINT
(not collected by the suite: the name does not start with ``test_``)."""

from __future__ import annotations

import signal
import subprocess
import sys

#: A child that says it is ready, then sleeps far longer than any deadline below.
CHILD = "import time; print('ready', flush=True); time.sleep(600)"


def test_a_child_of_the_test_process_stops_on_sigint() -> None:
    child = subprocess.Popen([sys.executable, "-c", CHILD], stdout=subprocess.PIPE, text=True)
    try:
        assert child.stdout is not None and child.stdout.readline() == "ready\n"
        child.send_signal(signal.SIGINT)
        # Python ends on an uncaught KeyboardInterrupt by SIGINT itself: -2; a child that
        # ignores SIGINT sleeps on and the wait runs out
        assert child.wait(60) == -signal.SIGINT
    finally:
        if child.poll() is None:
            child.kill()
            child.wait()
