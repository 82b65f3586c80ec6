"""Fixtures shared by the test folders: loopback ports and a served simulated box."""

from __future__ import annotations

import socket
import time
from collections.abc import Callable, Iterator
from contextlib import AbstractContextManager, contextmanager
from typing import Any

import pytest


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


#: Client timeout on the links to ``served`` daemons, seconds.
SERVED_TIMEOUT_S = 60.0


@contextmanager
def _served(url: str = "sim://?seed=4", **kwargs: Any) -> Iterator[tuple[Any, str]]:
    from softpad.box import BoxDaemon, open_box, simulator_of
    from softpad.harness import simulation_extensions

    port = _free_port()
    box = open_box(url)
    sim = simulator_of(box)
    services = simulation_extensions(sim) if sim is not None else None
    daemon = BoxDaemon(box, (f"tcp/127.0.0.1:{port}",), services=services, **kwargs)
    with daemon:
        # a generous deadline for every frame and answer (the client's default is 5 s): on a
        # busy machine the simulator's first frames can take longer than that (issue 36)
        yield daemon, f"zenoh://127.0.0.1:{port}?timeout_s={SERVED_TIMEOUT_S:g}"


@pytest.fixture(scope="session")
def free_port() -> Callable[[], int]:
    """``free_port()``: a TCP port on 127.0.0.1 that nobody listens on right now."""
    return _free_port


@pytest.fixture(scope="session")
def served() -> Callable[..., AbstractContextManager[tuple[Any, str]]]:
    """``with served(url="sim://?seed=4", **daemon_options) as (daemon, zenoh_url)``: a
    :class:`~softpad.box.BoxDaemon` serving ``url`` (with the simulator's services for a
    ``sim://`` box) on a free loopback port."""
    return _served


def _until(cond: Callable[[], object], what: str, limit_s: float = 20.0) -> None:
    end = time.monotonic() + limit_s
    while not cond():
        if time.monotonic() > end:
            raise AssertionError(f"timed out waiting for {what}")
        time.sleep(0.01)


@pytest.fixture(scope="session")
def until() -> Callable[..., None]:
    """``until(cond, what, limit_s=20.0)``: poll ``cond`` every 10 ms until it is true
    (bounded: fails naming ``what`` after ``limit_s`` seconds)."""
    return _until


@pytest.fixture
def cli(capsys: pytest.CaptureFixture[str]) -> Callable[..., tuple[int, str, str]]:
    """``cli(*argv)``: run the ``softpad`` command in this process and return its exit code,
    stdout and stderr (argparse's own exits count as exit codes); a traceback on stderr fails
    the test (the CLI contract: one line per error)."""
    from softpad.cli.main import main

    def run(*argv: str) -> tuple[int, str, str]:
        try:
            code = main(list(argv))
        except SystemExit as exc:
            code = int(exc.code or 0)
        out, err = capsys.readouterr()
        assert "Traceback" not in err, err
        return code, out, err

    return run
