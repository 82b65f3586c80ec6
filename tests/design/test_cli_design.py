"""``softpad design`` end to end: the quick thesis-set sweep on a local Dask cluster and on a
separately started ``dask scheduler`` + ``dask worker`` on 127.0.0.1 give the same table."""

from __future__ import annotations

import json
import socket
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import pytest

from softpad.cli.main import main

pytestmark = [pytest.mark.fem, pytest.mark.slow]

BIN = Path(sys.executable).parent
#: Bound on one quick sweep (about 30 s on 2 busy cores).
SWEEP_TIMEOUT_S = 300


def _design(*args: str, cache: Path) -> dict:
    cmd = [
        str(BIN / "softpad"),
        "design",
        "--example",
        "thesis-set",
        "--quick",
        "--json",
        "--no-progress",
        "--cache",
        str(cache),
        *args,
    ]
    out = subprocess.run(cmd, capture_output=True, text=True, timeout=SWEEP_TIMEOUT_S, check=False)
    assert out.returncode == 0, out.stderr[-2000:]
    return json.loads(out.stdout)


@pytest.fixture
def scheduler_address(free_port) -> Iterator[str]:
    """``dask scheduler`` and one ``dask worker`` (2 processes) on 127.0.0.1, stopped after."""
    port = free_port()
    address = f"tcp://127.0.0.1:{port}"
    loopback = ["--dashboard-address", "127.0.0.1:0"]
    procs = [
        subprocess.Popen(
            [
                str(BIN / "dask"),
                "scheduler",
                "--host",
                "127.0.0.1",
                "--port",
                str(port),
                "--no-dashboard",
                *loopback,
            ],
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
        )
    ]
    try:
        deadline = time.monotonic() + 60
        while True:
            try:
                socket.create_connection(("127.0.0.1", port), timeout=1).close()
                break
            except OSError:
                assert time.monotonic() < deadline, "the dask scheduler did not start in 60 s"
                time.sleep(0.3)
        procs.append(
            subprocess.Popen(
                [
                    str(BIN / "dask"),
                    "worker",
                    address,
                    "--host",
                    "127.0.0.1",
                    "--nworkers",
                    "2",
                    "--nthreads",
                    "1",
                    "--no-dashboard",
                    *loopback,
                ],
                stdout=subprocess.DEVNULL,
                stderr=subprocess.DEVNULL,
            )
        )
        yield address
    finally:
        for p in reversed(procs):
            p.terminate()
        for p in procs:
            try:
                p.wait(timeout=20)
            except subprocess.TimeoutExpired:
                p.kill()
                p.wait(timeout=5)


def test_quick_sweep_on_a_local_cluster_and_on_a_loopback_scheduler(
    scheduler_address: str, tmp_path: Path, design_keys: frozenset[str]
) -> None:
    """One test (the sweep runs once per xdist worker otherwise): the local cluster's table,
    then the same from the separately started scheduler and worker, with an empty cache."""
    local_run = _design("--workers", "2", cache=tmp_path / "cache-local")
    _check_table(local_run, design_keys)
    remote = _design("--scheduler", scheduler_address, cache=tmp_path / "cache-remote")
    assert remote["computed"] == local_run["computed"] and remote["cached"] == 0
    assert remote["designs"] == local_run["designs"]


def _check_table(local_run: dict, keys: frozenset[str]) -> None:
    designs = local_run["designs"]
    assert len(designs) >= 8
    for d in designs:
        assert keys <= set(d)
        lo, hi = d["success_interval"]
        assert 0 <= lo <= d["success"] <= hi <= 1
    base = [d for d in designs if d["baseline"]]
    assert len(base) == 1
    assert (base[0]["rows"], base[0]["cols"], base[0]["pitch_mm"]) == (2, 3, 45.0)
    # the FEM's minimum detectable mass of the thesis module at t_o (docs/design.md: about 9 g
    # with the brick's footprint; the thesis measured about 6 g)
    assert 7.0 < base[0]["min_detectable_mass_g"] < 11.0
    assert [d["rank"] for d in designs] == list(range(1, len(designs) + 1))
    # smaller modules feel lighter objects: the mass falls with the pitch
    by_pitch = {
        d["pitch_mm"]: d["min_detectable_mass_g"]
        for d in designs
        if d["thickness_mm"] == 1.5 and d["p0_kpa"] == 1.1 and d["material"] == "neo-hookean"
    }
    assert by_pitch[23.0] < by_pitch[34.0] < by_pitch[45.0]


def test_bad_options_one_line_exit_2(capsys: pytest.CaptureFixture[str]) -> None:
    for argv in (
        ["design", "--scheduler", "tcp://192.168.1.5:8786"],
        ["design", "--grid", "2x"],
        ["design", "--pitch-mm", "500"],
        ["design", "--material", "rubber", "--quick"],
        ["design", "--example", "nope"],
        ["design", "--objects", "/nonexistent.toml"],
        ["design", "--png", "/nonexistent-dir/p.png"],
    ):
        assert main(argv) == 2, argv
        err = capsys.readouterr().err.strip()
        assert len(err.splitlines()) == 1 and "Traceback" not in err, err
