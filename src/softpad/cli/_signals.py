"""SIGTERM stops a command like Ctrl-C, with the shell's exit code of each (docs/cli.md).

Ctrl-C (SIGINT) raises :class:`KeyboardInterrupt` and the command exits 130; SIGTERM (systemd,
``kill``) raises :class:`Terminated`, a :class:`KeyboardInterrupt`, so every ``finally`` and
``with`` that makes the box safe on Ctrl-C runs on SIGTERM too, and the command exits 143.
"""

from __future__ import annotations

import signal
import threading
from collections.abc import Iterator
from contextlib import contextmanager

#: Exit codes of a command stopped by a signal: 128 + the signal's number, as a shell reports.
EXIT_SIGINT = 128 + signal.SIGINT
EXIT_SIGTERM = 128 + signal.SIGTERM


class Terminated(KeyboardInterrupt):
    """SIGTERM arrived: stop as on Ctrl-C, exit :data:`EXIT_SIGTERM`."""


def _raise_terminated(signum: int, frame: object) -> None:
    raise Terminated


@contextmanager
def sigterm_stops() -> Iterator[None]:
    """While inside, SIGTERM raises :class:`Terminated` in the main thread (elsewhere, as when
    a test calls ``main`` from a thread, nothing changes)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous = signal.signal(signal.SIGTERM, _raise_terminated)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)


def exit_code_of_interrupt(exc: KeyboardInterrupt) -> int:
    """130 for Ctrl-C, 143 for SIGTERM."""
    return EXIT_SIGTERM if isinstance(exc, Terminated) else EXIT_SIGINT
