"""Fixtures shared by the test folders: loopback ports, a served simulated box and an
installation file with a non-zero pad pose."""

from __future__ import annotations

import math
import os
import resource
import signal
import socket
import time
from collections.abc import Callable, Generator, Iterator, Sequence
from contextlib import AbstractContextManager, contextmanager
from pathlib import Path
from typing import Any

import numpy as np
import pytest


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def pytest_addoption(parser: pytest.Parser) -> None:
    parser.addoption(
        "--cpu-durations",
        type=int,
        default=None,
        metavar="N",
        help="list the N tests that used the most CPU: user + system seconds of the test's "
        "process (all its threads) and of the children it waited for, set-up to teardown "
        "(wall times mislead on a shared machine; issue 38)",
    )


def pytest_configure(config: pytest.Config) -> None:
    """Ctrl-C's default disposition in the test process (each xdist worker and a plain run),
    so that the processes a test starts and stops with SIGINT hear it.

    A run started in the background of a shell script (``make test &``, without job control)
    starts ignoring SIGINT; every process it starts inherits the ignore through fork and exec,
    and Python keeps ignoring a SIGINT ignored at its start (it raises KeyboardInterrupt only
    where the parent left SIGINT's default). The ROS 2 node, the ROS 1 node and every
    ``softpad`` command a test stops with SIGINT then waited out their deadlines before
    SIGKILL (two ROS 2 teardowns of 20 s each in the quiet full runs at d17d7d5; issue 50). A
    handler set here is reset to the default in each child at exec."""
    del config
    if signal.getsignal(signal.SIGINT) is signal.SIG_IGN:
        signal.signal(signal.SIGINT, signal.default_int_handler)


_CPU_KEY = pytest.StashKey[float]()
_cpu_by_test: dict[str, float] = {}


def _cpu_s() -> float:
    own = resource.getrusage(resource.RUSAGE_SELF)
    kids = resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime + kids.ru_utime + kids.ru_stime


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_protocol(item: pytest.Item) -> Generator[None, None, None]:
    item.stash[_CPU_KEY] = _cpu_s()
    yield


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item: pytest.Item) -> Generator[None, Any, None]:
    outcome = yield
    report = outcome.get_result()
    if report.when == "teardown" and item.config.getoption("cpu_durations") is not None:
        report.user_properties.append(("cpu_s", _cpu_s() - item.stash[_CPU_KEY]))


def pytest_runtest_logreport(report: pytest.TestReport) -> None:
    for name, value in report.user_properties:
        if name == "cpu_s" and report.when == "teardown":
            _cpu_by_test[report.nodeid] = float(value)  # type: ignore[arg-type]


def pytest_terminal_summary(terminalreporter: Any, config: pytest.Config) -> None:
    n = config.getoption("cpu_durations")
    if n is None or not _cpu_by_test:
        return
    terminalreporter.section("CPU seconds by test (user + sys)")
    total = sum(_cpu_by_test.values())
    for nodeid, cpu in sorted(_cpu_by_test.items(), key=lambda kv: -kv[1])[: n or None]:
        terminalreporter.write_line(f"{cpu:8.2f}s  {nodeid}")
    terminalreporter.write_line(f"{total:8.2f}s  total over {len(_cpu_by_test)} tests")


#: Seconds a test file takes on a quiet 2-core machine (estimates: 2026-11-28, issue 50; the
#: ROS 1 and docs files wait on processes, masters and servers more than they compute). Under
#: pytest-xdist the heaviest files start first, spread over the workers (below); a file not
#: listed counts 0.05 s a test. Only the order changes, never what runs.
FILE_SECONDS = {
    "tests/ros/test_ros.py": 85.0,
    "tests/test_docs.py": 45.0,
    "tests/trials/test_calibrate.py": 11.0,
    "tests/test_examples.py": 11.0,
    "tests/cli/test_signals.py": 7.0,
    "tests/control/test_faults_safe_state.py": 8.0,
    "tests/ros2/test_ros2_node.py": 6.0,
    "tests/trials/test_no_oracle_pairs.py": 7.0,
    "tests/control/test_table_6_1_loop.py": 6.5,
    "tests/sensing/test_adaptive.py": 6.5,
    "tests/control/test_execution.py": 6.5,
    "tests/box/test_security.py": 4.0,
    "tests/design/test_evaluate.py": 6.0,
    "tests/trials/test_hold_coast_equivalence.py": 6.0,
    "tests/control/test_fault_campaign.py": 6.0,
    "tests/fem/test_cast.py": 6.0,
    "tests/cli/test_fuzz.py": 6.0,
    "tests/design/test_density_response.py": 6.0,
    "tests/control/test_inflation.py": 5.5,
    "tests/fem/test_cli.py": 5.5,
    "tests/cli/test_run_box_cli.py": 5.5,
    "tests/trials/test_column_figures.py": 4.0,
    "tests/harness/test_remote.py": 4.0,
    "tests/trials/test_catalogue_trials.py": 4.0,
    "tests/trials/test_still_valve_check.py": 4.0,
    "tests/test_misuse.py": 4.0,
    "tests/ros/test_adapters.py": 3.5,
    "tests/trials/test_trial_recording.py": 3.0,
    "tests/fem/test_fitting.py": 3.0,
    "tests/sim/test_hold_coast.py": 3.0,
    "tests/test_fuzz_campaign.py": 3.0,
    "tests/box/test_box_safety.py": 3.0,
}


