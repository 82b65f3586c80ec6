"""Shared helpers of the zenoh tests: free loopback ports, a served simulated box."""

from __future__ import annotations

import socket
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

from softpad.box import BoxDaemon, SimBox, open_box


def free_port() -> int:
    """A TCP port on 127.0.0.1 that nobody listens on right now."""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


@contextmanager
def served(url: str = "sim://?seed=4", **kwargs: Any) -> Iterator[tuple[BoxDaemon, str]]:
    """A :class:`BoxDaemon` serving ``url`` on a free loopback port, and its zenoh:// URL."""
    from softpad.harness import simulation_extensions

    port = free_port()
    box = open_box(url)
    services = simulation_extensions(box) if isinstance(box, SimBox) else None
    daemon = BoxDaemon(box, (f"tcp/127.0.0.1:{port}",), services=services, **kwargs)
    with daemon:
        yield daemon, f"zenoh://127.0.0.1:{port}"
