"""Long-running commands stop on Ctrl-C with exit 130 and on SIGTERM with 143 (docs/cli.md),
and say on their first line which box they talk to (issue 51).

Every command runs in its own process; each test waits for the line that shows the command
is at work (generous deadlines, no fixed sleeps) before it sends the signal.
"""

from __future__ import annotations

import os
import queue
import shutil
import signal
import subprocess
import sys
import threading
from pathlib import Path

import pytest

from softpad.cli.main import build_parser

CLI = [sys.executable, "-c", "import sys; from softpad.cli.main import main; sys.exit(main())"]
#: Seconds to wait for a line or an exit: a bound on a hang on a loaded machine, not a speed.
DEADLINE_S = 120.0
SIGNALS = [
    pytest.param(signal.SIGINT, 130, id="SIGINT-130"),
    pytest.param(signal.SIGTERM, 143, id="SIGTERM-143"),
]


def default_sigint() -> None:
    """In the child: Ctrl-C's default disposition, which a test run started in the background
    of a shell script ignores (and a process that starts ignoring SIGINT keeps ignoring it)."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


class Command:
    """A ``softpad`` command in its own process, its stdout read line by line."""

    def __init__(self, *argv: str, env: dict[str, str] | None = None) -> None:
        self.proc = subprocess.Popen(
            [*CLI, *argv],
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
            env=env,
            preexec_fn=default_sigint,
        )
        self.lines: queue.Queue[str | None] = queue.Queue()
        threading.Thread(target=self._read, daemon=True).start()

    def _read(self) -> None:
        assert self.proc.stdout is not None
        for line in self.proc.stdout:
            self.lines.put(line)
        self.lines.put(None)

    def line(self) -> str:
        """The next line of stdout (fails with stderr when the command ended first)."""
        try:
            line = self.lines.get(timeout=DEADLINE_S)
        except queue.Empty:
            raise AssertionError(f"no line within {DEADLINE_S} s") from None
        if line is None:
            raise AssertionError(f"ended {self.proc.wait()}: {self.stderr()}")
        return line

    def stop(self, signum: int) -> int:
        """Send ``signum``; the exit code."""
        self.proc.send_signal(signum)
        return self.proc.wait(timeout=DEADLINE_S)

    def stderr(self) -> str:
        assert self.proc.stderr is not None
        return self.proc.stderr.read() if self.proc.poll() is not None else ""

    def kill(self) -> None:
        if self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait(timeout=DEADLINE_S)


@pytest.fixture(scope="module")
def served(free_port):  # type: ignore[no-untyped-def]
    """A simulated box served on a free loopback port: (its zenoh URL, its first line); one
    server for the module's monitors (each a client of its own: the server is not what they
    check, and its start-up is a process's)."""
    port = free_port()
    serve = Command("box", "serve", "--sim", "--port", str(port))
    try:
        yield f"zenoh://127.0.0.1:{port}", serve.line()
    finally:
        serve.kill()


@pytest.mark.parametrize(("signum", "code"), SIGNALS)
def test_box_serve_names_the_simulated_box_and_stops_on_a_signal(
    free_port, signum: int, code: int
) -> None:
    port = free_port()
    serve = Command("box", "serve", "--sim", "--port", str(port))
    try:
        first = serve.line()
        assert first.startswith("softpad box serve: serving the simulated box sim://"), first
        assert f"tcp/127.0.0.1:{port}" in first
        assert serve.stop(signum) == code
        err = serve.stderr()
        assert "valves closed" in err
        assert "Unreachable" not in first + err  # a wrapper layer's class name, not the box
    finally:
        serve.kill()


@pytest.mark.parametrize(("signum", "code"), SIGNALS)
def test_box_monitor_names_the_box_and_stops_on_a_signal(served, signum: int, code: int) -> None:
    url, _ = served
    monitor = Command("box", "monitor", "--box", url, "--period-s", "0.1")
    try:
        first = monitor.line()
        assert first.startswith(f"softpad box monitor: the served box at {url}"), first
        monitor.line()  # the header
        monitor.line()  # a period's figures: it is watching
        assert monitor.stop(signum) == code
    finally:
        monitor.kill()


def test_box_monitor_watches_the_installations_link_by_default() -> None:
    args = build_parser().parse_args(["box", "monitor"])
    assert args.box == "zenoh://127.0.0.1:7447"


