"""The test session's signal dispositions (tests/conftest.py, ``pytest_configure``)."""

from __future__ import annotations

import signal
import subprocess
import sys
from pathlib import Path

PROBE = Path(__file__).with_name("_sigint_probe.py")


def _ignore_sigint() -> None:
    """In the child: SIGINT ignored, as a shell script's background job (``make test &``
    without job control) starts."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)


def test_a_run_started_ignoring_sigint_still_stops_its_children_with_sigint() -> None:
    """A pytest started ignoring SIGINT: a process one of its tests starts still ends on the
    SIGINT the test sends (before the fix it inherited the ignore and slept through it: the
    ROS 2 node's teardowns waited 20 s each for their SIGKILL; issue 50)."""
    r = subprocess.run(
        [sys.executable, "-m", "pytest", "-p", "no:xdist", "-p", "no:cacheprovider", "-q",
         str(PROBE)],
        cwd=PROBE.parent.parent, capture_output=True, text=True, timeout=300, check=False,
        preexec_fn=_ignore_sigint,
    )  # fmt: skip
    assert r.returncode == 0, r.stdout[-3000:] + r.stderr[-2000:]
    assert "1 passed" in r.stdout, r.stdout[-3000:]
