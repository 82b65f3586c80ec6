"""The Dask ``distributed`` client of design sweeps and trial seeds: loopback only.

By default a :class:`distributed.LocalCluster` on 127.0.0.1 (worker processes, one thread
each, dashboard and HTTP endpoints on a free loopback port); ``scheduler="tcp://127.0.0.1:PORT"``
joins a running ``dask scheduler --host 127.0.0.1`` instead. Other addresses are refused:
this project's processes listen and connect on the loopback interface only.
"""

from __future__ import annotations

import contextlib
import os
import re
from collections.abc import Iterator
from typing import Any

from softpad.errors import InputError

_ADDRESS = re.compile(r"^tcp://(127\.0\.0\.1|localhost):(\d{1,5})$")


def check_scheduler_address(address: str) -> str:
    """``address`` if it is ``tcp://127.0.0.1:PORT`` (or ``localhost``), else InputError."""
    m = _ADDRESS.match(str(address).strip())
    if m is None or not 1 <= int(m.group(2)) <= 65535:
        raise InputError(
            f"--scheduler must be tcp://127.0.0.1:PORT (a scheduler on this machine's loopback "
            f"interface), got {address!r}"
        )
    return f"tcp://127.0.0.1:{int(m.group(2))}"


def available_cpus() -> int:
    """CPUs this process may use."""
    if hasattr(os, "sched_getaffinity"):
        return len(os.sched_getaffinity(0))
    return os.cpu_count() or 1


def has_dask() -> bool:
    """Whether ``distributed`` is installed (``pip install softpad[design]``)."""
    import importlib.util

    return importlib.util.find_spec("distributed") is not None


@contextlib.contextmanager
def dask_client(
    scheduler: str | None = None, workers: int | None = None, timeout_s: float = 20.0
) -> Iterator[Any]:
    """A connected ``distributed.Client``: to ``scheduler`` or to a new local cluster.

    Parameters
    ----------
    scheduler
        ``tcp://127.0.0.1:PORT`` of a running scheduler, or None for a local cluster.
    workers
        Worker processes of the local cluster (default: the CPUs available).
    timeout_s
        Time allowed to connect, seconds.
    """
    if not has_dask():
        raise InputError(
            "Dask distributed is not installed: pip install 'softpad[design]' "
            "(or 'dask[distributed]')"
        )
    from distributed import Client, LocalCluster

    if scheduler is not None:
        address = check_scheduler_address(scheduler)
        try:
            client = Client(address, timeout=timeout_s)
        except OSError as exc:
            raise InputError(f"no Dask scheduler answers at {address}: {exc}") from None
        with client:
            yield client
        return
    n = available_cpus() if workers is None else workers
    if isinstance(n, bool) or not isinstance(n, int) or not 1 <= n <= 256:
        raise InputError(f"workers must be an integer from 1 to 256, got {workers!r}")
    cluster = LocalCluster(
        n_workers=n,
        threads_per_worker=1,
        processes=True,
        host="127.0.0.1",
        protocol="tcp",
        dashboard_address="127.0.0.1:0",
        worker_dashboard_address="127.0.0.1:0",
        scheduler_kwargs={"dashboard": False},
        silence_logs=40,
    )
    with cluster, Client(cluster) as client:
        yield client