def test_box_monitor_fails_naming_the_link_when_nothing_serves(free_port, tmp_path: Path) -> None:
    """The installation's link (here on a free port: nothing serves there) is what a monitor
    without --box watches; it ends with exit 3 and a message naming that link."""
    port = free_port()
    site = tmp_path / "site.toml"
    site.write_text(f'[link]\nconnect = ["tcp/127.0.0.1:{port}"]\n')
    done = subprocess.run(
        [*CLI, "box", "monitor", "--config", str(site)],
        capture_output=True,
        text=True,
        timeout=DEADLINE_S,
        check=False,
    )
    assert done.returncode == 3, done.stderr
    assert f"127.0.0.1:{port}" in done.stderr
    assert "softpad box serve --sim" in done.stderr
    assert "Traceback" not in done.stderr


def test_a_simulated_box_is_paced_at_real_time_unless_asked(capsys) -> None:
    """51 frames of the 100 Hz simulated box span 0.5 s of box time: read paced, they take at
    least that long on the wall clock (a lower bound: pacing, not speed); realtime=0 is not
    paced (before the fix a monitor ran its private simulator at about 270,000 frames/s)."""
    import time

    from softpad.box import Pacer
    from softpad.cli.main import main

    t0 = time.monotonic()
    assert main(["box", "read", "--count", "51", "--box", "sim://?noise=0"]) == 0
    assert time.monotonic() - t0 >= 0.5
    assert "paced at real time" in capsys.readouterr().out.splitlines()[0]
    assert not Pacer("sim://?realtime=0").on and not Pacer("zenoh://127.0.0.1:7447").on
    assert Pacer("sim://?object=banana").on


@pytest.mark.parametrize(("signum", "code"), SIGNALS)
def test_run_stops_on_a_signal(signum: int, code: int) -> None:
    """A run at real time (so that it is still at work when the signal comes)."""
    run = Command("run", "--objects", "object-5", "--box", "sim://?realtime=1", "--hold-s", "30")
    try:
        first = run.line()
        assert first.startswith("softpad run: object-5 on sim://"), first
        assert run.stop(signum) == code
    finally:
        run.kill()


@pytest.fixture(scope="module")
def ros_master(free_port):  # type: ignore[no-untyped-def]
    """The environment of the clients of a ROS 1 master on a free loopback port, up; one
    master for the module's nodes (each node registers and leaves on its signal)."""
    core, env = _roscore(free_port)
    try:
        yield env
    finally:
        os.killpg(core.pid, signal.SIGINT)
        core.wait(timeout=DEADLINE_S)


def _roscore(free_port) -> tuple[subprocess.Popen[bytes], dict[str, str]]:  # type: ignore[no-untyped-def]
    """A ROS 1 master on a free loopback port, up, and the environment of its clients."""
    from softpad.ros import rospy_available

    if not (rospy_available() and shutil.which("roscore")):
        pytest.skip("ROS 1 not installed (make ros-deps)")
    port = free_port()
    env = {
        **os.environ,
        "ROS_MASTER_URI": f"http://127.0.0.1:{port}",
        "ROS_IP": "127.0.0.1",
        "ROS_HOSTNAME": "localhost",
    }
    core = subprocess.Popen(
        ["roscore", "-p", str(port)],
        env=env,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        start_new_session=True,
    )
    probe = "import rosgraph, sys; sys.exit(not rosgraph.is_master_online())"
    for _ in range(300):  # each probe waits on the master's socket
        up = subprocess.run(["/usr/bin/python3", "-c", probe], env=env, check=False, timeout=60)
        if up.returncode == 0:
            return core, env
        if core.poll() is not None:
            break
    os.killpg(core.pid, signal.SIGKILL)
    raise AssertionError("roscore did not come up")


@pytest.mark.parametrize(("signum", "code"), SIGNALS)
def test_ros_node_stops_on_a_signal(ros_master, signum: int, code: int) -> None:  # type: ignore[no-untyped-def]
    node = Command("ros", "node", "--box", "sim://", "--place", "object-5", env=ros_master)
    try:
        first = node.line()
        assert first.startswith("softpad ros node: box sim://"), first
        assert node.stop(signum) == code
    finally:
        node.kill()
