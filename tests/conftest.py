"""Fixtures shared by the test packages."""

from __future__ import annotations

import threading
from collections.abc import Callable, Iterator
from typing import Any

import pytest

from softpad.box import BoxServer


@pytest.fixture
def serve_box() -> Iterator[Callable[..., BoxServer]]:
    """``serve_box(box, **server_options)``: serve ``box`` on 127.0.0.1 (a free port) from a
    background thread; every server started is stopped and closed after the test."""
    started: list[tuple[BoxServer, threading.Thread]] = []

    def serve(box: Any, **options: Any) -> BoxServer:
        server = BoxServer(box, "127.0.0.1", 0, **options)
        thread = threading.Thread(target=server.serve, daemon=True)
        thread.start()
        started.append((server, thread))
        return server

    yield serve
    for server, thread in started:
        server.stop()
        thread.join(timeout=5)
        server.close()
