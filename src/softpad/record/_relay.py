"""Frames of a box relayed to live viewers at the box's pace (never faster than real time)."""

from __future__ import annotations

import time
from typing import Any


def relay_frames(box: Any, live: Any, count: int = 0, source: str = "monitor") -> int:
    """Read frames from ``box`` and hand each to ``live.frame``, paced to the wall clock
    (a simulated box runs faster than real time).

    Parameters
    ----------
    box
        The box read.
    live
        A :class:`~softpad.record.FoxgloveLive` (anything with ``frame(frame, source)``).
    count
        Frames relayed, 0 for endless.
    source
        What the frames are, for the viewer.

    Returns
    -------
    int
        Frames relayed.
    """
    wall0 = t0 = None
    i = 0
    while count == 0 or i < count:
        f = box.read()
        if wall0 is None or t0 is None:
            wall0, t0 = time.monotonic(), f.t_s
        delay = wall0 + (f.t_s - t0) - time.monotonic()
        if delay > 0:  # a simulated box runs faster than real time: keep pace
            time.sleep(delay)
        live.frame(f, source)
        i += 1
    return i


__all__ = ["relay_frames"]