def _file_of(item: pytest.Item) -> str:
    return item.nodeid.split("::", 1)[0]


def _bins(files: dict[str, list[pytest.Item]], sizes: list[int]) -> list[list[str]]:
    """The files dealt to workers that take ``sizes`` tests each, heaviest first, each to the
    worker with the least work so far that has room for it; a file that fits nowhere is
    split (its module fixtures then start on both workers)."""
    weight = {f: FILE_SECONDS.get(f, 0.05 * len(its)) for f, its in files.items()}
    load, room = [0.0] * len(sizes), list(sizes)
    bins: list[list[str]] = [[] for _ in sizes]
    for f in sorted(files, key=lambda f: -weight[f]):  # stable: ties in collection order
        n = len(files[f])
        fits = [b for b in range(len(sizes)) if room[b] >= n]
        b = (
            min(fits, key=lambda b: load[b])
            if fits
            else max(range(len(sizes)), key=room.__getitem__)
        )
        bins[b].append(f)
        load[b] += weight[f]
        room[b] -= n
    return bins


@pytest.hookimpl(trylast=True)  # after -m and -k deselected what does not run
def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    """Under pytest-xdist (``make test``: three workers, ``--dist worksteal``), the order that
    balances the workers: worksteal gives each worker a contiguous share of the collection
    (the first ``n // k`` tests to one, and so on) and an idle worker takes tests from the
    end of another's queue; so each share starts with its heaviest files (FILE_SECONDS) and
    the long ROS 1 and docs files no longer share one worker (issue 50)."""
    k = int(os.environ.get("PYTEST_XDIST_WORKER_COUNT", "1"))
    if k < 2 or len(items) < 2 * k:
        return
    files: dict[str, list[pytest.Item]] = {}
    for item in items:
        files.setdefault(_file_of(item), []).append(item)
    sizes, left = [], len(items)
    for i in range(k):  # worksteal's first deal: len(pending) // nodes_remaining each
        sizes.append(left // (k - i))
        left -= sizes[-1]
    order = [it for b in _bins(files, sizes) for f in b for it in files[f]]
    assert len(order) == len(items)
    items[:] = order


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


#: An installation file whose pad stands away from the base frame's origin (issue 48: the
#: ``[pad.pose]`` never reached ``/tf_static``): 400, -100, 20 mm, turned 30 degrees.
SITE_TOML = """
[pad]
rows = 2
cols = 3
[pad.pose]
x_mm = 400.0
y_mm = -100.0
z_mm = 20.0
yaw_deg = 30.0
"""


class Site:
    """An installation file (``path``) with a non-zero pad pose, and that pose in SI."""

    #: The pose of ``SITE_TOML`` in metres and radians.
    xyz_m = (0.4, -0.1, 0.02)
    yaw_rad = math.radians(30.0)

    def __init__(self, path: Path) -> None:
        self.path = path
        path.write_text(SITE_TOML)

    @property
    def quaternion(self) -> tuple[float, float, float, float]:
        """The yaw as a quaternion (x, y, z, w)."""
        return (0.0, 0.0, math.sin(self.yaw_rad / 2), math.cos(self.yaw_rad / 2))

    def check_pad_transform(
        self, frames: tuple[str, str], xyz: Sequence[float], q: Sequence[float]
    ) -> None:
        """Assert that base -> softpad (``frames``: parent, child) is this installation's
        pose: ``xyz`` in m within 1 um, the quaternion ``q`` (x, y, z, w) within 1e-9."""
        assert tuple(frames) == ("base", "softpad")
        np.testing.assert_allclose(xyz, self.xyz_m, atol=1e-6)
        np.testing.assert_allclose(q, self.quaternion, atol=1e-9)


@pytest.fixture
def site(tmp_path: Path) -> Site:
    """``site.path``: ``tmp_path/site.toml`` with a non-zero ``[pad.pose]``; ``site.xyz_m``,
    ``site.yaw_rad``, ``site.quaternion`` and ``site.check_pad_transform(...)`` to check it."""
    return Site(tmp_path / "site.toml")


@pytest.fixture(scope="module")
def module_site(tmp_path_factory: pytest.TempPathFactory) -> Site:
    """:func:`site` once for a test module (its module-scoped fixtures)."""
    return Site(tmp_path_factory.mktemp("site") / "site.toml")
